"""What type checkers and help() see in the installed package: the extension's stub
(pupwave/_pupwave.pyi) and py.typed shipped beside it, the stub naming the extension's functions
with their parameters, and a docstring on every public function and class."""

import ast
import importlib
import inspect
import pathlib
import re

import pytest

import pupwave

MODULES = ["pupwave", "pupwave.hdf5", "pupwave.numcodecs", "pupwave.pillow", "pupwave.dtypes"]


def stub_functions(installed):
    """{name: [parameter names]} of the functions in the installed _pupwave.pyi."""
    stub = pathlib.Path(installed.locate_file("pupwave/_pupwave.pyi"))
    tree = ast.parse(stub.read_text())
    return {f.name: [a.arg for a in f.args.args] for f in tree.body if isinstance(f, ast.FunctionDef)}


def runtime_parameters(function):
    """Parameter names from pybind11's signature line, "name(a: T, b: T = x) -> R"."""
    signature = function.__doc__.splitlines()[0]
    inside = signature[signature.index("(") + 1 : signature.rindex(") ->")]
    return re.findall(r"(?:^|, )(\w+):", inside)


def test_stub_and_marker_are_shipped_and_match_the_extension(installed):
    assert pathlib.Path(installed.locate_file("pupwave/py.typed")).is_file()
    stub = stub_functions(installed)
    compiled = {n: f for n, f in vars(pupwave._pupwave).items() if callable(f) and not n.startswith("_")}
    assert sorted(stub) == sorted(compiled)
    for name, function in compiled.items():
        assert stub[name] == runtime_parameters(function), name


def public_objects():
    """(module.name, object) for every public function and class a package module defines, and the
    public methods those classes define."""
    for module_name in MODULES:
        try:
            module = importlib.import_module(module_name)
        except ImportError:  # pupwave.numcodecs and pupwave.pillow need their frameworks
            continue
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != module_name:
                continue
            if inspect.isfunction(obj) or inspect.isclass(obj):
                yield f"{module_name}.{name}", obj
            if inspect.isclass(obj):
                for method_name, method in vars(obj).items():
                    if not method_name.startswith("_") and inspect.isfunction(method):
                        yield f"{module_name}.{name}.{method_name}", method


def test_every_public_name_has_a_docstring(installed):
    missing = [name for name, obj in public_objects() if not (obj.__doc__ or "").strip()]
    assert missing == []
    for name in pupwave.__all__:
        assert hasattr(pupwave, name), name
        if name != "__version__":
            assert (getattr(pupwave, name).__doc__ or "").strip(), name
    assert re.fullmatch(r"\d+\.\d+\.\d+", pupwave.__version__)


@pytest.mark.parametrize("function", ["compress", "compress_volume"])
def test_help_shows_arguments_defaults_return_and_errors(function):
    text = pydoc_text(getattr(pupwave, function))
    assert "threads=None" in text and "strict=False" in text
    for word in ("Returns", "Raises", "PupwaveTargetWarning", "threads:", "strict:"):
        assert word in text, word


def pydoc_text(obj):
    import pydoc

    return pydoc.plain(pydoc.render_doc(obj))

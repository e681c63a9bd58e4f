"""Builds the pupwave Python package with CMake (docs/python.md, "Install with pip").

The package is tools/python/pupwave/ (pure Python), the extension pupwave._pupwave and the HDF5
filter plugin, shipped as pupwave/hdf5_plugin/libh5pupwave.so. build_ext builds the two CMake
targets and copies them into the package:

- PUPWAVE_CMAKE_BUILD_DIR=DIR names a configured CMake build folder (the one of scripts/build.sh,
  say): the targets are brought up to date there (nothing is compiled when it is current);
- otherwise the tree is configured with only the library, the Python module and the HDF5 plugin
  in setuptools' build_temp, and built there.
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
TARGETS = ("_pupwave", "h5pupwave")
PLUGIN_NAME = "libh5pupwave.so"
PLUGIN_FOLDER = "hdf5_plugin"  # inside the package; pupwave/hdf5.py registers it with h5py
# Where tools/python/CMakeLists.txt and tools/hdf5/CMakeLists.txt put the two targets.
MODULE_DIR = pathlib.Path("python", "pupwave")
PLUGIN_DIR = pathlib.Path("lib", "hdf5", "plugins")
# A configure of only what the package needs: no CLI (and so no tests, benchmarks, OIIO plugin).
CONFIGURE_OPTIONS = ("-DCMAKE_BUILD_TYPE=Release", "-DPUPWAVE_BUILD_TOOLS=OFF", "-DPUPWAVE_BUILD_HDF5=ON",
                     "-DPUPWAVE_BUILD_PYTHON=ON", "-DPUPWAVE_BUILD_FUZZERS=OFF")


def cmake_version():
    """The project's version, from the top-level CMakeLists.txt's project() call."""
    text = (ROOT / "CMakeLists.txt").read_text()
    match = re.search(r"project\(\s*pupwave\s+VERSION\s+([0-9][0-9.]*)", text)
    if match is None:
        sys.exit(f"setup.py: {ROOT / 'CMakeLists.txt'}: no `project(pupwave VERSION x.y.z ...)` line")
    return match.group(1)


def run(command):
    if shutil.which(command[0]) is None:
        sys.exit(f"setup.py: {command[0]} not found in PATH (Debian: apt-get install {command[0]})")
    print(" ".join(str(c) for c in command), flush=True)
    subprocess.run([str(c) for c in command], check=True)


def parallel_flags():
    """-j for cmake --build unless CMAKE_BUILD_PARALLEL_LEVEL (read by cmake itself) is set."""
    return [] if os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") else ["-j", str(os.cpu_count() or 1)]


def check_build_dir(build_dir):
    """Refuses a PUPWAVE_CMAKE_BUILD_DIR that is no configured build with both components on."""
    cache = build_dir / "CMakeCache.txt"
    if not cache.is_file():
        sys.exit(f"setup.py: PUPWAVE_CMAKE_BUILD_DIR={build_dir}: no CMakeCache.txt there (configure it with cmake "
                 f"first, or unset the variable to build in build_temp)")
    text = cache.read_text(errors="replace")
    for option in ("PUPWAVE_BUILD_PYTHON", "PUPWAVE_BUILD_HDF5"):
        if re.search(rf"^{option}:BOOL=(OFF|0|FALSE|NO)$", text, re.MULTILINE | re.IGNORECASE):
            sys.exit(f"setup.py: PUPWAVE_CMAKE_BUILD_DIR={build_dir}: configured with {option}=OFF; the package "
                     f"needs it ON")


class CMakeBuild(build_ext):
    """Builds the extension and the HDF5 plugin with CMake and copies them into the package."""

    def run(self):
        build_dir = self.cmake_build()
        module = build_dir / MODULE_DIR / ("_pupwave" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not module.is_file():
            found = sorted(p.name for p in (build_dir / MODULE_DIR).glob("_pupwave*.so"))
            sys.exit(f"setup.py: {module} not found: {build_dir} built the module for another Python ({found}); "
                     f"configure it with -DPython_EXECUTABLE={sys.executable}")
        self.copy_into_package(module, pathlib.Path(self.get_ext_fullpath("pupwave._pupwave")))
        self.copy_into_package(build_dir / PLUGIN_DIR / PLUGIN_NAME, self.plugin_path())

    def cmake_build(self):
        """The build folder with both targets up to date."""
        given = os.environ.get("PUPWAVE_CMAKE_BUILD_DIR")
        if given:
            build_dir = pathlib.Path(given).resolve()
            check_build_dir(build_dir)
        else:
            build_dir = pathlib.Path(self.build_temp).resolve() / "cmake"
            run(["cmake", "-S", ROOT, "-B", build_dir, *CONFIGURE_OPTIONS, f"-DPython_EXECUTABLE={sys.executable}"])
        run(["cmake", "--build", build_dir, "--target", *TARGETS, *parallel_flags()])
        return build_dir

    def plugin_path(self):
        return pathlib.Path(self.get_ext_fullpath("pupwave._pupwave")).parent / PLUGIN_FOLDER / PLUGIN_NAME

    def copy_into_package(self, source, destination):
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(source, destination)
        print(f"copied {source} -> {destination}", flush=True)

    def get_outputs(self):
        return super().get_outputs() + [str(self.plugin_path())]


# setuptools' build folders and egg-info beside the CMake build of scripts/build.sh (build/), in
# the git-ignored /build* rather than the source tree.
SETUPTOOLS_DIR = pathlib.Path("build", "setuptools")
SETUPTOOLS_DIR.mkdir(parents=True, exist_ok=True)

setup(
    options={"build": {"build_base": str(SETUPTOOLS_DIR)}, "egg_info": {"egg_base": str(SETUPTOOLS_DIR)}},
    version=cmake_version(),
    packages=["pupwave"],
    package_dir={"pupwave": "tools/python/pupwave"},
    # The extension's type stub and the marker that the package is typed (PEP 561).
    package_data={"pupwave": ["_pupwave.pyi", "py.typed"]},
    # No sources: CMakeBuild builds the extension (setuptools needs one listed to call build_ext
    # and to tag the wheel for this platform).
    ext_modules=[Extension("pupwave._pupwave", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
)

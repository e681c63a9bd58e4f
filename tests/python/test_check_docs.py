"""scripts/check-docs.sh: the real docs name only flags the CLI has; a made-up flag in a docs page
or a README command, and a README sh block that fails, are reported with FILE:LINE."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "check-docs.sh"


def check_docs(cli, *args, readme=None, pages=None, timeout=60):
    env = dict(os.environ, CHECK_DOCS_TIMEOUT=str(timeout))
    if readme is not None:
        env["CHECK_DOCS_README"] = str(readme)
    if pages is not None:
        env["CHECK_DOCS_PAGES"] = " ".join(str(p) for p in pages)
    result = subprocess.run(["bash", str(SCRIPT), *args, cli], env=env, capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


def test_real_docs_name_only_flags_the_cli_has(cli):
    rc, out = check_docs(cli, "--flags-only")
    assert rc == 0, out
    assert "every pupwave flag in" in out


def test_made_up_flags_in_a_docs_page_are_reported(cli, tmp_path):
    page = tmp_path / "cli.md"
    page.write_text(
        "# Conventions\n"
        "\n"
        "`--quiet` everywhere, and `--frobnicate` nowhere.\n"
        "\n"
        "## `pupwave decompress`\n"
        "\n"
        "`--level k` decodes less; `--bpp 1` is not a decompress option.\n"
        "\n"
        "```sh\n"
        "pupwave compress testimages/camera.png out/c.pw --bpp 1 --made-up-rate 2   # or --psnr 40\n"
        "pupwave bench rd --images testimages \\\n"
        "    --jobs 2 --bogus-jobs 3\n"
        "cmake --build build --not-a-pupwave-flag\n"
        "```\n"
        "\n"
        "```console\n"
        "$ pupwave info out/c.pw --made-up-detail\n"
        "```\n"
    )
    rc, out = check_docs(cli, "--flags-only", readme=ROOT / "README.md", pages=[page])
    assert rc == 1, out
    assert f"{page}:3: no pupwave subcommand has the option --frobnicate" in out
    assert f"{page}:7: pupwave decompress has no option --bpp" in out
    assert f"{page}:10: pupwave compress has no option --made-up-rate" in out
    assert f"{page}:11: pupwave bench rd has no option --bogus-jobs" in out
    assert f"{page}:17: pupwave info has no option --made-up-detail" in out
    # real options and other programs' flags are not reported
    for flag in ("--quiet", "--level", "--psnr", "--jobs", "--not-a-pupwave-flag"):
        assert f"option {flag}\n" not in out + "\n", flag


def test_made_up_flag_in_a_readme_command_is_reported(cli, tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("```sh\npupwave info testimages/camera.png --made-up-detail\n```\n")
    rc, out = check_docs(cli, "--flags-only", readme=readme, pages=[])
    assert rc == 1, out
    assert f"{readme}:2: pupwave info has no option --made-up-detail" in out


def test_failing_readme_sh_block_is_reported(cli, tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text(
        "```sh\n"
        "bash scripts/test.sh\n"  # line 2: skipped (CI runs it); the 60 s limit would catch it
        "pupwave info testimages/camera.png\n"
        "```\n"
        "\n"
        "```console\n"
        "pupwave decompress out/no-such-stream.pw out/never.png\n"  # not run: console block
        "```\n"
        "\n"
        "```sh\n"
        "pupwave psnr testimages/camera.png testimages/camera.png\n"
        "pupwave info testimages/no-such-image.png\n"  # line 12 fails
        "echo not reached\n"
        "```\n"
    )
    rc, out = check_docs(cli, readme=readme, pages=[])
    assert rc == 1, out
    assert f"{readme}:12: sh block (from line 10) failed with exit 1" in out
    assert "no-such-image.png" in out
    assert out.count("sh block") == 1, out

    readme.write_text("```sh\npupwave info testimages/camera.png\n```\n")
    rc, out = check_docs(cli, readme=readme, pages=[])
    assert rc == 0, out
    assert "1 README sh blocks ran" in out


def test_readme_block_writing_outside_out_is_reported(cli, tmp_path):
    if subprocess.run(["git", "-C", str(ROOT), "rev-parse"], capture_output=True).returncode != 0:
        pytest.skip("not a git work tree: the check reads git status")
    stray = ROOT / f"check_docs_stray_{os.getpid()}.pw"
    readme = tmp_path / "README.md"
    readme.write_text(
        "```sh\n"
        f"pupwave compress testimages/camera.png out/check_docs_{os.getpid()}.pw --bpp 0.25 -q\n"
        f"pupwave compress testimages/camera.png {stray.name} --bpp 0.25 -q\n"
        "```\n"
    )
    try:
        rc, out = check_docs(cli, readme=readme, pages=[])
    finally:
        stray.unlink(missing_ok=True)
        (ROOT / "out" / f"check_docs_{os.getpid()}.pw").unlink(missing_ok=True)
    assert rc == 1, out
    assert f"{readme}:1: sh block wrote into the repository (write under out/): {stray.name}" in out
    assert "out/check_docs_" not in out  # out/ is git-ignored: where examples write

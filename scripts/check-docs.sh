#!/usr/bin/env bash
# Fails when the docs promise what the CLI does not do. Lists each problem as FILE:LINE: ...
#
#   bash scripts/check-docs.sh [--flags-only] [PUPWAVE_BINARY]     (default build/tools/pupwave)
#
# 1. Flags: every pupwave command line in README.md and docs/*.md may use only the options its
#    subcommand has, as `pupwave SUB [SUBSUB] --help` lists them (subcommands found by walking
#    `pupwave --help`). Checked:
#    - in code blocks and inline code, each shell command (split at ; && || $( and at a spaced |
#      not followed by a flag) that starts with pupwave, build/tools/pupwave, a path ending in
#      /pupwave or $pw, after a `$ ` prompt, VAR=value words and do/then/time/nice/timeout/env/
#      sudo; a usage line continued by a trailing \ or by an indented line starting with [ or -
#      is one command; long flags in a `# ...` comment on that line count too (the comment is
#      about the command);
#    - inline code starting with a subcommand and then a flag, a subsubcommand or ... (`decompress
#      --level k`, `bench ... --out`);
#    - inline code starting with a flag, in README.md and docs/cli.md only (pages about the CLI):
#      checked against the subcommand named in the section heading of docs/cli.md, else against
#      every subcommand's options together.
#    A lower-case word where a subcommand belongs that names none (`pupwave encode`) is reported.
#    Not checked: flags of other programs (cmake, oiiotool, cjxl, ...), flags after a placeholder
#    subcommand (SUBCOMMAND, ..., <x>) beyond "some subcommand below has it", short flags in
#    comments.
# 2. README commands run: each fenced block whose info string is exactly `sh` is run from the
#    repository root as one `set -e` bash script, with the binary's folder first in PATH, out/
#    created (git-ignored; examples write there), stdin empty and a 300 s limit per block. A block
#    that adds or changes a file git sees (an output outside out/) is reported too. Lines
#    running what CI runs itself (bash scripts/test.sh, bash scripts/sanitize.sh) are skipped.
#    Blocks tagged console, text, bash, ... are not run. --flags-only skips this part.
#
# Environment: CHECK_DOCS_README (default README.md) and CHECK_DOCS_PAGES (space-separated
# pages, default docs/*.md) name other files to check; CHECK_DOCS_TIMEOUT the block limit (s).
set -euo pipefail
cd "$(dirname "$0")/.."
exec python3 - "$@" <<'PY'
import glob
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.getcwd()
# Commands CI already runs (.ci/run): a README block repeating them is not run again.
SKIPPED_LINES = {"bash scripts/test.sh", "bash scripts/sanitize.sh"}
# Words that may precede the program name in a shell command.
PREFIX_WORDS = {"$", "do", "then", "else", "time", "/usr/bin/time", "timeout", "nice", "exec", "env", "sudo", "!"}
PROGRAM = re.compile(r"""^["']?(\$\{?pw\}?|(\S*/)?pupwave)["']?$""")
FLAG = re.compile(r"(?<![\w\-/.=:])(--[A-Za-z][\w-]*|-[A-Za-z])(?![\w-])")
LONG_FLAG = re.compile(r"(?<![\w\-/.=:])(--[A-Za-z][\w-]*)(?![\w-])")
ENV_ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*=")
SUBCOMMAND_NAME = re.compile(r"^[a-z][a-z0-9-]*$")


def usage_error(message):
    sys.exit(f"check-docs: {message}\nusage: bash scripts/check-docs.sh [--flags-only] [PUPWAVE_BINARY]")


# ---- the CLI's truth ---------------------------------------------------------------------------


class Command:
    def __init__(self, path, flags, children):
        self.path = path  # ("bench", "rd")
        self.flags = flags
        self.children = children  # name -> Command

    def all_flags(self):
        """Flags of this command and every command below it."""
        flags = set(self.flags)
        for child in self.children.values():
            flags |= child.all_flags()
        return flags

    def name(self):
        return " ".join(("pupwave",) + self.path)


def read_command(binary, path):
    """Parses CLI11's help: option lines start with two spaces and '-', subcommand lines with two
    spaces and a name (descriptions continue further indented)."""
    text = subprocess.run([binary, *path, "--help"], capture_output=True, text=True, check=True).stdout
    flags, children, in_subcommands = set(), {}, False
    for line in text.splitlines():
        if not line.startswith(" "):
            in_subcommands = line.strip() == "Subcommands:"
            continue
        option = re.match(r"^  (-\S+)", line)
        if option:
            flags.update(name for name in option.group(1).split(",") if name.startswith("-"))
        elif in_subcommands:
            sub = re.match(r"^  ([a-z][\w-]*)(\s|$)", line)
            if sub:
                children[sub.group(1)] = None
    for name in children:
        children[name] = read_command(binary, path + (name,))
    return Command(path, flags, children)


# ---- flag checks -------------------------------------------------------------------------------


def is_placeholder(word):
    return not SUBCOMMAND_NAME.match(word)


def check_words(root, words, comment, problems, where):
    """words: the command line after the program name. Walks the subcommands it names and checks
    every flag against the deepest one (or, after a placeholder, against all below it)."""
    command, rest = root, list(words)
    exact = True
    while rest and command.children and not rest[0].startswith("-"):
        word = rest[0].strip("`'\"")
        if word in command.children:
            command = command.children[word]
            rest.pop(0)
        elif is_placeholder(word):
            exact = False
            break
        else:
            problems.append(f"{where}: {command.name()} has no subcommand '{word}'")
            return
    allowed = command.flags if exact else command.all_flags()
    text = " ".join(rest)
    found = FLAG.findall(text) + LONG_FLAG.findall(comment)
    for flag in dict.fromkeys(found):
        if flag not in allowed:
            scope = command.name() if exact else f"any subcommand of {command.name()}"
            problems.append(f"{where}: {scope} has no option {flag}")


def split_commands(text):
    """Shell commands of one line: split at ; && || $( ) and at a spaced pipe not followed by a
    flag (a usage line's `--levels N | --range R` and `--kind a|b` stay one command)."""
    parts = re.split(r";|&&|\|\||\$\(|\)|`|(?<=\s)\|(?=\s+[^\s-])", text)
    return [part.strip() for part in parts if part.strip()]


def program_words(command):
    """The words after the pupwave program name, or None when the command runs something else."""
    words = command.split()
    i = 0
    while i < len(words) and (ENV_ASSIGNMENT.match(words[i]) or words[i] in PREFIX_WORDS):
        i += 1
        # /usr/bin/time -f "FORMAT", timeout 300: skip to the program itself
        if words[i - 1] in {"time", "/usr/bin/time", "timeout"}:
            while i < len(words) and not PROGRAM.match(words[i]):
                i += 1
    if i < len(words) and PROGRAM.match(words[i]):
        return words[i + 1 :]
    return None


def check_shell_line(root, text, problems, where):
    code, _, comment = text.partition(" #")
    if code.lstrip().startswith("#"):
        return
    commands = split_commands(code)
    for index, command in enumerate(commands):
        words = program_words(command)
        if words is not None:
            # the comment belongs to the last command of the line
            check_words(root, words, comment if index == len(commands) - 1 else "", problems, where)


def fenced_blocks(lines):
    """(info string, first content line index, content lines) of each ``` block."""
    blocks, i = [], 0
    while i < len(lines):
        fence = re.match(r"^\s*(```+)\s*(.*)$", lines[i])
        if not fence:
            i += 1
            continue
        start, body = i + 1, []
        i += 1
        while i < len(lines) and not lines[i].strip().startswith(fence.group(1)):
            body.append(lines[i])
            i += 1
        blocks.append((fence.group(2).strip(), start, body))
        i += 1
    return blocks


def joined_commands(body, start):
    """(line number, text) of each command in a code block: backslash continuations and indented
    usage continuations ([--opt] or --opt on the next line) joined to their first line."""
    commands = []
    for offset, line in enumerate(body):
        number = start + offset + 1
        continuation = commands and (
            commands[-1][1].endswith("\\") or re.match(r"^\s+[\[-]", line) and commands[-1][2])
        if continuation:
            first, text, _ = commands[-1]
            commands[-1] = (first, text.rstrip("\\") + " " + line.strip(), True)
        else:
            commands.append((number, line.rstrip(), program_words(line.split(" #")[0]) is not None))
    return [(number, text) for number, text, _ in commands]


def section_commands(root, lines):
    """For docs/cli.md: the subcommand each line's section heading names (`pupwave compress` or
    `compress` in backticks), else None."""
    current, result = None, []
    for line in lines:
        heading = re.match(r"^#+\s+(.*)", line)
        if heading:
            current = None
            for span in re.findall(r"`([^`]+)`", heading.group(1)):
                words = span.split()
                if words and PROGRAM.match(words[0]):
                    words = words[1:]
                command = root
                while words and words[0] in command.children:
                    command = command.children[words.pop(0)]
                if command is not root:
                    current = command
        result.append(current)
    return result


def check_inline_code(root, path, lines, problems):
    in_fence, prose = False, []
    for line in lines:
        if re.match(r"^\s*```", line):
            in_fence = not in_fence
            prose.append("")
        else:
            prose.append("" if in_fence else line)
    text = "\n".join(prose)
    name = os.path.basename(path)
    bare_flags_checked = name in {"cli.md", "README.md"}
    sections = section_commands(root, lines) if name == "cli.md" else [None] * len(lines)
    for span in re.finditer(r"`([^`]+)`", text):
        number = text.count("\n", 0, span.start()) + 1
        where = f"{path}:{number}"
        code = " ".join(span.group(1).split())
        words = code.split()
        if program_words(code) is not None:
            check_shell_line(root, code, problems, where)
        elif words[0] in root.children and len(words) > 1 and (
            words[1].startswith("-") or words[1] == "..." or words[1] in root.children[words[0]].children):
            check_words(root, words, "", problems, where)
        elif bare_flags_checked and FLAG.match(words[0]) and words[0].startswith("-"):
            command = sections[number - 1]
            allowed = command.flags if command else root.all_flags()
            for flag in dict.fromkeys(FLAG.findall(code)):
                if flag not in allowed:
                    scope = command.name() if command else "no pupwave subcommand"
                    problems.append(f"{where}: {scope} has no option {flag}"
                                    if command else f"{where}: {scope} has the option {flag}")


def check_flags(root, path, problems):
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    for _, start, body in fenced_blocks(lines):
        for number, text in joined_commands(body, start):
            check_shell_line(root, text, problems, f"{path}:{number}")
    check_inline_code(root, path, lines, problems)


# ---- README sh blocks --------------------------------------------------------------------------


def run_block(start, body, bin_dir, timeout, readme):
    """Runs one sh block; returns a problem line or None."""
    script_lines = ["set -e", f'export PATH="{bin_dir}:$PATH"',
                    'trap \'echo "$LINENO" > "$CHECK_DOCS_FAILED_LINE"\' ERR']
    head = len(script_lines)
    for line in body:
        skipped = line.split(" #")[0].strip() in SKIPPED_LINES
        script_lines.append(": skipped, CI runs it" if skipped else line)
    with tempfile.TemporaryDirectory() as scratch:
        script, failed_line = os.path.join(scratch, "block.sh"), os.path.join(scratch, "failed")
        with open(script, "w") as f:
            f.write("\n".join(script_lines) + "\n")
        result = subprocess.run(
            ["timeout", "--kill-after=10", str(timeout), "bash", script], cwd=ROOT,
            stdin=subprocess.DEVNULL, capture_output=True, text=True,
            env=dict(os.environ, CHECK_DOCS_FAILED_LINE=failed_line))
        marks = open(failed_line).read().split() if os.path.exists(failed_line) else []
    if result.returncode == 0:
        return None
    if result.returncode in (124, 137):
        return f"{readme}:{start}: sh block ran past {timeout} s"
    number = start + 1
    if marks and int(marks[-1]) > head:
        number = start + int(marks[-1]) - head
    tail = (result.stderr or result.stdout).strip().splitlines()[-3:]
    detail = "".join(f"\n    {line}" for line in tail)
    return f"{readme}:{number}: sh block (from line {start}) failed with exit {result.returncode}{detail}"


def repository_changes():
    """git status lines (untracked files one by one, ignored ones such as out/ left out)."""
    status = subprocess.run(["git", "status", "--porcelain", "--untracked-files=all"], cwd=ROOT,
                            capture_output=True, text=True)
    return set(status.stdout.splitlines()) if status.returncode == 0 else set()


def check_readme_blocks(readme, bin_dir, timeout, problems):
    with open(readme, encoding="utf-8") as f:
        lines = f.read().splitlines()
    os.makedirs(os.path.join(ROOT, "out"), exist_ok=True)
    ran = 0
    for info, start, body in fenced_blocks(lines):
        if info != "sh":
            continue
        ran += 1
        before_block = repository_changes()
        problem = run_block(start, body, bin_dir, timeout, readme)
        if problem:
            problems.append(problem)
        # examples write under out/ (git-ignored): a block must not add or change repository files
        for change in sorted(repository_changes() - before_block):
            problems.append(f"{readme}:{start}: sh block wrote into the repository (write under out/): {change[3:]}")
    return ran


def main(argv):
    flags_only = "--flags-only" in argv
    args = [a for a in argv if a != "--flags-only"]
    if len(args) > 1 or any(a.startswith("-") for a in args):
        usage_error(f"unexpected arguments: {' '.join(args)}")
    binary = os.path.abspath(args[0] if args else "build/tools/pupwave")
    if not os.access(binary, os.X_OK):
        usage_error(f"cannot run {binary}: not an executable file (build it: cmake --build build --target pupwave)")
    readme = os.environ.get("CHECK_DOCS_README", "README.md")
    pages = os.environ.get("CHECK_DOCS_PAGES", "").split() or sorted(glob.glob("docs/*.md"))
    timeout = int(os.environ.get("CHECK_DOCS_TIMEOUT", "300"))
    for page in [readme, *pages]:
        if not os.path.isfile(page):
            usage_error(f"cannot read {page}: no such file")

    root = read_command(binary, ())
    problems = []
    for page in [readme, *pages]:
        check_flags(root, page, problems)
    ran = 0 if flags_only else check_readme_blocks(readme, os.path.dirname(binary), timeout, problems)
    if problems:
        print("check-docs: the docs do not match the CLI, or a README command fails:")
        print("\n".join(f"  {p}" for p in problems))
        return 1
    runs = "" if flags_only else f", {ran} README sh blocks ran"
    print(f"check-docs: every pupwave flag in {1 + len(pages)} pages exists{runs}")
    return 0


sys.exit(main(sys.argv[1:]))
PY

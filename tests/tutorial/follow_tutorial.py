#!/usr/bin/python3
"""Follows a tutorial page of docs/ literally, in a copy of the source tree.

The page marks its steps with HTML comments, each followed by a fenced block:
  <!-- tutorial file PATH -->   the block is the whole content of PATH (new or replaced)
  <!-- tutorial patch -->       the block is a unified diff, applied with `patch -p1`
  <!-- tutorial run -->         the block is shell commands, run with bash -e in the tree's root
  <!-- tutorial expect REGEX --> the previous run block's output (stdout and stderr) has a
                                 line matching REGEX (Python re, multiline)
Steps run in the page's order. Any failure (a patch that does not apply, a
command that exits non-zero, an expectation not met) fails the test with the
step's line in the page.

usage: follow_tutorial.py SOURCE_DIR PAGE [--keep]
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

MARK = re.compile(r"^<!-- tutorial (file|patch|run|expect)\s*(.*?)\s*-->\s*$")
FENCE = re.compile(r"^```")


def steps(page):
    """(kind, argument, block text, line) for every marked step of the page."""
    lines = open(page, encoding="utf-8").read().split("\n")
    out = []
    i = 0
    while i < len(lines):
        m = MARK.match(lines[i])
        if not m:
            i += 1
            continue
        kind, arg, line = m.group(1), m.group(2), i + 1
        if kind == "expect":
            out.append((kind, arg, "", line))
            i += 1
            continue
        j = i + 1
        if j >= len(lines) or not FENCE.match(lines[j]):
            sys.exit(f"{page}:{line}: a 'tutorial {kind}' mark must be followed by a fenced block")
        k = j + 1
        while k < len(lines) and not FENCE.match(lines[k]):
            k += 1
        if k == len(lines):
            sys.exit(f"{page}:{line}: unterminated block")
        out.append((kind, arg, "\n".join(lines[j + 1:k]) + "\n", line))
        i = k + 1
    return out


def copy_tree(src, dst):
    """The tracked files of src (all of it but build/ and out/ outside git)."""
    try:
        names = subprocess.run(["git", "-C", src, "ls-files", "-z"], check=True, capture_output=True).stdout
        files = [n for n in names.decode().split("\0") if n]
    except (subprocess.CalledProcessError, FileNotFoundError):
        files = []
        for root, dirs, fs in os.walk(src):
            dirs[:] = [d for d in dirs if os.path.relpath(os.path.join(root, d), src) not in ("build", "out", ".git")]
            files += [os.path.relpath(os.path.join(root, f), src) for f in fs]
    for f in files:
        s = os.path.join(src, f)
        if not os.path.isfile(s):
            continue  # deleted in the work tree
        os.makedirs(os.path.dirname(os.path.join(dst, f)), exist_ok=True)
        shutil.copy2(s, os.path.join(dst, f))


def main():
    args = [a for a in sys.argv[1:] if a != "--keep"]
    if len(args) != 2:
        sys.exit(__doc__)
    src, page = os.path.abspath(args[0]), os.path.abspath(args[1])
    todo = steps(page)
    if not any(k == "run" for k, *_ in todo):
        sys.exit(f"{page}: no 'tutorial run' step")
    work = tempfile.mkdtemp(prefix="chaosweep-tutorial.")
    tree = os.path.join(work, "src")
    os.makedirs(tree)
    copy_tree(src, tree)
    name = os.path.relpath(page, src)
    output = None
    try:
        for kind, arg, block, line in todo:
            where = f"{name}:{line}"
            print(f"--- {where}: tutorial {kind} {arg}", flush=True)
            if kind == "file":
                path = os.path.join(tree, arg)
                os.makedirs(os.path.dirname(path), exist_ok=True)
                with open(path, "w", encoding="utf-8") as f:
                    f.write(block)
            elif kind == "patch":
                r = subprocess.run(["patch", "-p1", "--forward", "--no-backup-if-mismatch", "-F0"], cwd=tree,
                                   input=block, text=True, capture_output=True)
                if r.returncode != 0:
                    sys.exit(f"FAIL {where}: the patch does not apply to the tree as it is:\n{r.stdout}{r.stderr}")
            elif kind == "run":
                r = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", block], cwd=tree, text=True,
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
                output = r.stdout
                if r.returncode != 0:
                    sys.exit(f"FAIL {where}: the commands exited {r.returncode}:\n{output[-6000:]}")
                print(output[-3000:], flush=True)
            elif kind == "expect":
                if output is None:
                    sys.exit(f"FAIL {where}: an expectation before any run step")
                if not re.search(arg, output, re.MULTILINE):
                    sys.exit(f"FAIL {where}: no line of the previous run's output matches {arg!r}:\n{output[-4000:]}")
        print(f"followed {name}: {len(todo)} steps")
    finally:
        if "--keep" in sys.argv:
            print(f"kept {work}")
        else:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()

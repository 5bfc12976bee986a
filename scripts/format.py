#!/usr/bin/env python3
"""The C and C++ sources in the project's style (.clang-format), with the pinned clang-format
(scripts/requirements.txt, in the venv).

    python3 scripts/format.py --check [ROOT]   lists the files that differ; exit status 1 if any
    python3 scripts/format.py --apply [ROOT]   formats them in place
    python3 scripts/format.py --self-test      --check finds a misformatted file, --apply fixes it

The files are the repository's C and C++ sources (.c, .cc, .cpp, .h, .hpp, .inc: `git ls-files`,
or a walk of the tree outside a git checkout), build trees and the venv aside; the X-macro lists
(*.def) are tables, not formatted. ctest format_check runs --check on the repository.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
C_ENDINGS = {".c", ".cc", ".cpp", ".h", ".hpp", ".inc"}
# Trees of generated or installed files, never the project's sources.
SKIPPED_DIRS = {".git", ".venv", ".cache", "out", "__pycache__"}


def pinned_version():
    """The clang-format version scripts/requirements.txt pins."""
    text = (ROOT / "scripts" / "requirements.txt").read_text()
    match = re.search(r"^clang-format==(\S+)", text, re.MULTILINE)
    return match.group(1) if match else None


def find_clang_format():
    """The pinned clang-format: the venv's (beside this interpreter, or the project's .venv), else
    one on PATH of the same version; exits naming the fix when there is none."""
    want = pinned_version()
    candidates = [Path(sys.executable).parent / "clang-format",
                  ROOT / ".venv" / "bin" / "clang-format"]
    on_path = shutil.which("clang-format")
    candidates += [Path(on_path)] if on_path else []
    seen = []
    for tool in candidates:
        if not tool.is_file():
            continue
        out = subprocess.run([str(tool), "--version"], capture_output=True, text=True).stdout
        version = re.search(r"version (\S+)", out)
        seen.append(f"{tool} ({version.group(1) if version else 'unknown version'})")
        if version and version.group(1) == want:
            return str(tool)
    sys.exit(f"format.py: no clang-format {want} (the version scripts/requirements.txt pins; "
             f"found: {', '.join(seen) or 'none'}); run scripts/setup.sh to install it in .venv")


def source_files(root):
    """The C and C++ sources under root, relative paths, sorted."""
    listed = None
    if (root / ".git").exists():
        try:  # git may be missing, or refuse a checkout another user owns: walk the tree then
            listed = subprocess.run(["git", "-C", str(root), "ls-files", "-z"],
                                    capture_output=True, text=True, check=True).stdout.split("\0")
        except (OSError, subprocess.CalledProcessError):
            listed = None
    if listed is not None:
        paths = [Path(p) for p in listed if p]
    else:
        paths = []
        for folder, dirs, files in os.walk(root):
            dirs[:] = [d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("build")]
            paths += [Path(folder, f).relative_to(root) for f in files]
    return sorted(p for p in paths
                  if p.suffix in C_ENDINGS and (root / p).is_file()
                  and p.parts[0] not in SKIPPED_DIRS and not p.parts[0].startswith("build"))


def formatted(tool, root, path):
    """The file's text as clang-format lays it out (the style from root/.clang-format)."""
    result = subprocess.run([tool, f"--style=file:{root / '.clang-format'}",
                             f"--assume-filename={path}"], input=(root / path).read_bytes(),
                            capture_output=True)
    if result.returncode != 0:
        sys.exit(f"format.py: clang-format failed on {path}: {result.stderr.decode().strip()}")
    return result.stdout


def run(root, apply):
    """Lists (or, apply, rewrites) the files that differ from their formatted text; returns them."""
    tool = find_clang_format()
    files = source_files(root)
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        texts = list(pool.map(lambda p: formatted(tool, root, p), files))
    differ = []
    for path, text in zip(files, texts):
        if text != (root / path).read_bytes():
            differ.append(path)
            if apply:
                (root / path).write_bytes(text)
    return files, differ


def self_test():
    """A planted misformatted file is listed by --check and fixed by --apply; a formatted one
    is not listed."""
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        shutil.copy(ROOT / ".clang-format", root / ".clang-format")
        (root / "good.c").write_text("int twice(int x) { return 2 * x; }\n")
        (root / "bad.cpp").write_text("int  twice( int x ){\nreturn 2*x;}\n")
        (root / "table.def").write_text("X( a,1 )\n")  # not a C source: never formatted
        _, differ = run(root, apply=False)
        assert differ == [Path("bad.cpp")], differ
        _, differ = run(root, apply=True)
        assert differ == [Path("bad.cpp")], differ
        _, differ = run(root, apply=False)
        assert differ == [], differ
        assert (root / "bad.cpp").read_text() == "int twice(int x) { return 2 * x; }\n"
        assert (root / "table.def").read_text() == "X( a,1 )\n"
    print("format.py self-test: the misformatted file found and fixed")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--check", action="store_true", help="list the files that differ, exit 1")
    mode.add_argument("--apply", action="store_true", help="format the files in place")
    mode.add_argument("--self-test", action="store_true", help="test this script")
    parser.add_argument("root", nargs="?", type=Path, default=ROOT, help="the repository")
    args = parser.parse_args()
    if args.self_test:
        return self_test()
    root = args.root.resolve()
    files, differ = run(root, apply=args.apply)
    for path in differ:
        print(path)
    if args.apply:
        print(f"format.py: formatted {len(differ)} of {len(files)} files")
        return 0
    if differ:
        print(f"format.py: {len(differ)} of {len(files)} files differ from .clang-format's style; "
              f"run python3 scripts/format.py --apply")
        return 1
    print(f"format.py: {len(files)} files in .clang-format's style")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""The product functions over a length (default 80 lines, the project's standard): C and C++ under
csrc/ and fmu/, Python and C++ under python/ (benchmarks, csrc/bench, aside).

    python3 scripts/long_functions.py [--over N] [ROOT]

One line a function, longest first: lines, file:first line, name; then the count. The exit status
is 1 when there is any (ctest long_function_gate runs it on the repository), else 0. A function's
lines run from its signature's first line to its closing brace (C, C++) or its last line (Python,
decorators aside). C and C++ are read as text: a body is a brace block at the top level, in a
namespace, extern "C" block, struct or class, whose head ends in `)` (after any const, noexcept,
override or a constructor's initialisers); lambdas count in the function around them.
"""
import ast
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
C_ENDINGS = {".c", ".cc", ".cpp", ".h", ".hpp", ".inc"}
TRANSPARENT = re.compile(r"\b(namespace|extern\s+\"C\"|struct|class|union)\b[^;()]*$")
NAME = re.compile(r"([A-Za-z_~][\w:~]*(?:operator\W+)?)\s*\($")


def strip(text):
    """The text with comments, strings and character literals blanked (lines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * max(0, j - i - 1) + c)
            i = j + 1
        elif c == "#" and (i == 0 or text[i - 1] == "\n"):
            j = i  # a preprocessor line (with continuations) is no code of a body's head
            while True:
                k = text.find("\n", j)
                if k < 0:
                    k = n
                    break
                if text[k - 1] != "\\":
                    break
                j = k + 1
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:k]))
            i = k
        else:
            out.append(c)
            i += 1
    return "".join(out)


def function_head(head):
    """The function's name if the text before a `{` is a function's head, else None."""
    h = re.sub(r"\s+", " ", head).strip()
    h = re.sub(r"\b(const|noexcept|override|final|mutable)\b\s*$", "", h).strip()
    h = re.sub(r"\s*->\s*[\w:<>,\s*&]+$", "", h)  # a trailing return type
    # a constructor's initialisers: cut at the ':' after the parameter list
    m = re.search(r"\)\s*:(?!:)", h)
    if m:
        h = h[:m.start() + 1].strip()
    h = re.sub(r"\b(const|noexcept|override|final)\b\s*$", "", h).strip()
    if not h.endswith(")"):
        return None
    depth = 0
    for k in range(len(h) - 1, -1, -1):
        if h[k] == ")":
            depth += 1
        elif h[k] == "(":
            depth -= 1
            if depth == 0:
                m = NAME.search(h[:k + 1])
                if not m:
                    return None
                name = m.group(1)
                if name in ("if", "for", "while", "switch", "catch", "return", "sizeof",
                            "decltype", "alignof", "defined"):
                    return None
                return name
    return None


def c_functions(path):
    """(first line, last line, name) of every function body in a C or C++ file."""
    text = strip(path.read_text(errors="replace"))
    found = []
    stack = []  # per open brace: ("transparent" | "body" | "other", start line, name)
    head_start = 0  # where the text before the next brace starts
    line = 1
    for i, ch in enumerate(text):
        if ch == "\n":
            line += 1
        elif ch in ";{}":
            inside_body = any(kind == "body" for kind, _, _ in stack)
            if ch == "{" and not inside_body:
                head = text[head_start:i]
                name = function_head(head)
                if name:
                    lead = head[:len(head) - len(head.lstrip())]
                    first = line - head.count("\n") + lead.count("\n")
                    stack.append(("body", first, name))
                elif TRANSPARENT.search(re.sub(r"\s+", " ", head).strip()):
                    stack.append(("transparent", line, None))
                else:
                    stack.append(("other", line, None))
            elif ch == "{":
                stack.append(("other", line, None))
            elif ch == "}" and stack:
                kind, first, name = stack.pop()
                if kind == "body":
                    found.append((first, line, name))
            head_start = i + 1
    return found


def python_functions(path):
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield node.lineno, node.end_lineno, node.name


def long_functions(root, over):
    rows = []
    for top in ("csrc", "fmu", "python"):
        for path in sorted((root / top).rglob("*")):
            if not path.is_file() or "bench" in path.relative_to(root).parts:
                continue
            rel = path.relative_to(root).as_posix()
            if path.suffix in C_ENDINGS:
                functions = c_functions(path)
            elif path.suffix == ".py":
                functions = python_functions(path)
            else:
                continue
            for first, last, name in functions:
                if last - first + 1 > over:
                    rows.append((last - first + 1, f"{rel}:{first}", name))
    return sorted(rows, key=lambda r: (-r[0], r[1]))


def main(argv):
    over = 80
    if argv[:1] == ["--over"]:
        over, argv = int(argv[1]), argv[2:]
    root = Path(argv[0]) if argv else ROOT
    rows = long_functions(root, over)
    for lines, where, name in rows:
        print(f"{lines:5d}  {where}  {name}")
    print(f"{len(rows)} functions over {over} lines")
    return 1 if rows else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""Every code block of README.md and docs/*.md that is meant to run runs, as a newcomer would run
it: from the repository root, the Python blocks of one page in order in one namespace (a page's
later examples use the names of its earlier ones), each shell block in bash -euo pipefail, JSON
blocks parsed (sweeps.md's spec resolved by the sweep checks). The examples check their own
claims (docs/python.md's forward-dynamics round trip asserts that the poses come back).

A block that is not meant to run (a usage synopsis with [OPTIONS], the install-and-test commands,
a cluster) says so in its info string: ```sh no-run. Blocks with no language or another one
(diagrams, C, FMI variable lists) are text."""
import json
import os
import pathlib
import re
import subprocess
import textwrap

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
RUN = {"python": "python", "sh": "sh", "bash": "sh", "json": "json"}
# A fence at any indentation (a block in a list item is indented with it), closed at the same one.
FENCE = re.compile(r"^( *)```([^\n`]*)\n(.*?)^\1```[ \t]*$", re.M | re.S)


def blocks(page):
    """(language, info string, line, code) of the fenced blocks of page; an indented block's code
    without its indentation."""
    text = page.read_text()
    for m in FENCE.finditer(text):
        info = m.group(2).strip()
        words = info.split()
        code = textwrap.dedent(m.group(3))
        yield (words[0] if words else ""), info, text[:m.start()].count("\n") + 1, code


def runnable(page):
    return [(RUN[lang], line, code) for lang, info, line, code in blocks(page)
            if lang in RUN and "no-run" not in info.split()]


def test_every_page_has_its_blocks_found():
    """The fence pattern sees the blocks (a page whose fences it missed would pass silently)."""
    for page in PAGES:
        fences = sum(1 for line in page.read_text().splitlines()
                     if line.lstrip(" ").startswith("```"))
        assert fences == 2 * len(list(blocks(page))), page


@pytest.mark.parametrize("page", [p for p in PAGES if runnable(p)], ids=lambda p: p.name)
def test_code_blocks_run(page, monkeypatch, build_dir):
    monkeypatch.chdir(ROOT)
    namespace = {"__name__": f"doc_{page.stem}"}
    for kind, line, code in runnable(page):
        where = f"{page.relative_to(ROOT)}:{line}"
        if kind == "python":
            exec(compile(code, where, "exec"), namespace)
        elif kind == "json":
            value = json.loads(code)
            if page.name == "sweeps.md":
                from stewart.sweeps import resolve
                resolve(value, ROOT / "scenes")
        else:
            env = {**os.environ, "PATH": f"{ROOT / '.venv' / 'bin'}:{os.environ['PATH']}"}
            r = subprocess.run(["bash", "-euo", "pipefail", "-c", code], cwd=ROOT, env=env,
                               capture_output=True, text=True, timeout=600)
            assert r.returncode == 0, f"{where}:\n{code}\n{r.stdout}\n{r.stderr}"


def test_indented_blocks_are_found_and_dedented(tmp_path):
    """A block inside a list item (indented with it) is a block like any other: found, its code
    without the indentation, closed only by a fence at its own indentation."""
    page = tmp_path / "page.md"
    page.write_text("* a step:\n\n  ```python\n  x = 1\n  if x:\n      y = 2\n  ```\n"
                    "```sh no-run\nls\n```\n")
    found = list(blocks(page))
    assert [(lang, line) for lang, _, line, _ in found] == [("python", 3), ("sh", 8)]
    assert found[0][3] == "x = 1\nif x:\n    y = 2\n"
    assert sum(1 for _, _, _, _ in found) * 2 == sum(
        1 for line in page.read_text().splitlines() if line.lstrip(" ").startswith("```"))


def imported_distributions(page):
    """The distributions (PyPI names) of the third-party modules a page's Python blocks import."""
    import ast
    import importlib.metadata
    import sys
    owners = importlib.metadata.packages_distributions()
    names = set()
    for kind, _, code in runnable(page):
        if kind != "python":
            continue
        for node in ast.walk(ast.parse(code)):
            if isinstance(node, ast.Import):
                names.update(a.name.split(".")[0] for a in node.names)
            elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
                names.add(node.module.split(".")[0])
    names -= set(sys.stdlib_module_names) | {"stewart"}
    return {owners[n][0].lower() for n in names if n in owners}


def test_the_modules_the_docs_import_come_with_an_extra_the_page_names():
    """pip install .[extra]: every third-party module a page's examples import is a dependency of
    the package or of an extra, and the page names that extra (`.[name]`)."""
    import tomllib
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]

    def name(requirement):
        return re.split(r"[<>=!~\[; ]", requirement, maxsplit=1)[0].lower()
    base = {name(r) for r in project["dependencies"]}
    extras = {e: {name(r) for r in rs} for e, rs in project["optional-dependencies"].items()}
    for page in PAGES:
        text = page.read_text()
        for dist in imported_distributions(page) - base:
            giving = [e for e, dists in extras.items() if dist in dists]
            assert giving, f"{page.name} imports {dist}, which no extra of pyproject.toml brings"
            assert any(f".[{e}]" in text for e in giving), \
                f"{page.name} imports {dist} (extra {' or '.join(giving)}) without naming the extra"

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

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
RUN = {"python": "python", "sh": "sh", "bash": "sh", "json": "json"}
FENCE = re.compile(r"^```([^\n`]*)\n(.*?)^```\s*$", re.M | re.S)


def blocks(page):
    """(language, info string, line, code) of the fenced blocks of page."""
    text = page.read_text()
    for m in FENCE.finditer(text):
        info = m.group(1).strip()
        words = info.split()
        yield (words[0] if words else ""), info, text[:m.start()].count("\n") + 1, m.group(2)


def runnable(page):
    return [(RUN[lang], line, code) for lang, info, line, code in blocks(page)
            if lang in RUN and "no-run" not in info.split()]


def test_every_page_has_its_blocks_found():
    """The fence pattern sees the blocks (a page whose fences it missed would pass silently)."""
    for page in PAGES:
        fences = sum(1 for line in page.read_text().splitlines() if line.startswith("```"))
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

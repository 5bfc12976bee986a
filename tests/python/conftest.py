"""Shared fixtures: where the build is, and how to run stewart-solve."""
import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))


@pytest.fixture(scope="session")
def build_dir():
    path = pathlib.Path(os.environ.get("STEWART_BUILD_DIR", ROOT / "build"))
    if not (path / "stewart-solve").exists():
        pytest.fail(f"{path}/stewart-solve is missing: build first (bash scripts/build.sh)")
    return path


@pytest.fixture
def solve(build_dir):
    """Runs stewart-solve with the given arguments; returns the CompletedProcess."""
    def run(*args):
        return subprocess.run([str(build_dir / "stewart-solve"), *map(str, args)],
                              capture_output=True, text=True, timeout=120)
    return run

"""Shared fixtures: where the build is, and how to run stewart-solve and stewart-simulate."""
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


def program(build_dir, name):
    """A call that runs the build's program `name` with the given arguments and returns the
    CompletedProcess."""
    def run(*args):
        return subprocess.run([str(build_dir / name), *map(str, args)],
                              capture_output=True, text=True, timeout=120)
    return run


@pytest.fixture
def solve(build_dir):
    """Runs stewart-solve with the given arguments; returns the CompletedProcess."""
    return program(build_dir, "stewart-solve")


@pytest.fixture
def simulate(build_dir):
    """Runs stewart-simulate with the given arguments; returns the CompletedProcess."""
    return program(build_dir, "stewart-simulate")

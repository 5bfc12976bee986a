"""What the Python wheel is: its extension `_core` exports its init and nothing else (no SUNDIALS
symbol a process with another SUNDIALS could bind to), the shared objects it ships need no newer
glibc than docs/python.md states, and its build compiles only what it ships (no command-line
program, benchmark or test)."""
import pathlib
import re
import shutil
import subprocess
import zipfile

import pytest

import stewart
from fmu_support import BUILD, REPO

SUNDIALS_PREFIXES = ("N_V", "SUN", "KIN", "CVode", "ARKode", "ARKStep", "ERKStep", "IDA")


def dynamic_symbols(path):
    """The names of the symbols a shared object exports (nm -D --defined-only), versions cut."""
    out = subprocess.run(["nm", "-D", "--defined-only", str(path)], capture_output=True,
                         text=True, check=True).stdout
    return {line.split()[-1].split("@")[0] for line in out.splitlines() if line.strip()}


def test_the_extension_exports_its_init_alone():
    core = pathlib.Path(stewart._core.__file__)
    exported = dynamic_symbols(core)
    print(f"{core.name}: {sorted(exported)}")
    assert not [s for s in exported if s.startswith(SUNDIALS_PREFIXES)]
    assert exported == {"PyInit__core"}


def newest_version(path, library):
    """The newest version of library (GLIBC or GLIBCXX) a shared object's symbols ask for
    (objdump -T), as a tuple of ints; (0,) if none."""
    out = subprocess.run(["objdump", "-T", str(path)], capture_output=True, text=True,
                         check=True).stdout
    versions = [tuple(int(p) for p in v.rstrip(".").split("."))
                for v in re.findall(rf"\b{library}_([0-9.]+)", out)]
    return max(versions, default=(0,))


def documented_bound(library):
    """The bound docs/python.md states: "glibc 2.NN or newer", "GLIBCXX_3.4.NN or newer"."""
    text = (REPO / "docs" / "python.md").read_text()
    pattern = r"glibc (\d+\.\d+) or newer" if library == "GLIBC" else \
        r"GLIBCXX_(\d+\.\d+\.\d+)`? or newer"
    match = re.search(pattern, text)
    assert match, f"docs/python.md states no {library} bound"
    return tuple(int(p) for p in match.group(1).split("."))


def shipped_shared_objects(tmp_path):
    """The extension and every FMU binary the package ships (extracted to tmp_path)."""
    objects = [pathlib.Path(stewart._core.__file__)]
    for fmu in sorted((pathlib.Path(stewart.__file__).parent / "fmus").glob("*/*.fmu")):
        with zipfile.ZipFile(fmu) as z:
            for name in z.namelist():
                if name.endswith(".so"):
                    target = tmp_path / fmu.parent.name / fmu.stem / pathlib.Path(name).name
                    target.parent.mkdir(parents=True, exist_ok=True)
                    target.write_bytes(z.read(name))
                    objects.append(target)
    return objects


@pytest.mark.parametrize("library", ["GLIBC", "GLIBCXX"])
def test_shipped_binaries_need_no_newer_c_libraries_than_documented(tmp_path, library):
    """glibc and libstdc++: the newest symbol version any shipped shared object asks for is at
    most the bound docs/python.md states (the platforms the wheel runs on)."""
    bound = documented_bound(library)
    objects = shipped_shared_objects(tmp_path)
    assert len(objects) == 1 + 2 * len(stewart.FMU_NAMES)  # _core and each unit for each FMI version
    needed = {str(o.relative_to(tmp_path)) if tmp_path in o.parents else o.name:
              newest_version(o, library) for o in objects}
    newest = max(needed.values())
    print(f"newest {library} needed: " + ".".join(map(str, newest)) + " (" +
          ", ".join(f"{k}: {'.'.join(map(str, v))}" for k, v in needed.items()) + ")")
    assert newest <= bound, needed


def test_the_wheel_builds_only_what_it_ships():
    """The commands of the wheel's build target (pyproject.toml build.targets, in the build
    directory pip install . made) link no executable but the model-description generators the
    FMUs are made with."""
    import tomllib
    settings = tomllib.loads((REPO / "pyproject.toml").read_text())["tool"]["scikit-build"]
    targets = settings["build"]["targets"]
    build = sorted(REPO.glob("build/python-*"))
    if not build or not (build[-1] / "build.ninja").exists():
        pytest.skip("no wheel build directory with Ninja (build/python-*): pip install . first")
    ninja = shutil.which("ninja") or next(iter(REPO.glob(".venv/bin/ninja")), None)
    if ninja is None:
        pytest.skip("no ninja to list the build's commands")
    def linked(*targets):
        """The executables the commands of these targets link."""
        commands = subprocess.run([str(ninja), "-C", str(build[-1]), "-t", "commands", *targets],
                                  capture_output=True, text=True, check=True).stdout
        names = set()
        for line in commands.splitlines():
            out = re.search(r" -o (\S+)", line)
            if out and " -c " not in line and " -shared" not in line:
                names.add(pathlib.PurePosixPath(out.group(1)).name)
        return names

    shipped = linked(*targets)
    print("executables linked for the wheel:", sorted(shipped))
    assert shipped and all(name.endswith("_gen_model_description") for name in shipped), shipped
    # the same build's default target does link programs: the check sees them
    assert {"stewart-solve", "stewart-simulate"} <= linked("all")
    # the settings that keep the rest out
    assert settings["cmake"]["define"]["STEWART_BUILD_TESTS"] == "OFF"

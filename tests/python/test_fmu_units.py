"""The FMU units are one list: fmu/CMakeLists.txt's stewart_unit lines. The package names them
(stewart.FMU_NAMES) in that order and ships each for both FMI versions, and nothing else."""
import pathlib
import re

import stewart
from fmu_support import REPO


def units_in_the_build_file():
    """The names of fmu/CMakeLists.txt's stewart_unit(<NAME> ...) calls, in order (comments and
    the function's own definition skipped)."""
    names = []
    for line in (REPO / "fmu" / "CMakeLists.txt").read_text().splitlines():
        match = re.match(r"\s*stewart_unit\(\s*([A-Za-z_][A-Za-z0-9_]*)\s", line)
        if match:
            names.append(match.group(1))
    return names


def test_the_package_names_the_build_files_units_in_order():
    names = units_in_the_build_file()
    assert len(names) >= 5, names  # the five the package has always shipped, at least
    assert stewart.FMU_NAMES == tuple(names)


def test_the_package_ships_exactly_those_units():
    fmus = pathlib.Path(stewart.__file__).parent / "fmus"
    for version in stewart.FMI_VERSIONS:
        shipped = sorted(p.stem for p in (fmus / version).glob("*.fmu"))
        assert shipped == sorted(units_in_the_build_file()), version
    assert set(stewart.fmu_paths()) == set(units_in_the_build_file())

"""The FMI co-simulation units built with the library, shipped inside the package."""
from __future__ import annotations

import pathlib

FMI_VERSIONS = ("2.0", "3.0")
_HERE = pathlib.Path(__file__).resolve().parent


def fmu_path(version: str = "2.0") -> pathlib.Path:
    """Path of the installed StewartPlatform.fmu for FMI `version` ("2.0" or "3.0"), e.g. for
    ``fmpy.simulate_fmu(stewart.fmu_path("3.0"), ...)``. Raises FileNotFoundError if this install
    has no such unit, ValueError for an unknown version."""
    if version not in FMI_VERSIONS:
        raise ValueError(f"version = {version!r}: the FMU exists for FMI {', '.join(FMI_VERSIONS)}")
    path = _HERE / "fmus" / version / "StewartPlatform.fmu"
    if not path.is_file():
        raise FileNotFoundError(f"{path} is missing: reinstall the package (pip install .)")
    return path


def fmu_paths() -> dict[str, pathlib.Path]:
    """{FMI version: path} of both installed units."""
    return {v: fmu_path(v) for v in FMI_VERSIONS}

"""The FMI units built with the library, shipped inside the package: the co-simulation units
StewartPlatform (inverse), StewartPlant (the plant), StewartController and StewartScene (the scene
player), and the plant as Model Exchange, StewartPlantME; each for FMI 2.0 and 3.0."""
from __future__ import annotations

import pathlib

FMI_VERSIONS = ("2.0", "3.0")
FMU_NAMES = ("StewartPlatform", "StewartPlant", "StewartPlantME", "StewartController",
             "StewartScene")
_HERE = pathlib.Path(__file__).resolve().parent


def fmu_path(version: str = "2.0", model: str = "StewartPlatform") -> pathlib.Path:
    """Path of the installed FMU `model` (one of FMU_NAMES; default the inverse unit) for FMI
    `version` ("2.0" or "3.0"), e.g. for ``fmpy.simulate_fmu(stewart.fmu_path("3.0"), ...)``.
    Raises FileNotFoundError if this install has no such unit, ValueError for an unknown version
    or model."""
    if version not in FMI_VERSIONS:
        raise ValueError(f"version = {version!r}: the FMUs exist for FMI {', '.join(FMI_VERSIONS)}")
    if model not in FMU_NAMES:
        raise ValueError(f"model = {model!r}: the package ships {', '.join(FMU_NAMES)}")
    path = _HERE / "fmus" / version / f"{model}.fmu"
    if not path.is_file():
        raise FileNotFoundError(f"{path} is missing: reinstall the package (pip install .)")
    return path


def fmu_paths() -> dict[str, dict[str, pathlib.Path]]:
    """{model: {FMI version: path}} of every installed unit (FMU_NAMES x FMI_VERSIONS)."""
    return {m: {v: fmu_path(v, m) for v in FMI_VERSIONS} for m in FMU_NAMES}


def ssp_path(version: str = "2.0") -> pathlib.Path:
    """Path of the installed closed-loop SSP archive (docs/closed-loop.md: the scene player, the
    inverse unit, the controller and the plant with their connections, start values and default
    experiment) for FMI `version` ("2.0" or "3.0"), for an SSP master (ecos, OMSimulator,
    fmpy.ssp). Raises as fmu_path."""
    if version not in FMI_VERSIONS:
        raise ValueError(f"version = {version!r}: the archives exist for FMI {', '.join(FMI_VERSIONS)}")
    path = _HERE / "ssp" / version / "closed_loop.ssp"
    if not path.is_file():
        raise FileNotFoundError(f"{path} is missing: reinstall the package (pip install .)")
    return path

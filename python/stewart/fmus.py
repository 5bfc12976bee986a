"""The FMI units built with the library, shipped inside the package: the co-simulation units
StewartPlatform (inverse), StewartPlant (the plant), StewartController and StewartScene (the scene
player), and the plant as Model Exchange, StewartPlantME; each for FMI 2.0 and 3.0."""
from __future__ import annotations

import pathlib

FMI_VERSIONS = ("2.0", "3.0")
_HERE = pathlib.Path(__file__).resolve().parent


def _unit_names() -> tuple[str, ...]:
    """The units this install ships, in the order of fmu/CMakeLists.txt's stewart_unit lines (the
    build writes them into fmus/units.txt); none if the file is missing (then fmu_path says to
    reinstall)."""
    try:
        text = (_HERE / "fmus" / "units.txt").read_text(encoding="utf-8")
    except FileNotFoundError:
        return ()
    return tuple(line.strip() for line in text.splitlines() if line.strip())


FMU_NAMES = _unit_names()


def fmu_path(version: str = "2.0", model: str = "StewartPlatform") -> pathlib.Path:
    """Path of the installed FMU `model` (one of FMU_NAMES; default the inverse unit) for FMI
    `version` ("2.0" or "3.0"), e.g. for ``fmpy.simulate_fmu(stewart.fmu_path("3.0"), ...)``.
    Raises FileNotFoundError if this install has no such unit, ValueError for an unknown version
    or model."""
    if version not in FMI_VERSIONS:
        raise ValueError(f"version = {version!r}: the FMUs exist for FMI {', '.join(FMI_VERSIONS)}")
    if not FMU_NAMES:
        raise FileNotFoundError(f"{_HERE / 'fmus' / 'units.txt'} is missing: reinstall the "
                                "package (pip install .)")
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


#: The units that take the library's parameter table, and those that start from a pose.
PARAMETER_UNITS = ("StewartPlatform", "StewartPlant", "StewartPlantME")
PLANT_UNITS = ("StewartPlant", "StewartPlantME")
_POSE = ("x", "y", "z", "roll", "pitch", "yaw")


def fmu_start_values(platform, fmi_version: str = "2.0",
                     model: str = "StewartPlatform") -> dict[str, float]:
    """The start values that give an FMU unit of the library (StewartPlatform, StewartPlant,
    StewartPlantME) the platform `platform`: a Platform, a platform file's path, or a mapping of
    parameter names to values as Platform takes them. Arrays are expanded to the FMU's element
    names (``base_joint[1]`` .. ``base_joint[18]``; a scalar stroke fills ``stroke_min[1]`` ..
    ``stroke_min[6]``), every value in SI, for FMI `fmi_version` ("2.0" or "3.0": the names are
    the same). For a plant unit (`model` "StewartPlant" or "StewartPlantME") the values also
    hold its start state: the machine at its home pose (x0 .. yaw0: the tool in the user frame,
    in the file's rotation order and frame convention, as Platform.check().home), at rest
    (x_dot0 .. yaw_dot0 zero); the unit's own start, z0 = 0.5 m, is the thesis platform's home
    only. The platform is built first, so a bad file or value raises ParameterError here, not at
    the unit's instantiation. E.g. ``fmpy.simulate_fmu(stewart.fmu_path("2.0"),
    start_values={**stewart.fmu_start_values("machine.json"), ...})``."""
    import os
    from collections.abc import Mapping

    from .params import parameter_assignments, parameters
    from .platform import Platform

    if fmi_version not in FMI_VERSIONS:
        raise ValueError(f"fmi_version = {fmi_version!r}: the FMUs exist for FMI "
                         f"{', '.join(FMI_VERSIONS)}")
    if model not in PARAMETER_UNITS:
        raise ValueError(f"model = {model!r}: the units that take a platform are "
                         f"{', '.join(PARAMETER_UNITS)}")
    if isinstance(platform, Platform):
        built = platform
    elif isinstance(platform, Mapping):
        built = Platform(**platform)
    elif isinstance(platform, (str, os.PathLike)):
        built = Platform.from_file(platform)
    else:
        raise TypeError(f"platform is a {type(platform).__name__}: give a Platform, a platform "
                        "file's path or a mapping of parameter names to values")
    counts = {p["name"]: p["count"] for p in parameters()}
    values: dict[str, float] = {}
    for name, value in parameter_assignments(built.params):
        if counts.get(name, 1) > 1:  # a scalar that fills every element
            values.update({f"{name}[{k}]": value for k in range(1, counts[name] + 1)})
        else:
            values[name] = value
    if model in PLANT_UNITS:
        home = built.check().home
        values.update({f"{p}0": float(v) for p, v in zip(_POSE, home)})
        values.update({f"{p}_dot0": 0.0 for p in _POSE})
    return values

"""Sweep specs: parsing, validation before any work, and the split into chunks.

A spec is JSON (docs/sweeps.md has the full format). Two kinds:

* ``"kind": "envelope"``: cases = payload_mass x payload_com x manoeuvre (scene x amplitude scale
  x frequency scale) x fidelity; each case is one trajectory; per case the peaks (work.py).
* ``"kind": "workspace"``: slices of the pose space, each one or two pose components on a grid
  with the others fixed; per pose reachability within every limit, the limit margins, condition
  and static forces; optionally (``"volume"``) the constant-orientation workspace volume.

Every field is checked here, before anything is sent to a worker: a bad one raises SpecError
naming the field (``manoeuvres[1].amplitude``) and the value.
"""
from __future__ import annotations

import json
import math
import os
import pathlib
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ParameterError
from .. import scenes
from ..choices import Fidelity
from ..params import read_platform_file
from ..platform import Platform
from ..scenes import POSE

SOLVER_OPTIONS = ("tolerance", "max_iterations", "modified_newton", "warn_condition",
                  "singular_condition")
# Memory per item, rounded up, for the size checks before any work: a pose being solved (its
# inputs and InverseSolution, about 420 bytes), a row of a merged result table (about 30
# columns), a value of a range (a Python float in a list and its numpy source).
BYTES_PER_POSE = 512
BYTES_PER_ROW = 512
BYTES_PER_VALUE = 48
_COMMON = {"kind", "platform_file", "platform", "options", "fidelity", "title"}
_FIELDS = {
    "envelope": _COMMON | {"payload_mass", "payload_com", "manoeuvres", "duration", "step",
                           "cases_per_chunk"},
    "workspace": _COMMON | {"slices", "poses_per_chunk", "volume"},
}


class SpecError(ValueError):
    """A sweep spec (or OUT_DIR) that cannot run: the message names the field and its value."""


@dataclass(frozen=True)
class Chunk:
    """One unit of work: rows [start, stop) of a part (the cases, or one workspace slice)."""
    part: str
    index: int
    start: int
    stop: int

    @property
    def file_name(self) -> str:
        return f"{self.part}-{self.index:05d}.parquet"


def load(path: str | pathlib.Path, scene_dir: str | pathlib.Path) -> dict:
    """The spec in JSON file `path`, checked and resolved (see resolve); a relative
    platform_file is found beside the spec."""
    try:
        raw = json.loads(pathlib.Path(path).read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
        raise SpecError(f"{path}: {e}") from None
    return resolve(raw, scene_dir, pathlib.Path(path).parent)


def resolve(raw: Any, scene_dir: str | pathlib.Path,
            spec_dir: str | pathlib.Path = ".") -> dict:
    """A checked, self-contained spec: ranges expanded to lists, scenes read from scene_dir and
    the platform file (relative to spec_dir) read and embedded, so that workers need no files.
    Raises SpecError naming the first bad field."""
    if not isinstance(raw, dict):
        raise SpecError("the spec must be a JSON object")
    kind = raw.get("kind")
    if kind not in _FIELDS:
        raise SpecError(f"kind = {kind!r} must be 'envelope' or 'workspace'")
    unknown = sorted(set(raw) - _FIELDS[kind])
    if unknown:
        raise SpecError(f"unknown field {unknown[0]!r} for kind {kind!r} "
                        f"(known: {', '.join(sorted(_FIELDS[kind]))})")
    spec = {"kind": kind, "title": str(raw.get("title", "")),
            "platform": {**_platform_file(raw, pathlib.Path(spec_dir)), **_mapping(raw, "platform")},
            "options": _options(raw)}
    base = _platform(spec["platform"], {}, "platform")
    fidelity = raw.get("fidelity", ["massless"] if kind == "envelope" else "massless")
    if kind == "envelope":
        spec["fidelity"] = [_fidelity(f, f"fidelity[{i}]") for i, f in
                            enumerate(_list(fidelity, "fidelity"))]
        _check_options(base, spec["options"], spec["fidelity"])
        spec.update(_envelope(raw, spec, base, pathlib.Path(scene_dir)))
    else:
        spec["fidelity"] = _fidelity(fidelity, "fidelity")
        _check_options(base, spec["options"], [spec["fidelity"]])
        spec["slices"] = [_slice(s, f"slices[{i}]") for i, s in
                          enumerate(_list(raw.get("slices"), "slices"))]
        names = [s["name"] for s in spec["slices"]]
        if len(set(names)) != len(names):
            raise SpecError(f"slices: names {names} must differ")
        spec["poses_per_chunk"] = _positive_int(raw.get("poses_per_chunk", 65536), "poses_per_chunk")
        for i, s in enumerate(spec["slices"]):
            _fits(f"slices[{i}] ({s['name']}: "
                  f"{' x '.join(str(len(v)) for v in s['axes'].values())} grid)",
                  slice_size(s), BYTES_PER_ROW, "poses")
        _fits("poses_per_chunk", spec["poses_per_chunk"], BYTES_PER_POSE, "poses per chunk")
        if "volume" in raw:
            spec["volume"] = _volume(raw["volume"], "volume")
    return spec


def chunks(spec: dict) -> list[Chunk]:
    """The chunks of a resolved spec, in a fixed order that depends on the spec only (never on
    the number of workers), so that every run splits the work alike."""
    if spec["kind"] == "envelope":
        parts = [("cases", case_count(spec), spec["cases_per_chunk"])]
    else:
        parts = [(s["name"], slice_size(s), spec["poses_per_chunk"]) for s in spec["slices"]]
    out = []
    for part, n, size in parts:
        for i, start in enumerate(range(0, n, size)):
            out.append(Chunk(part, i, start, min(start + size, n)))
    return out


def case_count(spec: dict) -> int:
    """Number of envelope cases."""
    variants = sum(len(m["amplitude"]) * len(m["frequency"]) for m in spec["manoeuvres"])
    return len(spec["payload_mass"]) * len(spec["payload_com"]) * variants * len(spec["fidelity"])


def slice_size(s: dict) -> int:
    """Number of poses of a workspace slice."""
    return math.prod(len(v) for v in s["axes"].values())


# ---------------------------------------------------------------- envelope fields

def _envelope(raw: dict, spec: dict, base: Platform, scene_dir: pathlib.Path) -> dict:
    out: dict[str, Any] = {}
    for key in ("payload_mass", "payload_com"):
        if key in spec["platform"]:
            raise SpecError(f"platform.{key}: the envelope sweeps it; give it as the top-level {key}")
    out["payload_mass"] = _values(raw.get("payload_mass", [0.0]), "payload_mass")
    coms = _list(raw.get("payload_com", [[0.0, 0.0, 0.0]]), "payload_com")
    out["payload_com"] = []
    for i, c in enumerate(coms):
        c = np.asarray(c, dtype=float) if _is_numbers(c) else None
        if c is None or c.shape != (3,) or not np.all(np.isfinite(c)):
            raise SpecError(f"payload_com[{i}] = {coms[i]!r} must be 3 finite numbers [m]")
        out["payload_com"].append(c.tolist())
    out["duration"] = _optional_positive(raw, "duration")
    out["step"] = _optional_positive(raw, "step")
    out["manoeuvres"] = [_manoeuvre(m, f"manoeuvres[{i}]", scene_dir) for i, m in
                         enumerate(_list(raw.get("manoeuvres"), "manoeuvres"))]
    out["cases_per_chunk"] = _positive_int(raw.get("cases_per_chunk", 8), "cases_per_chunk")
    _check_envelope_size({**spec, **out})
    for i, m in enumerate(out["payload_mass"]):
        for j, c in enumerate(out["payload_com"]):
            _platform(spec["platform"], {"payload_mass": m, "payload_com": c},
                      f"payload_mass[{i}] = {m} with payload_com[{j}] = {c}")
    for i, m in enumerate(out["manoeuvres"]):
        _check_reachable(base, m, out, f"manoeuvres[{i}]")
    return out


def _check_envelope_size(spec: dict) -> None:
    """SpecError unless one case's trajectory and the table of all cases fit in memory."""
    for i, m in enumerate(spec["manoeuvres"]):
        samples = scenes.samples(m["scene"], spec["step"], spec["duration"]) + 1
        where = (f"manoeuvres[{i}] ({m['name']}): duration {spec['duration'] or m['scene']['duration']:g} s "
                 f"at step {spec['step'] or m['scene']['step']:g} s")
        _fits(where, samples, BYTES_PER_POSE, "poses per case")
    _fits("the envelope (payload_mass x payload_com x manoeuvres x fidelity)", case_count(spec),
          BYTES_PER_ROW, "cases")


def _manoeuvre(m: Any, field: str, scene_dir: pathlib.Path) -> dict:
    if not isinstance(m, dict) or "scene" not in m:
        raise SpecError(f"{field} = {m!r} must be an object with a 'scene' (a name in scenes/ "
                        "or an inline scene object)")
    unknown = sorted(set(m) - {"scene", "amplitude", "frequency"})
    if unknown:
        raise SpecError(f"{field}: unknown field {unknown[0]!r} (known: scene, amplitude, frequency)")
    scene = m["scene"]
    try:
        if isinstance(scene, str):
            if not (scene_dir / f"{scene}.json").is_file():
                raise SpecError(f"{field}.scene = {scene!r}: there is no {scene_dir / scene}.json")
            name, scene = scene, scenes.load(scene, scene_dir)
        elif isinstance(scene, dict):
            name = str(scene.get("name", f"inline{field}"))
            scenes.check(scene, f"{field}.scene")
        else:
            raise SpecError(f"{field}.scene = {scene!r} must be a scene name or a scene object")
    except scenes.SceneError as e:
        raise SpecError(f"{field}.scene: {e}" if isinstance(m["scene"], str) else str(e)) from None
    if "pose" not in scene:
        raise SpecError(f"{field}.scene = {name!r} has no pose (a mechanism scene cannot be swept)")
    return {"name": name, "scene": {"pose": scene["pose"], "duration": float(scene["duration"]),
                                    "step": float(scene["step"])},
            "amplitude": _values(m.get("amplitude", [1.0]), f"{field}.amplitude"),
            "frequency": _values(m.get("frequency", [1.0]), f"{field}.frequency")}


def _check_reachable(base: Platform, m: dict, spec: dict, field: str) -> None:
    """Every variant of the manoeuvre stays within the stroke (lengths do not depend on the
    payload, so the kinematic level on the base platform decides)."""
    for a in m["amplitude"]:
        for f in m["frequency"]:
            t, q, qd, qdd = scenes.sample(m["scene"], a, f, spec["duration"], spec["step"])
            sol = base.inverse(q, qd, qdd, fidelity="kinematic", max_messages=1)
            bad = np.flatnonzero(~sol.ok | (sol.warnings & 1).astype(bool))
            if bad.size:
                j = int(bad[0])
                why = sol.messages.get(j) or ("a leg length leaves the stroke: L = "
                                              f"{np.array2string(sol.length[j], precision=4)} m")
                raise SpecError(f"{field} ({m['name']}, amplitude x{a}, frequency x{f}) is "
                                f"unreachable at t = {t[j]:g} s: {why}")


# ---------------------------------------------------------------- workspace fields

def _slice(s: Any, field: str) -> dict:
    if not isinstance(s, dict):
        raise SpecError(f"{field} = {s!r} must be an object with name, fixed and axes")
    unknown = sorted(set(s) - {"name", "fixed", "axes"})
    if unknown:
        raise SpecError(f"{field}: unknown field {unknown[0]!r} (known: name, fixed, axes)")
    name = s.get("name")
    if not isinstance(name, str) or not name.replace("_", "").replace("-", "").replace(".", "").isalnum():
        raise SpecError(f"{field}.name = {name!r} must be a word (letters, digits, _ - .)")
    fixed = _mapping(s, "fixed", f"{field}.fixed")
    axes = _mapping(s, "axes", f"{field}.axes")
    if not 1 <= len(axes) <= 2:
        raise SpecError(f"{field}.axes has {len(axes)} components: give 1 or 2")
    for comp in (*fixed, *axes):
        if comp not in POSE:
            raise SpecError(f"{field}: {comp!r} is not a pose component {POSE}")
    both = set(fixed) & set(axes)
    if both:
        raise SpecError(f"{field}: {sorted(both)[0]!r} is both fixed and an axis")
    if "z" not in fixed and "z" not in axes:
        raise SpecError(f"{field}: z is neither fixed nor an axis (the base plane is singular)")
    out_fixed = {}
    for comp, v in fixed.items():
        if not isinstance(v, (int, float)) or not math.isfinite(v):
            raise SpecError(f"{field}.fixed.{comp} = {v!r} must be a finite number")
        out_fixed[comp] = float(v)
    return {"name": name, "fixed": out_fixed,
            "axes": {comp: _values(v, f"{field}.axes.{comp}") for comp, v in axes.items()}}


def _volume(v: Any, field: str) -> dict:
    """{"orientation": [roll, pitch, yaw] (default 0, 0, 0), "cells": columns per side (48)}."""
    if not isinstance(v, dict):
        raise SpecError(f"{field} = {v!r} must be an object with orientation and cells")
    unknown = sorted(set(v) - {"orientation", "cells"})
    if unknown:
        raise SpecError(f"{field}: unknown field {unknown[0]!r} (known: orientation, cells)")
    orientation = v.get("orientation", [0.0, 0.0, 0.0])
    if not (_is_numbers(orientation) and len(orientation) == 3 and
            all(math.isfinite(x) for x in orientation)):
        raise SpecError(f"{field}.orientation = {orientation!r} must be 3 finite numbers "
                        "(roll, pitch, yaw [rad])")
    cells = v.get("cells", 48)
    if not isinstance(cells, int) or isinstance(cells, bool) or not 2 <= cells <= 1024:
        raise SpecError(f"{field}.cells = {cells!r} must be an integer in [2, 1024]")
    return {"orientation": [float(x) for x in orientation], "cells": cells}


# ---------------------------------------------------------------- shared helpers

def _values(v: Any, field: str) -> list[float]:
    """A list of finite numbers from a list, a number, or {"start", "stop", "num"}."""
    if isinstance(v, dict):
        unknown = sorted(set(v) - {"start", "stop", "num"})
        if unknown or not {"start", "stop", "num"} <= set(v):
            raise SpecError(f"{field} = {v!r}: a range needs exactly start, stop, num")
        num = v["num"]
        whole = isinstance(num, (int, float)) and not isinstance(num, bool) and \
            math.isfinite(num) and num == int(num)
        if not whole:
            raise SpecError(f"{field}.num = {num!r} must be a whole number >= 1 (how many values)")
        if num < 1:
            raise SpecError(f"{field}.num = {num!r}: the range is empty (num must be >= 1)")
        if not all(isinstance(v[k], (int, float)) and math.isfinite(v[k]) for k in ("start", "stop")):
            raise SpecError(f"{field} = {v!r}: start and stop must be finite numbers")
        _fits(f"{field}.num", num, BYTES_PER_VALUE, "values")
        return np.linspace(v["start"], v["stop"], int(num)).tolist()
    values = _list(v, field)
    if not _is_numbers(values) or not all(math.isfinite(x) for x in values):
        raise SpecError(f"{field} = {v!r} must be finite numbers")
    return [float(x) for x in values]


def memory_bytes() -> int:
    """The machine's physical memory [bytes]."""
    return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")


def _fits(field: str, count: float, bytes_each: int, what: str) -> None:
    """SpecError naming field unless count items of bytes_each fit in the machine's memory
    (checked before any work: a sweep that cannot fit would fail after hours, or swap)."""
    need, have = count * bytes_each, memory_bytes()
    if not need <= have:  # also refuses an infinite or NaN count
        raise SpecError(f"{field}: {count:.3g} {what} need about {need / 1e9:.3g} GB "
                        f"({bytes_each} bytes each), more than this machine's memory "
                        f"({have / 1e9:.3g} GB)")


def _list(v: Any, field: str) -> list:
    if v is None:
        raise SpecError(f"{field} is missing")
    values = v if isinstance(v, list) else [v]
    if not values:
        raise SpecError(f"{field} is empty: give at least one value")
    return values


def _is_numbers(v: Any) -> bool:
    return isinstance(v, list) and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v)


def _mapping(raw: dict, key: str, field: str | None = None) -> dict:
    v = raw.get(key, {})
    if not isinstance(v, dict):
        raise SpecError(f"{field or key} = {v!r} must be an object")
    return dict(v)


def _positive_int(v: Any, field: str) -> int:
    if not isinstance(v, int) or isinstance(v, bool) or v < 1:
        raise SpecError(f"{field} = {v!r} must be an integer >= 1")
    return v


def _optional_positive(raw: dict, key: str) -> float | None:
    v = raw.get(key)
    if v is not None and not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
        raise SpecError(f"{key} = {v!r} must be a number > 0")
    return None if v is None else float(v)


def _fidelity(v: Any, field: str) -> str:
    try:
        return Fidelity.of(v).name.lower()
    except ParameterError as e:
        raise SpecError(f"{field}: {e}") from None


def _options(raw: dict) -> dict:
    options = _mapping(raw, "options")
    for k in options:
        if k not in SOLVER_OPTIONS:
            raise SpecError(f"options: unknown option {k!r} (known: {', '.join(SOLVER_OPTIONS)})")
    return options


def _check_options(base: Platform, options: dict, levels: list[str]) -> None:
    for level in levels:
        try:
            base.inverse(np.zeros((0, 6)), fidelity=level, **options)
        except (ParameterError, TypeError, ValueError) as e:
            raise SpecError(f"options: {e}") from None


def _platform_file(raw: dict, spec_dir: pathlib.Path) -> dict:
    """The parameters of the spec's platform_file (none without one); `platform` changes them."""
    if "platform_file" not in raw:
        return {}
    name = raw["platform_file"]
    if not isinstance(name, str) or not name:
        raise SpecError(f"platform_file = {name!r} must be the path of a platform file")
    try:
        return read_platform_file(spec_dir / name)
    except ParameterError as e:
        raise SpecError(f"platform_file: {e}") from None


def _platform(params: dict, extra: dict, field: str) -> Platform:
    try:
        return Platform(**params, **extra)
    except ParameterError as e:
        raise SpecError(f"{field}: {e}") from None

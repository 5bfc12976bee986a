#!/usr/bin/env python3
"""Writes the seed inputs of the C API fuzz target (tests/fuzz/fuzz_api.cpp) into a folder.

Field indices count the doubles of stewart_params in declaration order (cylinder_mass is 32,
piston_mass 37). Layout the target reads: 1 byte count of parameter edits (mod 8), each edit 1 byte field index +
a float64; 1 byte choice (fidelity = choice % 4, bit 2 modified Newton, bit 7: a float64 tolerance
follows); then poses of 18 float64 (q, q_dot, q_ddot).
"""
import math
import pathlib
import struct
import sys


def pose(q, qd=(0,) * 6, qdd=(0,) * 6):
    return struct.pack("<18d", *q, *qd, *qdd)


def seed(edits=(), fidelity=1, tolerance=None, poses=()):
    out = bytes([len(edits)])
    for field, value in edits:
        out += bytes([field]) + struct.pack("<d", value)
    out += bytes([fidelity | (0x80 if tolerance is not None else 0)])
    if tolerance is not None:
        out += struct.pack("<d", tolerance)
    return out + b"".join(poses)


HOME = (0, 0, 0.5, 0, 0, 0)
SEEDS = {
    "kinematic_home": seed(fidelity=0, poses=[pose(HOME)]),
    "massless_home": seed(fidelity=1, poses=[pose(HOME)]),
    "full_home": seed(fidelity=2, tolerance=1e-12, poses=[pose(HOME)]),
    "invalid_fidelity": seed(fidelity=3, poses=[pose(HOME)]),
    "yaw_sweep": seed(fidelity=1, poses=[pose((0, 0, 0.5, 0, 0, a)) for a in
                                         (0.5, 1.0, 1.5, math.pi / 2, 1.6)]),
    "moving": seed(fidelity=2, poses=[pose((0.01, -0.02, 0.52, 0.1, -0.05, 0.2),
                                           (0.1, 0, 0.2, 0.5, 0.3, -0.2), (1, 2, -3, 4, 5, -6))]),
    "nan_pose": seed(fidelity=1, poses=[pose((math.nan, 0, 0.5, 0, 0, 0))]),
    "inf_rate": seed(fidelity=2, poses=[pose(HOME, (0, 0, math.inf, 0, 0, 0))]),
    "huge_pose": seed(fidelity=1, poses=[pose((1e300, -1e300, 1e308, 1e10, -1e10, 1e20))]),
    "unreachable": seed(fidelity=2, poses=[pose((0, 0, 0, 0, 0, math.pi / 6))]),
    "tiny_radius": seed(edits=[(0, 1e-3), (1, 1e-3)], fidelity=2, poses=[pose((0, 0, 0.001, 0, 0, 0))]),
    "heavy_legs": seed(edits=[(32, 1e3), (37, 1e3)], fidelity=2, poses=[pose(HOME)]),
    "nan_parameter": seed(edits=[(14, math.nan)], fidelity=1, poses=[pose(HOME)]),
}


def main(folder):
    path = pathlib.Path(folder)
    path.mkdir(parents=True, exist_ok=True)
    for name, data in SEEDS.items():
        (path / name).write_bytes(data)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "tests/fuzz/corpus/api")

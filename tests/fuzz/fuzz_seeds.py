#!/usr/bin/env python3
"""Writes the seed inputs of the C API fuzz target (tests/fuzz/fuzz_api.cpp) into a folder, or
with --fmu those of the FMU target (tests/fuzz/fuzz_fmu.cpp, layout described below SEEDS).

usage: tests/fuzz/fuzz_seeds.py [FOLDER=tests/fuzz/corpus/api]
       tests/fuzz/fuzz_seeds.py --fmu [FOLDER=tests/fuzz/corpus/fmu]
       tests/fuzz/fuzz_seeds.py --plant [FOLDER=tests/fuzz/corpus/plant_fmu]
       tests/fuzz/fuzz_seeds.py --me [FOLDER=tests/fuzz/corpus/plant_me_fmu]

Field indices count the doubles of stewart_params in declaration order (cylinder_mass is 105,
piston_mass 110: after the general geometry's 73 doubles of issue 19). Layout the target reads: 1 byte count of parameter edits (mod 8), each edit 1 byte field index +
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
    "heavy_legs": seed(edits=[(105, 1e3), (110, 1e3)], fidelity=2, poses=[pose(HOME)]),
    "nan_parameter": seed(edits=[(14, math.nan)], fidelity=1, poses=[pose(HOME)]),
}


# ---- the FMU target: byte 0 flags (bit 0 logging on, bit 1 initialise at once with fidelity =
# bits 2-3 and derivatives = bit 4; bit 5 FMI 3 instead of FMI 2), then operations,
# each an opcode byte (tests/fuzz/fuzz_fmu.cpp: 0 SetReal any, 1 SetReal pose input (vr 0..17),
# 2 SetInteger, 3 DoStep, 4 read outputs, 5 SetRealInputDerivatives, 6 GetFMUstate, 7 SetFMUstate,
# 8 serialise round trip, 9 Reset, 10 Terminate, 11 initialise, 12 SetDebugLogging, 13 read all)
# and its arguments. A value is a selector byte; 255 is followed by a raw float64.
VR = {"x": 0, "y": 1, "z": 2, "roll": 3, "pitch": 4, "yaw": 5, "x_dot": 6, "z_ddot": 14,
      "yaw_dot": 11}


def val(x):
    return bytes([255]) + struct.pack("<d", x)


def set_pose(name, x):
    return bytes([1, VR[name]]) + val(x)


def step(h, t=None):
    """DoStep of h from the target's own time, or from t."""
    return bytes([3, 0 if t is None else 1]) + val(h) + (b"" if t is None else val(t))


def set_int(index, value):
    """SetInteger of the index-th Integer variable (table order: newton_iterations, status,
    fidelity, derivatives, max_iterations, modified_newton) to value 0..3."""
    return bytes([2, index, value])


READ = bytes([4])
FIDELITY, DERIVATIVES = 2, 3


def fmu_seed(*ops, logging=True, init=True, fidelity=1, derivatives=0, fmi3=False):
    flags = ((1 if logging else 0) | (2 if init else 0) | (fidelity << 2) | (derivatives << 4) |
             (32 if fmi3 else 0))
    return bytes([flags]) + b"".join(ops)


FMU_SEEDS = {
    "home_steps": fmu_seed(READ, step(0.1), READ, step(0.1), READ),
    "yaw_sweep": fmu_seed(*[set_pose("yaw", a) + step(0.01) + READ
                            for a in (0.5, 1.5, 1.5707, math.pi / 2, 0.2)]),
    "kinematic": fmu_seed(set_pose("z", 0.55), step(1e-9), READ, fidelity=0),
    "full": fmu_seed(set_pose("z", 0.55), step(0.1), READ, fidelity=2),
    "invalid_fidelity": fmu_seed(step(0.1), READ, fidelity=3),
    "set_fidelity_late": fmu_seed(set_int(FIDELITY, 0), bytes([11]) + val(0.0), step(0.1), READ,
                                  init=False),
    "taylor": fmu_seed(set_pose("x_dot", 0.1), set_pose("z_ddot", -1.0), step(10.0), READ,
                       step(1e-9), READ, derivatives=1),
    "nan_then_good": fmu_seed(set_pose("x", math.nan), step(0.1), READ, set_pose("x", 0.0),
                              step(0.1), READ),
    "bad_steps": fmu_seed(step(0.0), step(-1.0), step(math.inf), step(1e-300, 1e10),
                          step(1e308, 1e308), step(0.1), READ),
    "unreachable": fmu_seed(set_pose("z", 0.0), set_pose("yaw", math.pi / 6), step(0.1), READ,
                            set_pose("z", 0.5), step(0.1), READ),
    "stroke": fmu_seed(set_pose("z", 0.75), step(0.1), READ, set_pose("z", 0.3), step(0.1), READ),
    "state_roundtrip": fmu_seed(step(0.1), bytes([6]), set_pose("roll", 0.1), step(0.1), READ,
                                bytes([7]), READ, bytes([8, 0]), bytes([8, 1, 3, 0x55]), READ),
    "input_derivatives": fmu_seed(bytes([5, 2, 1]) + val(1.0), bytes([5, 2, 2]) + val(-3.0),
                                  step(0.5), READ, bytes([5, 7, 2]) + val(1.0), step(0.1), READ),
    "huge_pose": fmu_seed(set_pose("x", 1e300), set_pose("yaw_dot", 1e308), step(0.1), READ),
    "reset_terminate": fmu_seed(step(0.1), bytes([10]), step(0.1), READ, bytes([9]),
                                bytes([11]) + val(5.0), step(0.1), READ),
    # Real table index 53 is base_radius, 54 platform_radius (inputs, outputs, options first)
    "bad_parameter": fmu_seed(set_int(FIDELITY, 1), bytes([0, 53]) + val(math.nan),
                              bytes([11]) + val(0.0), READ, bytes([13]), init=False),
    "tiny_platform": fmu_seed(set_int(FIDELITY, 1), bytes([0, 53]) + val(1e-3),
                              bytes([0, 54]) + val(1e-3), bytes([11]) + val(0.0),
                              set_pose("z", 1e-3), step(0.1), READ, init=False),
    "logging": fmu_seed(bytes([12, 0]), bytes([12, 3]), bytes([12, 9]), set_pose("x", math.inf),
                        step(0.1), READ),
}
# the same sequences through the FMI 3 layer
# issue 23's probe: a serialised state whose mode is changed to terminated (8) or initialisation
# (2) (fmu_values.mode at byte 16 + 7200 of the inverse unit's state; 16 + 3792 before issue 19
# raised FMU_NVR from 301 to 585: 12 bytes per value reference), a subnormal step, and a
# run from t0 = 100 s with the communication points counted (t0 + n h).
def corrupt_int32(offset, value):
    """Op 8 with bit 3: the int32 at `offset` of the serialised state (taken by op 6) := value."""
    return bytes([8, 8, offset & 255, offset >> 8, value])


def corrupt_double(offset, x):
    """Op 8 with bit 2: the float64 at `offset` of the serialised state (taken by op 6) := x."""
    return bytes([8, 4, offset & 255, offset >> 8]) + val(x)


FMU_SEEDS.update({
    "probe_mode_terminated": fmu_seed(step(0.1), bytes([6]), corrupt_int32(7216, 8), READ,
                                      step(0.1), READ),
    "probe_mode_initialisation": fmu_seed(step(0.1), bytes([6]), corrupt_int32(7216, 2), READ,
                                          step(0.1), READ),
    "probe_subnormal_step": fmu_seed(step(4.9e-324), step(4.9e-324, 0.0), step(0.1), READ),
    "probe_counted_clock_t0_100": fmu_seed(bytes([11]) + val(100.0),
                                           *[step(0.1, 100.0 + i * 0.1) for i in range(4)], READ),
})
FMU_SEEDS.update({name + "_fmi3": bytes([seed[0] | 32]) + seed[1:]
                  for name, seed in list(FMU_SEEDS.items())})


# ---- the plant FMU target (tests/fuzz/fuzz_plant_fmu.cpp): byte 0 flags (bit 0 logging on, bit 1
# initialise at once with fidelity 1 + bit 2 and method = bits 3-4, bit 5 FMI 3), byte 1
# max_internal_steps - 1 (mod 32), then operations: the FMU target's opcodes, but 1 sets one force
# F[k] (k = 0..5) to 1000 * value, 5 takes any order of vr 0..7, and 13 sets all six forces to
# the static ones times 1 + offset/1000 (six int8 offsets).
def plant_seed(*ops, logging=True, init=True, fidelity=2, method=2, fmi3=False, steps=32):
    flags = ((1 if logging else 0) | (2 if init else 0) | ((fidelity - 1) << 2) | (method << 3) |
             (32 if fmi3 else 0))
    return bytes([flags, steps - 1]) + b"".join(ops)


def forces_near_statics(*offsets):
    return bytes([13]) + struct.pack("<6b", *offsets)


def set_force(leg, value_over_1000):
    return bytes([1, leg]) + val(value_over_1000)


STATICS = forces_near_statics(0, 0, 0, 0, 0, 0)
PLANT_SEEDS = {
    "at_rest": plant_seed(STATICS, step(1e-3), READ, step(1e-3), READ),
    "massless_adams": plant_seed(STATICS, step(1e-3), READ, fidelity=1, method=0),
    "full_bdf": plant_seed(forces_near_statics(5, -5, 3, 0, -2, 1), step(2e-3), READ, method=1),
    "erk54_wobble": plant_seed(forces_near_statics(50, -50, 30, 0, -20, 10), step(1e-3), READ,
                               forces_near_statics(-50, 50, -30, 0, 20, -10), step(1e-3), READ,
                               method=3),
    "free_fall": plant_seed(step(0.01), READ, step(0.01), READ),
    "nan_then_good": plant_seed(STATICS, set_force(2, math.nan), step(1e-3), READ, STATICS,
                                step(1e-3), READ),
    "huge_force": plant_seed(set_force(0, 1e300), step(1e-3), READ, STATICS, step(1e-3), READ),
    "too_few_internal_steps": plant_seed(STATICS, step(1.0), READ, step(1e-3), READ, steps=1),
    "gap_and_bad_steps": plant_seed(STATICS, step(1e-3), step(1e-3, 1.0), step(0.0), step(-1.0),
                                    step(math.inf), READ),
    "force_rates": plant_seed(STATICS, bytes([5, 1, 1]) + val(1.0), bytes([5, 7, 1]) + val(1.0),
                              bytes([5, 0, 2]) + val(1.0), step(1e-3), READ),
    "state_roundtrip": plant_seed(STATICS, step(1e-3), bytes([6]), forces_near_statics(9, 0, 0, 0, 0, 0),
                                  step(1e-3), READ, bytes([7]), READ, bytes([8, 0]),
                                  bytes([8, 1, 3, 0x55]), READ),
    "reset_terminate": plant_seed(step(1e-3), bytes([10]), step(1e-3), READ, bytes([9]),
                                  bytes([11]) + val(5.0), step(1e-3), READ),
    "logging": plant_seed(bytes([12, 0]), bytes([12, 3]), bytes([12, 9]), set_force(0, math.inf),
                          step(1e-3), READ),
}
# issue 23's probe on the plant: its serialised state (16 bytes of header, fmu_values with the
# mode at 7184, the Reals from 16 (value reference 210 = base_radius at 1696), then at 7200 the
# plant's 25 doubles: time, pose and quaternion, velocity (7264), angular velocity (7288), roll
# (7312), forces, warnings, step hint (7392)) with one field corrupted (offsets 3408 bytes later
# than before issue 19's FMU_NVR 585); a subnormal step; a bad
# force derivative retried with the forces alone; a run from t0 = 100 s on a counted clock.
PLANT_TAKEN = STATICS + step(1e-3) + bytes([6])
PLANT_SEEDS.update({
    "probe_subnormal_hint": plant_seed(PLANT_TAKEN, corrupt_double(7392, 4.9e-324), READ,
                                       step(1e-3), READ, step(1e-3), READ),
    "probe_plant_time": plant_seed(PLANT_TAKEN, corrupt_double(7200, 5.0), READ, step(1e-3)),
    "probe_roll_off_quaternion": plant_seed(PLANT_TAKEN, corrupt_double(7312, 1.8e308), READ,
                                            step(1e-3), READ),
    "probe_velocity": plant_seed(PLANT_TAKEN, corrupt_double(7264, 1e15), READ, step(1e-3)),
    "probe_angular_velocity": plant_seed(PLANT_TAKEN, corrupt_double(7288, 1.7e308), READ,
                                         step(1e-3)),
    "probe_mode_terminated": plant_seed(PLANT_TAKEN, corrupt_int32(7184, 8), READ, step(1e-3)),
    "probe_mode_initialisation": plant_seed(PLANT_TAKEN, corrupt_int32(7184, 2), READ,
                                            step(1e-3)),
    "probe_parameter_1e6": plant_seed(PLANT_TAKEN, corrupt_double(1696, 1e6), READ, step(1e-3)),
    "probe_subnormal_step": plant_seed(STATICS, step(4.9e-324), step(1e-3), READ),
    "probe_bad_rate_retry": plant_seed(STATICS, bytes([5, 1, 1]) + val(math.nan), step(1e-3),
                                       STATICS, step(1e-3), READ),
    "probe_counted_clock_t0_100": plant_seed(bytes([11]) + val(100.0), STATICS,
                                             *[step(1e-3, 100.0 + i * 1e-3) for i in range(6)],
                                             READ),
    # found by the 10^6-input campaign: a step refused (Discard) from a counted t0 a rounding off
    # the unit's time leaves the unit at the master's t0 (lastSuccessfulTime = t0), not at its own
    # time: the target's invariant, not the unit, was wrong
    "discard_on_counted_clock": plant_seed(bytes([11]) + val(100.0), STATICS,
                                           step(1e-3, 100.0), step(1e-3, 100.001),
                                           step(1.75e79, 100.002), READ, step(1e-3, 100.002),
                                           READ, init=False),
})
PLANT_SEEDS.update({name + "_fmi3": bytes([seed[0] | 32]) + seed[1:]
                    for name, seed in list(PLANT_SEEDS.items())})


# ---- the Model Exchange plant target (tests/fuzz/fuzz_plant_me_fmu.cpp): byte 0 flags (bit 0
# logging on, bit 1 initialise at once with fidelity 1 + bit 2, bit 4 SetTime relative to the
# target's time, bit 5 FMI 3), then operations: 0 SetReal any, 1 F[k] := 1000 * value, 2 SetInteger,
# 3 SetTime(value), 4 read outputs, 5 SetContinuousStates (a `how` byte: bit 0 one state
# (how >> 1) % 12 := value, else twelve int8 offsets / 1000; bits 6 and 7 both: a count of 11),
# 6 GetFMUstate, 7 SetFMUstate, 8 serialise round trip, 9 Reset, 10 Terminate, 11 initialise,
# 12 an event-mode call (selector % 6: enter event mode, update discrete states, enter
# continuous-time mode, completed integrator step, nominals, event indicators (n = bit 3)),
# 13 forces near the static ones, 14 explicit Euler (1 + byte % 16 steps of value),
# 15 GetDerivatives and SetDebugLogging.
def me_seed(*ops, logging=True, init=True, fidelity=2, relative_time=False, fmi3=False):
    flags = ((1 if logging else 0) | (2 if init else 0) | ((fidelity - 1) << 2) |
             (16 if relative_time else 0) | (32 if fmi3 else 0))
    return bytes([flags]) + b"".join(ops)


def event(selector):
    return bytes([12, selector])


def euler(steps, h):
    return bytes([14, steps - 1]) + val(h)


def set_state(index, x):
    """Op 5: state index (0..11: x .. yaw, x_dot .. yaw_dot) := x, the others kept."""
    return bytes([5, 1 | index << 1]) + val(x)


def nudge_states(*offsets, wrong_count=False):
    """Op 5: every state += offset / 1000 (twelve int8 offsets)."""
    return bytes([5, 0xC0 if wrong_count else 0]) + struct.pack("<12b", *offsets)


CONTINUOUS = event(2)
DERIVATIVES = bytes([15, 1])  # and logging on, every category
ME_SEEDS = {
    "euler_at_rest": me_seed(STATICS, CONTINUOUS, euler(16, 1e-3), READ, DERIVATIVES),
    "euler_massless": me_seed(STATICS, CONTINUOUS, euler(8, 1e-3), READ, fidelity=1),
    "free_fall": me_seed(CONTINUOUS, euler(16, 1e-2), READ, relative_time=True),
    "wobble": me_seed(forces_near_statics(50, -50, 30, 0, -20, 10), CONTINUOUS,
                      nudge_states(1, -2, 3, 4, -5, 6, 10, 0, -10, 20, 0, 5), euler(4, 1e-3), READ),
    "pitch_90": me_seed(STATICS, CONTINUOUS, set_state(4, math.pi / 2), DERIVATIVES, READ,
                        set_state(4, 0.0), DERIVATIVES, READ),
    "zero_length_leg": me_seed(STATICS, CONTINUOUS, set_state(2, 0.0), DERIVATIVES, READ),
    "nan_state": me_seed(CONTINUOUS, set_state(7, math.nan), set_state(0, math.inf),
                         DERIVATIVES, READ),
    "wrong_count": me_seed(CONTINUOUS, nudge_states(*[1] * 12, wrong_count=True), DERIVATIVES),
    "nan_force": me_seed(STATICS, CONTINUOUS, set_force(2, math.nan), DERIVATIVES, READ, STATICS,
                         DERIVATIVES, READ),
    "bad_time": me_seed(CONTINUOUS, bytes([3]) + val(math.nan), bytes([3]) + val(math.inf),
                        bytes([3]) + val(1e308), DERIVATIVES, READ),
    "event_cycle": me_seed(STATICS, CONTINUOUS, euler(2, 1e-3), *[event(k) for k in range(6)],
                           event(13), CONTINUOUS, euler(2, 1e-3), READ),
    "state_roundtrip": me_seed(STATICS, CONTINUOUS, euler(2, 1e-3), bytes([6]),
                               nudge_states(9, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0), euler(2, 1e-3),
                               READ, bytes([7]), READ, bytes([8, 0]), bytes([8, 1, 3, 0x55]), READ),
    "reset_terminate": me_seed(CONTINUOUS, euler(2, 1e-3), bytes([10]), DERIVATIVES, READ,
                               bytes([9]), bytes([11]) + val(5.0), CONTINUOUS, euler(2, 1e-3), READ),
    "not_initialised": me_seed(DERIVATIVES, nudge_states(*[0] * 12), bytes([3]) + val(1.0),
                               *[event(k) for k in range(6)], READ, init=False),
    "huge_step": me_seed(STATICS, CONTINUOUS, euler(3, 1e10), READ, DERIVATIVES),
    "logging": me_seed(bytes([15, 0]), bytes([15, 3]), bytes([15, 9]), set_force(0, math.inf),
                       CONTINUOUS, DERIVATIVES, READ),
}
ME_SEEDS.update({name + "_fmi3": bytes([seed[0] | 32]) + seed[1:]
                 for name, seed in list(ME_SEEDS.items())})


def main(argv):
    kinds = {"--fmu": "fmu", "--plant": "plant", "--me": "me"}
    kind = next((kinds[a] for a in argv if a in kinds), "api")
    args = [a for a in argv if a not in kinds]
    folder = {"api": "api", "fmu": "fmu", "plant": "plant_fmu", "me": "plant_me_fmu"}[kind]
    path = pathlib.Path(args[0] if args else f"tests/fuzz/corpus/{folder}")
    path.mkdir(parents=True, exist_ok=True)
    seeds = {"api": SEEDS, "fmu": FMU_SEEDS, "plant": PLANT_SEEDS, "me": ME_SEEDS}[kind]
    for name, data in seeds.items():
        (path / name).write_bytes(data)


if __name__ == "__main__":
    main(sys.argv[1:])

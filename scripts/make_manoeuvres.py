#!/usr/bin/env python3
"""Writes the vehicle manoeuvres of manoeuvres/ (manoeuvres/README.md says what each is, the models
and their sources): the specific force f and angular velocity w at the driver's or pilot's head
in the vehicle frame (x forward, y left, z up; f = (0, 0, +g) at rest), sampled at 100 Hz.

    python3 scripts/make_manoeuvres.py [--out DIR]     (default: manoeuvres/ of this repository)

Deterministic: the same numbers on every run (fixed-step integration, no randomness), so
tests/python/test_manoeuvres.py regenerates every file and compares it byte for byte.

The vehicles:
* aircraft_takeoff, aircraft_turn: point-mass aircraft kinematics. The take-off roll integrates
  m dv/dt = T - D - mu (m g - L) with a spool-up of the thrust, then rotates the aircraft about
  its centre of gravity at 3 deg/s to 15 deg nose up and lifts off into a 6 deg climb. The turn
  rolls into and out of a level coordinated turn at the standard rate (3 deg/s), the bank angle
  atan(v omega / g) at every instant, so that the specific force at the centre of gravity has no
  lateral part.
* car_braking: a point mass braking from 100 km/h at 8 m/s2 (the deceleration builds up over 0.3 s)
  to a stop.
* car_lane_change, car_slalom: the linear single-track ("bicycle") model with the parameters of
  Rajamani (2012), steered by a pure-pursuit driver (Coulter 1992) along the centre line of the
  ISO 3888-1 double lane change and of a slalom through cones 18 m apart.
The head is offset from the centre of gravity (HEAD_*): the lever-arm terms alpha x r and
w x (w x r) are in f.
"""
from __future__ import annotations

import argparse
import math
import pathlib

import numpy as np

G = 9.81
#: Output sample rate [Hz] and the integration step [s] of the models.
RATE = 100.0
STEP = 1e-3
HEADER = "t,f_x,f_y,f_z,w_x,w_y,w_z"
DEG = math.pi / 180

# Aircraft: representative of an A320-class twin (our values; see manoeuvres/README.md).
AIRCRAFT_MASS = 70000.0             # kg
WING_AREA = 122.6                   # m2
AIR_DENSITY = 1.225                 # kg/m3, sea level ISA
TAKEOFF_THRUST = 200e3              # N, both engines
SPOOL_UP = 4.0                      # s, idle to take-off thrust (modelled from zero)
ROLLING_FRICTION = 0.02             # dry concrete
DRAG_COEFFICIENT = 0.09             # take-off flaps, gear down
LIFT_COEFFICIENT_GROUND = 0.5       # on the runway, before rotation
ROTATION_SPEED = 75.0               # m/s, V_R
PITCH_RATE = 3.0 * DEG              # rad/s, rotation
PITCH_ATTITUDE = 15.0 * DEG         # rad, after rotation
LIFT_OFF_AFTER_ROTATION = 3.0       # s
CLIMB_ANGLE = 6.0 * DEG             # rad, flight path after lift-off
CLIMB_TRANSITION = 6.0              # s
HEAD_AIRCRAFT = np.array([14.0, 0.5, 1.5])  # m, pilot's head from the centre of gravity
TURN_SPEED = 100.0                  # m/s
TURN_RATE = 3.0 * DEG               # rad/s, standard rate
ROLL_IN = 5.0                       # s, also the roll-out
TURN_DURATION = 30.0                # s at the full bank angle: 90 deg of heading plus the rolls

# Car: linear single-track model, parameters of Rajamani (2012); the width is ours.
CAR_MASS = 1573.0                   # kg
CAR_YAW_INERTIA = 2873.0            # kg m2
CAR_FRONT = 1.1                     # m, centre of gravity to front axle
CAR_REAR = 1.58                     # m, centre of gravity to rear axle
CAR_FRONT_STIFFNESS = 2 * 80000.0   # N/rad, front axle (two tyres)
CAR_REAR_STIFFNESS = 2 * 80000.0    # N/rad, rear axle
CAR_WIDTH = 1.8                     # m
HEAD_CAR = np.array([0.0, 0.35, 0.6])  # m, driver's head from the centre of gravity
PREVIEW_TIME = 0.6                  # s, the pure-pursuit look-ahead distance over the speed
BRAKING_SPEED = 100 / 3.6           # m/s
BRAKING_DECELERATION = 8.0          # m/s2
BRAKING_BUILD_UP = 0.3              # s
LANE_CHANGE_SPEED = 60 / 3.6        # m/s
SLALOM_SPEED = 40 / 3.6             # m/s
SLALOM_PITCH = 18.0                 # m between cones
SLALOM_CONES = 8
SLALOM_AMPLITUDE = 1.45             # m, of the reference path at the cones


def smoothstep(x):
    """The quintic 0 -> 1 over x in [0, 1] with zero slope and curvature at both ends, and its
    first and second derivatives in x."""
    x = np.clip(x, 0.0, 1.0)
    return (x ** 3 * (10 - 15 * x + 6 * x * x), 30 * x * x * (1 - x) ** 2,
            60 * x * (1 - x) * (1 - 2 * x))


def rotation(axis: int, angle: np.ndarray) -> np.ndarray:
    """(n, 3, 3) rotations by angle about x (0), y (1) or z (2), right-handed."""
    c, s = np.cos(angle), np.sin(angle)
    r = np.zeros(angle.shape + (3, 3))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    r[..., axis, axis] = 1.0
    r[..., i, i], r[..., j, j], r[..., i, j], r[..., j, i] = c, c, -s, s
    return r


def at_head(attitude, accel_world, omega, alpha, head):
    """Specific force at the head in the body frame: R^T (a + g z) at the centre of gravity plus
    the lever-arm terms alpha x r + w x (w x r); attitude R (n, 3, 3) body to world."""
    f = np.einsum("nji,nj->ni", attitude, accel_world + np.array([0.0, 0.0, G]))
    r = np.broadcast_to(head, omega.shape)
    return f + np.cross(alpha, r) + np.cross(omega, np.cross(omega, r))


def rk4(rhs, state, t0, t1):
    """Fixed-step RK4 of state' = rhs(t, state) from t0 to t1 (STEP); the states at every step."""
    steps = int(round((t1 - t0) / STEP))
    out = np.empty((steps + 1, len(state)))
    out[0] = state
    for k in range(steps):
        t = t0 + k * STEP
        k1 = rhs(t, state)
        k2 = rhs(t + STEP / 2, state + STEP / 2 * k1)
        k3 = rhs(t + STEP / 2, state + STEP / 2 * k2)
        k4 = rhs(t + STEP, state + STEP * k3)
        state = state + STEP / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        out[k + 1] = state
    return out


def output_grid(duration: float) -> np.ndarray:
    return np.arange(int(round(duration * RATE)) + 1) / RATE


def decimate(fine: np.ndarray) -> np.ndarray:
    """The fine-step samples at the output times (RATE divides 1 / STEP)."""
    return fine[::int(round(1 / (STEP * RATE)))]


# --- aircraft ------------------------------------------------------------------------------------

def takeoff_thrust(t):
    return TAKEOFF_THRUST * smoothstep((t - 2.0) / SPOOL_UP)[0]


def ground_roll_acceleration(t, v):
    """dv/dt on the runway [m/s2]: thrust less drag and rolling friction on the unlifted weight."""
    q = 0.5 * AIR_DENSITY * v * v * WING_AREA
    lift = q * LIFT_COEFFICIENT_GROUND
    friction = ROLLING_FRICTION * max(AIRCRAFT_MASS * G - lift, 0.0) if t >= 2.0 else 0.0
    return (takeoff_thrust(t) - q * DRAG_COEFFICIENT - friction) / AIRCRAFT_MASS


def rotation_profile(t, t_rotate):
    """Nose-up pitch attitude [rad] and its first two derivatives: the rate rises over 1 s to
    PITCH_RATE, holds, and falls over 1 s to zero at PITCH_ATTITUDE."""
    hold = PITCH_ATTITUDE / PITCH_RATE - 1.0  # s at the full rate: ramps of 1 s each lose 0.5 s
    up, up_d, _ = smoothstep(t - t_rotate)
    down, down_d, _ = smoothstep(t - t_rotate - 1.0 - hold)
    rate = PITCH_RATE * (up - down)
    accel = PITCH_RATE * (up_d - down_d)
    # the attitude: the integral of the rate (the integral of a unit smoothstep ramp over 1 s
    # is the elapsed time less 1/2 once complete; in between it is x^4 (5/2 - 3 x + x^2))
    attitude = PITCH_RATE * (_ramp_integral(t - t_rotate) - _ramp_integral(t - t_rotate - 1.0 - hold))
    return attitude, rate, accel


def _ramp_integral(x):
    x = np.asarray(x, dtype=float)
    inside = np.clip(x, 0.0, 1.0)
    return np.where(x >= 1.0, x - 0.5, inside ** 4 * (2.5 - 3 * inside + inside * inside))


def aircraft_takeoff():
    """(t, f, w): rest, take-off roll, rotation, lift-off and the start of the climb."""
    def rhs(t, s):
        return np.array([ground_roll_acceleration(t, s[0])])
    roll = rk4(rhs, np.array([0.0]), 0.0, 60.0)[:, 0]
    t_rotate = np.argmax(roll >= ROTATION_SPEED) * STEP
    t_lift = t_rotate + LIFT_OFF_AFTER_ROTATION
    t = output_grid(t_lift + CLIMB_TRANSITION + 6.0)
    # along the path: the ground roll's speed until lift-off, then thrust less drag less the
    # weight's component along the climb path (point mass)
    def airborne(tt, s):
        gamma = CLIMB_ANGLE * smoothstep((tt - t_lift) / CLIMB_TRANSITION)[0]
        drag = 0.5 * AIR_DENSITY * s[0] ** 2 * WING_AREA * DRAG_COEFFICIENT
        return np.array([(takeoff_thrust(tt) - drag) / AIRCRAFT_MASS - G * math.sin(gamma)])
    lift_step = int(round(t_lift / STEP))
    climb = rk4(airborne, np.array([roll[lift_step]]), t_lift, t[-1])[:, 0]
    v = decimate(np.concatenate([roll[:lift_step], climb]))
    dv = np.array([ground_roll_acceleration(x, s) if x < t_lift else airborne(x, [s])[0]
                   for x, s in zip(t, v)])
    gamma, gamma_d, _ = smoothstep((t - t_lift) / CLIMB_TRANSITION)
    gamma, gamma_d = CLIMB_ANGLE * gamma, CLIMB_ANGLE * gamma_d / CLIMB_TRANSITION
    accel = np.column_stack([dv * np.cos(gamma) - v * gamma_d * np.sin(gamma), np.zeros_like(t),
                             dv * np.sin(gamma) + v * gamma_d * np.cos(gamma)])
    nose_up, nose_up_rate, nose_up_accel = rotation_profile(t, t_rotate)
    # right-handed about y (left): a nose-up attitude is a negative pitch angle
    attitude = rotation(1, -nose_up)
    omega = np.column_stack([np.zeros_like(t), -nose_up_rate, np.zeros_like(t)])
    alpha = np.column_stack([np.zeros_like(t), -nose_up_accel, np.zeros_like(t)])
    return t, at_head(attitude, accel, omega, alpha, HEAD_AIRCRAFT), omega


def aircraft_turn():
    """(t, f, w): level flight, roll into a level coordinated left turn at the standard rate, the
    turn, roll out, level flight; bank = atan(v omega / g) throughout."""
    t_in, t_out = 5.0, 5.0 + ROLL_IN + TURN_DURATION
    t = output_grid(t_out + ROLL_IN + 5.0)
    bank_full = math.atan(TURN_SPEED * TURN_RATE / G)
    s_in, d_in, dd_in = smoothstep((t - t_in) / ROLL_IN)
    s_out, d_out, dd_out = smoothstep((t - t_out) / ROLL_IN)
    bank = bank_full * (s_in - s_out)                       # magnitude, left wing down
    bank_d = bank_full * (d_in - d_out) / ROLL_IN
    bank_dd = bank_full * (dd_in - dd_out) / ROLL_IN ** 2
    turn_rate = G * np.tan(bank) / TURN_SPEED               # coordinated: omega = g tan(bank) / v
    turn_accel = G / np.cos(bank) ** 2 * bank_d / TURN_SPEED
    heading = np.concatenate([[0.0], np.cumsum((turn_rate[1:] + turn_rate[:-1]) / 2 / RATE)])
    phi, phi_d, phi_dd = -bank, -bank_d, -bank_dd           # left wing down: negative about x
    attitude = np.einsum("nij,njk->nik", rotation(2, heading), rotation(0, phi))
    omega = np.column_stack([phi_d, turn_rate * np.sin(phi), turn_rate * np.cos(phi)])
    alpha = np.column_stack([phi_dd, turn_accel * np.sin(phi) + turn_rate * phi_d * np.cos(phi),
                             turn_accel * np.cos(phi) - turn_rate * phi_d * np.sin(phi)])
    centripetal = TURN_SPEED * turn_rate
    accel = np.column_stack([-centripetal * np.sin(heading), centripetal * np.cos(heading),
                             np.zeros_like(t)])
    return t, at_head(attitude, accel, omega, alpha, HEAD_AIRCRAFT), omega


# --- car -----------------------------------------------------------------------------------------

def car_braking():
    """(t, f, w): cruising at BRAKING_SPEED, braking at BRAKING_DECELERATION (built up over
    BRAKING_BUILD_UP) to a stop, standing. A point mass: no pitch, no rotation."""
    t_brake = 2.0
    # the speed lost during the build-up is half of BRAKING_DECELERATION * BRAKING_BUILD_UP
    t_stop = t_brake + BRAKING_BUILD_UP / 2 + BRAKING_SPEED / BRAKING_DECELERATION
    t = output_grid(math.ceil(t_stop) + 3.0)
    decel = BRAKING_DECELERATION * smoothstep((t - t_brake) / BRAKING_BUILD_UP)[0]
    decel[t >= t_stop] = 0.0
    f = np.column_stack([-decel, np.zeros_like(t), np.full_like(t, G)])
    return t, f, np.zeros_like(f)


def single_track_rhs(speed, steer_of):
    """The linear single-track model at constant forward speed: state (X, Y, heading, v_y, r)
    in the road frame and the body; steer_of(state) is the front wheel angle [rad]."""
    def rhs(_t, s):
        _, _, heading, vy, r = s
        steer = steer_of(s)
        front = CAR_FRONT_STIFFNESS * (steer - (vy + CAR_FRONT * r) / speed)
        rear = CAR_REAR_STIFFNESS * (-(vy - CAR_REAR * r) / speed)
        return np.array([speed * math.cos(heading) - vy * math.sin(heading),
                         speed * math.sin(heading) + vy * math.cos(heading), r,
                         (front + rear) / CAR_MASS - speed * r,
                         (CAR_FRONT * front - CAR_REAR * rear) / CAR_YAW_INERTIA])
    return rhs


def pure_pursuit(path, speed):
    """Coulter's pure pursuit: steer for the arc through the path point PREVIEW_TIME * speed
    ahead (a kinematic wheelbase of CAR_FRONT + CAR_REAR)."""
    look_ahead = PREVIEW_TIME * speed
    wheelbase = CAR_FRONT + CAR_REAR

    def steer(s):
        x, y, heading = s[0], s[1], s[2]
        target_x = x + look_ahead
        dx, dy = target_x - x, path(target_x) - y
        lateral = -math.sin(heading) * dx + math.cos(heading) * dy
        return math.atan(2 * wheelbase * lateral / (dx * dx + dy * dy))
    return steer


def drive(path, speed, x_start, x_end):
    """(t, f, w) of the single-track car driven along path(X) from X = x_start to x_end."""
    steer = pure_pursuit(path, speed)
    rhs = single_track_rhs(speed, steer)
    duration = math.floor((x_end - x_start) / speed * RATE) / RATE
    fine = rk4(rhs, np.array([x_start, path(x_start), 0.0, 0.0, 0.0]), 0.0, duration)
    states = decimate(fine)
    rates = np.array([rhs(0.0, s) for s in states])
    vy, r, vy_d, r_d = states[:, 3], states[:, 4], rates[:, 3], rates[:, 4]
    t = np.arange(states.shape[0]) / RATE
    zero = np.zeros_like(t)
    # body-frame acceleration of the centre of gravity at constant forward speed, as "world"
    # with the identity attitude: at_head adds gravity and the lever arm of the head
    accel_body = np.column_stack([-r * vy, vy_d + r * speed, zero])
    omega = np.column_stack([zero, zero, r])
    alpha = np.column_stack([zero, zero, r_d])
    f = at_head(np.broadcast_to(np.eye(3), (t.size, 3, 3)), accel_body, omega, alpha, HEAD_CAR)
    return t, f, omega


def iso3888_1_lanes(vehicle_width=CAR_WIDTH):
    """The ISO 3888-1 double lane change as (x_start, x_end, y_right, y_left) cone lanes [m]: the
    right cone lines of sections 1 and 3 are 3.5 m apart, those of sections 1 and 5 aligned."""
    width_1, width_3, width_5 = (k * vehicle_width + 0.25 for k in (1.1, 1.2, 1.3))
    right = -width_1 / 2
    return [(0.0, 15.0, right, right + width_1), (45.0, 70.0, right + 3.5, right + 3.5 + width_3),
            (95.0, 125.0, right, right + width_5)]


def lane_change_path(x):
    """The reference: the centre lines of the three lanes joined by smoothsteps over sections 2
    and 4."""
    (_, _, r1, l1), (_, _, r3, l3), (_, _, r5, l5) = iso3888_1_lanes()
    c1, c3, c5 = (r1 + l1) / 2, (r3 + l3) / 2, (r5 + l5) / 2
    return (c1 + (c3 - c1) * smoothstep((x - 15.0) / 30.0)[0]
            + (c5 - c3) * smoothstep((x - 70.0) / 25.0)[0])


def car_lane_change():
    return drive(lambda x: float(lane_change_path(x)), LANE_CHANGE_SPEED, -40.0, 165.0)


def slalom_cones():
    """The cones' X [m] (on the line Y = 0); the car passes the first on its left."""
    return SLALOM_PITCH * np.arange(SLALOM_CONES)


def slalom_path(x):
    """SLALOM_AMPLITUDE cos(pi X / pitch) around the cones (left of the first), eased in and out
    over one pitch before the first cone and after the last."""
    last = SLALOM_PITCH * (SLALOM_CONES - 1)
    ease = (smoothstep((x + 1.5 * SLALOM_PITCH) / SLALOM_PITCH)[0]
            - smoothstep((x - last - 0.5 * SLALOM_PITCH) / SLALOM_PITCH)[0])
    return SLALOM_AMPLITUDE * ease * math.cos(math.pi * x / SLALOM_PITCH)


def car_slalom():
    last = SLALOM_PITCH * (SLALOM_CONES - 1)
    return drive(slalom_path, SLALOM_SPEED, -60.0, last + 60.0)


MANOEUVRES = {
    "aircraft_takeoff": aircraft_takeoff,
    "aircraft_turn": aircraft_turn,
    "car_braking": car_braking,
    "car_lane_change": car_lane_change,
    "car_slalom": car_slalom,
}


def csv_text(t, f, w) -> str:
    """The rows as text: 12 significant digits, '.' decimals whatever the locale."""
    rows = np.column_stack([t, f, w]) + 0.0  # + 0.0: no "-0"
    lines = [HEADER] + [",".join(format(float(x), ".12g") for x in row) for row in rows]
    return "\n".join(lines) + "\n"


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=pathlib.Path,
                        default=pathlib.Path(__file__).resolve().parents[1] / "manoeuvres")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    for name, make in MANOEUVRES.items():
        t, f, w = make()
        (args.out / f"{name}.csv").write_text(csv_text(t, f, w))
        print(f"{name}: {t.size} samples, {t[-1]:g} s, |f - g z| max "
              f"{np.max(np.linalg.norm(f - [0, 0, G], axis=1)):.2f} m/s2, |w| max "
              f"{np.max(np.linalg.norm(w, axis=1)) / DEG:.1f} deg/s")


if __name__ == "__main__":
    main()

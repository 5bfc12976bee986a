#!/usr/bin/env python3
"""Control design on the linearised plant (docs/control.md): the open-loop eigenvalues at the
home pose under its static forces (Platform.linearize, both fidelities), an LQR state feedback on
the six leg forces designed on the full model's (A, B) with scipy, and that controller closed
around the nonlinear plant FMU in fmpy on a scene, beside today's PD controller unit
(scripts/closed_loop.py) on the same scene.

The LQR loop: the inverse unit's forces F_ff (feed-forward, as for PD) plus
    F = F_ff - K (x - x_ref),   x = (pose, pose rates) of the plant, x_ref = the scene's,
with K the discrete LQR gain of the plant sampled at the communication step h (forces held over
a step: Ad = exp(A h), Bd = int_0^h exp(A s) ds B, from the exponential of [[A, B], [0, 0]] h),
K = (R + Bd^T P Bd)^-1 Bd^T P Ad with P from the discrete Riccati equation, at home;
Q = diag(1/position_tol^2 (x3), 1/angle_tol^2 (x3), 1/speed_tol^2 (x3), 1/rate_tol^2 (x3)),
R = I / force_tol^2 (Bryson's rule). A continuous design ignores the sampling: its fastest poles
(-1e5 1/s at these weights) are far beyond 1/h, and the sampled loop diverges.

usage: control_design.py [--scene combined] [--duration 4] [--step 0.001] [--fmus build/fmus/2.0]
                         [--platform FILE.json [--scale-to-ranges]]

A scene with a move (scenes/move_line.json) runs the move planned by stewart.move on the machine
(scenes.trajectory), in both loops, and holds its goal after it.

With --platform: the machine's home pose, its parameters in the units, the scene about its home,
the PD gains of closed_loop.machine_gains and FORCE_TOL scaled as the thesis' (1e3 N, about six
times its largest static leg force at home) to the machine's largest static leg force.
"""
import argparse
import pathlib

import numpy as np
import scipy.linalg

import closed_loop
import scenes
import stewart

ROOT = pathlib.Path(__file__).resolve().parents[1]
HOME = np.array([0, 0, 0.5, 0, 0, 0.0])
# Bryson's rule: the deviations that cost as much as each other.
POSITION_TOL, ANGLE_TOL = 1e-5, 1e-5   # [m], [rad]
SPEED_TOL, RATE_TOL = 1e-3, 1e-3       # [m/s], [rad/s]
FORCE_TOL = 1e3                        # [N]


def open_loop(platform, fidelity, home=HOME):
    """Eigenvalues of A at home, at rest, under the static forces."""
    return np.linalg.eigvals(platform.linearize(home, fidelity=fidelity).A)


def sampled(A, B, h):
    """(Ad, Bd): the plant over one step h with the forces held."""
    n, m = B.shape
    M = np.zeros((n + m, n + m))
    M[:n, :n], M[:n, n:] = A * h, B * h
    E = scipy.linalg.expm(M)
    return E[:n, :n], E[:n, n:]


def lqr(A, B, h, force_tol=FORCE_TOL):
    """The discrete LQR gain K (u = -K x) of (A, B) sampled at h, and Ad, Bd."""
    Q = np.diag([1 / POSITION_TOL**2] * 3 + [1 / ANGLE_TOL**2] * 3 + [1 / SPEED_TOL**2] * 3 +
                [1 / RATE_TOL**2] * 3)
    R = np.eye(6) / force_tol**2
    Ad, Bd = sampled(A, B, h)
    P = scipy.linalg.solve_discrete_are(Ad, Bd, Q, R)
    return np.linalg.solve(R + Bd.T @ P @ Bd, Bd.T @ P @ Ad), Ad, Bd


def run_lqr(K, scene, duration, h, fmus, fidelity=2, machine=None, platform=None):
    """The LQR loop around the plant FMU; the same shape of result as closed_loop.run.
    machine: the platform's FMU start values (None: the thesis platform); platform: the same
    machine, on which a scene's move is planned (scenes.trajectory; duration None: the move's
    own)."""
    machine = machine or {}
    t, cue, cue_dot, cue_ddot = scenes.trajectory(scene, platform, h, duration)
    n = len(t) - 1
    start = {f"{p}0": v for p, v in zip(closed_loop.POSE, cue[0])}
    start.update({f"{p}_dot0": v for p, v in zip(closed_loop.POSE, cue_dot[0])})
    fmus = pathlib.Path(fmus)
    inverse = closed_loop.Unit(fmus / "StewartPlatform.fmu", "inverse",
                               {"fidelity": fidelity, "derivatives": 1, **machine})
    plant = closed_loop.Unit(fmus / "StewartPlant.fmu", "plant",
                             {"fidelity": fidelity, **start, **machine})
    rates = [f"{p}_dot" for p in closed_loop.POSE]
    pose, force = np.zeros((n + 1, 6)), np.zeros((n + 1, 6))
    try:
        for j in range(n + 1):
            inverse.set(closed_loop.POSE + list(scenes.DOT) + list(scenes.DDOT),
                        [*cue[j], *cue_dot[j], *cue_ddot[j]])
            feed_forward = inverse.get(closed_loop.legs("F"))
            x = plant.get(closed_loop.POSE + rates)
            error = x - np.concatenate([cue[j], cue_dot[j]])
            force[j] = feed_forward - K @ error
            pose[j] = x[:6]
            if j == n:
                break
            plant.set(closed_loop.legs("F"), force[j])
            for unit in (inverse, plant):
                unit.step(t[j], h)
    finally:
        inverse.free()
        plant.free()
    return {"t": t, "cue": cue, "pose": pose, "force": force}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="combined")
    parser.add_argument("--duration", type=float,
                        help="[s] (default: 4, a move scene's: the move's own and its hold)")
    parser.add_argument("--step", type=float, default=1e-3, help="communication step [s]")
    parser.add_argument("--fmus", default=str(ROOT / "build" / "fmus" / "2.0"))
    scenes.add_platform_arguments(parser)
    args = parser.parse_args()
    scene, platform, machine = scenes.on_platform(scenes.load(args.scene), args)
    if args.duration is None and "move" not in scene:
        args.duration = 4.0
    home, force_tol, (kp, kd) = HOME, FORCE_TOL, (closed_loop.THESIS_KP, closed_loop.THESIS_KD)
    if args.platform:
        home = platform.check().home
        static = np.abs(platform.inverse(home).force).max()
        thesis_static = np.abs(stewart.Platform().inverse(HOME).force).max()
        force_tol = FORCE_TOL * static / thesis_static
        kp, kd = closed_loop.machine_gains(platform)
    np.set_printoptions(precision=3, linewidth=110)
    for fidelity in ("massless", "full"):
        ev = open_loop(platform, fidelity, home)
        ev = ev[np.argsort(-ev.real)]
        print(f"open loop, {fidelity}: eigenvalues of A at home under the static forces [1/s]:")
        print("  " + ", ".join(f"{e.real:+.4g}{e.imag:+.4g}j" for e in ev))
    lin = platform.linearize(home, fidelity="full")
    K, Ad, Bd = lqr(lin.A, lin.B, args.step, force_tol)
    closed = np.log(np.linalg.eigvals(Ad - Bd @ K).astype(complex)) / args.step
    print(f"LQR on the full model sampled at {args.step:g} s: closed-loop eigenvalues as rates "
          "log(z)/h [1/s], slowest first:")
    closed = closed[np.argsort(-closed.real)]
    print("  " + ", ".join(f"{e.real:+.4g}{e.imag:+.4g}j" for e in closed))
    # the PD on the legs as a state feedback of the same linear model: F = -kp dL - kd dL_dot,
    # dL = C_L dx, dL_dot = C_Ldot dx (rows 12-17 and 18-23 of C)
    K_pd = kp * lin.C[12:18] + kd * lin.C[18:24]
    pd = np.log(np.linalg.eigvals(Ad - Bd @ K_pd).astype(complex)) / args.step
    pd = pd[np.argsort(-pd.real)]
    gains = f"kp {kp:.4g} N/m, kd {kd:.4g} N s/m"
    print(f"PD ({gains}) on the same sampled model: closed-loop rates [1/s]:")
    print("  " + ", ".join(f"{e.real:+.4g}{e.imag:+.4g}j" for e in pd))
    try:
        lqr_run = run_lqr(K, scene, args.duration, args.step, args.fmus, machine=machine,
                          platform=platform)
        pd_run, _ = closed_loop.run(scene, args.duration, args.step, kp, kd, fmus=args.fmus,
                                    machine=machine, platform=platform)
    except ValueError as e:  # SceneError, stewart.MoveError: the message names the cause
        raise SystemExit(f"control_design: {e}") from None
    duration = lqr_run["t"][-1]
    for name, run in ((f"PD (controller unit, {gains})", pd_run),
                      ("LQR (state feedback on the linear model)", lqr_run)):
        position, angle = closed_loop.tracking_error(run)
        peak = np.abs(run["force"]).max()
        print(f"{name}: {scene['name']} over {duration:g} s at h = {args.step:g} s: "
              f"tracking error max {position:.3e} m, {angle:.3e} rad; peak force {peak:.4g} N")


if __name__ == "__main__":
    main()

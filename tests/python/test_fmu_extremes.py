"""The unit at the edges (issue 6, FMU side), FMI 2 and FMI 3 through fmpy: near the yaw singularity,
at a Cardan lock, at and beyond the stroke limits, unreachable poses, communication steps from 1e-9 s
to 10 s, variable, zero, negative and non-advancing steps, parameters at the extremes, Newton at its
limits, and a long run.

References are independent of the unit: the numpy closed forms of reference.py (static equilibrium
of the massless-leg platform, the leg Jacobian and its condition number, leg lengths) and stewart-solve
(the library's command-line tool) for moving poses. Fidelity-2 variants skip while the build does not
solve the full model (detected at run time).
"""
import ctypes
import math
import os
import resource

import numpy as np
import pytest

from fmu_support import (VERSIONS, REAL_OUTPUTS, L, L_DOT, L_DDOT, F, POSE, POSE_DOT, POSE_DDOT,
                         OK, WARNING, DISCARD, ERROR, Unit, backward_fd, reference_matrix,
                         require_fidelity, stewart_solve, every_leg, opened_unit)
from reference import (BETA, G, M_PLATFORM, TAU, condition, geometry, leg_axes, rotation,
                       static_forces)
from reference import lengths as closed_form_lengths

WARN_DEFAULT, SINGULAR_DEFAULT = 1e3, 1e10
WIDE_STROKE = every_leg(stroke_min=0.01, stroke_max=10.0)


# ---------------------------------------------------------------- poses and manoeuvres

def yawed(yaw, z=0.5):
    return [0.0, 0.0, z, 0.0, 0.0, yaw]


def combined(t, scale=1.0):
    """A combined heave/roll/pitch/yaw manoeuvre (thesis amplitudes, 5 rad/s, different phases):
    pose, first and second derivatives, each (n, 6)."""
    t = np.atleast_1d(np.asarray(t, dtype=float))
    w = 5.0
    amp = np.array([0.0, 0.0, 0.04 * scale, math.pi / 18, math.pi / 18, math.pi / 18])
    phase = np.array([0.0, 0.0, 0.0, 0.5, 1.0, 1.5])
    q = amp * np.sin(w * t[:, None] + phase)
    qd = amp * w * np.cos(w * t[:, None] + phase)
    qdd = -amp * w * w * np.sin(w * t[:, None] + phase)
    q[:, 2] += 0.5 * scale
    return q, qd, qdd


def assert_within(got, ref, atol):
    """|got - ref| <= atol element-wise (atol may be an array)."""
    got, ref = np.asarray(got, dtype=float), np.asarray(ref, dtype=float)
    bad = ~(np.abs(got - ref) <= atol)
    assert not np.any(bad), (f"beyond tolerance at {np.flatnonzero(bad)}: got {got[bad]}, "
                             f"reference {ref[bad]}, atol {np.broadcast_to(atol, got.shape)[bad]}")


def unit_time(u):
    """The unit's current time: the variable `time` (FMI 3), or lastSuccessfulTime (FMI 2)."""
    if "time" in u.vr:
        return u.get(["time"])[0]
    value = ctypes.c_double()
    assert u.dll.fmi2GetRealStatus(u.c, 2, ctypes.byref(value)) == OK  # fmi2LastSuccessfulTime
    return value.value


def new_unit(version, **params):
    u = Unit(version)
    s = u.init(**params)
    assert s in (OK, WARNING), u.messages
    return u


def step_messages(u, status):
    return [m for s, c, m in u.messages if s == status]


# ---------------------------------------------------------------- singularity

@pytest.mark.parametrize("version", VERSIONS)
def test_yaw_singularity_sweep(version):
    """Toward yaw = 90 deg (z = 0.5 m) the condition number grows like 1/e (e the distance in rad),
    the forces follow the massless closed form and grow like 1/e, the unit warns (status 2) as soon
    as condition > warn_condition, long before the forces lose accuracy, and at yaw = pi/2 exactly
    it returns Discard, keeps the last valid outputs, and the next good pose is solved."""
    # zero rates: every pose is static; a stroke wide enough not to interfere
    u = new_unit(version, fidelity=1, derivatives=1, **WIDE_STROKE)
    try:
        distances = [10.0 ** -k for k in range(1, 9)]
        t, h = 0.0, 0.01
        prev_cond, scaled, first_warned = 0.0, [], None
        for e in distances:
            pose = yawed(math.pi / 2 - e)
            u.set_values(dict(zip(POSE, pose)))
            s = u.do_step(t, h)
            t += h
            cond, status = u.get(["condition", "status"])
            forces = u.get_reals(F)
            ref_cond = condition(pose)
            np.testing.assert_allclose(cond, ref_cond, rtol=1e-6)
            assert cond > prev_cond
            prev_cond = cond
            ref = static_forces(pose)
            # the closed form itself loses about cond * eps: compare within that
            tol = max(1e-12, 50 * cond * np.finfo(float).eps) * np.max(np.abs(ref))
            np.testing.assert_allclose(forces, ref, rtol=0, atol=tol)
            if cond > WARN_DEFAULT:
                assert s == WARNING and status == 2, (e, cond, s, status)
                if first_warned is None:
                    first_warned = e
                    # when the warning comes on, the forces are still right to 1e-12
                    np.testing.assert_allclose(forces, ref, rtol=1e-12 * cond)
                    assert any("condition" in m for m in step_messages(u, WARNING))
            else:
                assert s == OK and status == 0, (e, cond, s, status)
            scaled.append(np.max(np.abs(forces)) * e)
        assert first_warned is not None and prev_cond > 1e7
        # forces grow like 1/e: F e tends to a constant
        assert abs(scaled[-1] - scaled[-2]) < 1e-3 * scaled[-1]
        assert abs(scaled[-2] - scaled[-3]) < 1e-3 * scaled[-1]

        last = u.get_reals(REAL_OUTPUTS)
        u.set(yaw=math.pi / 2)
        assert u.do_step(t, h) == DISCARD
        assert u.get(["status"])[0] == 3
        assert u.get_reals(REAL_OUTPUTS).tobytes() == last.tobytes()
        discard = step_messages(u, DISCARD)
        assert discard and "1.5708" in discard[-1] and "singular" in discard[-1], discard
        u.set(yaw=0.3)
        assert u.do_step(t, h) == OK
        np.testing.assert_allclose(u.get_reals(F), static_forces(yawed(0.3)), rtol=1e-12)
        np.testing.assert_allclose(u.get_reals(L), closed_form_lengths(yawed(0.3)), rtol=1e-14)
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_condition_thresholds_are_parameters(version):
    """warn_condition and singular_condition decide Warning and Discard, against the condition
    number computed here."""
    u = new_unit(version, fidelity=1, derivatives=1, warn_condition=50.0, singular_condition=1e4,
                 **WIDE_STROKE)
    try:
        t = 0.0
        for e in (0.5, 0.1, 0.03, 1e-2, 1e-3, 1e-4, 1e-5):
            pose = yawed(math.pi / 2 - e)
            c = condition(pose)
            if abs(math.log(c / 50.0)) < 1e-6 or abs(math.log(c / 1e4)) < 1e-6:
                continue  # too close to a threshold to decide independently
            before = u.get_reals(REAL_OUTPUTS)
            u.set(yaw=pose[5])
            s = u.do_step(t, 0.1)
            if c > 1e4:
                assert s == DISCARD and u.get(["status"])[0] == 3
                assert u.get_reals(REAL_OUTPUTS).tobytes() == before.tobytes()
            else:
                t += 0.1
                assert s == (WARNING if c > 50 else OK), (e, c, s)
                assert u.get(["status"])[0] == (2 if c > 50 else 0)
    finally:
        u.free()


def cardan_lock_pose(pitch=0.6, length=0.45):
    """A pose with leg 1 along the tangential cross arm of its base Cardan (the base arm is
    s = (-sin beta, cos beta, 0), model.md section 2): that joint locks."""
    a, b = geometry()
    s = np.array([-math.sin(BETA[0]), math.cos(BETA[0]), 0.0])
    R = rotation(0.0, pitch, 0.0)
    p = a[0] + length * s - R @ b[0]
    return [p[0], p[1], p[2], 0.0, pitch, 0.0]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("fidelity", [1, 2])
def test_cardan_lock(version, fidelity):
    """Leg 1 lies along its base Cardan's cross arm. The massless model has no Cardan joints: its leg
    Jacobian is regular there and the forces follow the closed form. The full model must either
    solve it or say it cannot (Warning with status 2, or Discard), never Inf or NaN."""
    require_fidelity(version, fidelity)
    pose = cardan_lock_pose()
    n, _ = leg_axes(pose)
    assert abs(abs(n[0] @ np.array([0.0, 1.0, 0.0])) - 1) < 1e-12  # leg 1 along the arm
    u = new_unit(version, fidelity=fidelity, derivatives=1)
    try:
        before = u.get_reals(REAL_OUTPUTS)
        u.set_values(dict(zip(POSE, pose)))
        s = u.do_step(0.0, 0.1)
        out = u.get_reals(REAL_OUTPUTS)
        assert np.all(np.isfinite(out))
        status = u.get(["status"])[0]
        if s != DISCARD:
            np.testing.assert_allclose(u.get_reals(L), closed_form_lengths(pose), rtol=1e-13)
        if fidelity == 1:
            assert s in (OK, WARNING)
            assert condition(pose) < 1e3
            np.testing.assert_allclose(u.get_reals(F), static_forces(pose), rtol=1e-10)
        else:
            assert (s == WARNING and status == 2) or (s == DISCARD and status == 3), (s, status)
            if s == DISCARD:
                assert out.tobytes() == before.tobytes()
                assert step_messages(u, DISCARD)
    finally:
        u.free()


# ---------------------------------------------------------------- workspace edge

def home_height_for_length(length, rb=0.5, rt=0.5):
    """z at which every leg of the unrotated platform has this length (all legs equal there)."""
    d = closed_form_lengths([0, 0, 0, 0, 0, 0], rb, rt)[0]  # horizontal distance |b - a|
    return math.sqrt(length ** 2 - d ** 2)


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("limit", ["stroke_min", "stroke_max"])
def test_stroke_edges(version, limit):
    """Just inside a stroke limit: OK, status 0. Just outside: Warning, status 1, a message naming
    the leg and its length, and values still right. The next valid pose: OK, status 0."""
    stroke = {"stroke_min": 0.52, "stroke_max": 0.58}
    u = new_unit(version, fidelity=1, derivatives=1, **every_leg(**stroke))
    try:
        edge = stroke[limit]
        sign = 1 if limit == "stroke_max" else -1
        t = 0.0
        for delta, expect in ((-1e-9, OK), (1e-9, WARNING), (5e-2, WARNING)):
            length = edge + sign * delta
            pose = [0, 0, home_height_for_length(length), 0, 0, 0]
            u.set_values(dict(zip(POSE, pose)))
            assert u.do_step(t, 0.1) == expect, (delta, u.messages[-3:])
            t += 0.1
            assert u.get(["status"])[0] == (1 if expect == WARNING else 0)
            np.testing.assert_allclose(u.get_reals(L), length, rtol=1e-12)
            np.testing.assert_allclose(u.get_reals(F), static_forces(pose), rtol=1e-12)
            if expect == WARNING:
                w = step_messages(u, WARNING)[-1]
                assert "stroke" in w and "L[" in w and f"{edge:g}" in w, w
        u.set(z=home_height_for_length(0.55))
        assert u.do_step(t, 0.1) == OK and u.get(["status"])[0] == 0
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("pose", [[2.0, 0, 0.5, 0, 0, 0], [0, 0, 3.0, 0, 0, 0],
                                  [0, 0, 0.1, 0, 0, 0], [0, 0, 0.5, 1.2, 0, 0],
                                  [1e3, 0, 0.5, 0, 0, 0], [0, 0, 1e6, 0, 0, 0]])
def test_poses_beyond_the_stroke(version, pose):
    """Poses no real actuator reaches (2 m aside, 3 m up, the plate nearly flat on the base, rolled
    69 deg, 1 km aside, 1000 km up) are geometrically solvable: Warning with status 1 (2 where the
    condition number, computed here, exceeds warn_condition), the closed-form lengths and forces;
    or, beyond singular_condition, Discard. The next valid pose is solved."""
    u = new_unit(version, fidelity=1, derivatives=1)
    try:
        before = u.get_reals(REAL_OUTPUTS)
        u.set_values(dict(zip(POSE, pose)))
        s = u.do_step(0.0, 0.1)
        cond = condition(pose)
        assert np.any((closed_form_lengths(pose) > 0.7) | (closed_form_lengths(pose) < 0.4))
        if cond > 10 * SINGULAR_DEFAULT:
            assert s == DISCARD and u.get(["status"])[0] == 3
            assert u.get_reals(REAL_OUTPUTS).tobytes() == before.tobytes()
        elif cond < 0.1 * SINGULAR_DEFAULT:
            assert s == WARNING
            assert u.get(["status"])[0] == (2 if cond > WARN_DEFAULT else 1)
            np.testing.assert_allclose(u.get_reals(L), closed_form_lengths(pose), rtol=1e-13)
            ref = static_forces(pose)
            np.testing.assert_allclose(u.get_reals(F), ref, rtol=0,
                                       atol=1e-13 * max(cond, 1e3) * np.max(np.abs(ref)))
        u.set_values(dict(zip(POSE, yawed(0.0))))
        assert u.do_step(0.1, 0.1) == OK
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("leg", [0, 1])
def test_unreachable_pose_names_the_pose(version, leg):
    """A pose that puts platform point k on base point k (closed form: L_k = 0) has no leg
    direction: Discard, status 3, last valid outputs kept, a message naming the pose and the leg;
    the next valid pose is solved."""
    # yaw that maps tau_k onto beta_k, at z = 0
    yaw = (BETA[leg] - TAU[leg] + math.pi) % (2 * math.pi) - math.pi
    pose = [0.0, 0.0, 0.0, 0.0, 0.0, yaw]
    lengths = closed_form_lengths(pose)
    assert lengths[leg] < 1e-12
    first = int(np.argmax(lengths < 1e-12))  # the leg the message names
    u = new_unit(version, fidelity=1)
    try:
        before = u.get_reals(REAL_OUTPUTS)
        u.set_values(dict(zip(POSE, pose)))
        assert u.do_step(0.0, 0.1) == DISCARD
        assert u.get(["status"])[0] == 3
        assert u.get_reals(REAL_OUTPUTS).tobytes() == before.tobytes()
        m = step_messages(u, DISCARD)[-1]
        assert f"{yaw:g}" in m and f"leg {first + 1}" in m, m
        u.set(z=0.5, yaw=0.1)
        assert u.do_step(0.0, 0.1) == OK
        np.testing.assert_allclose(u.get_reals(L), closed_form_lengths(yawed(0.1)), rtol=1e-14)
    finally:
        u.free()


# ---------------------------------------------------------------- communication steps

STEPS = [1e-9, 1e-6, 1e-3, 0.1, 1.0, 10.0]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("h", STEPS)
def test_step_sizes_with_input_derivatives(version, h):
    """derivatives = 1, inputs set at every communication point t_j = j h of a combined manoeuvre:
    the outputs at t_j equal the library's (stewart-solve) at the same pose and derivatives; after
    doStep(t_j, h) they belong to the Taylor pose at t_j + h (lengths: closed form), or the step is
    discarded with the outputs kept."""
    n = 5
    ts = h * np.arange(n)
    q, qd, qdd = combined(ts)
    ref = reference_matrix(stewart_solve(np.arange(n), q, qd, qdd))
    u = new_unit(version, fidelity=1, derivatives=1)
    try:
        for j in range(n):
            u.set_values({**dict(zip(POSE, q[j])), **dict(zip(POSE_DOT, qd[j])),
                          **dict(zip(POSE_DDOT, qdd[j]))})
            got = u.get_reals(L + L_DOT + L_DDOT + F)
            scale = np.max(np.abs(ref[j].reshape(4, 6)), axis=1).repeat(6)
            assert_within(got, ref[j], 1e-11 * scale)
            before = u.get_reals(REAL_OUTPUTS)
            s = u.do_step(ts[j], h)
            taylor = q[j] + h * qd[j] + 0.5 * h * h * qdd[j]
            if s == DISCARD:
                assert u.get_reals(REAL_OUTPUTS).tobytes() == before.tobytes()
                assert u.get(["status"])[0] == 3 and step_messages(u, DISCARD)
            else:
                assert s in (OK, WARNING)
                advanced = np.array(u.get(POSE))
                np.testing.assert_allclose(advanced, taylor, rtol=1e-14,
                                           atol=1e-14 * np.max(np.abs(taylor)))
                np.testing.assert_allclose(u.get_reals(L), closed_form_lengths(advanced),
                                           rtol=1e-13)
                assert unit_time(u) == ts[j] + h
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("h", STEPS)
def test_step_sizes_with_finite_differences(version, h):
    """derivatives = 0: the lengths are exact at every step size; rates and accelerations are the
    documented finite differences (written independently in fmu_support.backward_fd, fed to
    stewart-solve). The FMU and the reference round differently: their difference is bounded by
    the rounding of the difference quotients, ~eps |q| / h for rates and ~eps |q| / h^2 for
    accelerations (which is why derivatives = 1 is the choice for steps below ~1e-5 s)."""
    n = 6
    ts = h * np.arange(n)
    q, _, _ = combined(ts)
    qd, qdd = backward_fd(ts, q)
    ref = reference_matrix(stewart_solve(np.arange(n), q, qd, qdd))
    u = new_unit(version, fidelity=1, derivatives=0)
    try:
        eps = np.finfo(float).eps
        for j in range(n):
            u.set_values(dict(zip(POSE, q[j])))
            got = u.get_reals(L + L_DOT + L_DDOT + F).reshape(4, 6)
            r = ref[j].reshape(4, 6)
            np.testing.assert_allclose(got[0], closed_form_lengths(q[j]), rtol=1e-14)
            np.testing.assert_allclose(got[0], r[0], rtol=1e-14)
            rate_tol = 1e-11 * np.max(np.abs(r[1])) + 64 * eps / h
            acc_tol = 1e-11 * np.max(np.abs(r[2])) + 64 * eps / h ** 2
            np.testing.assert_allclose(got[1], r[1], rtol=0, atol=rate_tol)
            np.testing.assert_allclose(got[2], r[2], rtol=0, atol=acc_tol)
            # forces: m a in the platform's own Newton-Euler, a error as above
            np.testing.assert_allclose(got[3], r[3], rtol=0,
                                       atol=1e-11 * np.max(np.abs(r[3])) + 1e3 * acc_tol)
            assert u.do_step(ts[j], h) in (OK, WARNING)
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("derivatives", [0, 1])
def test_variable_steps(version, derivatives):
    """Steps drawn log-uniformly from 1e-6 s to 1 s: every output equals the library's at the same
    pose (finite differences over the actual, uneven points when derivatives = 0)."""
    rng = np.random.default_rng(6)
    hs = 10.0 ** rng.uniform(-6, 0, size=25)
    ts = np.concatenate([[0.0], np.cumsum(hs)])
    q, qd, qdd = combined(ts)
    if derivatives == 0:
        qd, qdd = backward_fd(ts, q)
    ref = reference_matrix(stewart_solve(np.arange(len(ts)), q, qd, qdd))
    u = new_unit(version, fidelity=1, derivatives=derivatives)
    try:
        for j, t in enumerate(ts):
            values = dict(zip(POSE, q[j]))
            if derivatives:
                values.update({**dict(zip(POSE_DOT, qd[j])), **dict(zip(POSE_DDOT, qdd[j]))})
            u.set_values(values)
            got = u.get_reals(L + L_DOT + L_DDOT + F)
            scale = np.max(np.abs(ref[j].reshape(4, 6)), axis=1).repeat(6)
            # finite differences over steps down to 1e-6 s: rounding ~ eps |q| / h^2 ~ 1e-4
            tol = 1e-11 * scale if derivatives else 1e-11 * scale + 1e-2
            assert_within(got, ref[j], tol)
            if j + 1 < len(ts):
                assert u.do_step(t, ts[j + 1] - t) in (OK, WARNING)
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("t,h,words", [
    (0.0, 0.0, "communicationStepSize = 0"),
    (0.0, -0.1, "communicationStepSize = -0.1"),
    (0.0, -math.inf, "communicationStepSize = -inf"),
    (0.0, math.nan, "communicationStepSize = nan"),
    (0.0, math.inf, "communicationStepSize = inf"),
    (1e10, 1e-9, "does not advance"),        # below the resolution of t (ulp(1e10) = 1.9e-6)
    (1e308, 1.7e308, "does not advance"),    # t + h overflows
])
def test_steps_that_are_not_steps_are_errors(version, t, h, words):
    """A zero, negative, non-finite or non-advancing step is an invalid argument: Error (not
    Discard, which would invite the master to retry with a smaller step), a message naming the
    step, and nothing changed: the outputs, time and history stay, and the next valid step
    succeeds with the same result as if the bad call had not happened."""
    u = new_unit(version, fidelity=1, derivatives=0)
    v = new_unit(version, fidelity=1, derivatives=0)  # the same run without the bad call
    try:
        q, _, _ = combined([0.0, 0.1, 0.2])
        for w in (u, v):
            w.set_values(dict(zip(POSE, q[0])))
            assert w.do_step(0.0, 0.1) == OK
            w.set_values(dict(zip(POSE, q[1])))
        before = u.get_reals(REAL_OUTPUTS)
        assert u.do_step(0.1 if t == 0.0 else t, h) == ERROR
        m = [x for s, c, x in u.messages if s == ERROR]
        assert m and words in m[-1] and "communicationStepSize" in m[-1], u.messages[-2:]
        assert u.get_reals(REAL_OUTPUTS).tobytes() == before.tobytes()
        assert unit_time(u) == 0.1
        for w in (u, v):
            assert w.do_step(0.1, 0.1) == OK
            w.set_values(dict(zip(POSE, q[2])))
        assert u.get_reals(REAL_OUTPUTS).tobytes() == v.get_reals(REAL_OUTPUTS).tobytes()
    finally:
        u.free()
        v.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_steps_at_a_large_start_time(version):
    """Starting at t = 1e9 s, steps of 1e-3 s (t has ~1e-7 s resolution there) keep time and the
    finite differences consistent with the points the master passes (t_{j+1} = t_j + h, as the
    unit itself advances time; outputs read before doStep belong to the unit's own time)."""
    t0, h = 1e9, 1e-3
    ts = [t0]
    for _ in range(5):
        ts.append(ts[-1] + h)
    ts = np.array(ts)
    q, _, _ = combined(ts - t0)
    qd, qdd = backward_fd(ts, q)
    ref = reference_matrix(stewart_solve(np.arange(6), q, qd, qdd))
    with opened_unit(version) as u:
        assert u.init(start_time=t0, fidelity=1) in (OK, WARNING)
        for j, t in enumerate(ts):
            u.set_values(dict(zip(POSE, q[j])))
            got = u.get_reals(L + L_DOT)
            np.testing.assert_allclose(got[:6], ref[j][:6], rtol=1e-14)
            np.testing.assert_allclose(got[6:], ref[j][6:12], rtol=0, atol=1e-6)
            assert u.do_step(t, h) == OK
            assert unit_time(u) == t + h


# ---------------------------------------------------------------- parameters at the extremes

def scaled_params(s):
    return dict(base_radius=0.5 * s, platform_radius=0.5 * s, home_height=0.5 * s,
                leg_diameter=0.015 * s,
                **every_leg(stroke_min=0.4 * s, stroke_max=0.7 * s),
                **{f"platform_inertia[{i}]": v * s * s for i, v in
                   zip((1, 2, 3), (M_PLATFORM / 16, M_PLATFORM / 16, M_PLATFORM / 8))})


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("s", [2e-3, 200.0])  # platform radius 1 mm and 100 m
def test_scaled_platform(version, s):
    """Geometry scaled by s (radius 1e-3 m and 100 m): lengths scale by s, the condition number and
    the static forces do not change (F depends on L / h only), all against the closed forms."""
    pose = np.array([0.01, -0.02, 0.5, 0.05, -0.03, 0.2])
    scaled = pose.copy()
    scaled[:3] *= s
    u = new_unit(version, fidelity=1, derivatives=1, **scaled_params(s),
                 **dict(zip(POSE, scaled)))
    try:
        assert u.get(["status"])[0] == 0
        assert u.do_step(0.0, 0.1) == OK
        np.testing.assert_allclose(u.get_reals(L), s * closed_form_lengths(pose), rtol=1e-13)
        np.testing.assert_allclose(u.get_reals(L), closed_form_lengths(scaled, 0.5 * s, 0.5 * s),
                                   rtol=1e-13)
        np.testing.assert_allclose(u.get_reals(F), static_forces(pose), rtol=1e-11)
        np.testing.assert_allclose(u.get(["condition"])[0], condition(pose), rtol=1e-9)
        # the base wrench: the weight, and its moment about the origin
        np.testing.assert_allclose(u.get_reals(["base_force[1]", "base_force[2]", "base_force[3]"]),
                                   [0, 0, -M_PLATFORM * G], atol=1e-9 * M_PLATFORM * G)
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("fidelity", [1, 2])
@pytest.mark.parametrize("leg_mass", [1e-9, 1e3])
def test_leg_mass_extremes(version, fidelity, leg_mass):
    """Cylinder and piston masses of 1e-9 kg and 1e3 kg (inertias scaled with them). Massless model:
    the legs carry no mass, so the forces are the closed form whatever the leg mass. Full model:
    at rest the base carries the weight of everything (platform and 12 leg bodies), and with 1e-9 kg
    legs the forces are those of massless legs."""
    require_fidelity(version, fidelity)
    k = leg_mass / 0.14314
    params = {"cylinder_mass": leg_mass, "piston_mass": leg_mass}
    for body in ("cylinder", "piston"):
        rod = [0.14314 * (3 * 0.0075 ** 2 + 0.3 ** 2) / 12] * 2 + [0.14314 * 0.0075 ** 2 / 2]
        params.update({f"{body}_inertia[{i + 1}]": k * v for i, v in enumerate(rod)})
    pose = [0.02, -0.01, 0.52, 0.05, 0.03, -0.1]
    u = new_unit(version, fidelity=fidelity, derivatives=1, **params, **dict(zip(POSE, pose)))
    try:
        assert u.do_step(0.0, 0.1) in (OK, WARNING)
        forces = u.get_reals(F)
        assert np.all(np.isfinite(u.get_reals(REAL_OUTPUTS)))
        if fidelity == 1 or leg_mass < 1e-6:
            np.testing.assert_allclose(forces, static_forces(pose), rtol=1e-8)
        total = M_PLATFORM + (12 * leg_mass if fidelity == 2 else 0)
        np.testing.assert_allclose(u.get_reals(["base_force[3]"])[0], -total * G, rtol=1e-9)
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("com", [(10.0, 0.0, 0.0), (0.0, -100.0, 5.0), (3.0, 3.0, -0.4)])
def test_payload_far_outside(version, com):
    """A 50 kg payload with its centre of mass far outside the plate: forces from the closed form
    (some legs in tension), the base carries the total weight and its moment."""
    pose = [0.0, 0.0, 0.5, 0.02, -0.01, 0.1]
    mp, ml = M_PLATFORM, 50.0
    u = new_unit(version, fidelity=1, derivatives=1, payload_mass=ml,
                 **{f"payload_com[{i + 1}]": c for i, c in enumerate(com)}, **dict(zip(POSE, pose)))
    try:
        s = u.do_step(0.0, 0.1)
        c = ml * np.array(com) / (mp + ml)
        ref = static_forces(pose, mass=mp + ml, com=c)
        assert np.min(ref) < 0  # some legs pull
        cond = condition(pose)
        assert s == (WARNING if cond > WARN_DEFAULT else OK)
        np.testing.assert_allclose(u.get_reals(F), ref, rtol=1e-10)
        weight = np.array([0, 0, -(mp + ml) * G])
        r = np.array(pose[:3]) + rotation(*pose[3:]) @ c
        wrench = u.get_reals(["base_force[1]", "base_force[2]", "base_force[3]",
                              "base_torque[1]", "base_torque[2]", "base_torque[3]"])
        np.testing.assert_allclose(wrench[:3], weight, atol=1e-9 * (mp + ml) * G)
        np.testing.assert_allclose(wrench[3:], np.cross(r, weight),
                                   atol=1e-9 * (mp + ml) * G * np.linalg.norm(r))
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("name,value,words", [
    ("platform_radius", 0.0, "platform_radius"),
    ("base_radius", -1e-3, "base_radius"),
    ("home_height", 0.0, "home_height"),
    ("platform_mass", 0.0, "platform_mass"),
    ("payload_mass", -1.0, "payload_mass"),
    ("cylinder_mass", -1e-9, "cylinder_mass"),
    ("piston_mass", math.inf, "piston_mass"),
    ("gravity[3]", math.nan, "gravity[3]"),
    ("payload_com[1]", -math.inf, "payload_com[1]"),
    ("platform_inertia[3]", 100.0, "platform_inertia"),  # violates the triangle inequality
    ("stroke_min[1]", 0.0, "stroke"),
    ("stroke_max[2]", 0.4, "stroke"),  # equal to stroke_min[2]
    ("warn_condition", 0.5, "warn"),
    ("singular_condition", 10.0, "singular"),  # below warn_condition
    ("tolerance", math.nan, "tolerance"),
    ("tolerance", 1e-16, "below what the position residual can reach"),
])
def test_invalid_parameters_are_errors_naming_them(version, name, value, words):
    with opened_unit(version) as u:
        u.set_values({"fidelity": 1, name: value})
        assert u.enter_init() == OK
        assert u.exit_init() == ERROR
        errors = [m for s, c, m in u.messages if s == ERROR]
        assert errors and words in errors[-1], u.messages
        assert all(c == "logStatusError" for s, c, m in u.messages if s == ERROR)
        assert u.reset() == OK
        assert u.init(fidelity=1) == OK


# ---------------------------------------------------------------- Newton at its limits (fidelity 2)

FAR = [0.05, -0.04, 0.58, 0.15, -0.12, 0.3]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("options", [dict(tolerance=1e-15), dict(max_iterations=1),
                                     dict(tolerance=1e-15, max_iterations=1),
                                     dict(modified_newton=1, max_iterations=2)])
def test_newton_at_its_limits(version, options):
    """A jump from home to a far pose in one step with a tight tolerance, a single iteration or
    modified Newton. The unit places all 14 bodies in closed form before Newton runs, and that
    placement satisfies the constraints to the last bits, so the jump costs at most one
    iteration (to reach 1e-15) and never fails: the Newton options cannot starve it. (Newton
    itself, started from a guess of its own, is exercised on the multibody core in ctest:
    test_newton_from_home.) The lengths are the closed form; L[2] = 0.754 m is beyond the stroke,
    hence Warning and status 1."""
    require_fidelity(version, 2)
    u = new_unit(version, fidelity=2, derivatives=1, **options)
    try:
        u.set_values(dict(zip(POSE, FAR)))
        assert u.do_step(0.0, 0.1) == WARNING, u.messages_text()
        assert u.get(["status"])[0] == 1
        tol = options.get("tolerance", 1e-12)
        residual, iterations = u.get(["residual", "newton_iterations"])
        assert residual <= tol, residual
        # the guess's residual (3.2e-16) passes 1e-12 at once; 1e-15 asks for one iteration
        assert iterations == (1 if tol < 1e-14 else 0), iterations
        np.testing.assert_allclose(u.get_reals(L), closed_form_lengths(FAR), rtol=0, atol=1e-15)
        assert np.all(np.isfinite(u.get_reals(REAL_OUTPUTS)))
        # and back to an ordinary pose
        u.set_values(dict(zip(POSE, yawed(0.0))))
        assert u.do_step(0.1, 0.1) == OK
    finally:
        u.free()


# ---------------------------------------------------------------- long run

def _rss_kib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("fidelity", [0, 1, 2])
def test_long_run(version, fidelity):
    """N steps of 1 ms of the combined manoeuvre through the FMI calls (set pose and derivatives,
    doStep; lengths read every 1e4 steps): the lengths stay the closed form to 1e-13 (no drift with
    the number of steps), no step fails, and the resident memory does not grow from 10 % of the run
    (at least two chunks in) to its end. N = 1e5 by default; STEWART_LONG_RUN_STEPS=1e7 gives the issue's run (about a
    minute per unit, docs/limits.md section 5.3)."""
    require_fidelity(version, fidelity)
    n = int(float(os.environ.get("STEWART_LONG_RUN_STEPS", "1e5")))
    h, chunk = 1e-3, 10_000
    u = new_unit(version, fidelity=fidelity, derivatives=1)
    try:
        dll, c = u.dll, u.c
        vr_in = (ctypes.c_uint * 18)(*[u.vr[x] for x in POSE + POSE_DOT + POSE_DDOT])
        vr_len = (ctypes.c_uint * 6)(*[u.vr[x] for x in L])
        values, lengths = (ctypes.c_double * 18)(), (ctypes.c_double * 6)()
        if version == "2.0":
            def set_inputs():
                return dll.fmi2SetReal(c, vr_in, 18, values)

            def get_lengths():
                return dll.fmi2GetReal(c, vr_len, 6, lengths)

            def step(t):
                return dll.fmi2DoStep(c, ctypes.c_double(t), ctypes.c_double(h), 1)
        else:
            from fmpy.fmi3 import fmi3Boolean, fmi3Float64
            flags, last = [fmi3Boolean() for _ in range(3)], fmi3Float64()

            def set_inputs():
                return dll.fmi3SetFloat64(c, vr_in, 18, values, 18)

            def get_lengths():
                return dll.fmi3GetFloat64(c, vr_len, 6, lengths, 6)

            def step(t):
                return dll.fmi3DoStep(c, ctypes.c_double(t), ctypes.c_double(h), fmi3Boolean(True),
                                      ctypes.byref(flags[0]), ctypes.byref(flags[1]),
                                      ctypes.byref(flags[2]), ctypes.byref(last))
        worst, failed, rss_early = 0.0, 0, None
        for start in range(0, n, chunk):
            m = min(chunk, n - start)
            q, qd, qdd = combined(h * np.arange(start, start + m))
            rows = np.hstack([q, qd, qdd])  # one block per chunk, released before the next
            for j in range(m):
                values[:] = rows[j]
                assert set_inputs() == OK
                if (start + j) % 10_000 == 0 or start + j == n - 1:
                    assert get_lengths() == OK
                    worst = max(worst, np.max(np.abs(np.array(lengths[:]) -
                                                     closed_form_lengths(q[j]))))
                if step((start + j) * h) not in (OK, WARNING):
                    failed += 1
            del q, qd, qdd, rows
            if rss_early is None and start + m >= max(n // 10, 2 * chunk):
                rss_early = _rss_kib()
        assert failed == 0
        assert worst < 1e-13, worst
        assert _rss_kib() - rss_early < 1024, (rss_early, _rss_kib())  # < 1 MiB
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_finite_differences_over_vanishing_steps_refused_by_the_usual_step(version):
    """As test_finite_differences_over_vanishing_steps, the moved pose set and stepped at once (no
    output read in between, so the step is the usual hold step, which writes the quadratic's
    rates into the history's free slot before the library call): the refusal names the finite
    differences from that slot, the outputs and the history stay as they were, and a later
    step of ordinary size is solved."""
    u = new_unit(version, fidelity=1, derivatives=0)
    try:
        for k in range(3):  # history: points 1e-300 s apart, the same pose
            assert u.do_step(k * 1e-300, 1e-300) == OK
        before = u.get_reals(REAL_OUTPUTS)
        u.set(z=0.51)
        assert u.do_step(3e-300, 1e-300) == DISCARD
        m = step_messages(u, DISCARD)[-1]
        assert "finite-difference" in m and "derivatives = 1" in m and " z " in m, m
        assert u.get_reals(REAL_OUTPUTS).tobytes() == before.tobytes()
        assert u.get(["status"])[0] == 3
        assert u.do_step(0.1, 0.1) == OK
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_finite_differences_over_vanishing_steps(version):
    """derivatives = 0 with steps of 1e-300 s (1/h^2 overflows): a pose that does not move is at
    rest (zero rates, the static closed-form forces), not NaN; a pose that moves over such a step
    has no finite acceleration: Discard with a message saying so, outputs kept; a later step of
    ordinary size is solved with the finite differences over the points actually committed."""
    u = new_unit(version, fidelity=1, derivatives=0)
    try:
        home = yawed(0.0)
        assert u.do_step(0.0, 1e-300) == OK
        assert u.do_step(1e-300, 1e-300) == OK  # history: two points 1e-300 s apart, same pose
        assert u.do_step(2e-300, 1e-300) == OK
        np.testing.assert_array_equal(u.get_reals(L_DOT + L_DDOT), 0.0)
        np.testing.assert_allclose(u.get_reals(F), static_forces(home), rtol=1e-12)
        before = u.get_reals(REAL_OUTPUTS)
        u.set(z=0.51)
        assert u.get(["status"])[0] == 3
        assert u.do_step(3e-300, 1e-300) == DISCARD
        assert u.get_reals(REAL_OUTPUTS).tobytes() == before.tobytes()
        m = step_messages(u, DISCARD)[-1]
        assert "finite-difference" in m and "derivatives = 1" in m and " z " in m, m
        # an ordinary step later: the quadratic through (1e-300, home), (2e-300, home) and
        # (0.1, z = 0.51) is, to 1e-298, z = 0.5 + t^2: z' = 0.2 m/s, z'' = 2 m/s^2 at t = 0.1
        assert u.do_step(0.1, 0.1) == OK
        qs = np.array([[0, 0, 0.51, 0, 0, 0]])
        qd, qdd = np.array([[0, 0, 0.2, 0, 0, 0]]), np.array([[0, 0, 2.0, 0, 0, 0]])
        ref = reference_matrix(stewart_solve(np.arange(1), qs, qd, qdd))[0]
        assert_within(u.get_reals(L + L_DOT + L_DDOT + F), ref,
                      1e-10 * np.max(np.abs(ref.reshape(4, 6)), axis=1).repeat(6))
    finally:
        u.free()

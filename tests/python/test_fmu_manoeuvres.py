"""The thesis manoeuvres through the FMU equal stewart-solve on the same poses, for each fidelity
level and each derivative source, FMI 2 and FMI 3.

Both paths end in the same library, so these tests check the unit's plumbing (inputs, derivative
sources, Taylor advance, finite-difference history, outputs), not the physics: that is checked
against closed forms, finite differences and balances in tests/unit and test_cli.py, and through
the FMU in test_fmu_extremes.py (numpy closed forms, weight on the base)."""
import numpy as np
import pytest

from fmu_support import (MANOEUVRES, THESIS_T, VERSIONS, L, L_DOT, L_DDOT, F, POSE, POSE_DOT,
                         POSE_DDOT, OK, WARNING, Unit, backward_fd, reference_matrix,
                         require_fidelity, stewart_solve, thesis_manoeuvre, opened_unit)

FIDELITY_NAMES = {0: "kinematic", 1: "massless", 2: "full"}
OUT = L + L_DOT + L_DDOT + F


def _run(version, fidelity, derivatives, t, q, qd=None, qdd=None):
    """Master loop: set the inputs of t_j, read the outputs, step to t_{j+1}."""
    with opened_unit(version) as u:
        u.set(fidelity=fidelity, derivatives=derivatives)
        u.set_values(dict(zip(POSE, q[0])))
        if qd is not None:
            u.set_values(dict(zip(POSE_DOT + POSE_DDOT, np.concatenate([qd[0], qdd[0]]))))
        assert u.enter_init(t[0]) == OK
        assert u.exit_init() in (OK, WARNING), u.messages_text()
        rows = []
        for j in range(len(t)):
            inputs = dict(zip(POSE, q[j]))
            if qd is not None:
                inputs.update(zip(POSE_DOT + POSE_DDOT, np.concatenate([qd[j], qdd[j]])))
            u.set_values(inputs)
            rows.append(u.get_reals(OUT))
            assert u.get(["status"])[0] == 0
            if j + 1 < len(t):
                assert u.do_step(t[j], t[j + 1] - t[j]) == OK, u.messages_text()
        return np.array(rows)


def _tol(fidelity):
    # Levels 0 and 1 are the same arithmetic on the same poses: identical up to the CSV round
    # trip (17 digits). The full level iterates from a warm start, so allow its tolerance.
    return dict(rtol=1e-12, atol=1e-12) if fidelity < 2 else dict(rtol=1e-8, atol=1e-8)


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("fidelity", [0, 1, 2])
@pytest.mark.parametrize("kind", MANOEUVRES)
def test_thesis_manoeuvre_with_derivative_inputs(version, fidelity, kind):
    require_fidelity(version, fidelity)
    q, qd, qdd = thesis_manoeuvre(kind, THESIS_T)
    got = _run(version, fidelity, 1, THESIS_T, q, qd, qdd)
    ref = reference_matrix(stewart_solve(THESIS_T, q, qd, qdd, FIDELITY_NAMES[fidelity]))
    np.testing.assert_allclose(got, ref, **_tol(fidelity))
    if fidelity == 0:
        assert np.all(got[:, 18:] == 0.0)


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("fidelity", [0, 1, 2])
@pytest.mark.parametrize("kind", MANOEUVRES)
def test_thesis_manoeuvre_with_finite_differences(version, fidelity, kind):
    """derivatives = 0 on a variable step grid: the FMU differentiates the poses it was given at
    earlier communication points; stewart-solve gets the same differences, computed here."""
    require_fidelity(version, fidelity)
    rng = np.random.default_rng(4)
    t = np.concatenate([[0.0], np.cumsum(rng.uniform(0.02, 0.15, 80))])
    q, _, _ = thesis_manoeuvre(kind, t)
    got = _run(version, fidelity, 0, t, q)
    qd, qdd = backward_fd(t, q)
    ref = reference_matrix(stewart_solve(t, q, qd, qdd, FIDELITY_NAMES[fidelity]))
    np.testing.assert_allclose(got, ref, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("version", VERSIONS)
def test_finite_differences_are_exact_for_a_quadratic(version):
    """A motion with constant acceleration: the quadratic through three poses is exact, so from
    the third point on derivatives = 0 gives the derivative-input result (and the closed-form
    derivatives of the pose). At the second point the rate is the chord's slope, the mean of the
    rates at the two ends, and the acceleration zero."""
    t = np.array([0.0, 0.05, 0.12, 0.2, 0.33, 0.4, 0.52])
    a = np.array([0.1, -0.2, 0.3, 0.2, -0.1, 0.25])
    v0 = np.array([0.05, 0.02, -0.04, 0.1, 0.03, -0.2])   # already under way at the first point
    q0 = np.array([0.0, 0.0, 0.5, 0.0, 0.0, 0.0])
    q = q0 + v0 * t[:, None] + 0.5 * a * t[:, None] ** 2
    qd = v0 + a * t[:, None]
    qdd = np.tile(a, (len(t), 1))
    fd = _run(version, 1, 0, t, q)
    exact = _run(version, 1, 1, t, q, qd, qdd)
    # the first point is taken at rest: its lengths are exact
    np.testing.assert_allclose(fd[0, :6], exact[0, :6], rtol=1e-12, atol=1e-12)
    # the second: the pose moving at the chord's rate (qd0 + qd1) / 2 without acceleration
    chord_rate = np.tile((qd[0] + qd[1]) / 2, (2, 1))
    chord = _run(version, 1, 1, t[:2], q[:2], chord_rate, np.zeros((2, 6)))
    np.testing.assert_allclose(fd[1], chord[1], rtol=1e-9, atol=1e-9)
    # and from the third on, exact
    np.testing.assert_allclose(fd[2:], exact[2:], rtol=1e-7, atol=1e-7)
    # the rates are not trivially zero
    assert np.max(np.abs(exact[1:, 6:12])) > 1e-3


@pytest.mark.parametrize("version", VERSIONS)
def test_first_point_is_at_rest(version):
    q, _, _ = thesis_manoeuvre("heave", np.array([0.3]))
    got = _run(version, 1, 0, np.array([0.3]), q)
    ref = reference_matrix(stewart_solve(np.array([0.3]), q, np.zeros((1, 6)), np.zeros((1, 6))))
    np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("version", VERSIONS)
def test_taylor_advance_over_a_step(version):
    """derivatives = 1: after doStep(t, h) without new inputs, the outputs belong to t + h: the
    pose advanced by its second-order Taylor expansion (computed here), the rate by the first."""
    q, qd, qdd = thesis_manoeuvre("roll", np.array([0.37]))
    q, qd, qdd = q + [0.01, -0.02, 0, 0, 0.03, 0.1], qd + [0.1, 0.2, -0.1, 0, 0.05, 0.3], \
        qdd + [1.0, -0.5, 0.2, 0.3, 0, -0.4]
    hs = [0.1, 0.03, 0.2]
    with opened_unit(version) as u:
        u.set(fidelity=1, derivatives=1)
        u.set_values(dict(zip(POSE + POSE_DOT + POSE_DDOT, np.concatenate([q[0], qd[0], qdd[0]]))))
        assert u.enter_init(0.37) == OK and u.exit_init() == OK
        t, p, v, a = 0.37, q[0].copy(), qd[0].copy(), qdd[0].copy()
        for h in hs:
            assert u.do_step(t, h) == OK
            t += h
            p, v = p + v * h + 0.5 * a * h * h, v + a * h
            got = u.get_reals(OUT)
            ref = reference_matrix(stewart_solve(np.array([t]), p[None], v[None], a[None]))[0]
            np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-12)
            np.testing.assert_allclose(u.get_reals(POSE), p, rtol=1e-15, atol=1e-15)


def test_fmi2_input_derivatives_interpolate_over_the_step():
    """FMI 2 canInterpolateInputs: with derivatives = 0, fmi2SetRealInputDerivatives (orders 1
    and 2) supplies the derivatives for the solve at t and the Taylor advance to t + h."""
    q, qd, qdd = thesis_manoeuvre("yaw", np.array([1.3]))
    qd = qd + [0.05, 0, 0.1, 0, 0, 0]
    qdd = qdd + [0, 0.2, 0, 0.3, 0, 0]
    with opened_unit("2.0") as u:
        u.set(fidelity=1, derivatives=0)
        assert u.enter_init(1.3) == OK and u.exit_init() == OK
        u.set_values(dict(zip(POSE, q[0])))
        vrs = [u.vr[n] for n in POSE]
        u.fmu.setRealInputDerivatives(vrs, [1] * 6, list(qd[0]))
        u.fmu.setRealInputDerivatives(vrs, [2] * 6, list(qdd[0]))
        got_t = u.get_reals(OUT)
        ref_t = reference_matrix(stewart_solve(np.array([1.3]), q, qd, qdd))[0]
        np.testing.assert_allclose(got_t, ref_t, rtol=1e-12, atol=1e-12)
        h = 0.08
        assert u.do_step(1.3, h) == OK
        p, v = q[0] + qd[0] * h + 0.5 * qdd[0] * h * h, qd[0] + qdd[0] * h
        ref = reference_matrix(stewart_solve(np.array([1.3 + h]), p[None], v[None], qdd))[0]
        np.testing.assert_allclose(u.get_reals(OUT), ref, rtol=1e-12, atol=1e-12)


def test_fmi2_input_derivatives_not_given_are_zero():
    """An order the master does not give before a step is zero for that step: the second step
    gets only first derivatives, so its acceleration is zero, not the one of the first step."""
    q, qd, qdd = thesis_manoeuvre("yaw", np.array([1.3, 1.4]))
    qdd = qdd + [0.5, 0.2, -0.3, 0.3, 0.1, -0.2]  # large, so a left-over one would show
    with opened_unit("2.0") as u:
        u.set(fidelity=1, derivatives=0)
        assert u.enter_init(1.3) == OK and u.exit_init() == OK
        vrs = [u.vr[n] for n in POSE]
        u.set_values(dict(zip(POSE, q[0])))
        u.fmu.setRealInputDerivatives(vrs, [1] * 6, list(qd[0]))
        u.fmu.setRealInputDerivatives(vrs, [2] * 6, list(qdd[0]))
        assert u.do_step(1.3, 0.1) == OK
        u.set_values(dict(zip(POSE, q[1])))
        u.fmu.setRealInputDerivatives(vrs, [1] * 6, list(qd[1]))
        ref = reference_matrix(stewart_solve(np.array([1.4]), q[1:], qd[1:], np.zeros((1, 6))))[0]
        np.testing.assert_allclose(u.get_reals(OUT), ref, rtol=1e-12, atol=1e-12)
        h = 0.05
        assert u.do_step(1.4, h) == OK
        p = q[1] + qd[1] * h
        ref = reference_matrix(stewart_solve(np.array([1.4 + h]), p[None], qd[1:],
                                             np.zeros((1, 6))))[0]
        np.testing.assert_allclose(u.get_reals(OUT), ref, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("version", VERSIONS)
def test_hold_without_derivatives(version):
    """derivatives = 0 and no input derivatives: over a step the unit holds its inputs, so the
    outputs after doStep are those of the pose set at t."""
    q, _, _ = thesis_manoeuvre("pitch", np.array([0.0, 0.1]))
    with opened_unit(version) as u:
        assert u.init(fidelity=1, derivatives=0, **dict(zip(POSE, q[0]))) == OK
        u.set_values(dict(zip(POSE, q[0])))
        before = u.get_reals(OUT)
        assert u.do_step(0.0, 0.1) == OK
        np.testing.assert_array_equal(u.get_reals(OUT), before)
        np.testing.assert_array_equal(u.get_reals(POSE), q[0])


@pytest.mark.parametrize("version", VERSIONS)
def test_changed_geometry_and_payload_parameters(version):
    """Parameters reach the model: lengths follow the closed form L = |p + R b - a| for another
    geometry; a payload adds its weight to the vertical force on the base."""
    from reference import lengths as closed_form_lengths
    import math
    beta = (5, 25, 125, 145, 245, 265)
    tau = (335, 55, 95, 175, 215, 295)
    params = {"base_radius": 0.6, "platform_radius": 0.4}
    params.update({f"base_angle[{k + 1}]": math.radians(b) for k, b in enumerate(beta)})
    params.update({f"platform_angle[{k + 1}]": math.radians(t) for k, t in enumerate(tau)})
    params["payload_mass"] = 50.0
    params["payload_inertia[1]"] = params["payload_inertia[2]"] = 1.0
    params["payload_inertia[3]"] = 1.5
    pose = [0.01, -0.02, 0.55, 0.05, -0.03, 0.1]
    with opened_unit(version) as u:
        assert u.init(fidelity=1, **params, **dict(zip(POSE, pose))) == OK, u.messages_text()
        np.testing.assert_allclose(u.get_reals(L), closed_form_lengths(
            pose, 0.6, 0.4, np.radians(beta), np.radians(tau)), rtol=1e-12)
        m = u.get(["platform_mass"])[0] + 50.0
        fz = u.get_reals(["base_force[3]"])[0]
        np.testing.assert_allclose(fz, -m * 9.81, rtol=1e-10)

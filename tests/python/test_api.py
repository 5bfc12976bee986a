"""The Python package (stewart.Platform.inverse) against independent references: stewart-solve and
the FMU (fmpy) on the thesis manoeuvres, numpy closed forms for lengths and the weight a platform
at rest puts on its base; per-row statuses in a batch; parameter errors; the shipped FMUs."""
import zipfile

import numpy as np
import pytest

import fmu_support
import reference
from fmu_support import (MANOEUVRES, THESIS_T, L, L_DDOT, L_DOT, F, POSE, POSE_DDOT, POSE_DOT, OK,
                         WARNING, reference_matrix, stewart_solve, thesis_manoeuvre)

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")

LEVELS = ("kinematic", "massless", "full")


def _matrix(sol):
    return np.hstack([sol.length, sol.length_rate, sol.length_accel, sol.force])


@pytest.mark.parametrize("fidelity", LEVELS)
@pytest.mark.parametrize("kind", MANOEUVRES)
def test_manoeuvre_equals_stewart_solve_bit_for_bit(fidelity, kind):
    """Same library, same order of poses, fresh start: identical numbers (the CLI prints 17
    digits, which round-trip)."""
    q, qd, qdd = thesis_manoeuvre(kind, THESIS_T)
    sol = stewart.Platform().inverse(q, qd, qdd, fidelity=fidelity)
    ref = stewart_solve(THESIS_T, q, qd, qdd, fidelity)
    assert sol.ok.all()
    np.testing.assert_array_equal(_matrix(sol), reference_matrix(ref))
    np.testing.assert_array_equal(sol.condition, ref["condition"])
    np.testing.assert_array_equal(sol.iterations, ref["iterations"])


def test_parameters_reach_the_cli_and_the_api_alike():
    q, qd, qdd = thesis_manoeuvre("roll", THESIS_T[:40])
    params = {"payload_mass": 80.0, "payload_com": [0.02, -0.01, 0.15], "base_radius": 0.55}
    sol = stewart.Platform(**params).inverse(q, qd, qdd, fidelity="massless")
    cli_args = ["payload_mass=80.0", "payload_com[1]=0.02", "payload_com[2]=-0.01",
                "payload_com[3]=0.15", "base_radius=0.55"]
    ref = _cli_with_params(THESIS_T[:40], q, qd, qdd, cli_args)
    np.testing.assert_array_equal(_matrix(sol), ref)


def _cli_with_params(t, q, qd, qdd, assignments):
    import pathlib
    import subprocess
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        inp, out = pathlib.Path(d, "in.csv"), pathlib.Path(d, "out.csv")
        cols = ["t", *POSE, *POSE_DOT, *POSE_DDOT]
        rows = np.hstack([np.asarray(t)[:, None], q, qd, qdd])
        inp.write_text(",".join(cols) + "\n" + "".join(",".join(repr(float(v)) for v in r) + "\n" for r in rows))
        args = [str(fmu_support.stewart_solve_path())]
        for a in assignments:
            args += ["--param", a]
        r = subprocess.run(args + ["--fidelity", "massless", str(inp), str(out)],
                           capture_output=True, text=True, timeout=60)
        assert r.returncode == 0, r.stderr
        body = np.loadtxt(out, delimiter=",", skiprows=1, usecols=range(27))  # status is text
    return body[:, 1:25]


@pytest.fixture
def shipped_fmus(monkeypatch):
    """fmu_support's FMU driver pointed at the FMUs inside the installed package."""
    monkeypatch.setattr(fmu_support, "fmu_path", stewart.fmu_path)
    monkeypatch.setattr(fmu_support, "_unzipped", {})
    monkeypatch.setattr(fmu_support, "_descriptions", {})


@pytest.mark.parametrize("version", stewart.FMI_VERSIONS)
@pytest.mark.parametrize("fidelity", [0, 1, 2])
def test_manoeuvre_equals_the_shipped_fmu(shipped_fmus, version, fidelity):
    """The combined-axis thesis manoeuvre (yaw) through the package's own FMU with its derivative
    inputs, against the API. Levels 0 and 1 are the same arithmetic; the full level iterates from
    the FMU's own warm start, hence its tolerance."""
    q, qd, qdd = thesis_manoeuvre("yaw", THESIS_T[:60])
    u = fmu_support.Unit(version)
    try:
        u.set(fidelity=fidelity, derivatives=1)
        rows = []
        for j in range(len(q)):
            u.set_values(dict(zip(POSE + POSE_DOT + POSE_DDOT, np.concatenate([q[j], qd[j], qdd[j]]))))
            if j == 0:
                assert u.enter_init(0.0) == OK
                assert u.exit_init() in (OK, WARNING), u.messages_text()
            rows.append(u.get_reals(L + L_DOT + L_DDOT + F))
            if j + 1 < len(q):
                assert u.do_step(THESIS_T[j], THESIS_T[j + 1] - THESIS_T[j]) == OK
    finally:
        u.free()
    sol = stewart.Platform().inverse(q, qd, qdd, fidelity=fidelity)
    tol = dict(rtol=1e-12, atol=1e-12) if fidelity < 2 else dict(rtol=1e-8, atol=1e-8)
    np.testing.assert_allclose(np.array(rows), _matrix(sol), **tol)


def test_fmu_paths_are_the_six_units_for_both_versions():
    """The package ships every unit the build makes (the inverse unit, the plant in co-simulation
    and Model Exchange, the controller, the scene player, the cueing unit), for FMI 2.0 and 3.0,
    each one the model its name says."""
    import fmpy
    paths = stewart.fmu_paths()
    assert set(paths) == {"StewartPlatform", "StewartPlant", "StewartPlantME", "StewartController",
                          "StewartScene", "StewartCueing"}
    for model, by_version in paths.items():
        assert set(by_version) == {"2.0", "3.0"}
        for version, path in by_version.items():
            assert zipfile.is_zipfile(path)
            md = fmpy.read_model_description(str(path))
            assert (md.fmiVersion, md.modelName) == (version, model)
            assert stewart.fmu_path(version, model) == path
    with pytest.raises(ValueError, match="1.0"):
        stewart.fmu_path("1.0")
    with pytest.raises(ValueError, match="StewartPlnt"):
        stewart.fmu_path("2.0", "StewartPlnt")


def test_lengths_against_numpy_closed_form_with_changed_geometry():
    rng = np.random.default_rng(7)
    n = 200
    q = np.column_stack([rng.uniform(-0.1, 0.1, (n, 2)), rng.uniform(0.4, 0.6, n),
                         rng.uniform(-0.2, 0.2, (n, 3))])
    beta = (5, 25, 125, 145, 245, 265)
    platform = stewart.Platform(base_radius=0.6, platform_radius=0.45,
                                base_angle=np.radians(beta))
    sol = platform.inverse(q, fidelity="kinematic")
    ref = np.array([reference.lengths(p, rb=0.6, rt=0.45, beta=np.radians(beta)) for p in q])
    np.testing.assert_allclose(sol.length, ref, rtol=0, atol=1e-14)
    assert np.all(sol.force == 0)


def test_platform_at_rest_puts_its_weight_on_the_base():
    """Legs as massless two-force members: the base carries platform + payload weight (m g) and
    the torque of that weight about the origin (r x m g) for a centre of mass off the axis."""
    m_p, m_l, com = 100.0, 50.0, np.array([0.05, -0.03, 0.1])
    platform = stewart.Platform(platform_mass=m_p, platform_com=[0, 0, 0], payload_mass=m_l,
                                payload_com=com)
    sol = platform.inverse([[0, 0, 0.5, 0, 0, 0]], fidelity="massless")
    g = np.array([0, 0, -9.81])
    np.testing.assert_allclose(sol.base_force[0], (m_p + m_l) * g, rtol=1e-12, atol=1e-9)
    r = (m_l * (com + [0, 0, 0.5]) + m_p * np.array([0, 0, 0.5])) / (m_p + m_l)
    np.testing.assert_allclose(sol.base_torque[0], np.cross(r, (m_p + m_l) * g), rtol=1e-12, atol=1e-9)


def test_bad_rows_get_their_status_and_the_others_are_solved():
    good = np.array([[0.02, 0.01, 0.5, 0.05, -0.03, 0.1], [0, 0, 0.55, 0, 0.1, 0]])
    bad_nan = [np.nan, 0, 0.5, 0, 0, 0]
    on_base_point = [0, 0, 0, 0, 0, np.pi / 6]  # leg 1's platform point lands on its base point
    flat = [0, 0, 0, 0, 0, 0]                    # every leg in the base plane: singular
    poses = np.array([good[0], bad_nan, on_base_point, flat, good[1]])
    for level in ("kinematic", "massless"):
        sol = stewart.Platform().inverse(poses, fidelity=level)
        alone = stewart.Platform().inverse(good, fidelity=level)
        np.testing.assert_array_equal(_matrix(sol)[[0, 4]], _matrix(alone))
        assert sol.status[0] == 0 and sol.status[4] == 0
        assert sol.status[1] == -1 and "x is nan" in sol.messages[1]
        assert sol.status[2] == -4 and sol.status_name(2) == "unreachable pose"
        assert np.all(_matrix(sol)[1:3] == 0) and np.all(np.isfinite(_matrix(sol)))
    assert sol.status[3] == -3 and "singular" in sol.status_name(3)
    assert sorted(sol.messages) == [1, 2, 3]
    assert stewart.Platform().inverse(poses, max_messages=1).messages.keys() == {1}


@pytest.mark.parametrize("params, words", [
    ({"payload_mass": -1.0}, ["payload_mass", "-1"]),
    ({"paylod_mass": 5.0}, ["paylod_mass", "payload_mass"]),
    ({"stroke_min": 0.8, "stroke_max": 0.7}, ["stroke", "0.8"]),
    ({"base_angle": [0.0, 1.0]}, ["base_angle", "2 values"]),
    ({"base_angle": np.zeros(7)}, ["base_angle", "7 values", "needs 6"]),
    ({"gravity": [[0, 0, -9.81]]}, ["gravity"]),
    ({"payload_mass": [1.0, 2.0]}, ["payload_mass", "one number"]),
])
def test_bad_parameters_raise_naming_parameter_and_value(params, words):
    with pytest.raises(stewart.ParameterError) as e:
        stewart.Platform(**params)
    for w in words:
        assert w in str(e.value)


def test_bad_options_and_shapes_raise():
    p = stewart.Platform()
    with pytest.raises(stewart.ParameterError, match="tolerance = 1e-20"):
        p.inverse(np.zeros((1, 6)), fidelity="full", tolerance=1e-20)
    with pytest.raises(stewart.ParameterError, match="fidelity = 'fast'"):
        p.inverse(np.zeros((1, 6)), fidelity="fast")
    with pytest.raises(ValueError, match=r"poses has shape \(3, 5\)"):
        p.inverse(np.zeros((3, 5)))
    with pytest.raises(ValueError, match="rates has 2 rows"):
        p.inverse(np.zeros((3, 6)), rates=np.zeros((2, 6)))


def test_a_platform_pickles_and_solves_alike_in_threads():
    import pickle
    from concurrent.futures import ThreadPoolExecutor
    q, qd, qdd = thesis_manoeuvre("pitch", THESIS_T)
    p = stewart.Platform(payload_mass=20.0)
    ref = _matrix(p.inverse(q, qd, qdd, fidelity="full"))
    copy = pickle.loads(pickle.dumps(p))
    # Many more calls than threads on a shared Platform: threads queue for its data block
    # while another solves (a deadlock here once: the GIL held while waiting for the block).
    with ThreadPoolExecutor(4) as pool:
        results = list(pool.map(lambda pl: _matrix(pl.inverse(q, qd, qdd, fidelity="full")),
                                [p, copy] * 20))
    for r in results:
        np.testing.assert_array_equal(r, ref)


def test_solving_into_a_reused_solution_gives_the_same_numbers():
    q, qd, qdd = thesis_manoeuvre("heave", THESIS_T)
    p = stewart.Platform()
    fresh = p.inverse(q, qd, qdd, fidelity="massless")
    reused = p.inverse(q[::-1], fidelity="massless")
    assert p.inverse(q, qd, qdd, fidelity="massless", out=reused) is reused
    np.testing.assert_array_equal(_matrix(reused), _matrix(fresh))
    with pytest.raises(ValueError, match="out has 121 rows but poses has 2"):
        p.inverse(q[:2], out=reused)


def test_the_parameter_table_round_trips_through_platform():
    """Every parameter of the library's table, set to its default by name, gives the default
    platform's numbers bit for bit; one element set by its own name equals the array form."""
    table = stewart.parameters()
    assert {"payload_mass", "base_angle", "stroke_max"} <= {p["name"] for p in table}
    defaults = {p["name"]: p["defaults"][0] if p["count"] == 1 else p["defaults"] for p in table}
    q, qd, qdd = thesis_manoeuvre("roll", THESIS_T)
    ref = _matrix(stewart.Platform().inverse(q, qd, qdd, fidelity="full"))
    np.testing.assert_array_equal(_matrix(stewart.Platform(**defaults).inverse(q, qd, qdd, fidelity="full")), ref)
    angles = list(defaults["base_angle"])
    angles[1] += 0.01
    by_array = stewart.Platform(base_angle=angles).inverse(q, fidelity="kinematic")
    by_element = stewart.Platform(**{"base_angle[2]": angles[1]}).inverse(q, fidelity="kinematic")
    np.testing.assert_array_equal(by_array.length, by_element.length)

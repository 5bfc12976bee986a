"""Sweeps (stewart.sweeps, scripts/sweep.py) against independent references: the same results on
1 and 2 LocalCluster workers and from stewart-solve; the workspace's reachability and boundary
against the closed-form length limits in numpy; map values at sample points against direct
calls; bad specs refused before any work; failing cases recorded; a rerun computes only missing
chunks; cases beyond a limit as rows (their class and margin against lengths computed here, on
every shipped machine against its axis ranges); CSV manoeuvres against stewart-solve on the
scaled trajectory; inline scenes and platform files with a payload; results in the units asked
for."""
import json
import math
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import reference
from fmu_support import POSE, POSE_DDOT, POSE_DOT, stewart_solve_path

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")
pq = pytest.importorskip("pyarrow.parquet")
pytest.importorskip("distributed")
from stewart.sweeps import SpecError, chunks, resolve, run  # noqa: E402
from stewart.sweeps.run import compute_chunk  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"

ENVELOPE = {
    "kind": "envelope", "fidelity": ["massless", "full"],
    "payload_mass": {"start": 0, "stop": 60, "num": 2}, "payload_com": [[0.0, 0.0, 0.1], [0.05, -0.02, 0.1]],
    "manoeuvres": [{"scene": "heave", "amplitude": [1.0, 1.5]}, {"scene": "yaw", "frequency": [1.0, 2.0]}],
    "duration": 1.5, "cases_per_chunk": 3,
}
STROKE = (0.43, 0.68)
WORKSPACE = {
    "kind": "workspace",
    "platform": {"payload_mass": 40.0, "stroke_min": STROKE[0], "stroke_max": STROKE[1]},
    "slices": [
        {"name": "xy", "fixed": {"z": 0.52, "yaw": 0.05},
         "axes": {"x": {"start": -0.25, "stop": 0.25, "num": 57}, "y": {"start": -0.2, "stop": 0.2, "num": 43}}},
        {"name": "rp", "fixed": {"x": 0.02, "z": 0.52},
         "axes": {"roll": {"start": -0.4, "stop": 0.4, "num": 41}, "pitch": {"start": -0.35, "stop": 0.35, "num": 37}}},
    ],
    "poses_per_chunk": 700,
}


def _sweep(tmp_path, spec, name, **kw):
    path = tmp_path / f"{name}.json"
    path.write_text(json.dumps(spec))
    out = tmp_path / name
    summary = run(path, out, SCENES, progress=False, log=lambda m: None, **kw)
    return out, summary


def _table(out, name):
    t = pq.read_table(out / name)
    return {k: t[k].to_numpy(zero_copy_only=False) for k in t.column_names}


def _assert_tables_equal(a, b):
    assert a.keys() == b.keys()
    for k in a:
        if a[k].dtype.kind == "f":
            np.testing.assert_array_equal(a[k], b[k], err_msg=k)
        else:
            assert list(a[k]) == list(b[k]), k


@pytest.fixture(scope="module")
def envelope_runs(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("envelope")
    one, _ = _sweep(tmp, ENVELOPE, "one", workers=1)
    two, summary = _sweep(tmp, ENVELOPE, "two", workers=2)
    return one, two, summary


def test_envelope_same_bit_for_bit_on_one_and_two_workers(envelope_runs):
    one, two, summary = envelope_runs
    a, b = _table(one, "envelope.parquet"), _table(two, "envelope.parquet")
    assert len(a["case"]) == 2 * 2 * 4 * 2 and np.all(a["status"] == 0)
    _assert_tables_equal(a, b)
    assert summary["workers"] == 2
    for f in ("spec.json", "version.json", "envelope_massless.png", "envelope_full.png"):
        assert (two / f).stat().st_size > 0
    assert json.loads((two / "version.json").read_text())["stewart"] == stewart.__version__


def _scene_poses(name, amplitude, frequency, duration):
    """The scene's sinusoids written out here, from the scene file."""
    scene = json.loads((SCENES / f"{name}.json").read_text())
    dt = scene["step"]
    t = np.arange(int(round(duration / dt)) + 1) * dt
    q, qd, qdd = (np.zeros((t.size, 6)) for _ in range(3))
    for i, c in enumerate(POSE):
        s = scene["pose"].get(c, {})
        a, w, ph = amplitude * s.get("amplitude", 0.0), frequency * s.get("omega", 0.0), s.get("phase", 0.0)
        q[:, i] = s.get("mean", 0.0) + a * np.sin(w * t + ph)
        qd[:, i] = a * w * np.cos(w * t + ph)
        qdd[:, i] = -a * w * w * np.sin(w * t + ph)
    return t, q, qd, qdd


def _cli(t, q, qd, qdd, fidelity, params, tmp_path):
    inp, out = tmp_path / "in.csv", tmp_path / "out.csv"
    rows = np.hstack([t[:, None], q, qd, qdd])
    inp.write_text(",".join(["t", *POSE, *POSE_DOT, *POSE_DDOT]) + "\n" +
                   "".join(",".join(repr(float(v)) for v in r) + "\n" for r in rows))
    args = [str(stewart_solve_path()), "--fidelity", fidelity]
    for k, v in params.items():
        args += ["--param", f"{k}={float(v)!r}"]
    r = subprocess.run(args + [str(inp), str(out)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    return np.loadtxt(out, delimiter=",", skiprows=1, usecols=range(27))  # status is text


@pytest.mark.parametrize("case", [0, 7, 21, 30])
def test_envelope_case_equals_stewart_solve(envelope_runs, case, tmp_path):
    """The case's trajectory through stewart-solve, its peaks computed here: equal bit for bit."""
    row = {k: v[case] for k, v in _table(envelope_runs[1], "envelope.parquet").items()}
    com = [row["payload_com_x"], row["payload_com_y"], row["payload_com_z"]]
    t, q, qd, qdd = _scene_poses(row["manoeuvre"], row["amplitude"], row["frequency"], ENVELOPE["duration"])
    params = {"payload_mass": row["payload_mass"], **{f"payload_com[{k + 1}]": c for k, c in enumerate(com)}}
    out = _cli(t, q, qd, qdd, row["fidelity"], params, tmp_path)
    L, Ld, Ldd, F, cond = out[:, 1:7], out[:, 7:13], out[:, 13:19], out[:, 19:25], out[:, 25]
    for k in range(6):
        assert row[f"peak_force_{k + 1}"] == max(abs(v) for v in F[:, k])
    assert row["peak_length_rate"] == np.abs(Ld).max()
    assert row["peak_length_accel"] == np.abs(Ldd).max()
    assert (row["length_min"], row["length_max"]) == (L.min(), L.max())
    assert row["stroke_used"] == max(L[:, k].max() - L[:, k].min() for k in range(6))
    assert row["max_condition"] == cond.max() and row["min_inverse_condition"] == 1.0 / cond.max()
    power = [sum_in_order(F[j], Ld[j]) for j in range(len(t))]
    assert row["peak_power"] == max(abs(p) for p in power)


def sum_in_order(f, ld):
    p = f[0] * ld[0]
    for k in range(1, 6):
        p = p + f[k] * ld[k]
    return p


@pytest.fixture(scope="module")
def workspace_run(tmp_path_factory):
    out, _ = _sweep(tmp_path_factory.mktemp("workspace"), WORKSPACE, "ws", workers=2)
    return out


@pytest.mark.parametrize("name", ["xy", "rp"])
def test_workspace_reachable_exactly_within_the_length_limits(workspace_run, name):
    t = _table(workspace_run, f"workspace_{name}.parquet")
    s = next(x for x in WORKSPACE["slices"] if x["name"] == name)
    q = np.column_stack([t[c] for c in POSE])
    L = np.array([reference.lengths(p) for p in q])
    inside = np.all((L >= STROKE[0]) & (L <= STROKE[1]), axis=1)
    differ = inside != t["reachable"]
    # A disagreement is only allowed on a length within rounding of a limit.
    near = np.min(np.abs(L[:, :, None] - np.array(STROKE)), axis=(1, 2)) < 1e-12
    assert not np.any(differ & ~near)
    assert 0.1 < inside.mean() < 0.9  # the slice crosses the boundary
    shape = [s["axes"][k]["num"] for k in s["axes"]]
    grid = inside.reshape(shape)
    edge = np.zeros_like(grid)
    edge[:-1] |= grid[:-1] != grid[1:]
    edge[1:] |= grid[1:] != grid[:-1]
    edge[:, :-1] |= grid[:, :-1] != grid[:, 1:]
    edge[:, 1:] |= grid[:, 1:] != grid[:, :-1]
    np.testing.assert_array_equal(t["boundary"], (grid & edge).reshape(-1))


@pytest.mark.parametrize("slice_index", [0, 1])
def test_workspace_rows_are_the_grid_row_major(workspace_run, slice_index):
    """Row j of a slice is grid point unravel_index(j) over its axes in spec order: the indices,
    and the pose with the axes' values there, the fixed values, zeros elsewhere."""
    s = resolve(WORKSPACE, SCENES)["slices"][slice_index]
    t = _table(workspace_run, f"workspace_{s['name']}.parquet")
    axes = list(s["axes"].items())
    shape = [len(values) for _, values in axes]
    np.testing.assert_array_equal(t["row"], np.arange(np.prod(shape)))
    index = np.unravel_index(t["row"], shape)
    for col, (comp, values) in enumerate(axes):
        np.testing.assert_array_equal(t[f"i_{comp}"], index[col])
        np.testing.assert_array_equal(t[comp], np.asarray(values, dtype=float)[index[col]])
    for comp in POSE:
        if comp not in s["axes"]:
            np.testing.assert_array_equal(t[comp], s["fixed"].get(comp, 0.0))


def test_workspace_values_at_sample_points_equal_direct_calls(workspace_run):
    rng = np.random.default_rng(3)
    t = _table(workspace_run, "workspace_xy.parquet")
    rows = rng.choice(len(t["x"]), 40, replace=False)
    q = np.column_stack([t[c][rows] for c in POSE])
    sol = stewart.Platform(**WORKSPACE["platform"]).inverse(q, fidelity="massless")
    np.testing.assert_array_equal(t["status"][rows], sol.status)
    np.testing.assert_array_equal(t["condition"][rows], sol.condition)
    for k in range(6):
        np.testing.assert_array_equal(t[f"F{k + 1}"][rows], sol.force[:, k])
        np.testing.assert_array_equal(t[f"L{k + 1}"][rows], sol.length[:, k])


@pytest.mark.parametrize("change, words", [
    ({"platform": {"paylod_mass": 3}}, ["platform", "paylod_mass", "payload_mass"]),
    ({"payload_mass": {"start": 0, "stop": 1, "num": 0}}, ["payload_mass.num", "empty"]),
    ({"payload_mass": []}, ["payload_mass", "empty"]),
    ({"payload_mass": [10, -5]}, ["payload_mass[1] = -5", "payload_mass = -5"]),
    ({"manoeuvres": [{"scene": "hevae"}]}, ["manoeuvres[0].scene = 'hevae'"]),
    ({"fidelity": ["massless", "fast"]}, ["fidelity[1]", "fast"]),
    ({"options": {"tolerance": -1}}, ["options", "tolerance = -1"]),
    ({"payloads": [1]}, ["unknown field 'payloads'"]),
    ({"manoeuvres": [{"scene": {"pose": {"z": 0.5}, "duration": 1, "step": 0.1}}]},
     ["manoeuvres[0].scene.pose.z = 0.5"]),
    ({"duration": math.inf}, ["duration = inf", "> 0"]),
    ({"step": 1e-300}, ["manoeuvres[0] (heave)", "step 1e-300 s", "memory"]),
    ({"duration": 1e7, "step": 1e-3}, ["manoeuvres[0] (heave)", "duration 1e+07 s", "1e+10 poses", "memory"]),
    ({"payload_mass": {"start": 0, "stop": 1, "num": 2e9}}, ["payload_mass.num", "2e+09 values", "memory"]),
    ({"payload_mass": {"start": 0, "stop": 1, "num": 5.5}}, ["payload_mass.num = 5.5", "whole number"]),
    ({"payload_mass": {"start": 0, "stop": 1, "num": "5"}}, ["payload_mass.num = '5'", "whole number"]),
    ({"payload_mass": {"start": 0, "stop": 60, "num": 10**6}, "payload_com": [[0, 0, 0.1]] * 3000},
     ["the envelope", "2.4e+10 cases", "memory"]),
    ({"platform": {"stroke_max": "long"}}, ["platform", "stroke_max = 'long'", "not a number"]),
    ({"manoeuvres": [{"scene": {"pose": {"z": {"mean": 0.5}}, "duration": math.inf, "step": 0.1}}]},
     ["manoeuvres[0].scene.duration = inf"]),
    ({"manoeuvres": [{"scene": "slider_crank"}]}, ["manoeuvres[0].scene = 'slider_crank'", "no pose"]),
])
def test_bad_specs_fail_before_any_work_naming_the_field(tmp_path, change, words):
    _assert_refused(tmp_path, {**ENVELOPE, **change}, words)


def _assert_refused(tmp_path, spec, words, out=None, scenes=SCENES):
    """sweep.py exits 2 (no traceback) with every word in its message, and writes nothing."""
    path = tmp_path / "bad.json"
    path.write_text(spec if isinstance(spec, str) else json.dumps(spec))
    out = out or tmp_path / "out"
    r = subprocess.run([sys.executable, str(ROOT / "scripts/sweep.py"), str(path), str(out),
                        "--scenes", str(scenes)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stderr
    assert "Traceback" not in r.stderr, r.stderr
    for w in words:
        assert w in r.stderr, r.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("text, words", [
    ("{not json", ["manoeuvres[0].scene", "broken.json is not JSON"]),
    ("[1, 2]", ["manoeuvres[0].scene", "holds a list"]),
    ('{"pose": {"z": {"mean": 0.5}}, "duration": Infinity, "step": 0.01}', ["duration = inf"]),
    ('{"pose": {"z": {"mean": 0.5}}, "duration": 1, "step": 0.01}', []),
])
def test_bad_scene_files_fail_naming_the_manoeuvre(tmp_path, text, words):
    scenes = tmp_path / "scenes"
    scenes.mkdir()
    (scenes / "broken.json").write_text(text)
    spec = {**ENVELOPE, "manoeuvres": [{"scene": "broken"}]}
    if not words:  # a valid scene file: the spec resolves
        assert resolve(spec, scenes)["manoeuvres"][0]["name"] == "broken"
        return
    _assert_refused(tmp_path, spec, words, scenes=scenes)


def test_bad_spec_files_fail_naming_the_file(tmp_path):
    _assert_refused(tmp_path, "{", ["bad.json", "Expecting property name"])
    _assert_refused(tmp_path, "[]", ["the spec must be a JSON object"])


def test_an_out_dir_that_cannot_be_made_fails_naming_it(tmp_path):
    _assert_refused(tmp_path, ENVELOPE, ["OUT_DIR = /proc/stewart-sweep/out"],
                    out=pathlib.Path("/proc/stewart-sweep/out"))
    a_file = tmp_path / "a_file"
    a_file.write_text("")
    _assert_refused(tmp_path, ENVELOPE, [f"OUT_DIR = {a_file}"], out=a_file)
    _assert_refused(tmp_path, ENVELOPE, [f"OUT_DIR = {a_file / 'below'}"], out=a_file / "below")


def test_a_workspace_grid_larger_than_memory_is_refused_at_once(tmp_path):
    """10^6 x 10^6 poses: refused before any work, saying how much memory it needs."""
    huge = {"start": -0.1, "stop": 0.1, "num": 1000000}
    spec = {**WORKSPACE, "slices": [{"name": "xy", "fixed": {"z": 0.5}, "axes": {"x": huge, "y": huge}}]}
    _assert_refused(tmp_path, spec, ["slices[0] (xy: 1000000 x 1000000 grid)", "1e+12 poses", "memory"])
    _assert_refused(tmp_path, {**WORKSPACE, "poses_per_chunk": 10**13}, ["poses_per_chunk", "memory"])


def test_a_whole_number_written_as_a_float_is_a_count():
    """JSON writers put 5.0 for 5: the same range."""
    as_float = {**ENVELOPE, "payload_mass": {"start": 0, "stop": 60, "num": 2.0}}
    assert resolve(as_float, SCENES) == resolve(ENVELOPE, SCENES)


def test_workspace_spec_errors_name_the_slice_field():
    bad = {**WORKSPACE, "slices": [{"name": "a", "fixed": {"z": 0.5}, "axes": {"x": [], "y": [0.0]}}]}
    with pytest.raises(SpecError, match=r"slices\[0\].axes.x is empty"):
        resolve(bad, SCENES)
    bad = {**WORKSPACE, "slices": [{"name": "a", "fixed": {"x": 0.0}, "axes": {"y": [0.0]}}]}
    with pytest.raises(SpecError, match=r"slices\[0\]: z is neither fixed nor an axis"):
        resolve(bad, SCENES)


def test_failing_cases_are_recorded_and_a_rerun_computes_only_missing_chunks(tmp_path):
    """A singularity threshold between the two manoeuvres' conditions (heave reaches about 12.0,
    yaw stays near 11.9 at these amplitudes) fails the heave cases as singular, the others solve."""
    spec = {**ENVELOPE, "fidelity": ["massless"], "options": {"warn_condition": 1, "singular_condition": 11.95}}
    out, first = _sweep(tmp_path, spec, "fail", workers=1)
    t = _table(out, "envelope.parquet")
    heave = t["manoeuvre"] == "heave"
    assert np.all(t["status"][heave] == -3) and np.all(t["status"][~heave] == 0)
    assert all("singular" in m and "condition" in m for m in t["message"][heave])
    assert all(m is None for m in t["peak_power"][heave]) or np.all(np.isnan(t["peak_power"][heave].astype(float)))
    assert np.all(t["max_condition"][~heave].astype(float) <= 11.95)
    # Interrupted: two chunk files lost. The rerun computes those two only, to the same result.
    chunk_files = sorted((out / "chunks").glob("*.parquet"))
    for f in chunk_files[1:3]:
        f.unlink()
    (out / "envelope.parquet").unlink()
    _, second = _sweep(tmp_path, spec, "fail", workers=1)
    assert sorted(c["chunk"] for c in second["computed"]) == [f.name for f in chunk_files[1:3]]
    _assert_tables_equal(_table(out, "envelope.parquet"), t)


def test_a_worker_that_cannot_see_out_dir_sends_its_table(envelope_runs, tmp_path):
    """Workers on another machine return their chunk's table for the client to write: the same
    table the workers that saw OUT_DIR wrote."""
    out = envelope_runs[1]
    spec = json.loads((out / "spec.json").read_text())
    chunk = chunks(spec)[2]
    table, stats = compute_chunk(spec, chunk, str(tmp_path / "not-there"))
    assert stats["worker"] == "local" and stats["cases"] == chunk.stop - chunk.start
    assert table.equals(pq.read_table(out / "chunks" / chunk.file_name))


def test_dictionary_columns_equal_arrow_s_own_encoding():
    """work.dictionary_column (a workspace chunk's slice and message columns, built without a
    loop over rows) against pyarrow's dictionary_encode of the row-by-row list: same indices,
    same dictionary in the same order, same type, whatever rows hold text."""
    import random
    import pyarrow as pa
    from stewart.sweeps.work import dictionary_column
    rng = random.Random(7)
    for _ in range(2000):
        n = rng.randint(1, 25)
        texts = {r: rng.choice(["unreachable", "singular", "", "x"])
                 for r in rng.sample(range(n), rng.randint(0, n))}
        default = rng.choice(["", "xy", "singular"])
        expected = pa.array([texts.get(j, default) for j in range(n)]).dictionary_encode()
        got = dictionary_column(n, default, texts)
        assert got.type == expected.type and got.equals(expected), (n, default, texts)


def test_workspace_chunks_in_reused_arrays_and_blocks_equal_one_call(tmp_path, monkeypatch):
    """A workspace chunk built in the arrays of the thread's previous chunk (reuse=True, as a
    worker that writes its own file builds it), solved and checked in blocks of 96 rows, is the
    table one call per chunk in fresh arrays gives, bit for bit: slices of two and of one axis,
    the shorter last chunk of a slice (a new size), a last block shorter than the others, and
    failing rows with their messages. A worker that sends its table back (no OUT_DIR here) gets
    one that owns its arrays."""
    from stewart.sweeps import load
    from stewart.sweeps import work
    spec = json.loads(json.dumps(WORKSPACE))
    spec["slices"].append({"name": "z", "fixed": {"x": 0.01, "roll": 0.1},
                           "axes": {"z": {"start": 0.3, "stop": 0.8, "num": 900}}})
    spec["options"] = {"singular_condition": 12.4, "warn_condition": 12.0}  # about half the rows fail
    path = tmp_path / "spec.json"
    path.write_text(json.dumps(spec))
    spec = load(path, SCENES)
    failed = 0
    for chunk in chunks(spec):
        monkeypatch.setattr(work, "BLOCK_ROWS", 10**9)
        fresh, _ = work.workspace_chunk(spec, chunk)
        monkeypatch.setattr(work, "BLOCK_ROWS", 96)
        reused, _ = work.workspace_chunk(spec, chunk, reuse=True)
        assert reused.schema == fresh.schema and reused.equals(fresh), chunk
        for name in fresh.column_names:
            a = fresh[name].to_numpy(zero_copy_only=False)
            b = reused[name].to_numpy(zero_copy_only=False)
            if a.dtype.kind == "f":
                assert np.array_equal(a.view(np.int64), b.view(np.int64)), (chunk, name)
        failed += sum(1 for m in fresh["message"].to_pylist() if m)
    assert failed > 100
    chunk = chunks(spec)[1]
    sent, _ = compute_chunk(spec, chunk, str(tmp_path / "not-there"))
    expected, _ = work.workspace_chunk(spec, chunk)
    work.workspace_chunk(spec, chunks(spec)[0], reuse=True)  # another chunk in this thread's arrays
    assert sent.equals(expected)


def _assert_rows_equal(a, b, what):
    """The same schema and the same values, floats bit for bit, text decoded (a table written
    block by block has one message dictionary per block)."""
    assert a.schema == b.schema, what
    for name in a.column_names:
        x = a[name].to_numpy(zero_copy_only=False)
        y = b[name].to_numpy(zero_copy_only=False)
        if x.dtype.kind == "f":
            assert np.array_equal(x.view(np.int64), y.view(np.int64)), (what, name)
        else:
            assert list(x) == list(y), (what, name)


def test_workspace_chunks_written_block_by_block_equal_one_call(tmp_path, monkeypatch):
    """A workspace chunk written by the worker that computes it (compute_chunk with an OUT_DIR)
    goes to its file block by block, one row group per block, the table's columns block-sized:
    the file's rows are the table one call per chunk in fresh arrays gives, bit for bit (blocks
    of 96 rows, a shorter last block and chunk, failing rows with their messages), and a chunk of
    one block is the same file as write_parquet writes, byte for byte. The merged slices equal
    the concatenated one-call tables."""
    from stewart.sweeps import load, work
    from stewart.sweeps.run import merge, prepare, write_parquet
    spec = json.loads(json.dumps(WORKSPACE))
    spec["options"] = {"singular_condition": 12.4, "warn_condition": 12.0}  # about half the rows fail
    path = tmp_path / "spec.json"
    path.write_text(json.dumps(spec))
    spec, out = prepare(path, tmp_path / "out", SCENES)
    monkeypatch.setattr(work, "BLOCK_ROWS", 96)
    expected = {}
    for chunk in chunks(spec):
        _, stats = compute_chunk(spec, chunk, str(out))
        assert stats["write_seconds"] > 0
        written = pq.read_table(out / "chunks" / chunk.file_name)
        assert pq.ParquetFile(out / "chunks" / chunk.file_name).num_row_groups == -(-(chunk.stop - chunk.start) // 96)
        expected[chunk] = work.workspace_chunk(spec, chunk)[0]
        _assert_rows_equal(written, expected[chunk], chunk)
    assert not list((out / "chunks").glob(".*.tmp"))
    merge(spec, out)
    for s in spec["slices"]:
        merged = pq.read_table(out / f"workspace_{s['name']}.parquet").drop_columns(["boundary"])
        import pyarrow as pa
        one = pa.concat_tables(expected[c] for c in chunks(spec) if c.part == s["name"])
        _assert_rows_equal(merged, one, s["name"])
    monkeypatch.setattr(work, "BLOCK_ROWS", 10**9)
    chunk = chunks(spec)[0]
    compute_chunk(spec, chunk, str(out))
    write_parquet(work.workspace_chunk(spec, chunk)[0], tmp_path / "one.parquet")
    assert (out / "chunks" / chunk.file_name).read_bytes() == (tmp_path / "one.parquet").read_bytes()


# ---------------------------------------------------------------- feasibility studies


def _solve_cli_peaks(t, q, tmp_path, params, derivatives=None):
    """stewart-solve on a CSV of t and poses (its own finite differences when derivatives is
    None): the envelope's peaks computed here from its output."""
    inp, out = tmp_path / "in.csv", tmp_path / "out.csv"
    cols = ["t", *POSE] + ([] if derivatives is None else [*POSE_DOT, *POSE_DDOT])
    rows = np.hstack([t[:, None], q] + ([] if derivatives is None else list(derivatives)))
    inp.write_text(",".join(cols) + "\n" + "".join(",".join(repr(float(v)) for v in r) + "\n" for r in rows))
    args = [str(stewart_solve_path()), "--fidelity", "massless"]
    for k, v in params.items():
        args += ["--param", f"{k}={float(v)!r}"]
    r = subprocess.run(args + [str(inp), str(out)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    o = np.loadtxt(out, delimiter=",", skiprows=1, usecols=range(27))  # status is text
    return {"L": o[:, 1:7], "Ld": o[:, 7:13], "Ldd": o[:, 13:19], "F": o[:, 19:25]}


@pytest.mark.parametrize("machine", [None, "simona_motion_base"])
def test_inline_scenes_take_the_spec_s_duration_and_step(tmp_path, machine):
    """An inline scene without duration and step plays for the spec's top-level duration at its
    step (before: refused with "scene.duration = None", a field the user never wrote), on the
    thesis platform and on the motion simulator where it was met."""
    scene = {"name": "nod", "pose": {"z": {"mean": 0.5}, "pitch": {"amplitude": 0.05, "omega": 3.0}}}
    spec = {"kind": "envelope", "manoeuvres": [{"scene": scene}], "duration": 0.6, "step": 0.02}
    if machine is not None:
        spec["platform_file"] = str(stewart.platform_files()[machine])
    resolved = resolve(spec, SCENES)
    assert resolved["manoeuvres"][0]["scene"]["duration"] == 0.6
    out, _ = _sweep(tmp_path, spec, "inline", workers=1)
    t = _table(out, "envelope.parquet")
    assert list(t["poses"]) == [31] and list(t["status"]) == [0] and list(t["manoeuvre"]) == ["nod"]
    with pytest.raises(SpecError, match=r"manoeuvres\[0\].scene has no step: give it in the "
                                         r"scene or as the spec's top-level step"):
        resolve({**spec, "step": None}, SCENES)


def test_platform_files_with_a_payload_are_swept(tmp_path):
    """A platform file that gives payload_mass and payload_com (any field a machine has): its
    payload is the sweep's single case, or the top-level ranges sweep it (before: refused with
    "platform.payload_mass: the envelope sweeps it", a field the user never wrote)."""
    import json as _json
    machine = _json.loads(stewart.platform_files()["thesis"].read_text())
    machine.update(payload_mass=35.0, payload_com=[0.01, 0.0, 0.1])
    (tmp_path / "machine.json").write_text(_json.dumps(machine))
    spec = {"kind": "envelope", "platform_file": "machine.json",
            "manoeuvres": [{"scene": "heave"}], "duration": 0.5}
    path = tmp_path / "spec.json"
    path.write_text(_json.dumps(spec))
    resolved = stewart.sweeps.load(path, SCENES)
    assert resolved["payload_mass"] == [35.0] and resolved["payload_com"] == [[0.01, 0.0, 0.1]]
    assert "payload_mass" not in resolved["platform"]
    path.write_text(_json.dumps({**spec, "payload_mass": [0, 70]}))
    assert stewart.sweeps.load(path, SCENES)["payload_mass"] == [0.0, 70.0]
    both = {**ENVELOPE, "platform": {"payload_mass": 3}, "payload_mass": [1, 2]}
    with pytest.raises(SpecError, match="platform.payload_mass and the top-level payload_mass"):
        resolve(both, SCENES)


def test_cases_beyond_a_limit_are_rows_with_their_class_and_margin(tmp_path):
    """Heave amplitudes x1 .. x4: the larger ones leave the stroke. Every case is a row (before:
    one case beyond the stroke refused the whole sweep); its limit class, the time of the first
    pose beyond a limit and the smallest stroke margin against the lengths computed here."""
    spec = {"kind": "envelope", "platform": {"stroke_min": STROKE[0], "stroke_max": STROKE[1]},
            "manoeuvres": [{"scene": "heave", "amplitude": [1, 2, 3, 4]}], "duration": 1.0}
    out, _ = _sweep(tmp_path, spec, "feasible", workers=1)
    t = _table(out, "envelope.parquet")
    assert list(t["amplitude"]) == [1, 2, 3, 4] and np.all(t["status"] == 0)
    assert t["feasible"][0] and not t["feasible"][3]
    for row, amplitude in enumerate(t["amplitude"]):
        time, q, _, _ = _scene_poses("heave", amplitude, 1.0, 1.0)
        L = np.array([reference.lengths(p) for p in q])
        margin = np.minimum(L - STROKE[0], STROKE[1] - L).min(axis=1)
        assert t["margin_stroke"][row] == pytest.approx(margin.min(), abs=1e-12)
        beyond = np.flatnonzero(margin < 0)
        assert t["feasible"][row] == (beyond.size == 0)
        if beyond.size:
            assert t["limit_class"][row] == 1 and t["limit_t"][row] == pytest.approx(time[beyond[0]])
        else:
            assert t["limit_class"][row] == 0 and np.isnan(t["limit_t"][row].astype(float))
    assert t["peak_force_1"][3] is not None and float(t["peak_force_1"][3]) > 0


def _trajectory(n=60):
    """A smooth made-up move: t not evenly spaced, every component moving."""
    t = np.cumsum(np.r_[0.0, 0.01 + 0.005 * np.sin(np.arange(n - 1))])
    s = t / t[-1]
    q = np.column_stack([0.02 * np.sin(3 * s), -0.015 * s ** 2, 0.5 + 0.03 * s * (1 - s),
                         0.04 * np.sin(2 * s), -0.03 * s, 0.05 * np.sin(5 * s)])
    return t, q


@pytest.mark.parametrize("derivatives", [False, True])
def test_csv_manoeuvres_are_swept_in_amplitude_and_frequency(tmp_path, derivatives):
    """A CSV trajectory (t and poses, with or without derivative columns) scaled about its first
    pose by amplitude and played faster by frequency: each case's peaks equal stewart-solve's on
    the scaled trajectory written here (stewart-solve differentiating it itself when the file
    has no derivative columns)."""
    t, q = _trajectory()
    cols = ["t", *POSE]
    rows = [t[:, None], q]
    if derivatives:
        from stewart.sweeps.trajectory import finite_difference
        qd = np.column_stack([finite_difference(t, q[:, i], 1) for i in range(6)]) * 1.01
        qdd = np.column_stack([finite_difference(t, q[:, i], 2) for i in range(6)]) * 0.99
        cols += [*POSE_DOT, *POSE_DDOT]
        rows += [qd, qdd]
    (tmp_path / "move.csv").write_text(",".join(cols) + "\n" + "".join(
        ",".join(repr(float(v)) for v in r) + "\n" for r in np.hstack(rows)))
    spec = {"kind": "envelope", "payload_mass": [20.0],
            "manoeuvres": [{"csv": "move.csv", "amplitude": [0.5, 2.0], "frequency": [1.0, 3.0]}]}
    out, _ = _sweep(tmp_path, spec, "csv", workers=1)
    table = _table(out, "envelope.parquet")
    assert len(table["case"]) == 4 and np.all(table["status"] == 0)
    assert list(table["manoeuvre"]) == ["move"] * 4
    for row in range(4):
        a, f = table["amplitude"][row], table["frequency"][row]
        scaled_t = t[0] + (t - t[0]) / f
        scaled_q = q[0] + a * (q - q[0])
        d = None if not derivatives else (a * f * qd, a * f * f * qdd)
        ref = _solve_cli_peaks(scaled_t, scaled_q, tmp_path, {"payload_mass": 20.0}, d)
        for k in range(6):
            assert table[f"peak_force_{k + 1}"][row] == pytest.approx(np.abs(ref["F"][:, k]).max(), rel=1e-9)
        assert table["peak_length_rate"][row] == pytest.approx(np.abs(ref["Ld"]).max(), rel=1e-9)
        assert table["peak_length_accel"][row] == pytest.approx(np.abs(ref["Ldd"]).max(), rel=1e-9)
        assert table["length_max"][row] == pytest.approx(ref["L"].max(), rel=1e-12)


@pytest.mark.parametrize("text, words", [
    ("t,x,y,z,roll,pitch\n0,0,0,0.5,0,0\n", ["manoeuvres[0].csv", "'yaw' is missing"]),
    ("t,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0,0\n0,0,0,0.5,0,0,0\n", ["line 3", "does not increase"]),
    ("t,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0,nan\n", ["line 2", "column yaw = 'nan'"]),
    ("t,x,y,z,roll,pitch,yaw,x_dot\n0,0,0,0.5,0,0,0,0\n", ["_dot columns must be all six"]),
])
def test_bad_csv_manoeuvres_are_refused_naming_the_line(tmp_path, text, words):
    (tmp_path / "move.csv").write_text(text)
    spec = {**ENVELOPE, "manoeuvres": [{"csv": str(tmp_path / "move.csv")}]}
    _assert_refused(tmp_path, spec, words)


def test_results_follow_the_units_asked_for(tmp_path):
    """--units mm,deg: lengths x 1000, angles x 180/pi in the merged tables, the CSV and
    volume.json, each field's unit in its metadata; forces, conditions and flags unchanged;
    the chunks stay SI (the same files either way)."""
    spec = {**WORKSPACE, "slices": [WORKSPACE["slices"][1]], "volume": {"cells": 24}}
    si, _ = _sweep(tmp_path, spec, "si", workers=1)
    path = tmp_path / "mm.json"
    path.write_text(json.dumps(spec))
    r = subprocess.run([sys.executable, str(ROOT / "scripts/sweep.py"), str(path), str(tmp_path / "mm"),
                        "--workers", "1", "--no-progress", "--units", "mm,deg"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    mm = tmp_path / "mm"
    a, b = _table(si, "workspace_rp.parquet"), _table(mm, "workspace_rp.parquet")
    for name in a:
        factor = {"x": 1e3, "y": 1e3, "z": 1e3, "margin_stroke": 1e3, "margin_interference": 1e3,
                  **{f"L{k}": 1e3 for k in range(1, 7)}, "roll": 180 / np.pi, "pitch": 180 / np.pi,
                  "yaw": 180 / np.pi, "margin_base_joint": 180 / np.pi,
                  "margin_platform_joint": 180 / np.pi}.get(name, 1)
        if a[name].dtype.kind == "f":
            np.testing.assert_allclose(b[name], a[name] * factor, rtol=1e-15, err_msg=name)
        else:
            assert list(a[name]) == list(b[name]), name
    schema = pq.read_schema(mm / "workspace_rp.parquet")
    assert schema.field("x").metadata[b"unit"] == b"mm" and schema.field("roll").metadata[b"unit"] == b"deg"
    assert schema.field("F1").metadata[b"unit"] == b"N"
    for chunk in (si / "chunks").glob("*.parquet"):
        assert chunk.read_bytes() == (mm / "chunks" / chunk.name).read_bytes()
    va, vb = (json.loads((d / "volume.json").read_text()) for d in (si, mm))
    assert vb["volume_unit"] == "mm^3" and vb["volume"] == pytest.approx(va["volume_m3"] * 1e9, rel=1e-15)
    assert va["volume_unit"] == "m^3" and va["volume"] == va["volume_m3"]


def test_envelope_csv_in_the_units_asked_for(tmp_path):
    spec = {**ENVELOPE, "fidelity": ["massless"], "payload_mass": [10.0]}
    path = tmp_path / "spec.json"
    path.write_text(json.dumps(spec))
    run(path, tmp_path / "out", SCENES, workers=1, progress=False, log=lambda m: None, units="mm")
    t = _table(tmp_path / "out", "envelope.parquet")
    import csv
    with open(tmp_path / "out" / "envelope.csv") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    assert "length_max [mm]" in header and "peak_length_rate [mm/s]" in header
    assert "peak_force_1 [N]" in header and "manoeuvre" in header
    col = header.index("length_max [mm]")
    np.testing.assert_array_equal([float(r[col]) for r in rows[1:]], t["length_max"].astype(float))
    assert 400 < float(rows[1][col]) < 700  # the thesis legs' half-metre in mm
    with pytest.raises(ValueError, match="'furlong' is neither a length unit"):
        run(path, tmp_path / "bad", SCENES, workers=1, progress=False, log=lambda m: None, units="furlong")


@pytest.mark.parametrize("name", sorted(stewart.platform_files()))
def test_feasibility_on_every_shipped_machine(name):
    """A heave written about each shipped machine's home ("place": "absolute": its poses as
    written; its platform file as it is, payload and all):
    at half the distance to the nearer end of home's z axis range every pose is within every
    limit; at 1.5 times it the case is a row beyond the limit that ends the axis range first,
    with a negative margin of that class (a machine whose home is beyond a limit: every case,
    from t = 0, with home's class)."""
    from stewart.sweeps.work import envelope_chunk
    from test_workspace_volume import home
    path = stewart.platform_files()[name]
    plat = stewart.Platform.from_file(path)
    q0 = home(plat)
    ranges = plat.axis_ranges(q0, details=True)
    (low, high), (low_class, high_class) = ranges.ends[0, 2], ranges.limit[0, 2]
    up, down = high - q0[2], q0[2] - low
    amplitude = max(min(up, down), 1e-3)
    scene = {"name": "heave", "pose": {c: {"mean": float(v)} for c, v in zip(POSE, q0)}}
    scene["pose"]["z"].update(amplitude=amplitude, omega=2 * np.pi)
    spec = resolve({"kind": "envelope", "platform_file": str(path), "duration": 1.0, "step": 0.005,
                    "manoeuvres": [{"scene": scene, "place": "absolute",
                                    "amplitude": [0.5, 1.5]}]}, SCENES)
    table, _ = envelope_chunk(spec, chunks(spec)[0])
    t = {k: table[k].to_pylist() for k in table.column_names}
    assert t["status"] == [0, 0] and t["poses"] == [201, 201]
    at_home = plat.limits(q0)
    if not at_home.within[0]:
        assert t["feasible"] == [False, False] and t["limit_t"] == [0.0, 0.0]
        assert t["limit_class"] == [int(at_home.first[0])] * 2
        return
    assert t["feasible"] == [True, False] and t["limit_class"][0] == 0
    expected = high_class if 1.5 * amplitude >= up else low_class
    assert t["limit_class"][1] == expected != 0
    from stewart.limits import LIMIT_CLASSES
    assert t[f"margin_{LIMIT_CLASSES[expected - 1]}"][1] < 0


@pytest.mark.parametrize("about", ["home", [0.01, -0.02, 0.45, 0.0, 0.02, 0.1]])
def test_csv_manoeuvres_scale_about_home_or_a_given_pose(tmp_path, about):
    """about = "home" (the machine's home pose, from its frames, computed in the test) or 6
    numbers: q = about + amplitude (q_file - about), rates x amplitude x frequency."""
    from stewart.sweeps.spec import manoeuvre_samples
    from test_workspace_volume import home
    t, q = _trajectory()
    (tmp_path / "move.csv").write_text("t,x,y,z,roll,pitch,yaw\n" + "".join(
        ",".join(repr(float(v)) for v in r) + "\n" for r in np.hstack([t[:, None], q])))
    frames = {"tool_frame": [0.0, 0.0, 0.1, 0.0, 0.0, 0.2], "user_frame": [0.0, 0.0, 0.05, 0, 0, 0]}
    spec = resolve({"kind": "envelope", "platform": frames,
                    "manoeuvres": [{"csv": str(tmp_path / "move.csv"), "about": about}]}, SCENES)
    reference_pose = home(stewart.Platform(**frames)) if about == "home" else np.array(about)
    scaled_t, scaled_q, scaled_qd, _ = manoeuvre_samples(spec, spec["manoeuvres"][0], 3.0, 2.0)
    np.testing.assert_allclose(scaled_q, reference_pose + 3.0 * (q - reference_pose), atol=1e-14)
    np.testing.assert_allclose(scaled_t, t / 2.0, atol=1e-15)
    from stewart.sweeps.trajectory import finite_difference
    np.testing.assert_allclose(scaled_qd[:, 2], 6.0 * finite_difference(t, q[:, 2], 1), rtol=1e-13)

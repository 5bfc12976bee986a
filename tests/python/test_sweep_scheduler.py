"""scripts/sweep.py on an external Dask cluster: a `dask scheduler` and two `dask worker`
processes on 127.0.0.1, started and stopped here. Both workers must do work, and the results must
equal a LocalCluster run of the same spec."""
import json
import os
import pathlib
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")
pq = pytest.importorskip("pyarrow.parquet")
distributed = pytest.importorskip("distributed")
from stewart.sweeps import run  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
DASK = pathlib.Path(sys.executable).with_name("dask")
SPEC = {
    "kind": "envelope", "fidelity": ["full"], "payload_mass": [0.0, 30.0, 60.0],
    "payload_com": [[0.0, 0.0, 0.1]],
    "manoeuvres": [{"scene": "roll", "amplitude": [0.5, 1.0]}, {"scene": "combined", "frequency": [1.0, 1.5]}],
    "duration": 4.0, "cases_per_chunk": 1,
}


def _start(args, log):
    return subprocess.Popen([str(DASK), *args], stdout=log, stderr=subprocess.STDOUT,
                            start_new_session=True)


def _stop(proc):
    """SIGTERM to the process group this test started (a worker's nanny and its child), then
    SIGKILL if it is still there after 15 s."""
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(15)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(5)


@pytest.fixture
def cluster(tmp_path):
    if not DASK.exists():
        pytest.fail(f"{DASK} is missing: install distributed (scripts/requirements.txt)")
    scheduler_file = tmp_path / "scheduler.json"
    log = open(tmp_path / "dask.log", "w")
    procs = [_start(["scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                     "--scheduler-file", str(scheduler_file)], log)]
    try:
        deadline = time.monotonic() + 60
        while not scheduler_file.exists():
            assert time.monotonic() < deadline and procs[0].poll() is None, (tmp_path / "dask.log").read_text()
            time.sleep(0.2)
        for name in ("w1", "w2"):
            procs.append(_start(["worker", "--scheduler-file", str(scheduler_file), "--host", "127.0.0.1",
                                 "--nthreads", "1", "--no-dashboard", "--name", name,
                                 "--death-timeout", "60"], log))
        address = json.loads(scheduler_file.read_text())["address"]
        assert address.startswith("tcp://127.0.0.1:")
        with distributed.Client(address, timeout="30s") as client:
            client.wait_for_workers(2, timeout=60)
            # Both workers answer (and have imported the solver) before the sweep starts: on a
            # loaded machine a worker still starting up would leave every chunk to the other.
            answered = client.run(exec, "import stewart.sweeps.work", wait=True)
            workers = set(client.scheduler_info()["workers"])
            assert set(answered) == workers
        yield address, workers
    finally:
        for p in reversed(procs):
            _stop(p)
        log.close()


def test_sweep_on_an_external_scheduler_equals_the_local_one(cluster, tmp_path):
    """Every sweep on the cluster equals the local run. Dask decides which worker takes a chunk:
    on a loaded machine (CI's test run) one worker once took all twelve of a sweep's 20 ms chunks,
    so the sweep runs up to three times, and at least one must have used both workers."""
    address, workers = cluster
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps(SPEC))
    run(spec, tmp_path / "local", ROOT / "scenes", workers=1, progress=False, log=lambda m: None)
    local = pq.read_table(tmp_path / "local/envelope.parquet")
    used_by_sweep = []
    for attempt in range(3):
        out = tmp_path / f"remote{attempt}"
        r = subprocess.run([sys.executable, str(ROOT / "scripts/sweep.py"), str(spec), str(out),
                            "--scheduler", address, "--no-progress"],
                           capture_output=True, text=True, timeout=120)
        assert r.returncode == 0, r.stderr
        summary = json.loads((out / "run.json").read_text())
        used = {c["worker"] for c in summary["computed"]}
        assert used <= workers
        remote = pq.read_table(out / "envelope.parquet")
        assert remote.num_rows == 12 and np.all(remote["status"].to_numpy() == 0)
        assert remote.equals(local)
        for column in remote.column_names:
            if remote[column].type == "double":
                np.testing.assert_array_equal(remote[column].to_numpy(), local[column].to_numpy())
        used_by_sweep.append(len(used))
        if used == workers:
            break
    assert used_by_sweep[-1] == 2, f"workers used by each sweep: {used_by_sweep}"

"""A suite on a real multi-process Dask cluster: a scheduler and two single-threaded workers
started here on 127.0.0.1 with the ``dask`` command line, connected to by address."""

import io
import json
import os
import shutil
import subprocess
import time
from pathlib import Path

import pandas as pd
import pytest

from femoat.suite import load_suite, load_table, run_suite

ROOT = Path(__file__).resolve().parents[1]
PEER = Path(__file__).parent / "data" / "peer"

pytestmark = pytest.mark.skipif(shutil.which("dask") is None,
                                reason="the dask command line (dask[distributed]) is missing")

SUITE = """
[records]
files = {files}
duration = 3.0
extra_time = 0.5
[variations]
"walls.law" = ["E", "H"]
[scaling]
method = "pga"
targets = [0.3, 0.9]
[run]
batch_size = 2
"""


@pytest.fixture
def cluster(tmp_path):
    path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    env = {**os.environ, "PYTHONPATH": path}
    file = tmp_path / "scheduler.json"
    procs = [subprocess.Popen(["dask", "scheduler", "--host", "127.0.0.1", "--port", "0",
                               "--no-dashboard", "--scheduler-file", str(file)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        deadline = time.monotonic() + 60
        while not file.is_file() and time.monotonic() < deadline:
            time.sleep(0.1)
        address = json.loads(file.read_text())["address"]
        for _ in range(2):
            procs.append(subprocess.Popen(
                ["dask", "worker", address, "--nthreads", "1", "--no-nanny",
                 "--host", "127.0.0.1", "--no-dashboard"], env=env, cwd=tmp_path,
                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        from dask.distributed import Client

        with Client(address, timeout=60) as client:
            client.wait_for_workers(2, timeout=60)
        yield address, file
    finally:
        for p in procs:  # only the processes started here, by their ids
            p.kill()
            p.wait(timeout=20)


def test_suite_on_a_two_worker_cluster_equals_the_serial_run(cluster, tmp_path):
    path = tmp_path / "suite.toml"
    # three of the shipped records: 3 x 2 laws x 2 PGAs = 12 runs
    files = [(PEER / n).as_posix() for n in ("Rinaldi228.AT2", "RSN77_SFERN_PUL164.AT2",
                                              "RSN181_IMPVALL.H_H-E06230.AT2")]
    path.write_text(SUITE.format(files=json.dumps(files)), encoding="utf-8")
    suite = load_suite(path)
    address, scheduler_file = cluster
    summary = run_suite(suite, tmp_path / "dask", scheduler=address, stream=io.StringIO())
    # 3 records x 2 laws x 2 PGAs = 12 runs in 6 batches of 2
    assert summary["runs"] == 12 and summary["failed_tasks"] == 0
    assert len(list((tmp_path / "dask" / "runs").glob("part-*.parquet"))) == 6
    run_suite(suite, tmp_path / "serial", serial=True, stream=io.StringIO())
    timing = ["cpu_seconds", "solver_seconds"]
    got, want = (load_table(tmp_path / d).sort_values("run_id").reset_index(drop=True)
                 .drop(columns=timing) for d in ("dask", "serial"))
    pd.testing.assert_frame_equal(got, want)
    # lose half the parts, resume through the scheduler file: the same table again
    for part in sorted((tmp_path / "dask" / "runs").glob("part-*.parquet"))[:3]:
        part.unlink()
    again = run_suite(suite, tmp_path / "dask", scheduler_file=scheduler_file,
                      stream=io.StringIO())
    assert again["todo"] == 6 and again["runs"] == 6
    got = load_table(tmp_path / "dask").sort_values("run_id").reset_index(drop=True)
    pd.testing.assert_frame_equal(got.drop(columns=timing), want)


def test_local_cluster_by_default(tmp_path):
    # what `femoat suite FILE` does without --serial: a LocalCluster of single-threaded workers
    path = tmp_path / "suite.toml"
    files = [(PEER / "Rinaldi228.AT2").as_posix()]
    text = SUITE.format(files=json.dumps(files)).replace('["E", "H"]', '["H"]')
    path.write_text(text.replace("duration = 3.0", "duration = 1.0"), encoding="utf-8")
    summary = run_suite(load_suite(path), tmp_path / "out", workers=1, stream=io.StringIO())
    # 1 record x 1 law x 2 PGAs
    assert summary["runs"] == 2 and summary["failed_tasks"] == 0
    # the client compiled the kernels into numba's cache before the worker started: the worker
    # loads every entry point from it and compiles nothing itself
    assert summary["worker_compiles"] == [0]
    assert len(load_table(tmp_path / "out")) == 2


def test_a_run_that_kills_its_task_is_isolated_and_stored(tmp_path, monkeypatch):
    # a worker thread in this process (processes=False) sees a Batch task that fails whenever
    # it holds one particular run: the batch is split, the others are stored
    from dask.distributed import LocalCluster

    from femoat.suite import runs

    path = tmp_path / "suite.toml"
    files = [(PEER / "Rinaldi228.AT2").as_posix()]
    path.write_text(SUITE.format(files=json.dumps(files)).replace("batch_size = 2",
                                                                  "batch_size = 4"))
    suite = load_suite(path)
    poisoned = runs.plan(suite)[1].run_id
    real = runs.Batch.run

    def run(batch, suite, out_dir=None):
        if any(s.run_id == poisoned for s in batch.specs):
            raise RuntimeError("worker lost")
        return real(batch, suite, out_dir)

    monkeypatch.setattr(runs.Batch, "run", run)
    with LocalCluster(n_workers=1, processes=False, dashboard_address=None) as cluster:
        summary = run_suite(suite, tmp_path / "out", scheduler=cluster.scheduler_address,
                            stream=io.StringIO())
    df = load_table(tmp_path / "out")
    # 1 record x 2 laws x 2 PGAs = 4 runs in one batch: split into 4, 3 ok and 1 error row
    assert summary["runs"] == 4 and len(df) == 4
    bad = df[df["run_id"] == poisoned].iloc[0]
    assert bad["status"] == "error" and "worker lost" in bad["error"]
    assert bad["error"].startswith(f"run {poisoned} (")
    assert set(df[df["run_id"] != poisoned]["status"]) <= {"ok", "collapsed"}

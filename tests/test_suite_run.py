"""Running suites: same numbers as run(), failures stored, resume after a kill, exports."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import DATA, three_records
from femoat.suite import load_suite, load_table, run_suite, to_demand_csv, to_xarray

PEER = DATA / "peer"
ROOT = Path(__file__).resolve().parents[1]

SMALL = """
[records]
folder = "{folder}"
duration = {duration}
extra_time = 0.5
[variations]
"walls.law" = ["E", "H"]
[scaling]
method = "ida"
period = 1.0
levels = [0.5, 1.5]
[run]
batch_size = {batch}
"""


def _suite(tmp_path, text=SMALL, duration=3.0, batch=3, name="suite.toml"):
    path = tmp_path / name
    folder = three_records(tmp_path / "peer")
    path.write_text(text.format(folder=folder.as_posix(), duration=duration, batch=batch),
                    encoding="utf-8")
    return path


def _quiet():
    import io

    return io.StringIO()


def test_suite_runs_equal_single_runs_bit_for_bit(tmp_path):
    from femoat.collapse import CollapseCriteria
    from femoat.ground_motions import GroundMotion, read_at2, response_spectrum
    from femoat.run import run
    from femoat.scenario import building_from_dict, walls_from_dict
    from femoat.structure.pounding import PoundingModel
    from femoat.units import G

    from dataclasses import replace

    from femoat.results import RunResult
    from femoat.suite.runs import run_id

    suite = load_suite(_suite(tmp_path))
    # the full history of one run, by its id ([run] histories does not change the suite hash)
    wanted = run_id(suite, [r.label for r in suite.records].index("Rinaldi228"), 1, 1.5)
    suite = replace(suite, histories=(wanted,))
    run_suite(suite, tmp_path / "out", serial=True, stream=_quiet())
    df = load_table(tmp_path / "out")
    # 3 records x 2 laws x 2 levels, each stored once
    assert len(df) == 12 and df["run_id"].is_unique and set(df["status"]) <= {"ok", "collapsed"}
    row = df[(df["record"] == "Rinaldi228") & (df["walls.law"] == "H") & (df["im"] == 1.5)]
    row = row.iloc[0]
    # the same run by hand: first 3 s of the published record (301 samples at 0.01 s),
    # scaled so that Sa(T = 0.5 s) of the time-scaled record (= Sa(1 s) unscaled) is 1.5 g
    gm = read_at2(PEER / "Rinaldi228.AT2")
    gm = GroundMotion(gm.accel_g[:301], gm.dt, gm.name)
    factor = 1.5 / float(response_spectrum(gm.time_scaled(0.5), 0.5, 0.05).psa)
    assert row["scale_factor"] == factor
    building = building_from_dict({})
    walls = walls_from_dict({"law": "H"}, base_mass=building.base_weight / G)
    model = PoundingModel(building, walls)
    # the suite's default criteria: drift ratio 0.10, isolator capacity 7 in, stop at collapse
    ref = run(model, gm.scaled(factor).time_scaled(0.5), extra_time=0.5,
              collapse=CollapseCriteria())
    p = ref.peaks
    assert row["collapsed"] == ref.collapse["collapsed"]
    assert row["t_reached"] == ref.time[-1]
    assert row["peak_impact_force_pos"] == p["peak_impact_force_pos"]
    assert row["peak_impact_force_neg"] == p["peak_impact_force_neg"]
    assert row["peak_base_displacement"] == p["peak_base_displacement"]
    assert row["peak_drift_1"] == p["peak_drift"][0]
    assert row["peak_floor_acceleration_3"] == p["peak_floor_acceleration"][2]
    assert row["steps"] == p["steps"]
    assert row["run_id"] == wanted
    saved = RunResult.load(tmp_path / "out" / "histories" / f"{wanted}.npz")
    assert np.array_equal(saved.displacement, ref.displacement)
    assert row["sa_t"] == pytest.approx(1.5, rel=1e-12)
    assert row["pga"] == pytest.approx(gm.pga * factor, rel=1e-12)
    # drift ratio = drift / 39 in (default story height)
    assert row["peak_drift_ratio_1"] == pytest.approx(p["peak_drift"][0] / 39.0, rel=1e-15)

    # exports: an xarray Dataset record x intensity x variation, a pelicun demand file
    ds = to_xarray(df)
    assert dict(ds.sizes) == {"record": 3, "intensity": 2, "variation": 2}
    assert float(ds["peak_base_displacement"].sel(record="Rinaldi228", intensity=1.5,
                                                  variation="walls.law=H")) == \
        row["peak_base_displacement"]
    to_demand_csv(df, tmp_path / "demand.csv")
    demand = pd.read_csv(tmp_path / "demand.csv", index_col=0)
    assert demand.loc["Units", "PID-1-1"] == "rad" and demand.loc["Units", "PFA-4-1"] == "g"
    assert float(demand.loc[row["run_id"], "PID-1-1"]) == pytest.approx(
        row["peak_drift_ratio_1"], rel=1e-12)
    # pelicun's location 0 is the ground (PGA), 1 the base mat, k + 1 the floor atop story k
    assert float(demand.loc[row["run_id"], "PFA-0-1"]) == pytest.approx(row["pga"], rel=1e-12)
    assert float(demand.loc[row["run_id"], "PFA-4-1"]) == pytest.approx(
        row["peak_floor_acceleration_3"], rel=1e-12)


def test_a_newmark_suite_equals_newmark_single_runs_bit_for_bit(tmp_path):
    # [solver] method = "newmark" in a suite file: its rows are those of run() with
    # Integrator(method="newmark"), to the last bit (the default method's twin is above)
    from femoat.collapse import CollapseCriteria
    from femoat.ground_motions import GroundMotion, read_at2, response_spectrum
    from femoat.integration import Integrator
    from femoat.run import run
    from femoat.scenario import building_from_dict, walls_from_dict
    from femoat.structure.pounding import PoundingModel
    from femoat.units import G

    text = SMALL.replace("[variations]", '[solver]\nmethod = "newmark"\n[variations]')
    suite = load_suite(_suite(tmp_path, text))
    run_suite(suite, tmp_path / "out", serial=True, stream=_quiet())
    df = load_table(tmp_path / "out")
    row = df[(df["record"] == "Rinaldi228") & (df["walls.law"] == "E") & (df["im"] == 0.5)]
    row = row.iloc[0]
    gm = read_at2(PEER / "Rinaldi228.AT2")
    gm = GroundMotion(gm.accel_g[:301], gm.dt, gm.name)
    factor = 0.5 / float(response_spectrum(gm.time_scaled(0.5), 0.5, 0.05).psa)
    building = building_from_dict({})
    model = PoundingModel(building, walls_from_dict({"law": "E"},
                                                    base_mass=building.base_weight / G))
    ref = run(model, gm.scaled(factor).time_scaled(0.5), Integrator(method="newmark"),
              extra_time=0.5, collapse=CollapseCriteria())
    default = run(model, gm.scaled(factor).time_scaled(0.5), extra_time=0.5,
                  collapse=CollapseCriteria())
    p = ref.peaks
    assert row["steps"] == p["steps"] != default.peaks["steps"]  # really the other method
    assert row["peak_base_displacement"] == p["peak_base_displacement"]
    assert row["peak_drift_1"] == p["peak_drift"][0]
    assert row["peak_floor_acceleration_3"] == p["peak_floor_acceleration"][2]


def test_a_run_that_cannot_converge_is_stored_and_the_suite_goes_on(tmp_path):
    # two Newton iterations per attempt converge only with small enough steps: with the default
    # min_step the solver cuts its way through, with min_step = 0.004 s it gives up
    text = SMALL.replace('"walls.law" = ["E", "H"]', '"solver.min_step" = [1e-10, 0.004]') + \
        "[solver]\nmax_newton = 2\n"
    suite = load_suite(_suite(tmp_path, text))
    summary = run_suite(suite, tmp_path / "out", serial=True, stream=_quiet())
    df = load_table(tmp_path / "out")
    assert len(df) == 12 and summary["failed_tasks"] == 0
    bad = df[df["solver.min_step"] == 0.004]
    good = df[df["solver.min_step"] == 1e-10]
    assert set(good["status"]) <= {"ok", "collapsed"}
    assert "solver_failure" in set(bad["status"])
    for _, r in bad[bad["status"] == "solver_failure"].iterrows():
        # the error names its run: id, record, scale, intensity and variation, then the solver's
        assert r["error"].startswith(f"run {r['run_id']} ({r['record_name']} ")
        assert "solver.min_step=0.004" in r["error"] and "SolverError" not in r["error"]
        assert not r["collapsed"] and np.isnan(r["peak_base_displacement"])
        assert pd.isna(r["pounding"]) and pd.isna(r["steps"])


def _cli(args, **kw):
    path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    env = {**os.environ, "PYTHONPATH": path}
    return subprocess.Popen([sys.executable, "-m", "femoat.cli", "suite", *map(str, args)],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, **kw)


def test_resume_after_a_killed_suite_equals_an_uninterrupted_run(tmp_path):
    # full records (20-40 s, ~20-50 ms per run), one run per part: time to kill it half-way
    path = _suite(tmp_path, SMALL.replace("duration = {duration}\n", ""), batch=1)
    out = tmp_path / "killed"
    proc = _cli([path, "--serial", "--out", out])
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if len(list(out.glob("runs/part-*.parquet"))) >= 2:
            break
        time.sleep(0.005)
    proc.send_signal(signal.SIGKILL)
    proc.communicate()
    done = len(list((out / "runs").glob("part-*.parquet")))
    if done >= 12:
        pytest.skip("the suite finished before it could be killed (machine too fast)")
    assert done >= 2
    rerun = _cli([path, "--serial", "--out", out])
    _, err = rerun.communicate(timeout=300)
    assert rerun.returncode == 0, err.decode()
    resumed = load_table(out).sort_values("run_id").reset_index(drop=True)
    suite = load_suite(path)
    run_suite(suite, tmp_path / "whole", serial=True, stream=_quiet())
    whole = load_table(tmp_path / "whole").sort_values("run_id").reset_index(drop=True)
    # no duplicates, no missing run_ids, and the same numbers (timings aside)
    assert resumed["run_id"].is_unique and len(resumed) == 12
    assert list(resumed["run_id"]) == list(whole["run_id"])
    timing = ["cpu_seconds", "solver_seconds"]
    pd.testing.assert_frame_equal(resumed.drop(columns=timing), whole.drop(columns=timing))
    # a third run has nothing left to do
    assert run_suite(suite, out, serial=True, stream=_quiet())["todo"] == 0


def test_a_changed_suite_never_mixes_with_old_rows(tmp_path):
    suite = load_suite(_suite(tmp_path, duration=1.0))
    run_suite(suite, tmp_path / "out", serial=True, stream=_quiet())
    changed = load_suite(_suite(tmp_path, SMALL.replace("[0.5, 1.5]", "[0.5, 1.0]"),
                                duration=1.0))
    with pytest.raises(ValueError, match="--overwrite"):
        run_suite(changed, tmp_path / "out", serial=True, stream=_quiet())
    run_suite(changed, tmp_path / "out", serial=True, overwrite=True, stream=_quiet())
    df = load_table(tmp_path / "out")
    assert set(df["suite_hash"]) == {changed.hash} and set(df["im"]) == {0.5, 1.0}


def test_hunt_and_fill_suite_resumes_its_traces(tmp_path):
    text = SMALL.replace("levels = [0.5, 1.5]", "hunt_fill = true\nstep0 = 1.0\n"
                         "step_increment = 1.0\nresolution = 0.5\nmax_runs = 4") + \
        "[collapse]\ndrift_ratio = 0.02\n"
    suite = load_suite(_suite(tmp_path, text.replace('"walls.law" = ["E", "H"]',
                                                     '"walls.law" = ["H"]'), duration=2.0))
    summary = run_suite(suite, tmp_path / "out", serial=True, stream=_quiet())
    df = load_table(tmp_path / "out")
    assert summary["unit"] == "traces" and len(df) == summary["runs"]
    assert df["collapsed"].any()  # 2 % drift is reached within 4 runs by some record
    # every trace is at most max_runs long and starts at step0
    assert df.groupby("record").size().max() <= 4 and (df["im"] == 1.0).sum() == 3
    again = run_suite(suite, tmp_path / "out", serial=True, stream=_quiet())
    assert again["todo"] == 0
    # the report half reads this folder: femoat suite report DIR
    from femoat.cli import main

    assert main(["suite", "report", str(tmp_path / "out")]) == 0
    assert (tmp_path / "out" / "report" / "collapse_summary.csv").is_file()


def _verdict_table(stdout):
    """The rows of the verdict table printed by femoat suite: {heading: cell}."""
    lines = stdout.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("variation "))
    rows = []
    for line in lines[start:]:
        if not line.strip():
            break
        rows.append(line.split())
    heads = ["variation", "records", "analyses", "runs", "collapsed", "failed", "S_CT [g]",
             "CMR [-]", "SSF [-]", "ACMR [-]", "ACMR10% [-]", "ACMR20% [-]"]
    # headings with a space ("S_CT [g]") split in two; the verdict may have spaces
    return [dict(zip(heads, r[:12]), verdict=" ".join(r[12:])) for r in rows[1:]]


def test_femoat_suite_command_writes_the_table_and_the_report(tmp_path, capsys, no_figures):
    # the command a user runs: the runs, then the report in OUT/report (IDA stripes at 0.5 and
    # 1.5 g for 3 records x 2 laws = 12 runs); the report's tables and README, written five
    # times here (its figures: tests/test_suite_methods.py, through the same command)
    from femoat.cli import main

    out, path = tmp_path / "out", _suite(tmp_path)
    assert main(["suite", str(path), "--serial", "--out", str(out)]) == 0
    assert len(load_table(out)) == 12
    for name in ("collapse_summary.csv", "response_by_variation.csv", "README.txt"):
        assert (out / "report" / name).stat().st_size > 0
    first = capsys.readouterr().out
    assert "report in" in first and "24 runs stored" not in first
    # the verdict on the terminal is collapse_summary.csv, for every stored run: 12 here
    assert "12 runs stored" in first
    printed = _verdict_table(first)
    csv = pd.read_csv(out / "report" / "collapse_summary.csv")
    assert [r["variation"] for r in printed] == list(csv["variation"]) == ["E", "H"]
    for row, (_, c) in zip(printed, csv.iterrows()):
        assert int(row["runs"]) == c["n_runs"] and int(row["collapsed"]) == c["n_collapsed"]
        for heading, column in (("S_CT [g]", "S_CT empirical [g]"), ("CMR [-]", "CMR [-]"),
                                ("ACMR [-]", "ACMR [-]"), ("ACMR10% [-]", "ACMR10% [-]")):
            assert float(row[heading].lstrip(">=")) == c[column]
        assert row["verdict"] == c["verdict"]
    # a rerun of the finished suite runs nothing and prints the same verdict (without
    # validating the suite file again: it is marked finished)
    assert main(["suite", str(path), "--serial", "--out", str(out)]) == 0
    again = capsys.readouterr().out
    assert "every run is stored" in again and _verdict_table(again) == printed
    # a [p695] table added to the finished suite: nothing runs, the report takes it
    path.write_text(path.read_text() + "[p695]\nmu_t = 1.5\n", encoding="utf-8")
    assert main(["suite", str(path), "--serial", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "ran 0 runs" in text and "mu_T = 1.5 (suite file [p695] mu_t)" in text
    assert "mu_T = 1.5" in " ".join((out / "report" / "README.txt").read_text().split())
    # the report command prints it too, with a given mu_T stated as given
    assert main(["suite", "report", str(out), "--mu-t", "1"]) == 0
    assert "mu_T = 1 (given (--mu-t))" in capsys.readouterr().out
    # --json: the same rows, keys with their units
    import json

    assert main(["suite", "report", str(out), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [r["variation"] for r in data["verdict"]] == ["E", "H"]
    assert data["stored"]["runs"] == 12 and "S_CT empirical [g]" in data["verdict"][0]
    # --no-report leaves the report out (a rerun resumes: nothing to run)
    out2 = tmp_path / "out2"
    assert main(["suite", str(_suite(tmp_path)), "--serial", "--out", str(out2),
                 "--no-report"]) == 0
    assert not (out2 / "report").exists()


@pytest.mark.slow
def test_headline_suite_runs_to_collapse_and_reports(tmp_path):
    # `femoat suite` with no file: 44 far-field records x 10 variations, hunt-and-fill IDA
    import pandas as pd

    from femoat.cli import main
    from femoat.suite.huntfill import collapse_bracket

    out = tmp_path / "headline"
    assert main(["suite", "--out", str(out)]) == 0
    df = load_table(out)
    assert df["variation"].nunique() == 10 and df["record"].nunique() == 44
    assert set(df["status"]) <= {"ok", "collapsed"}
    summary = pd.read_csv(out / "report" / "collapse_summary.csv")
    assert len(summary) == 10
    unresolved = 0
    for (variation, record), trace in df.groupby(["variation", "record"]):
        runs = list(zip(trace["im"], trace["status"] != "ok"))
        low, high = collapse_bracket(runs)
        # every trace collapses and brackets its lowest collapse intensity to the suite's
        # resolution (0.01 g), unless a collapse found late (a non-monotone curve) left too few
        # of its 20 runs to refine it
        assert high is not None
        assert high - low <= 0.01 + 1e-12 or len(runs) == 20
        unresolved += high - low > 0.01 + 1e-12
    assert unresolved <= 4  # of 440 traces (19 before a late collapse was re-bracketed)
    # the report's empirical S_CT is the median over the records of the bracket's upper end
    for _, row in summary.iterrows():
        mine = df[(df["walls.law"] == row["walls.law"])
                  & (df["walls.preset"] == row["walls.preset"])]
        assert mine["record"].nunique() == 44
        highs = [collapse_bracket(list(zip(t["im"], t["status"] != "ok")))[1]
                 for _, t in mine.groupby("record")]
        # (the CSV carries 4 significant digits)
        assert row["S_CT empirical [g]"] == pytest.approx(float(pd.Series(highs).median()),
                                                          rel=5e-4)


def test_ctrl_c_on_a_dask_suite_prints_one_line_and_no_traceback(tmp_path):
    # Ctrl-C on a terminal sends SIGINT to the whole process group: the CLI and its local Dask
    # worker (one: a second would only start another process). Full records, one run per
    # task, 3 records x 5 laws x 6 levels = 90 runs: long enough to interrupt after the first
    # parts.
    text = SMALL.replace("duration = {duration}\n", "").replace(
        '["E", "H"]', '["E", "V", "J", "H", "M"]').replace(
        "[0.5, 1.5]", "[0.5, 0.75, 1.0, 1.25, 1.5, 2.0]")
    path = _suite(tmp_path, text, batch=1)
    out = tmp_path / "out"
    proc = _cli([path, "--workers", "1", "--out", out], start_new_session=True)
    deadline = time.monotonic() + 180
    while time.monotonic() < deadline and proc.poll() is None:
        if len(list(out.glob("runs/part-*.parquet"))) >= 1:
            break
        time.sleep(0.01)
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGINT)  # the group of the process started here
    _, err = proc.communicate(timeout=120)
    err = err.decode()
    stored = len(load_table(out))
    if stored >= 90:
        pytest.skip("the suite finished before it could be interrupted (machine too fast)")
    assert proc.returncode == 130, err
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err
    assert f"interrupted; {stored} runs stored in" in err


def test_the_finished_mark_goes_stale_with_any_change(tmp_path):
    # the mark lets a rerun skip validation; anything that could give the rerun work must
    # invalidate it: the suite file, a record file, a part file added or removed
    import os

    from femoat.suite import finished

    path, out = _suite(tmp_path), tmp_path / "out"
    (out / "runs").mkdir(parents=True)
    (out / "runs" / "part-a.parquet").write_bytes(b"x")
    finished.mark(path, out)
    assert finished.is_finished(path, out)
    record = next((tmp_path / "peer").glob("*.AT2"))
    st = record.stat()
    os.utime(record, ns=(st.st_atime_ns, st.st_mtime_ns + 10**9))  # a record replaced
    assert not finished.is_finished(path, out)
    finished.mark(path, out)
    (out / "runs" / "part-b.parquet").write_bytes(b"x")  # a part stored since
    assert not finished.is_finished(path, out)
    finished.mark(path, out)
    path.write_text(path.read_text() + "[p695]\nmu_t = 2.0\n")  # the suite file edited
    assert not finished.is_finished(path, out)
    assert not finished.is_finished(path, tmp_path / "elsewhere")  # no mark at all


def test_hunt_and_fill_onset_runs_are_rows_and_a_cut_trace_resumes(tmp_path):
    # real runs (3 records, law H, 2 s): every trace brackets its collapse and then its onsets
    # of pounding (pounding_onsets = true) to 0.02 g, within its 12 runs
    import pyarrow.parquet as pq

    from femoat.suite import table as tb
    from femoat.suite.huntfill import Outcome, hunt_fill, onset_bracket
    from femoat.suite.runs import hunt_settings

    text = SMALL.replace("levels = [0.5, 1.5]", "hunt_fill = true\nstep0 = 0.2\n"
                         "step_increment = 0.1\nresolution = 0.02\nmax_runs = 12\n"
                         "pounding_onsets = true").replace(
        '"walls.law" = ["E", "H"]', '"walls.law" = ["H"]') + "[collapse]\ndrift_ratio = 0.02\n"
    suite = load_suite(_suite(tmp_path, text, duration=2.0))
    out = tmp_path / "out"
    run_suite(suite, out, serial=True, stream=_quiet())
    whole = load_table(out)

    def runs_of(trace):
        return {im: Outcome(st != "ok", frozenset(w for w in suite.walls if trace[f"impacts_{w}"]
                                                  .to_numpy()[i] > 0))
                for i, (im, st) in enumerate(zip(trace["im"], trace["status"]))}

    pounded = 0
    for _, trace in whole.groupby("record"):
        # the stored rows are the trace hunt_fill makes from them, run for run: the onset runs
        # are ordinary rows (every column), read back with their walls
        known = runs_of(trace)
        again = hunt_fill(known.__getitem__, **hunt_settings(suite))
        assert sorted(r.im for r in again) == sorted(known) and len(known) <= 12
        for w in ("any", *suite.walls):
            b = onset_bracket(again, w)
            if b is not None:
                pounded += 1
                assert b[1] - b[0] <= 0.02 + 1e-12 or len(known) == 12
    # every trace pounded some wall below its collapse (with pounding_onsets = false the same
    # traces leave e.g. RSN181's pos onset in (0.425, 0.5], 0.075 g wide)
    assert pounded >= 3
    # cut one trace to its first 3 runs (as if its task had stored only those): the rerun
    # runs that one trace again, from its stored runs on, to the same rows
    part = next(p for p in tb.part_files(out) if pq.read_table(p).num_rows > 3)
    rows = pq.read_table(part).to_pylist()
    part.unlink()
    tb.write_part(rows[:3], suite, out)
    assert run_suite(suite, out, serial=True, stream=_quiet())["todo"] == 1
    resumed = load_table(out)
    timing = ["cpu_seconds", "solver_seconds"]
    pd.testing.assert_frame_equal(resumed.drop(columns=timing), whole.drop(columns=timing))
    assert run_suite(suite, out, serial=True, stream=_quiet())["todo"] == 0

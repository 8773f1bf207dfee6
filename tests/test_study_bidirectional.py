"""tests/test_study_bidirectional.py: ``femoat study bidirectional --quick`` end to end (1D
against 2D pounding at the MCE, femoat.studies.bidirectional): the envelopes, the shared scale
factors, the table recomputed from the Parquet run tables, and two physics checks on the
study's own models (a pair with its b component zeroed is the 1D run of a; a quarter turn of the
pair turns the response with it, the ground for sampling the angles in [0, 90) deg only)."""

import contextlib
import dataclasses
import io

import numpy as np
import pandas as pd
import pytest

from femoat.cli import main
from femoat.studies import bidirectional as bd

ROW = ("steel", "H")  # the (wall, law) recomputed by hand


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    """The quick study run once through the command line: (folder, printed table)."""
    out = tmp_path_factory.mktemp("study") / "bidirectional"
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed), contextlib.redirect_stderr(io.StringIO()):
        code = main(["study", "bidirectional", "--quick", "--serial", "--out", str(out)])
    assert code == 0
    return out, printed.getvalue()


def _parquet(folder):
    """A suite's run table read straight from its Parquet parts (not through load_table)."""
    df = pd.concat([pd.read_parquet(p) for p in sorted((folder / "runs").glob("*.parquet"))])
    return df.drop_duplicates("run_id").reset_index(drop=True)


def test_the_command_prints_and_writes_the_table(study):
    out, printed = study
    table = pd.read_csv(out / "table.csv")
    laws, walls = bd.QUICK["laws"], bd.WALLS
    # one row per law x wall x case, each case over the three quick records
    assert len(table) == len(laws) * len(walls) * len(bd.CASES)
    assert set(table["records"]) == {len(bd.QUICK["ids"])}
    # runs behind each case: 1D two components per record, 2D 0 deg one pair per record,
    # 2D worst one pair per record at each of the six angles
    runs = table.groupby("case")["runs"].unique().to_dict()
    n = len(bd.QUICK["ids"])
    assert {k: list(v) for k, v in runs.items()} == {"1d": [2 * n], "2d_0": [n],
                                                     "2d_worst": [n * len(bd.ANGLES)]}
    assert (out / "table.markdown").read_text(encoding="utf-8") in printed
    for wall in walls:
        for law in laws:
            assert f"| {wall} | {law} |" in printed


def test_the_worst_angle_envelope_is_never_below_0_deg(study):
    out, _ = study
    table = pd.read_csv(out / "table.csv").set_index(["wall", "law", "case"])
    # the worst case takes, per record, the largest peak and "any" pounding over the angles,
    # 0 deg among them: its median displacement and its pounding probability cannot be lower
    for wall in bd.WALLS:
        for law in bd.QUICK["laws"]:
            zero, worst = table.loc[(wall, law, "2d_0")], table.loc[(wall, law, "2d_worst")]
            assert worst["median peak base displacement [in]"] >= \
                zero["median peak base displacement [in]"]
            assert worst["pounding probability [-]"] >= zero["pounding probability [-]"]
            assert worst["collapsed runs"] >= zero["collapsed runs"]
    # the force's median is over the records that pounded, a set that grows with the angles, so
    # the envelope holds record by record (not necessarily for the median)
    recs = bd.per_record(_parquet(out / "1d"), _parquet(out / "2d")).set_index(
        ["law", "wall", "record", "case"])
    zero = recs.xs("2d_0", level="case")
    worst = recs.xs("2d_worst", level="case").loc[zero.index]
    assert (worst["force"] >= zero["force"]).all()
    assert (worst["displacement"] >= zero["displacement"]).all()


def test_1d_and_2d_scale_each_record_by_the_same_factor(study):
    out, _ = study
    one_d, two_d = _parquet(out / "1d"), _parquet(out / "2d")
    # FEMA P695 anchoring over the 2N components in both suites: record k's factor is
    # SF x NF_k whether its components run alone (a, b) or together at any angle
    f1 = one_d.groupby("record_id")["scale_factor"].unique()
    f2 = two_d.groupby("record_id")["scale_factor"].unique()
    assert sorted(f1.index) == sorted(f2.index) == sorted(str(i) for i in bd.QUICK["ids"])
    for rid in f1.index:
        assert len(f1[rid]) == 1 and list(f2[rid]) == list(f1[rid])
    # and the records differ (NF_k is the record's own): a shared factor is not one number
    assert len({f[0] for f in f1}) == len(f1)


def test_one_row_recomputed_from_the_parquet_tables(study):
    out, _ = study
    wall, law = ROW
    one_d = _parquet(out / "1d")
    one_d = one_d[(one_d["walls.preset"] == wall) & (one_d["walls.law"] == law)]
    two_d = _parquet(out / "2d")
    two_d = two_d[(two_d["moat.preset"] == wall) & (two_d["moat.law"] == law)]
    assert set(one_d["status"]) | set(two_d["status"]) <= {"ok", "collapsed"}  # none left out

    def force(df, walls):
        return df[[f"peak_impact_force_{w}" for w in walls]].max(axis=1)

    expected = {}
    # 1D: per record the larger of its two components' peaks, pounding if either pounds
    g = one_d.assign(F=force(one_d, ("pos", "neg"))).groupby("record_id")
    expected["1d"] = (g["peak_base_displacement"].max(), g["pounding"].any(), g["F"].max(),
                      one_d["collapsed"].sum())
    at0 = two_d[two_d["angle"] == 0]
    at0 = at0.assign(F=force(at0, ("px", "mx", "py", "my")))
    at0 = at0.set_index("record_id")
    expected["2d_0"] = (at0["peak_base_displacement"], at0["pounding"], at0["F"],
                        at0["collapsed"].sum())
    g = two_d.assign(F=force(two_d, ("px", "mx", "py", "my"))).groupby("record_id")
    expected["2d_worst"] = (g["peak_base_displacement"].max(), g["pounding"].any(),
                            g["F"].max(), two_d["collapsed"].sum())
    table = pd.read_csv(out / "table.csv").set_index(["wall", "law", "case"])
    for case, (u, pounded, f, collapsed) in expected.items():
        row = table.loc[(wall, law, case)]
        assert row["median peak base displacement [in]"] == pytest.approx(np.median(u),
                                                                          rel=1e-12)
        assert row["pounding probability [-]"] == pytest.approx(pounded.mean(), rel=1e-12)
        assert row["records that pounded"] == pounded.sum()
        assert row["median peak impact force, pounded [kip]"] == pytest.approx(
            np.median(f[pounded]), rel=1e-12)
        assert row["collapsed runs"] == collapsed
    # the row is not trivial: records pounded in every case (at the full study's scaling all
    # three quick pairs pound), and the envelope over the angles raises the force above 0 deg's
    assert table.loc[(wall, law, "1d"), "records that pounded"] > 0
    assert table.loc[(wall, law, "2d_worst"), "median peak impact force, pounded [kip]"] > \
        table.loc[(wall, law, "2d_0"), "median peak impact force, pounded [kip]"]


def test_the_definitions_on_run_tables_built_by_hand():
    nan = float("nan")

    def one_d(rid, comp, u, pos, neg, status="ok", collapsed=False):
        return {"walls.law": "H", "walls.preset": "concrete", "record_id": rid,
                "component": comp, "status": status, "peak_base_displacement": u,
                "peak_impact_force_pos": pos, "peak_impact_force_neg": neg,
                "pounding": None if np.isnan(u) else pos + neg > 0, "collapsed": collapsed}

    def two_d(rid, angle, u, px=0.0, mx=0.0, py=0.0, my=0.0):
        return {"moat.law": "H", "moat.preset": "concrete", "record_id": rid, "angle": angle,
                "status": "ok", "peak_base_displacement": u, "peak_impact_force_px": px,
                "peak_impact_force_mx": mx, "peak_impact_force_py": py,
                "peak_impact_force_my": my, "pounding": px + mx + py + my > 0,
                "collapsed": False}

    runs_1d = pd.DataFrame([
        one_d("1", "a", 3.0, 0.0, 0.0), one_d("1", "b", 4.5, 100.0, 50.0, collapsed=True),
        one_d("2", "a", 2.0, 0.0, 0.0), one_d("2", "b", 1.0, 0.0, 0.0),
        one_d("3", "a", nan, nan, nan, status="solver_failure"), one_d("3", "b", 5.0, 200.0, 0.0)])
    runs_2d = pd.DataFrame([
        two_d("1", 0.0, 5.0, px=120.0), two_d("1", 45.0, 6.0, py=150.0),
        two_d("2", 0.0, 3.0), two_d("2", 45.0, 4.2, mx=80.0),
        two_d("3", 0.0, 4.0), two_d("3", 45.0, 4.1)])
    t = bd.study_table(runs_1d, runs_2d).set_index("case")
    # 1D per record (the larger peak of a and b, pounding if either): 1 -> 4.5 in, pounded,
    # 100 kip; 2 -> 2.0 in, no pounding; 3 left out (a failed). Median (4.5 + 2.0) / 2 = 3.25,
    # P = 1/2, F over the one record that pounded = 100; 1 collapsed and 1 failed of 6 runs
    assert t.loc["1d", "records"] == 2 and t.loc["1d", "runs"] == 6
    assert t.loc["1d", "median peak base displacement [in]"] == 3.25
    assert t.loc["1d", "pounding probability [-]"] == 0.5
    assert t.loc["1d", "median peak impact force, pounded [kip]"] == 100.0
    assert (t.loc["1d", "collapsed runs"], t.loc["1d", "failed runs"]) == (1, 1)
    # 2D 0 deg: 5.0, 3.0, 4.0 in -> median 4.0; only record 1 pounded (120 kip): P = 1/3
    assert t.loc["2d_0", "median peak base displacement [in]"] == 4.0
    assert t.loc["2d_0", "pounding probability [-]"] == pytest.approx(1 / 3)
    assert t.loc["2d_0", "median peak impact force, pounded [kip]"] == 120.0
    # 2D worst, per record over 0 and 45 deg: 6.0, 4.2, 4.1 in -> median 4.2; records 1 and 2
    # pounded (2 only at 45 deg): P = 2/3, F median of 150 and 80 = 115
    assert t.loc["2d_worst", "median peak base displacement [in]"] == 4.2
    assert t.loc["2d_worst", "pounding probability [-]"] == pytest.approx(2 / 3)
    assert t.loc["2d_worst", "median peak impact force, pounded [kip]"] == 115.0
    assert t.loc["2d_worst", "runs"] == 6
    # collapsed, per record and enveloped as the other columns, over one denominator (the
    # records): 1D record 1 collapsed in its b run: 1 of the 2 records; in 2D none
    assert t.loc["1d", "records that collapsed"] == 1
    assert t.loc["2d_worst", "records that collapsed"] == 0
    md = bd.to_markdown(bd.study_table(runs_1d, runs_2d))
    assert "| 1/2 | 0/3 | 0/3 |" in md and "records that collapsed / records" in md


def test_quick_scales_its_pairs_as_the_full_study_does():
    """--quick previews the full table: its three pairs get the full study's factors NF x SF
    (SF of the 44 components, not re-anchored on its own six), whole records, the same model
    tables; so each of its rows is the full study's row of that record (the runs are
    deterministic)."""
    from femoat.suite import suite_from_dict

    full, quick = bd.definitions(), bd.definitions(quick=True)
    for key in ("1d", "2d"):
        drop = ("variations", "records", "scaling")
        assert {k: v for k, v in full[key].items() if k not in drop} == \
            {k: v for k, v in quick[key].items() if k not in drop}
        assert "duration" not in quick[key]["records"]
    q = suite_from_dict({**quick["2d"], "variations": {"moat.law": ["H"]}})
    f = suite_from_dict({**full["2d"], "variations": {"moat.law": ["H"]}})
    # the full set's SF (4.235 at S_MT(3.5 s, Dmax), docs/plan.md §9), not the three pairs' own
    assert q.scaling.anchor == f.scaling.anchor == pytest.approx(4.235, abs=5e-4)
    level = f.scaling.levels[0]
    for i, r in enumerate(q.records):
        j = [x.label for x in f.records].index(r.label)
        assert q.scaling.factor(i, level) == f.scaling.factor(j, level)


def test_both_suites_model_the_paper_building_and_walls():
    from femoat.paper import paper_model
    from femoat.suite.model import build_variation
    from femoat.suite.variations import MODEL_TABLES, apply

    d = bd.definitions()
    one_d = {k: v for k, v in d["1d"].items() if k in MODEL_TABLES}
    two_d = {k: v for k, v in d["2d"].items() if k in MODEL_TABLES}
    for wall in bd.WALLS:
        for law in bd.LAWS:
            paper = paper_model(wall, law)  # the paper's building between two walls, 4 in gaps
            model = build_variation(apply(one_d, {"walls.law": law, "walls.preset": wall}))
            assert model.pounding == paper
            # the plan model is that building in x and in y, with that wall on both axes
            plan = build_variation(apply(two_d, {"moat.law": law, "moat.preset": wall}))
            assert plan.pounding.along("x") == paper and plan.pounding.along("y") == paper


def _models_and_records():
    """The quick study's H concrete variation in plan, and its records (1D and 2D suites)."""
    from femoat.suite import suite_from_dict
    from femoat.suite.model import build_variation
    from femoat.suite.variations import MODEL_TABLES, apply

    d1, d2 = (bd.definitions(quick=True)[k] for k in ("1d", "2d"))
    tables = {k: v for k, v in d2.items() if k in MODEL_TABLES}
    plan = build_variation(apply(tables, {"moat.law": "H", "moat.preset": "concrete"}))
    return plan, suite_from_dict(d1), suite_from_dict(d2), d2["records"]["extra_time"]


def test_a_pair_with_its_b_component_zeroed_is_the_1d_run_of_a(study):
    from femoat.ground_motions import GroundMotion
    from femoat.ground_motions.pair import RecordPair
    from femoat.suite.model import run_variation
    from femoat.suite.records import applied_motion

    out, _ = study
    plan, s1, _, extra = _models_and_records()
    row = _parquet(out / "1d").set_index(["record", "walls.law", "walls.preset"]).loc[
        ("farfield/1a", "H", "concrete")]
    a = applied_motion(next(r for r in s1.records if r.label == "farfield/1a"),
                       row["scale_factor"], s1.time_scale, s1.duration)
    zero = GroundMotion(np.zeros_like(a.accel_g), a.dt, "zero")
    result = run_variation(plan, RecordPair(a, zero), extra)
    p = result.peaks
    # with no y ground motion nothing pushes the building along y: the y DOFs stay at rest,
    # the friction acts along x alone, the +-y walls are never reached, and the plan run is
    # the 1D run of a along x (the plan solver's own claim, bit for bit: the study's ark5 is
    # dp5 along a line); the 1D suite's row must be that run. The plan peak is the crest of
    # |u| between samples, the 1D one the crest of u: the same interpolant, other roundings
    # (measured 1 ulp)
    assert row["pounding"]  # the check covers impacts: record 1a at the MCE pounds (4.5 in)
    assert p["peak_plan_base_displacement"] == pytest.approx(row["peak_base_displacement"],
                                                             rel=1e-14)
    assert p["peak_impact_force_px"] == row["peak_impact_force_pos"]
    assert p["peak_impact_force_mx"] == row["peak_impact_force_neg"]
    assert p["impacts_py"] == p["impacts_my"] == 0


def test_a_quarter_turn_of_the_pair_turns_the_response_with_it(study):
    from femoat.suite.model import run_variation
    from femoat.suite.records import applied

    out, _ = study
    plan, _, s2, extra = _models_and_records()
    two_d = _parquet(out / "2d").set_index(["record", "moat.law", "moat.preset"])
    at0 = two_d.loc[("farfield/1@0", "H", "concrete")]
    ref = dataclasses.replace(next(r for r in s2.records if r.label == "farfield/1@0"),
                              angle=90.0)
    p = run_variation(plan, applied(ref, at0["scale_factor"], s2.time_scale, s2.duration),
                      extra).peaks
    # the pair turned by +90 deg is the 0 deg problem turned by +90 deg (the building alike in
    # x and y, the pendulum isotropic, four identical walls at the same gap): the same plan
    # displacement, each wall's force on the wall a quarter turn on (+x -> +y -> -x -> -y ->
    # +x); equal up to the step sequences (the solver's error scales are per axis), which
    # differ: within 1e-3, the accuracy every peak has at the default rtol
    assert p["peak_plan_base_displacement"] == pytest.approx(at0["peak_base_displacement"],
                                                             rel=1e-3)
    for before, after in (("px", "py"), ("py", "mx"), ("mx", "my"), ("my", "px")):
        assert p[f"peak_impact_force_{after}"] == pytest.approx(
            at0[f"peak_impact_force_{before}"], rel=1e-3, abs=1e-6)
        assert p[f"impacts_{after}"] == at0[f"impacts_{before}"]
    assert at0["pounding"] and at0["peak_impact_force_px"] > 0 and at0["peak_impact_force_py"] > 0


def test_bad_workers_are_refused_by_name(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["study", "bidirectional", "--quick", "--workers", "0", "--out", str(out)]) == 2
    assert "--workers 0" in capsys.readouterr().err
    assert not out.exists()


def test_on_dask_the_suites_share_one_local_cluster(tmp_path, monkeypatch):
    # Not serial: both suites of the study run on one local cluster (started once, its worker
    # loading the compiled loop once), and every run is the serial run's: the same table, to
    # the printed digits and in every stored number. On a smaller quick study (one pair, one
    # law), run both ways here.
    from femoat.suite import execute

    monkeypatch.setattr(bd, "QUICK", {"ids": [6], "laws": ("H",)})
    started = []
    real = execute.local_cluster

    @contextlib.contextmanager
    def counted(workers=None):
        with real(workers) as address:
            started.append(address)
            yield address

    monkeypatch.setattr(execute, "local_cluster", counted)
    printed = {}
    for how in ("--serial", "--workers"):
        out = tmp_path / how.strip("-")
        buffer = io.StringIO()
        with contextlib.redirect_stdout(buffer), contextlib.redirect_stderr(io.StringIO()):
            code = main(["study", "bidirectional", "--quick", how,
                         *(["1"] if how == "--workers" else []), "--out", str(out)])
        assert code == 0
        printed[how] = buffer.getvalue().replace(str(out), "OUT")
    assert len(started) == 1
    assert printed["--workers"] == printed["--serial"]
    table = pd.read_csv(tmp_path / "workers" / "table.csv")
    assert len(table) == len(bd.WALLS) * len(bd.CASES) and set(table["law"]) == {"H"}
    pd.testing.assert_frame_equal(table, pd.read_csv(tmp_path / "serial" / "table.csv"))

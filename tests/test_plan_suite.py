"""Plan suites (issue 18): a building in plan under record pairs, each at several angles, through
the suite machinery: validation, scaling of pairs, rows equal to single plan runs, the report's
pounding probability per wall."""

import io
import math

import numpy as np
import pytest

from conftest import DATA
from femoat.cli import main
from femoat.suite import load_suite, load_table, run_suite

PEER = DATA / "peer"
RINALDI, SFERN = PEER / "Rinaldi228.AT2", PEER / "RSN77_SFERN_PUL164.AT2"  # both dt = 0.01 s
NORTHR = PEER / "RSN1084_NORTHR_SCS052.AT2"  # dt = 0.005 s

PLAN = """
[building]
plan = true
[moat]
law = "H"
gap = {gap}
[solver]
method = "newmark"
rtol = 1e-4
[records]
{records}
duration = 3.0
extra_time = 1.0
[scaling]
{scaling}
"""
FEMA = 'set = "farfield"\nids = [1, 2]\npairs = true\nangles = [0, 45]'
FILES = f'pairs = [["{RINALDI.as_posix()}", "{SFERN.as_posix()}"]]\nangles = [0, 90]'


def _write(tmp_path, records=FEMA, scaling='method = "pga"\ntargets = [0.4]', gap=2.0,
           extra=""):
    path = tmp_path / "plan_suite.toml"
    path.write_text(PLAN.format(records=records, scaling=scaling, gap=gap) + extra,
                    encoding="utf-8")
    return path


def _fails(tmp_path, capsys, *names, **kw):
    """The CLI refuses the file with exit code 2 naming each of ``names``; nothing is run."""
    path = _write(tmp_path, **kw)
    out = tmp_path / "out"
    assert main(["suite", str(path), "--out", str(out), "--serial"]) == 2
    err = capsys.readouterr().err
    for name in names:
        assert name in err, err
    assert not out.exists()
    return err


# ---- definition --------------------------------------------------------------------------------
def test_a_plan_suite_lists_each_pair_at_each_angle(tmp_path):
    suite = load_suite(_write(tmp_path))
    assert suite.plan and suite.walls == ("px", "mx", "py", "my")
    assert [r.label for r in suite.records] == ["farfield/1@0", "farfield/1@45", "farfield/2@0",
                                                "farfield/2@45"]
    assert [(r.x.component, r.y.component) for r in suite.records] == [("a", "b")] * 4


def test_file_pairs_are_read_and_checked(tmp_path):
    suite = load_suite(_write(tmp_path, records=FILES))
    assert [r.label for r in suite.records] == ["Rinaldi228+RSN77_SFERN_PUL164@0",
                                                "Rinaldi228+RSN77_SFERN_PUL164@90"]


def test_pairs_without_a_plan_building_are_refused(tmp_path, capsys):
    text = PLAN.replace("plan = true", "").replace("[moat]", "[walls]")
    path = tmp_path / "s.toml"
    path.write_text(text.format(records=FEMA, scaling='method = "pga"\ntargets = [0.4]', gap=2),
                    encoding="utf-8")
    assert main(["suite", str(path), "--out", str(tmp_path / "out"), "--serial"]) == 2
    assert "plan = true" in capsys.readouterr().err


def test_a_plan_suite_needs_pairs(tmp_path, capsys):
    _fails(tmp_path, capsys, "pairs = true", records='set = "farfield"\nids = [1]')


def test_components_are_refused_in_a_plan_suite(tmp_path, capsys):
    _fails(tmp_path, capsys, "components", records=FEMA + '\ncomponents = ["a"]')


@pytest.mark.parametrize("angles", ['["north"]', "[]", "[0, 0.0]", '"0"'])
def test_bad_angles_are_named(tmp_path, capsys, angles):
    _fails(tmp_path, capsys, "angles", records=f'set = "farfield"\nids = [1]\npairs = true\n'
                                                f"angles = {angles}")


def test_a_pair_of_files_with_different_time_steps_is_named(tmp_path, capsys):
    records = f'pairs = [["{RINALDI.as_posix()}", "{NORTHR.as_posix()}"]]'
    _fails(tmp_path, capsys, "time steps differ", "Rinaldi228", records=records)


def test_a_missing_file_of_a_pair_is_named(tmp_path, capsys):
    records = f'pairs = [["{RINALDI.as_posix()}", "missing_y.AT2"]]'
    _fails(tmp_path, capsys, "[records] pairs", "missing_y.AT2", "does not exist",
           records=records)


def test_a_negative_gap_in_a_variation_is_named(tmp_path, capsys):
    _fails(tmp_path, capsys, "moat.gap=-1", "gap", extra='[variations]\n"moat.gap" = [2.0, -1.0]\n')


def test_one_wall_of_the_moat_can_be_varied(tmp_path):
    suite = load_suite(_write(tmp_path, extra='[variations]\n"moat.+x.gap" = [1.0, 3.0]\n'))
    from femoat.suite.runs import _variation

    gaps = [[w.gap for w in _variation(suite, v).pounding.walls] for v in range(2)]
    # the +x wall first (femoat.plan.moat.SIDES order), the others at the [moat] gap of 2 in
    assert gaps == [[1.0, 2.0, 2.0, 2.0], [3.0, 2.0, 2.0, 2.0]]


# ---- scaling -----------------------------------------------------------------------------------
def test_a_pair_is_scaled_by_its_geometric_mean_and_alike_at_every_angle(tmp_path):
    from femoat.ground_motions import fema_p695_record, response_spectrum

    suite = load_suite(_write(tmp_path, scaling='method = "ida"\nim = "sa"\nperiod = 2.0\n'
                                                'levels = [0.3]'))
    sc = suite.scaling
    for i, ref in enumerate(suite.records):
        rid = int(ref.record_id)
        # Sa(T) of each component as applied: the first 3 s, time-scaled by 0.5, at the model
        # period 2.0 x 0.5 = 1 s (femoat.suite.scaling); the pair's Sa is their geometric mean
        parts = []
        for c in "ab":
            gm = fema_p695_record("farfield", rid, c)
            n = int(round(3.0 / gm.dt)) + 1
            from femoat.ground_motions import GroundMotion

            gm = GroundMotion(gm.accel_g[:n], gm.dt).time_scaled(0.5)
            parts.append(float(response_spectrum(gm, 1.0, 0.05).psa))
        assert sc.sa[i] == pytest.approx(math.sqrt(parts[0] * parts[1]), rel=1e-12)
        assert sc.factor(i, 0.3) == pytest.approx(0.3 / sc.sa[i], rel=1e-12)
    # the angle does not enter: farfield/1 at 0 and 45 deg get one factor
    assert sc.factor(0, 0.3) == sc.factor(1, 0.3) and sc.factor(2, 0.3) == sc.factor(3, 0.3)


def test_p695_scales_a_pair_as_a_suite_of_its_components(tmp_path):
    """FEMA P695 anchors the median Sa(T) of the 2N normalized components: a plan suite of
    pairs and a 1D suite of components a and b of the same records get one anchor, so record k
    has one factor in both (NF_k x SF)."""
    p695 = 'method = "p695"\nperiod = 3.5\nmultipliers = [1.0]'
    plan = load_suite(_write(tmp_path, scaling=p695))
    one_d = tmp_path / "one_d.toml"
    one_d.write_text('[records]\nset = "farfield"\nids = [1, 2]\nduration = 3.0\n'
                     f"[scaling]\n{p695}\n", encoding="utf-8")
    line = load_suite(one_d)
    assert plan.scaling.anchor == pytest.approx(line.scaling.anchor, rel=1e-14)
    for i, ref in enumerate(plan.records):
        j = [r.label for r in line.records].index(f"farfield/{ref.record_id}a")
        assert plan.scaling.factor(i, plan.scaling.levels[0]) == pytest.approx(
            line.scaling.factor(j, line.scaling.levels[0]), rel=1e-14)


# ---- runs --------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def plan_table(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("plan_suite")
    suite = load_suite(_write(tmp, scaling='method = "pga"\ntargets = [1.0]', gap=1.0,
                              extra='[variations]\n"moat.law" = ["H", "E"]\n'))
    run_suite(suite, tmp / "out", serial=True, stream=io.StringIO())
    return suite, load_table(tmp / "out"), tmp / "out"


def test_plan_suite_rows_equal_single_plan_runs(plan_table):
    """Each row's peaks are those of the same plan run made by hand (history kept: the peaks are
    read from it, not from the loop's running peaks the suite uses)."""
    from femoat.ground_motions.pair import fema_p695_pair
    from femoat.run import run
    from femoat.suite.runs import _variation

    suite, table, _ = plan_table
    assert len(table) == 4 * 2 and set(table["status"]) <= {"ok", "collapsed"}
    for _, row in table[table["moat.law"] == "H"].iterrows():
        ref = suite.records[[r.label for r in suite.records].index(row["record"])]
        pair = fema_p695_pair("farfield", int(ref.record_id), angle=ref.angle)
        # the suite's motion: the first 3 s of each component, x the factor that brings the
        # pair's geometric-mean PGA to 1.0 g, time x 0.5
        n = int(round(3.0 / pair.dt)) + 1
        from femoat.ground_motions import GroundMotion
        from femoat.ground_motions.pair import RecordPair

        comps = [GroundMotion(m.accel_g[:n], m.dt).scaled(row["scale_factor"]).time_scaled(0.5)
                 for m in (pair.x, pair.y)]
        assert math.sqrt(comps[0].pga * comps[1].pga) == pytest.approx(1.0, rel=1e-12)
        assert row["pga"] == pytest.approx(1.0, rel=1e-12)
        v = _variation(suite, 0)
        r = run(v.pounding, RecordPair(*comps, angle=ref.angle), v.integrator, extra_time=1.0,
                collapse=v.criteria)
        assert row["angle"] == ref.angle and row["steps"] == r.peaks["steps"]
        assert row["peak_base_displacement"] == pytest.approx(
            r.peaks["peak_plan_base_displacement"], rel=1e-9)
        for axis in "xy":
            assert row[f"peak_base_displacement_{axis}"] == pytest.approx(
                r.peaks[f"peak_base_displacement_{axis}"], rel=1e-9)
        for w in suite.walls:
            assert row[f"impacts_{w}"] == r.peaks[f"impacts_{w}"]
            assert row[f"peak_impact_force_{w}"] == pytest.approx(
                r.peaks[f"peak_impact_force_{w}"], rel=1e-9, abs=1e-12)
        # the building-wide drift ratio is the larger of x and y, story by story
        ratio = np.maximum(r.peaks["peak_drift_ratio_x"], r.peaks["peak_drift_ratio_y"])
        assert row["peak_drift_ratio"] == pytest.approx(ratio.max(), rel=1e-9)
        assert row["pounding"] == any(r.peaks[f"impacts_{w}"] for w in suite.walls)


def test_plan_suite_pounds_and_its_report_gives_pounding_per_wall(plan_table):
    """A 1 in gap at 1.0 g pounds; the report's pounding probability per wall is the fraction
    of records (pairs at an angle) with an impact on that wall, counted here from the table
    (one stripe: a run that collapsed without touching a wall is counted apart)."""
    import pandas as pd

    from femoat.suite.report import run_report

    suite, table, out = plan_table
    assert table["pounding"].any()
    run_report(out)
    pound = pd.read_csv(out / "report" / "pounding_probability.csv")
    for law in ("H", "E"):
        rows = table[table["moat.law"] == law]
        got = pound[pound["moat.law"] == law].set_index("wall")
        assert list(got.index) == ["any", *suite.walls]
        for w in suite.walls:
            hit = rows[f"impacts_{w}"] > 0
            assert got.loc[w, "n_analyses"] == len(rows) == 4
            assert got.loc[w, "n_pounded"] == hit.sum()
            assert got.loc[w, "n_collapsed"] == (rows["collapsed"] & ~hit).sum()
            assert got.loc[w, "P(pounding) [-]"] == pytest.approx(hit.mean(), abs=1e-3)
        assert got.loc["any", "P(pounding) [-]"] == pytest.approx(rows["pounding"].mean(),
                                                                  abs=1e-3)


def test_hunt_and_fill_traces_each_pair_at_each_angle(tmp_path):
    """IDA by hunt-and-fill on the pairs' PGA, a 10 in moat (no pounding below ~1.6 g: the base
    mat stays within 4.7 in at 0.8 g), the isolator's capacity in plan (7 in, [building]
    default) as the collapse criterion: each (pair, angle) traces its own curve, and on it every
    intensity that collapsed lies above every one that survived (the bracket a trace closes)."""
    scaling = ('method = "ida"\nim = "pga"\nhunt_fill = true\nstep0 = 0.4\n'
               'step_increment = 0.4\nresolution = 0.2\nmax_runs = 6')
    path = _write(tmp_path, records='set = "farfield"\nids = [1]\npairs = true\n'
                                    'angles = [0, 30]', scaling=scaling, gap=10.0,
                  extra="[collapse]\nisolator = true\n")
    suite = load_suite(path)
    run_suite(suite, tmp_path / "out", serial=True, stream=io.StringIO())
    table = load_table(tmp_path / "out")
    assert set(table["record"]) == {"farfield/1@0", "farfield/1@30"}
    for _, curve in table.groupby("record"):
        assert 3 <= len(curve) <= 6
        gone = curve.loc[curve["collapsed"], "im"]
        kept = curve.loc[~curve["collapsed"], "im"]
        assert len(gone) and len(kept)  # the curve was bracketed
        assert gone.min() > kept.max() and gone.min() - kept.max() <= 0.2 + 1e-9
        assert curve.loc[curve["collapsed"], "collapse_isolator"].all()
        assert (curve.loc[curve["collapsed"], "peak_base_displacement"] >= 7.0 - 1e-9).all()


def test_plan_tables_export_to_xarray_and_to_a_two_direction_demand_file(plan_table, tmp_path):
    """pelicun's demand file of a plan suite has directions 1 (x) and 2 (y): PID-k-d is story k's
    peak drift ratio along that axis, PFA-(k+1)-d the floor above it; the xarray export is
    indexed by pair@angle."""
    import pandas as pd

    from femoat.suite import to_demand_csv, to_xarray

    suite, table, _ = plan_table
    path = to_demand_csv(table, tmp_path / "demand.csv")
    demand = pd.read_csv(path, index_col=0).drop(index="Units").astype(float)
    n = 3  # the paper building's stories
    assert {f"PID-{k}-{d}" for k in range(1, n + 1) for d in (1, 2)} <= set(demand.columns)
    for k in range(1, n + 1):
        for d, axis in ((1, "x"), (2, "y")):
            assert np.array_equal(demand[f"PID-{k}-{d}"].to_numpy(),
                                  table[f"peak_drift_ratio_{axis}_{k}"].to_numpy(float))
            assert np.array_equal(demand[f"PFA-{k + 1}-{d}"].to_numpy(),
                                  table[f"peak_floor_acceleration_{axis}_{k}"].to_numpy(float))
    ds = to_xarray(table)
    assert set(ds["record"].values) == {r.label for r in suite.records}
    assert ds["peak_base_displacement"].attrs["units"] == "in"


def test_each_kind_of_suite_gets_its_own_columns_and_every_shared_one(tmp_path):
    """A 1D suite's table has no plan-only column and every shared one (per story, per wall:
    pos, neg); a plan suite's has every column but the 1D-only ones (walls px, mx, py, my)."""
    from femoat.suite import columns as cols
    from femoat.suite.definition import load_suite as load

    one_d, plan = load(None), load_suite(_write(tmp_path))
    for suite, other in ((one_d, "plan"), (plan, "1d")):
        got = cols.fields(suite)
        rows = {f.column.name for f in got}
        expected = {c.name for c in cols.COLUMNS if c.models != other
                    and (c.per != "key" or suite.varied)}  # no variation: no {key} column
        assert rows == expected
        assert len({f.name for f in got}) == len(got)  # no column twice
        walls = {f.index for f in got if f.column.per == "wall"}
        assert walls == set(suite.walls)
        stories = [f.index for f in got if f.column.name == "peak_drift_ratio_{k}"]
        assert stories == list(range(1, suite.n_stories + 1))

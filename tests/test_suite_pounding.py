"""The onset of pounding as a fragility per wall (femoat.suite.pounding): every record counted
at every level from its own trace, a record that collapsed before it touched a wall its own
category, the onset's lognormal fit; the same fractions from stripes and from an IDA."""

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from femoat.suite import pounding
from femoat.suite.fragility import fit_ida
from femoat.suite.huntfill import Outcome, hunt_fill
from femoat.suite.report import write_report


def _run(rec, im, onset_pos, onset_neg, collapse):
    """A run of record ``rec`` at ``im`` [g]: it pounds on a wall at and above its onset there
    [g], collapses at and above ``collapse`` [g] (inf: never)."""
    return {"run_id": f"{rec}-{im:.6f}", "record_set": "farfield", "record_id": rec,
            "component": "a", "im": im, "im_kind": "sa", "status": "ok",
            "collapse": bool(im >= collapse), "collapsed": bool(im >= collapse),
            "impacts_pos": int(im >= onset_pos), "impacts_neg": int(im >= onset_neg),
            "pounding": bool(im >= min(onset_pos, onset_neg)),
            "peak_impact_force_pos": 10.0 * (im >= onset_pos), "peak_impact_force_neg": 0.0,
            "peak_wall_displacement_pos": 0.0, "peak_wall_displacement_neg": 0.0,
            "peak_base_displacement": 5.0 * im, "peak_drift_ratio": 0.01 * im,
            "peak_floor_acceleration_1": 0.3 * im}


def _trace(rec, ims, onset_pos, onset_neg, collapse):
    """An IDA trace: the runs at ``ims`` up to and including the first collapse."""
    rows = []
    for im in sorted(ims):
        rows.append(_run(rec, im, onset_pos, onset_neg, collapse))
        if im >= collapse:
            break
    return rows


# five records: onsets on pos at 0.5, 0.75, 1.0, 1.5 g and never for record 4, which collapses
# at 1.25 g before touching pos; record 2 collapses at 2.0 g. Every record pounds on neg, at
# θ·exp(β q_i), q_i the symmetric normal quantiles (i − ½)/5: a closed-form fit.
N, THETA, BETA = 5, 1.2, 0.5
Q = stats.norm.ppf((np.arange(1, N + 1) - 0.5) / N)
ONSET_POS = [0.5, 0.75, 1.0, 1.5, np.inf]
ONSET_NEG = list(THETA * np.exp(BETA * Q))
COLLAPSE = [np.inf, np.inf, 2.0, np.inf, 1.25]
GRID = np.round(np.arange(0.25, 3.001, 0.25), 10)


def synthetic():
    rows = []
    for r in range(N):
        ims = set(GRID) | {ONSET_NEG[r]}  # the trace runs at the neg onset (as a hunt brackets)
        rows += _trace(r, ims, ONSET_POS[r], ONSET_NEG[r], COLLAPSE[r])
    return pd.DataFrame(rows)


def test_fractions_per_wall_count_every_record_and_collapse_apart():
    t = synthetic()
    p = pounding.probability_table(t, ["pos", "neg"], [1.0, 1.25, 1.5, 3.0]).set_index(
        ["wall", "im [g]"])
    # at 1.0 g records 0, 1, 2 have pounded on pos (onsets 0.5, 0.75, 1.0), 3 and 4 not yet
    assert p.loc[("pos", 1.0), "P(pounding) [-]"] == pytest.approx(3 / 5)
    # at 1.25 g record 4 collapsed before touching pos: collapsed, not "did not pound"
    r = p.loc[("pos", 1.25)]
    assert (r["n_pounded"], r["n_collapsed"], r["n_not_pounded"]) == (3, 1, 1)
    # at 1.5 g record 3 pounds: 4 of 5; record 2's collapse at 2.0 g keeps it "pounded" (it
    # pounded at 1.0 g, below its collapse)
    assert p.loc[("pos", 1.5), "P(pounding) [-]"] == pytest.approx(4 / 5)
    r = p.loc[("pos", 3.0)]
    assert (r["n_pounded"], r["n_collapsed"], r["n_analyses"]) == (4, 1, 5)
    # neg: every record counts at every level; at 1.25 g the onsets below are θe^(βq) <= 1.25,
    # i.e. q <= ln(1.25/1.2)/0.5 = 0.082: the three lowest quantiles (−1.28, −0.52, 0)
    assert p.loc[("neg", 1.25), "n_analyses"] == N
    assert p.loc[("neg", 1.25), "n_pounded"] == np.sum(Q <= np.log(1.25 / THETA) / BETA) == 3
    # any wall: the first impact on either (record 4 pounds on neg at 1.2·e^(0.5·1.28) = 2.28 g
    # > its collapse at 1.25 g: it never pounds anything)
    assert p.loc[("any", 3.0), "n_pounded"] == 4 and p.loc[("any", 3.0), "n_collapsed"] == 1


def test_onset_fit_per_wall_from_the_traces():
    t = synthetic()
    f = pounding.fragility_table(t, ["pos", "neg"], True, list(GRID), smt=1.0).set_index("wall")
    # neg: every onset observed (record 4's at 2.28 g is above its collapse at 1.25 g, so it
    # is censored: only records 0-3 pound, their onsets 1.2·e^(0.5 q_i)). The MLE with record
    # 4 right-censored at its highest clear run, 1.0 g (1.25 g collapsed), is fit_ida's
    onsets = np.array(ONSET_NEG[:4])
    expected = fit_ida(onsets, [1.0])
    assert f.loc["neg", "theta fitted [g]"] == pytest.approx(expected.theta, rel=1e-9)
    assert f.loc["neg", "beta fitted [-]"] == pytest.approx(expected.beta, rel=1e-9)
    assert (f.loc["neg", "n_pounded_ever"], f.loc["neg", "n_collapsed_first"]) == (4, 1)
    # pos: onsets 0.5, 0.75, 1.0, 1.5 g and record 4 censored at 1.0 g; its empirical median
    # is the 3rd of 5 with the censored one above every onset: 1.0 g
    assert f.loc["pos", "onset median empirical [g]"] == pytest.approx(1.0)
    expected = fit_ida([0.5, 0.75, 1.0, 1.5], [1.0])
    assert f.loc["pos", "theta fitted [g]"] == pytest.approx(expected.theta, rel=1e-9)
    # at S_MT = 1.0 g: 3 of 5 records pound on pos, none collapsed yet
    assert f.loc["pos", "P(pounding) at S_MT [-]"] == pytest.approx(0.6)
    assert f.loc["pos", "P(collapsed first) at S_MT [-]"] == 0.0


def test_uncensored_onsets_give_the_closed_form_fit():
    # no record collapses: the neg onsets θ·e^(βq) are all observed; the MLE is closed form,
    # ln θ̂ = mean(ln x) = ln θ (symmetric q), β̂ = β·sqrt(mean q²) (the 1/n deviation)
    rows = []
    for r in range(N):
        rows += _trace(r, set(GRID) | {ONSET_NEG[r]}, np.inf, ONSET_NEG[r], np.inf)
    f = pounding.fragility_table(pd.DataFrame(rows), ["pos", "neg"], True, list(GRID))
    neg = f.set_index("wall").loc["neg"]
    assert neg["theta fitted [g]"] == pytest.approx(THETA, rel=1e-9)
    assert neg["beta fitted [-]"] == pytest.approx(BETA * np.sqrt(np.mean(Q**2)), rel=1e-9)
    # the median record (q = 0) pounds at exactly θ
    assert neg["onset median empirical [g]"] == pytest.approx(THETA, rel=1e-12)
    # pos: nobody pounds, so no fit, and it says why
    pos = f.set_index("wall").loc["pos"]
    assert np.isnan(pos["theta fitted [g]"]) and "no record pounded" in pos["note"]


def test_fractions_are_monotone_even_when_a_trace_is_not():
    # record 0 pounds at 0.5 g, not at 0.75 g (a resurrection), again at 1.0 g: once pounding
    # it counts as pounding above (the IDA reading of a collapse), so the fraction never falls
    t = synthetic()
    t.loc[(t["record_id"] == 0) & np.isclose(t["im"], 0.75), "impacts_pos"] = 0
    p = pounding.probability_table(t, ["pos", "neg"], list(GRID))
    for _, w in p.groupby("wall"):
        assert np.all(np.diff(w["P(pounding) [-]"].to_numpy()) >= 0)
        assert np.all(np.diff((w["n_pounded"] + w["n_collapsed"]).to_numpy()) >= 0)


def _hunt_fill_trace(rec, onset_pos, collapse, resolution, onsets=True):
    """The rows of a hunt-and-fill trace (step0 = increment = 0.1 g, 40 runs) of a record that
    pounds on pos at and above ``onset_pos`` and collapses at and above ``collapse`` [g]."""
    def run(im):
        return Outcome(im >= collapse, frozenset({"pos"}) if im >= onset_pos else frozenset())

    runs = hunt_fill(run, 0.1, 0.1, resolution, 40, ("pos", "neg") if onsets else ())
    return [_run(rec, r.im, onset_pos, np.inf, collapse) for r in runs]


@pytest.mark.parametrize("onsets", [True, False])
def test_stripes_and_a_hunt_and_fill_ida_of_the_same_records_agree(onsets):
    # the same five records run as stripes and as hunt-and-fill traces bracketing pos's onset
    # to res = 0.01 g (each collapses within its 40 runs: a trace that never collapses spends
    # them all on its hunt). Two onsets lie just below a stripe (0.995 < 1.0, 2.495 < 2.5 g),
    # one on it (1.5 g, a hunt run: 0.1 + 0.2 + 0.3 + 0.4 + 0.5). A trace's onset is the
    # upper end of a bracket that holds the true onset x and is at most res wide, so
    # x <= onset < x + res; a stripe at y pounds iff x <= y. So at each level y: pounded in
    # the IDA => pounded in the stripe at y, and pounded in the stripe at y - res =>
    # x <= y - res => onset < y => pounded in the IDA:
    #     P_stripes(y - res) <= P_IDA(y) <= P_stripes(y)
    res = 0.01
    onset_pos, collapses = [0.63, 0.995, 1.5, 1.77, 2.495], [3.1, 2.55, 3.2, 1.33, 2.9]
    levels = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0]

    def stripes(at):
        return pd.DataFrame([_run(r, x, onset_pos[r], np.inf, collapses[r])
                             for r in range(N) for x in at])

    ida = pd.DataFrame([row for r in range(N)
                        for row in _hunt_fill_trace(r, onset_pos[r], collapses[r], res, onsets)])
    p = pounding.probability_table(ida, ["pos", "neg"], levels)
    hi = pounding.probability_table(stripes(levels), ["pos", "neg"], levels)
    lo = pounding.probability_table(stripes([y - res for y in levels]), ["pos", "neg"],
                                    [y - res for y in levels])
    f = pounding.fragility_table(ida, ["pos", "neg"], True, levels).set_index("wall")
    if not onsets:
        # the collapse-only traces know the onsets to the spacing of the runs the collapse
        # and the fill happened to make: the hunt's 0.1 g steps halved by the fill, 0.1 g here
        assert f.loc["pos", "onset bracket widest [g]"] > 10 * res
        return
    col = "P(pounding) [-]"
    assert np.all(lo[col].to_numpy() <= p[col].to_numpy())
    assert np.all(p[col].to_numpy() <= hi[col].to_numpy())
    # at 1.5 g records 0, 1, 2 pounded (onsets 0.63, 0.995 and 1.5 itself, a hunt run), record
    # 3 collapsed at 1.33 g before its onset 1.77 g
    pos = p[p["wall"] == "pos"].set_index("im [g]")
    assert pos.loc[1.5, "n_pounded"] == 3 and pos.loc[1.5, "n_collapsed"] == 1
    # each record's onset bracket is at most res wide and holds its true onset (record 3
    # collapses at 1.33 g before its onset 1.77 g: no onset)
    tr = pounding.traces(ida, "pos")
    pounded = np.isfinite(tr["onset"]).to_numpy()
    assert list(pounded) == [True, True, True, False, True]
    x = np.array(onset_pos)[pounded]
    assert np.all((tr["clear"][pounded] < x) & (x <= tr["onset"][pounded]))
    assert f.loc["pos", "onset bracket widest [g]"] <= res
    # the empirical median onset (records 0, 1, 2, 4 and the censored 3 above them: the 3rd of
    # 5 is record 2's, 1.5 g) is within res of it
    assert 0 <= f.loc["pos", "onset median empirical [g]"] - 1.5 < res


def test_the_report_writes_the_pounding_fragility_and_a_panel_per_wall(tmp_path):
    meta = dict(varied=[], period=1.5, sdc="Dmax", time_scale=1.0,
                solver_failure="separate", record_set="farfield", scaling="ida",
                hunt_fill=True, definition={"p695": {"mu_t": 3.0}},
                scaling_detail={"hunt": {"pounding_onsets": True}})
    t = synthetic().assign(status=lambda d: np.where(d["collapse"], "collapsed", "ok"))
    paths = write_report(t.drop(columns="collapse"), meta, tmp_path)
    names = [p.name for p in paths]
    assert "pounding_fragility.csv" in names and "pounding_probability.png" in names
    p = pd.read_csv(tmp_path / "pounding_probability.csv")
    # S_MT (Dmax, T = 1.5 s) = 0.6 g; hunt-and-fill levels S_MT·(0.5, 1, 1.5, 2, 3): every
    # record at every level, per wall
    assert set(p["wall"]) == {"any", "pos", "neg"} and set(p["n_analyses"]) == {N}
    assert sorted(set(p["im [g]"])) == [0.3, 0.6, 0.9, 1.2, 1.8]
    f = pd.read_csv(tmp_path / "pounding_fragility.csv").set_index("wall")
    # at 0.6 g only record 0 (onset 0.5 g) has pounded on pos: 1 of 5
    assert f.loc["pos", "P(pounding) at S_MT [-]"] == pytest.approx(0.2)
    readme = (tmp_path / "README.txt").read_text()
    assert "pounding_fragility.csv" in readme and "collapsed before" in readme
    # the scaling line says how the onsets were found: bracketed by the hunt (suite.json)
    assert "onset of pounding on each wall" in " ".join(readme.split())
    assert "onset bracket widest [g]" in set(f.columns)

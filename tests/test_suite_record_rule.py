"""What a record is in a plan suite's verdict (femoat.suite.statistics.RECORD_RULE, FEMA P695's
three-dimensional analyses): a pair, each of its angles one analysis; S_CT and the fitted
dispersion over the analyses, the record count the pairs."""

import numpy as np
import pandas as pd
import pytest

from femoat.suite.p695_inputs import margin_basis
from femoat.suite.report import collapse_summary, p695_inputs, write_report
from femoat.suite.verdict import verdict_text

# three pairs at 0° and 90°, each analysis collapsing at a known Sa [g] on a 0.1 g IDA grid
COLLAPSE = {(1, 0.0): 0.8, (1, 90.0): 1.0, (2, 0.0): 1.3, (2, 90.0): 1.1, (3, 0.0): 1.6,
            (3, 90.0): 2.0}
META = dict(varied=[], period=1.5, sdc="Dmax", time_scale=1.0, solver_failure="separate",
            record_set="farfield", scaling="ida", hunt_fill=False, plan=True,
            definition={"p695": {"mu_t": 3.0}})


def plan_table():
    rows = []
    for (pair, angle), c in COLLAPSE.items():
        for im in np.round(np.arange(0.1, c + 1e-9, 0.1), 10):
            done = im >= c - 1e-9
            rows.append({"run_id": f"{pair}@{angle:g}-{im:.2f}", "record_set": "farfield",
                         "record_id": pair, "component": None, "angle": angle, "im": im,
                         "im_kind": "sa", "status": "collapsed" if done else "ok",
                         "collapsed": done, "pounding": False,
                         **{f"impacts_{w}": 0 for w in ("px", "mx", "py", "my")},
                         **{f"peak_{k}_{w}": 0.0 for w in ("px", "mx", "py", "my")
                            for k in ("impact_force", "wall_displacement")},
                         "peak_base_displacement": 3 * im, "peak_drift_ratio": 0.01 * im,
                         "peak_floor_acceleration_1": 0.2 * im})
    return pd.DataFrame(rows)


def test_a_plan_suites_verdict_counts_pairs_and_takes_s_ct_over_the_analyses(tmp_path):
    t = plan_table()
    write_report(t, META, tmp_path)
    s = pd.read_csv(tmp_path / "collapse_summary.csv").iloc[0]
    # 3 pairs (the records) at 2 angles: 6 analyses, each collapsing once
    assert (s["n_records"], s["n_analyses"], s["n_collapsed"]) == (3, 6, 6)
    # S_CT: the median of the 6 analyses' collapse intensities 0.8, 1.0, 1.1, 1.3, 1.6, 2.0 g
    # (FEMA P695 3D: half of the analyses collapse), the mean of the middle two = 1.2 g
    x = np.array(sorted(COLLAPSE.values()))
    assert s["S_CT empirical [g]"] == pytest.approx(1.2, rel=1e-3)
    # the fitted beta over the analyses: no censoring, the 1/n MLE std of ln x
    assert s["beta fitted [-]"] == pytest.approx(np.log(x).std(), rel=1e-3)
    assert s["theta fitted [g]"] == pytest.approx(np.exp(np.log(x).mean()), rel=1e-3)
    assert "3 pairs at 2 angles = 6 analyses" in s["note"]
    # the terminal: one record count (pairs) and the analyses beside it
    meta = {**META, "im_kind": "sa"}
    inputs = p695_inputs(meta)
    summary = collapse_summary(t, meta, inputs)
    text = verdict_text(t, summary, inputs, margin_basis(meta, inputs), "here")
    head, row = [line.split() for line in text.splitlines()
                 if line.startswith(("variation", "all"))][:2]
    assert row[head.index("records")] == "3" and row[head.index("analyses")] == "6"
    # README states the rule once: a record is a pair, each angle one analysis
    readme = (tmp_path / "README.txt").read_text().replace("\n", " ")
    readme = " ".join(readme.split())
    assert "In a plan suite a record is a pair" in readme
    assert "one horizontal component" in readme and readme.count("What a record is") == 1


def test_a_1d_suite_counts_each_component_as_a_record(tmp_path):
    t = plan_table().drop(columns="angle")
    t["component"] = np.where(t["run_id"].str.contains("@0"), "a", "b")
    write_report(t, {**META, "plan": False}, tmp_path)
    s = pd.read_csv(tmp_path / "collapse_summary.csv").iloc[0]
    # components a and b of 3 records: 6 records, 6 analyses (2D: each component a record)
    assert (s["n_records"], s["n_analyses"]) == (6, 6)
    assert "pairs at" not in str(s["note"])

"""The report of a record suite: per variation the collapse fragility and the FEMA P695 margin,
the responses side by side, and the probability of pounding; CSV tables and PNG figures.

Entry points: :func:`run_report` (``DIR/runs/*.parquet`` + ``DIR/suite.json`` → ``DIR/report/``)
and :func:`write_report` (a run table and the suite's meta dict → any folder).

Run-table columns used: status, collapsed, im [g], im_kind, record_set/record_id/component (a
record), the varied keys (``meta["varied"]``), pounding, peak_impact_force_pos/neg [kip],
peak_wall_displacement_pos/neg [in], peak_base_displacement [in], peak_drift_ratio [-],
peak_floor_acceleration_<k> [g]. Meta keys used: varied, period [s], sdc, smt [g], record_set,
scaling ("ida" | "p695" | "pga"), hunt_fill, solver_failure, time_scale; optional mu_t (μT,
default 3.0) and ratings (default B, B, B).

IDA suites ("scaling" = "ida") fit one collapse intensity per record (:func:`fit_ida`), the
others fit stripes (:func:`fit_stripes`). Responses and pounding are tabulated at every stripe
(every IM level of an ordinary IDA); a hunt-and-fill IDA has no common levels, so each record
contributes its run nearest (within ±25 %) to S_MT × (0.5, 1, 1.5, 2, 3), or to ``levels``.
"""

import json
from pathlib import Path

import pandas as pd

from femoat.atomic import atomic_path, write_text
from femoat.suite import statistics as st
from femoat.suite.margin import collapse_row
from femoat.suite.readme import readme_text

HUNT_FILL_LEVELS = (0.5, 1.0, 1.5, 2.0, 3.0)  # × S_MT


def run_report(directory, **options):
    """Read ``directory``/runs/*.parquet and suite.json, write ``directory``/report/; returns the
    written paths. ``options`` go to :func:`write_report`."""
    d = Path(directory)
    parts = sorted((d / "runs").glob("*.parquet"))
    if not parts:
        raise FileNotFoundError(f"no run table in {d / 'runs'} (expected *.parquet part files)")
    table = pd.concat([pd.read_parquet(p) for p in parts], ignore_index=True)
    meta = json.loads((d / "suite.json").read_text(encoding="utf-8"))
    return write_report(table, meta, d / "report", **options)


def _ida_panel(use, metric):
    value = st.METRICS[metric][1]
    return [(r["im"].to_numpy(float), value(r).to_numpy(float), r["collapse"].to_numpy(bool))
            for _, r in use.groupby(st.record_keys(use), sort=False, dropna=False)]


def _write_csv(df, path):
    with atomic_path(path) as tmp:
        df.to_csv(tmp, index=False)
    return Path(path)


def write_report(table, meta, out_dir, *, mu_t=None, ratings=None, levels=None):
    """Write collapse_summary.csv, response_by_variation.csv, pounding_probability.csv, the
    figures and README.txt into ``out_dir``; returns the written paths."""
    from femoat.suite import report_figures

    kinds = set(table["im_kind"].dropna()) if "im_kind" in table else set()
    if len(kinds) > 1:
        raise ValueError(f"one intensity measure per suite, not {sorted(kinds)}")
    meta = {**meta, "im_kind": meta.get("im_kind") or (kinds.pop() if kinds else "sa")}
    out, varied = Path(out_dir), list(meta.get("varied", []))
    smt, ida = float(meta["smt"]), meta.get("scaling") == "ida"
    p695_args = dict(period=float(meta["period"]), sdc=meta["sdc"], record_set=meta["record_set"],
                     mu_t=float(mu_t or meta.get("mu_t", 3.0)),
                     ratings=tuple(ratings or meta.get("ratings", ("B", "B", "B"))))
    mu_source = ("given" if mu_t else "from suite.json" if "mu_t" in meta
                 else "default, not measured: give mu_t")
    if levels is None and ida and meta.get("hunt_fill"):
        levels = [f * smt for f in HUNT_FILL_LEVELS]
    summary, responses, figs = [], [], []
    for label, key, rows in st.variations(table, varied):
        use = st.usable_runs(rows, meta.get("solver_failure", "separate"))
        row, curve = collapse_row(rows, use, meta, ida, p695_args)
        summary.append({"variation": label, **key, **row})
        resp = st.response_table(use, ida, levels)
        if len(resp):
            resp.insert(1, "im / S_MT [-]", resp["im [g]"] / smt)
            responses.append(resp.assign(**{"variation": label, **key}))
        panels = {m: _ida_panel(use, m) for m in ("peak_drift_ratio", "peak_base_displacement")}
        figs.append((label, key, curve, resp, panels))
    cols = ["variation", *varied]
    resp = pd.concat(responses, ignore_index=True) if responses else pd.DataFrame(columns=cols)
    resp = resp[cols + [c for c in resp.columns if c not in cols]]
    pound = resp[cols + ["im [g]", "im / S_MT [-]", "n_records", "pounding probability [-]"]] \
        if len(resp) else resp
    paths = [_write_csv(pd.DataFrame(summary), out / "collapse_summary.csv"),
             _write_csv(resp, out / "response_by_variation.csv"),
             _write_csv(pound, out / "pounding_probability.csv")]
    paths += report_figures.write_figures(figs, meta, out, ida)
    paths.append(out / "README.txt")
    names = [p.name for p in paths]
    write_text(paths[-1], readme_text(meta, p695_args, mu_source, ida, levels, names))
    return paths

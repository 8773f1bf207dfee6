"""The report of a record suite: per variation the collapse fragility and the FEMA P695 margin,
the responses side by side, and the probability of pounding; CSV tables and PNG figures.

Entry points: :func:`run_report` (the run table of ``DIR``, read by
:func:`femoat.suite.table.load_table`, + ``DIR/suite.json`` → ``DIR/report/``),
:func:`write_report` (a run table and the suite's meta dict → any folder) and
:func:`collapse_summary` (the collapse_summary.csv table alone, without figures: the terminal
verdict of :mod:`femoat.suite.verdict`).

Run-table columns used: status, collapsed, im [g], im_kind, record_set/record_id/component (a
record; a plan suite's: and angle), the varied keys (``meta["varied"]``), pounding,
impacts_<wall>, peak_impact_force_<wall> [kip], peak_wall_displacement_<wall> [in] (walls pos,
neg or px, mx, py, my), peak_base_displacement [in], peak_drift_ratio [-],
peak_floor_acceleration_<k> [g]. Meta keys used: varied, variations, definition, period [s],
sdc, record_set, scaling ("ida" | "p695" | "pga"), im_kind, hunt_fill, solver_failure,
time_scale. The P695 inputs (SDC, μT, quality ratings or β_TOT) come from the options, the
suite file's ``[p695]`` table or the defaults (:mod:`femoat.suite.p695_inputs`).

IDA suites ("scaling" = "ida") fit one collapse intensity per record (:func:`fit_ida`), the
others fit stripes (:func:`fit_stripes`). Responses and pounding are tabulated at every stripe
(every IM level of an ordinary IDA); a hunt-and-fill IDA has no common levels, so each record
contributes its run nearest (within ±25 %) to S_MT × (0.5, 1, 1.5, 2, 3), or to ``levels``.
Variations come in the order of the suite file, the contact law ("walls.law") innermost: with
walls and laws varied, the rows are the laws of the first wall, then those of the second.
Numbers are written to 4 significant digits.

Every scaling method gets a report: what does not apply to it is left out and README.txt says
what and why (:func:`femoat.suite.readme.not_reported`): no FEMA P695 margin (S_MT, CMR, ACMR,
verdict) without Sa(T) at a period, and no IDA curves for stripes (methods "pga", "p695").
"""

import json
from pathlib import Path
from typing import NamedTuple

import numpy as np
import pandas as pd

from femoat.atomic import atomic_path, write_text
from femoat.suite import policies
from femoat.suite import statistics as st
from femoat.suite.p695_inputs import RATING_KEYS, resolve
from femoat.suite.readme import readme_text

HUNT_FILL_LEVELS = (0.5, 1.0, 1.5, 2.0, 3.0)  # × S_MT
DIGITS = 4  # significant digits of every number in the CSV files


def load(directory):
    """(run table, suite.json dict) of a suite folder."""
    from femoat.suite.table import load_table

    d = Path(directory)
    if not (d / "suite.json").is_file():
        raise FileNotFoundError(f"{d} is not a suite folder (no suite.json): give the --out "
                                "folder of a suite")
    table = load_table(d)
    if not len(table):
        raise FileNotFoundError(f"no run table in {d / 'runs'} (expected *.parquet part files)")
    return table, json.loads((d / "suite.json").read_text(encoding="utf-8"))


def run_report(directory, table=None, meta=None, **options):
    """Read ``directory``'s run table and suite.json (unless given as ``table`` and
    ``meta``), write ``directory``/report/; returns the written paths. ``options`` go to
    :func:`write_report`."""
    if table is None or meta is None:
        table, meta = load(directory)
    paths = write_report(table, meta, Path(directory) / "report", **options)
    write_text(Path(directory) / "report" / FINGERPRINT, fingerprint(directory, options))
    return paths


FINGERPRINT = ".written_from"  # what the report was written from (see is_current)


def fingerprint(directory, options):
    """A digest of what a report of ``directory`` depends on: suite.json, the part files (each
    written once, named by its runs), the report options and femoat's version."""
    import hashlib

    from femoat import __version__
    from femoat.suite.table import part_files

    d = Path(directory)
    h = hashlib.sha256((d / "suite.json").read_bytes())
    h.update("|".join(p.name for p in part_files(d)).encode())
    h.update(json.dumps(options, sort_keys=True, default=str).encode())
    h.update(__version__.encode())
    return h.hexdigest() + "\n"


def is_current(directory, options):
    """Whether ``directory``/report was written from the stored runs and these options."""
    mark = Path(directory) / "report" / FINGERPRINT
    return mark.is_file() and (Path(directory) / "report" / "collapse_summary.csv").is_file() \
        and mark.read_text(encoding="utf-8") == fingerprint(directory, options)


def p695_inputs(meta, mu_t=None, sdc=None, ratings=None, beta_total=None, **ratings_by_name):
    """The :class:`femoat.suite.p695_inputs.P695Inputs` of a report: the given values
    (``ratings`` a (DR, TD, MDL) triple, or by name: design_requirements, test_data,
    modeling) over the suite file's over the defaults."""
    given = dict(mu_t=mu_t, sdc=sdc, beta_total=beta_total, **ratings_by_name)
    if ratings is not None:
        if len(ratings) != 3:
            raise ValueError(f"ratings = {ratings!r}: give three quality ratings (design "
                             "requirements, test data, modeling), e.g. ('B', 'B', 'C')")
        given.update(zip(RATING_KEYS, ratings))
    return resolve(meta, given)


def _with_im_kind(table, meta):
    kinds = set(table["im_kind"].dropna()) if "im_kind" in table else set()
    if len(kinds) > 1:
        raise ValueError(f"one intensity measure per suite, not {sorted(kinds)}")
    return {**meta, "im_kind": meta.get("im_kind") or (kinds.pop() if kinds else "sa")}


def ordered_variations(table, meta):
    """:func:`femoat.suite.statistics.variations` in the suite file's order, "walls.law"
    innermost (the laws of one wall together)."""
    varied = list(meta.get("varied", []))
    groups = st.variations(table, varied)
    listed = (meta.get("definition") or {}).get("variations") or {}
    keys = [k for k in varied if k != "walls.law"] + [k for k in varied if k == "walls.law"]

    def position(group):
        out = []
        for k in keys:
            values, value = listed.get(k, []), group[1][k]
            out.append(next((i for i, v in enumerate(values)  # 3 == 3.0; "E" == "E"
                             if v == value or str(v) == str(value)), len(values)))
        return out

    return sorted(groups, key=position)  # stable: unlisted values keep the table's order


class VariationResult(NamedTuple):
    """One variation's share of the report."""

    label: str  # e.g. "E / concrete"
    key: dict  # {varied key: value}
    rows: pd.DataFrame  # all its runs
    use: pd.DataFrame  # the runs the statistics use (statistics.usable_runs)
    summary: dict  # its collapse_summary.csv row
    curve: dict  # the fragility figure's data (femoat.suite.margin.collapse_row)


def _collapse_rows(table, meta, inputs):
    """([:class:`VariationResult`] in the suite file's order, the margin basis)."""
    from femoat.suite.margin import collapse_row  # scipy: imported when used
    from femoat.suite.p695_inputs import margin_basis

    ida = meta.get("scaling") == "ida"
    policy = meta.get("solver_failure", policies.DEFAULT)
    basis = margin_basis(meta, inputs)
    out = []
    for label, key, rows in ordered_variations(table, meta):
        use = st.usable_runs(rows, policy)
        row, curve = collapse_row(rows, use, policy, ida, basis)
        out.append(VariationResult(label, key, rows, use, {"variation": label, **key, **row},
                                   curve))
    return out, basis


def collapse_summary(table, meta, inputs):
    """collapse_summary.csv as a DataFrame, rounded as written."""
    meta = _with_im_kind(table, meta)
    results, _ = _collapse_rows(table, meta, inputs)
    return rounded(pd.DataFrame([r.summary for r in results]))


def rounded(df, digits=DIGITS):
    """``df`` with every float to ``digits`` significant digits (counts and text unchanged)."""
    def sig(x):
        return float(f"{x:.{digits}g}") if isinstance(x, float) and np.isfinite(x) else x

    out = df.copy()
    for c in out.columns:
        if out[c].dtype == float:
            out[c] = out[c].map(sig)
        elif out[c].dtype == object:
            out[c] = out[c].map(lambda v: sig(v) if isinstance(v, float) else v)
    return out


def _ida_panel(use, metric):
    value = st.METRICS[metric][1]
    return [(r["im"].to_numpy(float), value(r).to_numpy(float), r["collapse"].to_numpy(bool))
            for _, r in use.groupby(st.record_keys(use), sort=False, dropna=False)]


def _write_csv(df, path):
    with atomic_path(path) as tmp:
        rounded(df).to_csv(tmp, index=False)
    return Path(path)


def reference_intensity(table, smt):
    """The intensity [g] the response levels and the near-MCE figure refer to: S_MT, or
    without one the median intensity of the runs."""
    return smt if smt is not None else float(np.median(table["im"].to_numpy(float)))


def near_mce_by_pounding(use, ida, levels, reference):
    """Rows (pounding "yes"/"no", :func:`femoat.suite.statistics.response_row`) at the response
    level nearest ``reference`` [g]: the runs that pounded and those that did not, apart."""
    at = st.runs_at_levels(use, ida, levels)
    if not at:
        return []
    x, rows = min(at, key=lambda a: abs(np.log(a[0] / reference)))
    hit = rows["pounding"].fillna(False).astype(bool) if "pounding" in rows else \
        rows[["impacts_pos", "impacts_neg"]].fillna(0).sum(axis=1) > 0
    return [{"im [g]": x, "pounding": name, **st.response_row(part)}
            for name, part in (("yes", rows[hit.to_numpy()]), ("no", rows[~hit.to_numpy()]))
            if len(part)]


def pounding_levels(use, ida, levels):
    """The levels [g] of pounding_probability.csv: ``levels`` when given (a hunt-and-fill IDA:
    S_MT x HUNT_FILL_LEVELS), else the response tables' (every stripe, every common IDA
    level)."""
    return list(levels) if levels is not None else [x for x, _ in st.runs_at_levels(use, ida)]


def pounding_tables(use, ida, levels, walls, smt):
    """(pounding_probability rows, pounding_fragility rows) of one variation's usable runs
    (:mod:`femoat.suite.pounding`): every record at every level, read from its trace."""
    from femoat.suite import pounding

    at = pounding_levels(use, ida, levels)
    return (pounding.probability_table(use, walls, at),
            pounding.fragility_table(use, walls, ida, at, smt))


def pounding_summary(table, meta, inputs, levels=None):
    """pounding_fragility.csv as a DataFrame, rounded as written (the terminal's pounding
    lines after a suite)."""
    meta = _with_im_kind(table, meta)
    results, basis = _collapse_rows(table, meta, inputs)
    ida = meta.get("scaling") == "ida"
    if levels is None and ida and meta.get("hunt_fill"):
        levels = [f * reference_intensity(table, basis.smt) for f in HUNT_FILL_LEVELS]
    walls = st.walls(table)
    rows = [pounding_tables(v.use, ida, levels, walls, basis.smt)[1].assign(
        **{"variation": v.label, **v.key}) for v in results]
    return rounded(_leading(pd.concat(rows, ignore_index=True),
                            ["variation", *meta.get("varied", [])]))


def _leading(df, cols):
    """``df`` with the columns ``cols`` first."""
    return df[[c for c in cols if c in df] + [c for c in df.columns if c not in cols]]


def write_report(table, meta, out_dir, *, mu_t=None, sdc=None, ratings=None, beta_total=None,
                 levels=None, **ratings_by_name):
    """Write collapse_summary.csv, response_by_variation.csv, pounding_probability.csv,
    pounding_fragility.csv, responses_near_mce.csv, the figures and README.txt into
    ``out_dir``; returns the written paths. ``mu_t``, ``sdc``, ``ratings`` or the ratings by name, ``beta_total``: the P695
    inputs (:func:`p695_inputs`); ``levels`` [g]: the response levels of a hunt-and-fill IDA."""
    from femoat.suite import report_figures

    meta = _with_im_kind(table, meta)
    inputs = p695_inputs(meta, mu_t, sdc, ratings, beta_total, **ratings_by_name)
    out, varied = Path(out_dir), list(meta.get("varied", []))
    ida = meta.get("scaling") == "ida"
    results, basis = _collapse_rows(table, meta, inputs)
    smt = basis.smt
    ref = reference_intensity(table, smt)
    if levels is None and ida and meta.get("hunt_fill"):
        levels = [f * ref for f in HUNT_FILL_LEVELS]
    responses, near, figs, pounding, onsets = [], [], [], [], []
    walls = st.walls(table)
    for v in results:
        resp = st.response_table(v.use, ida, levels)
        if len(resp) and smt is not None:
            resp.insert(1, "im / S_MT [-]", resp["im [g]"] / smt)
        if len(resp):
            responses.append(resp.assign(**{"variation": v.label, **v.key}))
        prob, frag = pounding_tables(v.use, ida, levels, walls, smt)
        prob.insert(0, "variation", v.label)
        if smt is not None:
            prob.insert(3, "im / S_MT [-]", prob["im [g]"] / smt)
        pounding.append(prob.assign(**v.key))
        onsets.append(frag.assign(**{"variation": v.label, **v.key}))
        split = near_mce_by_pounding(v.use, ida, levels, ref)
        near += [{"variation": v.label, **v.key, **r} for r in split]
        panels = {m: _ida_panel(v.use, m) for m in ("peak_drift_ratio", "peak_base_displacement")}
        figs.append(report_figures.VariationFigures(v.label, v.key, v.curve, resp, panels, split,
                                                    prob, frag))
    cols = ["variation", *varied]
    resp = pd.concat(responses, ignore_index=True) if responses else pd.DataFrame(columns=cols)
    resp = resp[cols + [c for c in resp.columns if c not in cols]]
    pound = _leading(pd.concat(pounding, ignore_index=True), cols)
    onset = _leading(pd.concat(onsets, ignore_index=True), cols)
    paths = [_write_csv(pd.DataFrame([v.summary for v in results]), out / "collapse_summary.csv"),
             _write_csv(resp, out / "response_by_variation.csv"),
             _write_csv(pound, out / "pounding_probability.csv"),
             _write_csv(onset, out / "pounding_fragility.csv"),
             _write_csv(pd.DataFrame(near, columns=cols + ["im [g]", "pounding"])
                        if not near else pd.DataFrame(near), out / "responses_near_mce.csv")]
    paths += report_figures.write_figures(figs, meta, out, ida, smt)
    paths.append(out / "README.txt")
    names = [p.name for p in paths]
    write_text(paths[-1], readme_text(meta, inputs, basis, ida, levels, names))
    return paths

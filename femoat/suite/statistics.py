"""Per-variation views of a suite's run table: usable runs, collapse data, intensity levels and
response statistics (median and lognormal dispersion across records).

The run table has one row per run (columns: :mod:`femoat.suite.columns`). A *variation* is
one combination of the varied scenario keys (``meta["varied"]``, e.g. "walls.law" ×
"walls.preset"). What a record is (FEMA P695 Section 6.2, :func:`record_rule`): a 1D suite's
record is one horizontal component (record_set, record_id, component; both components of a
pair count, P695's 2D analyses); a plan suite's record is a pair (record_set, record_id), and
each of its angles is one *analysis* of it (P695's 3D analyses apply each pair at two
orientations and count every orientation as one analysis of the pair).

Solver failures follow ``meta["solver_failure"]``, one of :data:`femoat.suite.policies.
SOLVER_FAILURE`. Runs with status "error" never enter and are counted apart.
"""

import numpy as np
import pandas as pd

from femoat.suite import policies

RECORD_KEYS = ("record_set", "record_id", "component", "angle")
"""The columns that name an analysis: a record, and in a plan suite its angle (each angle one
analysis of the pair, :data:`RECORD_RULE`)."""
LEVEL_DIGITS = 4  # stripes: IMs equal to 4 significant digits are one level
NEAREST = np.log(1.25)  # hunt-and-fill IDA: a record's run within ±25 % of a level stands for it


def _largest(t, name, pattern):
    """Largest |value| over the columns matching ``pattern`` (pos/neg sides, stories), else the
    column ``name`` itself."""
    v = t.filter(regex=pattern)
    return (v if v.shape[1] else t[[name]]).abs().max(axis=1)


METRICS = {  # name: (unit, value per run)
    "peak_impact_force": ("kip", lambda t: _largest(
        t, "peak_impact_force", _per_wall("peak_impact_force"))),
    "peak_wall_displacement": ("in", lambda t: _largest(
        t, "peak_wall_displacement", _per_wall("peak_wall_displacement"))),
    "peak_base_displacement": ("in", lambda t: t["peak_base_displacement"].abs()),
    "peak_drift_ratio": ("-", lambda t: t["peak_drift_ratio"].abs()),
    "peak_floor_acceleration": ("g", lambda t: _largest(
        t, "peak_floor_acceleration", r"^peak_floor_acceleration_\d+$")),
}


def _per_wall(name):
    """The pattern of the per-wall columns ``name_<wall>``
    (:func:`femoat.suite.definition.wall_keys`)."""
    from femoat.suite.definition import wall_keys

    return rf"^{name}_({'|'.join(wall_keys())})$"


def record_keys(table):
    """The columns naming an analysis (a record, at its angle in a plan suite)."""
    return [k for k in RECORD_KEYS if k in table.columns]


def pair_keys(table):
    """The columns naming a record: a 1D suite's component, a plan suite's pair (its angles
    are analyses of it)."""
    return [k for k in record_keys(table) if k != "angle"]


RECORD_RULE = (
    "What a record is (FEMA P695, 2009, Section 6.2 and Appendix A): in a 1D (2D-frame) suite "
    "a record is one horizontal component, both components of each pair counted (the 44 "
    "far-field components). In a plan suite a record is a pair, applied with its two "
    "components along the building's axes, and each angle the suite turns it by is one "
    "analysis of that pair: FEMA P695's three-dimensional analyses apply each pair twice, "
    "the second time turned by 90 degrees, and take S_CT as the intensity at which half of "
    "the analyses (2 x 22 far-field pairs) collapse. femoat follows that: n_records counts "
    "the pairs, n_analyses the (pair, angle) analyses; S_CT, the collapse fractions and the "
    "fitted theta and beta are over the analyses, every pair weighing the same (each has "
    "every angle), so S_CT is the median over the pairs' orientations, not a worst angle. "
    "The fitted beta treats the angles of one pair as separate samples although they are "
    "correlated, so its sampling uncertainty is that of n_records pairs, not of n_analyses.")
"""The rule, as README.txt states it (one paragraph)."""


def usable_runs(table, policy):
    """The runs the fragility and statistics use, with an effective bool column ``collapse``."""
    policies.check(policy, "the report's")
    t = table[table["status"] != "error"]
    failed = (t["status"] == "solver_failure").to_numpy()
    collapsed = (t["status"] == "collapsed").to_numpy()
    if "collapsed" in t:
        collapsed = collapsed | t["collapsed"].astype("boolean").fillna(False).to_numpy(bool)
    t = t.assign(collapse=collapsed | (failed & (policy == "collapse")))
    return t if policy == "collapse" else t[~failed]


def variations(table, varied):
    """[(label, {key: value}, rows)] per combination of the varied keys, in table order."""
    if not varied:
        return [("all", {}, table)]
    missing = [k for k in varied if k not in table.columns]
    if missing:
        raise ValueError(f"the run table has no column for the varied key(s) {missing}")
    out = []
    for values, rows in table.groupby(list(varied), sort=False, dropna=False):
        values = values if isinstance(values, tuple) else (values,)
        key = dict(zip(varied, values))
        out.append((" / ".join(str(v) for v in values), key, rows))
    return out


def ida_collapse_data(t):
    """IDA collapse intensities [g]: per record the lowest IM that collapsed; records that never
    collapse are right-censored at their largest IM. Returns (collapse_im, censored_im)."""
    keys = record_keys(t)
    top = t.groupby(keys, sort=False, dropna=False)["im"].max()
    first = t[t["collapse"]].groupby(keys, dropna=False)["im"].min().reindex(top.index)
    hit = first.notna()
    return first[hit].to_numpy(float), top[~hit].to_numpy(float)


def level_of(im):
    """Stripe level of each IM [g]: the IM to LEVEL_DIGITS significant digits."""
    return np.array([float(f"{x:.{LEVEL_DIGITS}g}") for x in np.asarray(im, float)])


def stripe_counts(t):
    """(level [g], n runs, n collapsed) per stripe, ascending."""
    c = t.assign(level=level_of(t["im"])).groupby("level")["collapse"].agg(["size", "sum"])
    return c.index.to_numpy(float), c["size"].to_numpy(float), c["sum"].to_numpy(float)


def runs_at_levels(t, ida=False, levels=None):
    """[(level [g], rows)]. Stripes: every run of each stripe. IDA: at each level each record
    contributes its run there, or, once it has collapsed at or below the level, its collapse
    run (IDA: a record that collapsed stays collapsed); ``levels`` None takes every IM level
    run by more than half the records not collapsed below it, else each record's run nearest
    to each requested level within ±25 % in IM (hunt-and-fill, no common levels)."""
    lv = level_of(t["im"])
    if not ida:
        return [(x, t[lv == x]) for x in np.unique(lv)]
    keys = record_keys(t)
    rec = t.groupby(keys, sort=False, dropna=False).ngroup().to_numpy()
    im, col = t["im"].to_numpy(float), t["collapse"].to_numpy(bool)
    c = pd.Series(im[col]).groupby(rec[col]).min().reindex(rec).to_numpy()  # collapse IM [g]
    is_first = col & (im == c)
    tol = NEAREST if levels is not None else 1e-4
    out = []
    for x in (np.unique(lv) if levels is None else levels):
        gone = is_first & (c <= x * (1 + 1e-9))
        dist = np.abs(np.log(im / x))
        alive = ~col & ~(c <= x * (1 + 1e-9)) & (dist <= tol)
        near = t[alive].assign(_r=rec[alive], _d=dist[alive]).sort_values("_d")
        near = near.groupby("_r", sort=False).head(1).drop(columns=["_r", "_d"])
        rows = pd.concat([t[gone], near])
        if levels is None:  # a common level: run by most of the records still standing
            standing = np.unique(rec[~(c < x * (1 - 1e-9))])
            ran = np.unique(rec[dist <= tol])
            if not standing.size or np.isin(standing, ran).sum() <= 0.5 * standing.size:
                continue
        out.append((float(x), rows))
    return out


def walls(table):
    """The wall keys of a run table, in column order: pos, neg (1D) or px, mx, py, my (plan)."""
    return [c[len("impacts_"):] for c in table.columns if c.startswith("impacts_")]


def response_row(rows):
    """Counts and, over the runs that did not collapse, the median and lognormal dispersion
    (std of ln over the positive values, ddof 1) of each metric. The probability of pounding
    is :mod:`femoat.suite.pounding`'s (every record at every level, from its trace)."""
    alive = rows[~rows["collapse"]]
    row = {"n_records": len(rows), "n_collapsed": int(rows["collapse"].sum()),
           "n_not_collapsed": len(alive)}
    for name, (unit, value) in METRICS.items():
        v = value(alive).to_numpy(float) if len(alive) else np.array([])
        v = v[np.isfinite(v)]
        pos = v[v > 0]
        row[f"{name} median [{unit}]"] = float(np.median(v)) if v.size else np.nan
        row[f"{name} dispersion [-]"] = float(np.std(np.log(pos), ddof=1)) if pos.size > 1 \
            else np.nan
    return row


def response_table(t, ida=False, levels=None):
    """A DataFrame of :func:`response_row` per level, with ``im [g]``."""
    return pd.DataFrame([{"im [g]": x, **response_row(rows)}
                         for x, rows in runs_at_levels(t, ida, levels) if len(rows)])

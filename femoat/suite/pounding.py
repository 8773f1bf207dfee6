"""The onset of pounding as a fragility, per wall: P(a record pounds on wall w | IM = x).

Every record counts once at every level (a plan suite's pair once at each of its angles: its
analyses, :data:`femoat.suite.statistics.RECORD_RULE`), its state read from its own trace (its runs, in IM
[g] order), as the collapse fragility reads a record's collapse (:mod:`femoat.suite.fragility`):

- its **onset** on a wall is the lowest IM at which it pounded on that wall (the upper bound
  of the bracket [highest clear IM below it, onset], as P695 takes the collapse intensity);
  runs above its collapse do not enter (the collapse run itself does: it may have pounded).
  How narrow the bracket is depends on the runs: a stripe suite knows the onset to its stripe
  spacing; a hunt-and-fill trace with ``[scaling] pounding_onsets = true`` (default false)
  bisects each wall's bracket (and any wall's) to ``[scaling] resolution`` with runs of its
  own, ordinary rows of the table (:mod:`femoat.suite.huntfill`, step 3), unless its
  ``max_runs`` run out first; without it the onset is known to the spacing of the runs the
  collapse hunt happened to make. ``onset bracket widest [g]`` of the fragility table says
  how wide the widest record's bracket stayed;
- at a level x it **pounded** if onset <= x (once pounding, pounding above: the IDA
  assumption a collapse also makes), else **collapsed** if its collapse IM <= x (it
  collapsed before it touched that wall: its own category, never "did not pound"), else
  **beyond its trace** if x lies above its highest run (unknown), else **not pounded**.

So the fraction pounding at each level is monotone in the level, and the same whether the
runs are stripes or an IDA (hunt-and-fill or a grid): at any level between the two runs that
bracket a record's onset, the IDA and a stripe there can differ only within that bracket.

The lognormal fit of the onset intensity: IDA suites fit the onsets by maximum likelihood
(:func:`femoat.suite.fragility.fit_ida`), a record that never pounded on the wall being
right-censored at its highest clear IM (neither pounding on the wall nor collapsing: the
onset lies above it; a record that collapsed first is censored there too, the onset "had it
not collapsed"); stripe suites fit the counts pounded / (pounded + not pounded) per stripe
(:func:`femoat.suite.fragility.fit_stripes`), collapsed and unknown records left out of the
level. "any" is the first impact on any wall. Walls are the run table's ``impacts_<key>``
columns: 1D pos, neg; plan px, mx, py, my (+x, -x, +y, -y).
"""

import numpy as np
import pandas as pd

from femoat.suite import statistics as st
from femoat.suite.fragility import (FragilityError, fit_ida, fit_stripes, ida_empirical_median,
                                    stripe_empirical_median)
from femoat.suite.huntfill import ANY

TOL = 1e-9  # relative: an IM equal to a level to this is at the level
STATES = ("pounded", "collapsed", "beyond", "not pounded")
"""A record's state at a level (see the module docstring); counted as n_<state>."""


def hits(t, wall):
    """Whether each run of ``t`` had an impact on ``wall`` (or on any wall, ``wall`` = "any")."""
    if wall != ANY:
        return t[f"impacts_{wall}"].fillna(0).to_numpy(float) > 0
    if "pounding" in t:
        return t["pounding"].fillna(False).to_numpy(bool)
    return t[[f"impacts_{w}" for w in st.walls(t)]].fillna(0).to_numpy(float).sum(axis=1) > 0


def traces(t, wall):
    """One row per record of the usable runs ``t`` (:func:`femoat.suite.statistics.usable_runs`:
    columns im [g], collapse, impacts_<wall>): ``onset`` [g] (inf: never pounded on ``wall``
    up to its collapse), ``collapse`` [g] (inf: never collapsed), ``clear`` [g] (its highest IM
    below both with neither; 0: none), ``top`` [g] (its highest run)."""
    keys = st.record_keys(t)
    d = pd.DataFrame({"im": t["im"].to_numpy(float), "hit": hits(t, wall),
                      "col": t["collapse"].to_numpy(bool)})
    d["rec"] = t.groupby(keys, sort=False, dropna=False).ngroup().to_numpy()
    out = []
    for _, r in d.groupby("rec", sort=False):
        im = r["im"].to_numpy()
        collapse = im[r["col"].to_numpy()].min(initial=np.inf)
        upto = im <= collapse * (1 + TOL)
        onset = im[upto & r["hit"].to_numpy()].min(initial=np.inf)
        first = min(onset, collapse)
        clear = im[(im < first * (1 - TOL)) & ~r["hit"].to_numpy() & ~r["col"].to_numpy()]
        out.append((onset, collapse, clear.max(initial=0.0), im.max()))
    return pd.DataFrame(out, columns=["onset", "collapse", "clear", "top"], dtype=float)


def states(tr, level):
    """The state (:data:`STATES`) of each record of :func:`traces` ``tr`` at ``level`` [g]."""
    x = level * (1 + TOL)
    return np.select([tr["onset"] <= x, tr["collapse"] <= x, level > tr["top"] * (1 + TOL)],
                     list(STATES[:3]), STATES[3])


def level_row(tr, level):
    """Counts of each state at ``level`` [g] and the fraction of all records that pounded."""
    s = states(tr, level)
    row = {f"n_{k.replace(' ', '_')}": int((s == k).sum()) for k in STATES}
    row["P(pounding) [-]"] = row["n_pounded"] / len(tr) if len(tr) else np.nan
    return row


def probability_table(t, walls, levels):
    """Long table: per wall ("any" first) and level [g], :func:`level_row` with n_analyses."""
    rows = []
    for w in [ANY, *walls]:
        tr = traces(t, w)
        rows += [{"wall": w, "im [g]": float(x), "n_analyses": len(tr), **level_row(tr, x)}
                 for x in levels]
    columns = ["wall", "im [g]", "n_analyses", *(f"n_{k.replace(' ', '_')}" for k in STATES),
               "P(pounding) [-]"]
    return pd.DataFrame(rows, columns=columns)


def fit(tr, ida, levels):
    """(θ [g], β [-], empirical median onset [g], note) of one wall's traces ``tr``; NaN with
    the reason in the note when the data define no fit."""
    if ida:
        x = tr["onset"][np.isfinite(tr["onset"])].to_numpy(float)
        never = tr[~np.isfinite(tr["onset"])]
        c = never["clear"].to_numpy(float)
        notes = [f"{int((c <= 0).sum())} record(s) without a clear run left out"] \
            if (c <= 0).any() else []
        c = c[c > 0]
        med = ida_empirical_median(x, c)
        try:
            f = fit_ida(x, c) if x.size else None
        except FragilityError as e:
            return np.nan, np.nan, med, "; ".join(notes + [f"no fit: {e}"])
        if f is None:
            return np.nan, np.nan, med, "; ".join(notes + ["no fit: no record pounded"])
        return f.theta, f.beta, med, "; ".join(notes + ([f.note] if f.note else []))
    im = np.asarray(sorted(levels), float)
    n = np.array([level_row(tr, v) for v in im])
    pounded = np.array([r["n_pounded"] for r in n], float)
    known = pounded + np.array([r["n_not_pounded"] for r in n], float)
    keep = known > 0
    med = stripe_empirical_median(im[keep], known[keep], pounded[keep]) if keep.any() else np.nan
    try:
        f = fit_stripes(im[keep], known[keep], pounded[keep])
    except FragilityError as e:
        return np.nan, np.nan, med, f"no fit: {e}"
    return f.theta, f.beta, med, f.note


def fragility_table(t, walls, ida, levels, smt=None):
    """Per wall ("any" first): records, how many pounded / collapsed first / never, the
    empirical median onset [g], the fitted θ [g] and β [-], the widest onset bracket [g] (onset
    − clear over the records that pounded: how well the onsets are known; NaN: none pounded),
    and at S_MT [g] (when given) the fraction pounding read from the traces and the fitted
    probability."""
    rows = []
    for w in [ANY, *walls]:
        tr = traces(t, w)
        theta, beta, med, note = fit(tr, ida, levels)
        row = {"wall": w, "n_analyses": len(tr),
               "n_pounded_ever": int(np.isfinite(tr["onset"]).sum()),
               "n_collapsed_first": int((~np.isfinite(tr["onset"])
                                         & np.isfinite(tr["collapse"])).sum()),
               "onset median empirical [g]": med, "theta fitted [g]": theta,
               "beta fitted [-]": beta, "onset bracket widest [g]": _widest(tr)}
        if smt is not None:
            at = level_row(tr, smt)
            row.update({"S_MT [g]": smt, "P(pounding) at S_MT [-]": at["P(pounding) [-]"],
                        "P(collapsed first) at S_MT [-]": at["n_collapsed"] / max(len(tr), 1),
                        "P(pounding) at S_MT fitted [-]": _lognormal(smt, theta, beta)})
        row["note"] = note
        rows.append(row)
    return pd.DataFrame(rows)


def _widest(tr):
    """The widest onset bracket (onset − clear) [g] of the records that pounded; NaN: none."""
    pounded = np.isfinite(tr["onset"])
    return float((tr["onset"] - tr["clear"])[pounded].max()) if pounded.any() else np.nan


def _lognormal(x, theta, beta):
    from scipy import stats

    if not (np.isfinite(theta) and np.isfinite(beta) and beta > 0):
        return np.nan
    return float(stats.norm.cdf(np.log(x / theta) / beta))

"""The collapse_summary.csv row of one variation: counts, empirical Ŝ_CT, the fitted
fragility and the FEMA P695 margin, with notes that say why a number is missing or bounded.

When fewer than half of the records collapse, Ŝ_CT is not observed but bounded below (IDA: the
median of the collapse and censoring intensities, since a censored record's collapse intensity
exceeds its censoring IM; stripes: the highest stripe). The CMR and ACMR are then lower bounds,
P(collapse|MCE) from β_TOT an upper bound: a passing bound passes, a failing one is inconclusive.
"""

import numpy as np

from femoat.suite import statistics as st
from femoat.suite.fragility import (FragilityError, fit_ida, fit_stripes, ida_empirical_median,
                                    stripe_empirical_median)
from femoat.suite.p695 import assess


def _median(use, ida):
    """Empirical median collapse intensity Ŝ_CT [g] of the usable runs."""
    return ida_empirical_median(*st.ida_collapse_data(use)) if ida else \
        stripe_empirical_median(*st.stripe_counts(use))


def collapse_row(rows, use, policy, ida, basis):
    """(collapse_summary row, fragility-figure data) for one variation: ``rows`` all its runs,
    ``use`` the usable ones (:func:`femoat.suite.statistics.usable_runs` under ``policy``),
    ``basis`` the :func:`femoat.suite.p695_inputs.margin_basis` of the suite."""
    smt = basis.smt
    if ida:
        x, c = st.ida_collapse_data(use)
        s_ct, n, n_col, n_cens = ida_empirical_median(x, c), x.size + c.size, x.size, c.size
        bound = np.median(np.concatenate([x, c])) if n else np.nan  # true values >= c
        pts = np.sort(x)
        frac = np.arange(1, x.size + 1) / max(n, 1)
        fit = lambda: fit_ida(x, c)  # noqa: E731
    else:
        pts, nn, z = st.stripe_counts(use)
        s_ct, n = stripe_empirical_median(pts, nn, z), int(nn.sum())
        bound = pts.max() if len(pts) else np.nan  # no stripe reached 50 %
        n_col, n_cens = int(z.sum()), 0
        frac = z / nn
        fit = lambda: fit_stripes(pts, nn, z)  # noqa: E731
    notes, theta, beta = [], np.nan, np.nan
    try:
        f = fit()
        theta, beta = f.theta, f.beta
        notes += [f.note] if f.note else []
    except FragilityError as e:
        notes.append(f"no fit: {e}")
    lower = not np.isfinite(s_ct) and np.isfinite(bound)
    if lower:  # fewer than half collapsed: S_CT (and the margin) bounded below
        s_ct = float(bound)
        notes.append(f"fewer than half collapsed: S_CT >= {s_ct:.3g} g"
                     + (", so CMR and ACMR are lower bounds and P(collapse|MCE) beta_TOT an "
                        "upper bound" if smt is not None else ""))
    n_analyses = int(rows.groupby(st.record_keys(rows), dropna=False).ngroups)
    n_records = int(rows.groupby(st.pair_keys(rows), dropna=False).ngroups)
    if n_analyses > n_records:
        notes.append(f"a record is a pair: {n_records} pairs at {n_analyses // n_records} "
                     f"angles = {n_analyses} analyses (FEMA P695 3D: S_CT over the analyses, "
                     "each pair weighing the same)")
    row = {"method": "ida" if ida else "stripes",
           "n_records": n_records, "n_analyses": n_analyses,
           "n_runs": len(use), "n_collapsed": n_col, "n_censored": n_cens,
           "n_solver_failures": int((rows["status"] == "solver_failure").sum()),
           "n_errors": int((rows["status"] == "error").sum()),
           "solver_failure_policy": policy,
           "S_CT empirical [g]": s_ct, "S_CT is a lower bound": lower,
           "theta fitted [g]": theta, "beta fitted [-]": beta,
           "S_CT if solver failures collapsed [g]": _median(st.usable_runs(rows, "collapse"), ida),
           "S_MT [g]": np.nan if smt is None else smt}
    a = {}
    notes += [basis.note] if basis.note else []
    if smt is not None:
        try:
            a = assess(s_ct, smt, theta=None if np.isnan(theta) else theta,
                       beta=None if np.isnan(beta) else beta, **basis.args).as_dict()
        except ValueError as e:
            notes.append(f"no P695 check: {e}")
    names = {"cmr": "CMR [-]", "ssf": "SSF [-]", "acmr": "ACMR [-]", "mu_t": "mu_T [-]",
             "beta_total": "beta_TOT [-]", "acmr10": "ACMR10% [-]", "acmr20": "ACMR20% [-]",
             "p_collapse_mce": "P(collapse|MCE) fitted [-]",
             "p_collapse_mce_total": "P(collapse|MCE) beta_TOT [-]",
             "passes_acmr20": "pass ACMR>=ACMR20%", "passes_acmr10": "pass ACMR>=ACMR10%"}
    row.update({v: a.get(k, np.nan) for k, v in names.items()})
    for k in ("passes_acmr20", "passes_acmr10"):  # a bound that fails decides nothing
        if lower and a and not a[k]:
            row[names[k]] = "inconclusive"
    row["verdict"] = verdict(row)
    row["note"] = "; ".join(notes)
    curve = dict(x=pts, fraction=frac, theta=theta, beta=beta, n_collapsed=n_col, n=n, ida=ida)
    return row, curve


def verdict(row):
    """One word or phrase per variation, FEMA P695 Section 7.5 with the variation judged as a
    performance group of one: "pass" (ACMR >= ACMR10 %), "fail" (ACMR < ACMR20 %), "fail:
    >= ACMR20% only" (an archetype would pass, a group of one fails), "inconclusive" (a lower
    bound that fails) or "no margin"."""
    p10, p20 = row["pass ACMR>=ACMR10%"], row["pass ACMR>=ACMR20%"]
    if "inconclusive" in (p10, p20):
        return "pass" if p10 is True else "inconclusive"
    if not isinstance(p10, (bool, np.bool_)):
        return "no margin"
    if p10:
        return "pass"
    return "fail: >= ACMR20% only" if p20 else "fail"

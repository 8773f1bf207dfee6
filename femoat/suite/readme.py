"""README.txt of a suite report: what each file is and the choices behind the numbers."""

FILES = {
    "collapse_summary.csv": "one row per variation: counts (records, runs, collapses, censored "
    "records, solver failures, errors), the empirical median collapse intensity S_CT (when "
    "fewer than half collapsed, a lower bound, flagged; the CMR and ACMR then are lower bounds "
    "and a failed check reads 'inconclusive'), the fitted lognormal theta and beta, S_CT had every solver failure been a collapse (the sensitivity "
    "to the policy), S_MT, CMR = S_CT/S_MT, SSF, ACMR = SSF*CMR, mu_T, beta_TOT, the "
    "acceptable ACMR10% and ACMR20%, P(collapse|MCE) from the fitted fragility and from "
    "beta_TOT, pass/fail and notes. n_collapsed counts records (IDA) or runs (stripes).",
    "response_by_variation.csv": "per variation and intensity: records (IDA: a record that "
    "collapsed below the intensity counts as collapsed there; stripes: runs), collapses and, "
    "over the runs that did not collapse, the median and lognormal dispersion (std of ln over the "
    "positive values) across records of the peak impact force (max of both walls), peak wall "
    "displacement, peak base (isolator) displacement, peak drift ratio and peak floor "
    "acceleration; the probability of pounding counts every run, collapsed or not.",
    "pounding_probability.csv": "per variation and intensity: the fraction of runs (records) "
    "with any impact.",
    "fragility.png": "collapse fragility per variation: empirical points (IDA: fraction of "
    "records collapsed at or below each collapse intensity; stripes: fraction per stripe) and "
    "the fitted lognormal, with counts in the legend; dashed line at S_MT.",
    "pounding_probability.png": "probability of pounding against intensity per variation.",
    "ida_peak_drift_ratio.png": "IDA curves per record, a panel per variation: intensity against "
    "peak drift ratio; 'x' marks collapse (drawn at the right edge).",
    "ida_peak_base_displacement.png": "the same against the peak isolator (base) displacement.",
    "responses_near_mce.png": "median responses side by side per variation at the intensity "
    "nearest S_MT, bars median*exp(+-beta).",
}

POLICY = {"separate": "solver failures are left out of the fragility and the statistics and "
                      "reported apart (n_solver_failures)",
          "collapse": "solver failures count as collapses",
          "exclude": "solver failures are dropped (their count is still in n_solver_failures)"}


def readme_text(meta, p695_args, mu_source, ida, levels, written):
    """The README text; ``written`` are the file names in the report folder."""
    period, ts = p695_args["period"], meta.get("time_scale", 1.0)
    lines = ["femoat suite report", "",
             f"Record set: {meta.get('record_set')}; scaling: {meta.get('scaling')}"
             + ("; hunt-and-fill IDA" if meta.get("hunt_fill") else ""),
             f"Period used for Sa(T), S_MT and SSF: T = {period:.4g} s, the prototype period"
             + (f" (records time-scaled by {ts:g}: intensities refer to the prototype)"
                if ts not in (None, 1, 1.0) else ""),
             f"SDC {p695_args['sdc']}: S_MT = {float(meta['smt']):.4g} g; mu_T = "
             f"{p695_args['mu_t']:g} (period-based ductility, Eq. 6-6; {mu_source}); "
             f"quality ratings (DR, TD, MDL) = {', '.join(p695_args['ratings'])}",
             f"Solver-failure policy '{meta.get('solver_failure', 'separate')}': "
             + POLICY.get(meta.get("solver_failure", "separate"), "?") + "; runs with status "
             "'error' are always left out and counted in n_errors.", "",
             "Collapse intensity: " + (
                 "IDA, per record the lowest IM at which it collapsed (for hunt-and-fill the "
                 "upper bound of the final bracket); records that never collapse are "
                 "right-censored at their largest IM (survival term in the likelihood)."
                 if ida else "multiple stripes, binomial likelihood (Baker 2015)."),
             "CMR uses the empirical median S_CT (FEMA P695 Section 6.4), not the fitted theta."
             + (" The suite's intensity is PGA: S_CT and S_MT are PGAs here, whereas FEMA P695 "
                "defines the CMR on Sa(T)." if meta.get("im_kind") == "pga" else ""),
             "A record is one horizontal component (both components of a pair count, as in "
             "FEMA P695).",
             "Intensities of the response tables: " + (
                 "every stripe / IM level." if levels is None else
                 "each record's run nearest (within +-25 %) to " +
                 ", ".join(f"{x:.3g}" for x in levels) + " g."), "", "Files:"]
    lines += [f"  {name}: {FILES.get(name, '')}" for name in written if name in FILES]
    return "\n".join(lines) + "\n"

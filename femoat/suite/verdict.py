"""The suite's verdict on the terminal: what is stored (runs, collapses, failures), the FEMA P695
inputs with their sources, and per variation S_CT, CMR, SSF, ACMR against ACMR10 % / 20 % with
the verdict, as an aligned table with units. Always for the whole suite folder (its stored
rows), never for one invocation, and with the numbers of collapse_summary.csv as written (4
significant digits)."""

import math

COLUMNS = [  # (heading, collapse_summary.csv column)
    ("variation", "variation"), ("records", "n_records"), ("analyses", "n_analyses"),
    ("runs", "n_runs"),
    ("collapsed", "n_collapsed"), ("failed", None), ("S_CT [g]", "S_CT empirical [g]"),
    ("CMR [-]", "CMR [-]"), ("SSF [-]", "SSF [-]"), ("ACMR [-]", "ACMR [-]"),
    ("ACMR10% [-]", "ACMR10% [-]"), ("ACMR20% [-]", "ACMR20% [-]"), ("verdict", "verdict"),
]


def counts(table):
    """{runs, collapses, solver_failures, errors} of a run table."""
    status = table["status"]
    return dict(runs=int(len(table)), collapses=int((status == "collapsed").sum()),
                solver_failures=int((status == "solver_failure").sum()),
                errors=int((status == "error").sum()))


def cell(value):
    """A number as in the CSV (4 significant digits), a count as an integer, NaN as '-'."""
    if isinstance(value, bool) or value is None:
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            return "-"
        return str(int(value)) if value.is_integer() and abs(value) < 1e15 else f"{value:.4g}"
    return str(value)


def rows(summary):
    """The table's cells: a list of string lists, the headings first."""
    out = [[h for h, _ in COLUMNS]]
    for _, r in summary.iterrows():
        line = []
        for heading, col in COLUMNS:
            if col not in (None, *r.index):  # a summary written before the column existed
                line.append("-")
            elif col is None:  # failed: solver failures and errors
                line.append(str(int(r["n_solver_failures"]) + int(r["n_errors"])))
            elif col == "S_CT empirical [g]" and str(r.get("S_CT is a lower bound")) == "True":
                line.append(">=" + cell(r[col]))
            else:
                line.append(cell(r[col]))
        out.append(line)
    return out


def table_text(summary):
    """The aligned table: text columns left, numbers right."""
    cells = rows(summary)
    widths = [max(len(r[i]) for r in cells) for i in range(len(COLUMNS))]
    left = {0, len(COLUMNS) - 1}
    return "\n".join("  ".join(c.ljust(w) if i in left else c.rjust(w)
                               for i, (c, w) in enumerate(zip(r, widths))).rstrip()
                     for r in cells)


WALL_NAMES = {"any": "any wall", "pos": "pos", "neg": "neg", "px": "+x", "mx": "-x",
              "py": "+y", "my": "-y"}


def pounding_text(onsets, smt):
    """Per variation, the probability of pounding at S_MT per wall (any wall first) and the
    median onset theta [g] (beta [-]) of pounding_fragility.csv ``onsets``; without S_MT
    only the onsets."""
    if onsets is None or not len(onsets):
        return ""
    head = (f"Probability of pounding at S_MT = {smt:.4g} g, per wall (fraction of records "
            "that pounded; collapsed before touching the wall counted apart), and the median "
            "onset theta (beta):" if smt is not None else
            "Median onset of pounding theta (beta), per wall:")
    lines = [head]
    for label, rows in onsets.groupby("variation", sort=False):
        parts = []
        for _, r in rows.iterrows():
            fit = (f"theta {cell(float(r['theta fitted [g]']))} g "
                   f"(beta {cell(float(r['beta fitted [-]']))})")
            at = ""
            if smt is not None:
                at = f"P {cell(float(r['P(pounding) at S_MT [-]']))}"
                col = float(r["P(collapsed first) at S_MT [-]"])
                at += f" + collapsed {cell(col)}, " if col > 0 else ", "
            parts.append(f"{WALL_NAMES.get(r['wall'], r['wall'])}: {at}{fit}")
        lines.append(f"  {label}: " + "; ".join(parts))
    return "\n".join(lines) + "\n"


def verdict_text(table, summary, inputs, basis, where, onsets=None):
    """The whole verdict: counts of ``table`` (the stored runs), the P695 inputs and S_MT of
    the :class:`femoat.suite.p695_inputs.MarginBasis` ``basis`` (or why there is no margin),
    the table of ``summary`` (collapse_summary.csv) and where the report is."""
    c = counts(table)
    lines = [f"femoat suite: {where}: {c['runs']} runs stored, {c['collapses']} collapsed, "
             f"{c['solver_failures']} solver failures, {c['errors']} errors"]
    if basis.smt is None:
        lines.append(f"no FEMA P695 margin: {basis.note}")
        legend = ("verdict: 'no margin': no S_MT, so no CMR, ACMR or pass/fail; '>=' marks a "
                  "lower bound of S_CT (fewer than half of the records collapsed)")
    else:
        lines += ["FEMA P695 inputs:"] + [f"  {x}" for x in inputs.statements()]
        lines.append(f"  S_MT = {basis.smt:.4g} g" + (f"; {basis.note}" if basis.note else ""))
        legend = ("verdict: 'pass' ACMR >= ACMR10% (a variation judged as a performance group "
                  "of one, FEMA P695 Section 7.5); 'fail: >= ACMR20% only' passes as a single "
                  "archetype; '>=' marks a lower bound (fewer than half of the records "
                  "collapsed)")
    legend += ("; records: pairs (plan) or components (1D); analyses: a pair at each angle "
               "(FEMA P695 3D), S_CT over the analyses")
    lines += ["", table_text(summary), "", legend]
    text = "\n".join(lines) + "\n"
    pound = pounding_text(onsets, basis.smt)
    return text + ("\n" + pound if pound else "")

"""The bidirectional study (issue 18, item 6): does running each component of a record alone
(1D) tell how hard the building pounds its moat when the pair shakes it together in plan (2D)?

The paper building (:func:`femoat.paper.paper_model`'s: bilinear stories, friction pendulum
R = 30 in, mu = 0.06, 4 in gaps) under the 22 FEMA P695 far-field pairs at the MCE, for the five
contact laws x two walls (concrete, steel), as two suites (:mod:`femoat.suite`):

* **1D**: every component (a and b) alone, along the axis of two moat walls;
* **2D**: the building in plan in a square moat of four such walls, under each pair (a along
  x, b along y) turned by each angle of :data:`ANGLES`.

Both at the MCE: FEMA P695 anchoring at T = 3.5 s (the prototype period, as the headline
suite), one stripe at 1.0 x S_MT. The anchor is the median over the set's 2N normalized
components in both suites, so each record is scaled by the same factor in 1D and in 2D
(:mod:`femoat.suite.scaling`). Both run Newmark (a plan run cannot use the fifth-order open
phase, docs/plan.md §10; the 1D runs use the same method, so that a difference is the second
component's, not the integrator's: with b zeroed a plan run is the 1D run of a, bit for bit).

**Angles.** The building is the same in x and y, its pendulum isotropic, the moat square with
four identical walls: the problem is unchanged by a quarter turn. A pair turned by theta + 90 deg
is the pair at theta with the whole problem turned by 90 deg, so it gives the same plan
displacement, the same pounding and the same forces (on the next wall round); theta + 180 deg is
the mirror u -> -u of theta. The distinct orientations are therefore [0, 90) deg, and the study
samples them every 15 deg (six angles: as many runs as 0, 30, ..., 150 deg, which would repeat
0, 30, 60 deg at 90, 120, 150 deg).

**The table** (:func:`study_table`), per law x wall and per case, over the records:

* **1D**: per record, the envelope of its two components run alone: the larger peak base
  displacement and peak impact force, pounding if either pounds;
* **2D 0 deg**: per record, its pair at 0 deg (a along x, b along y);
* **2D worst**: per record, the envelope of its pair over the angles: the largest peak plan
  displacement |u| and peak impact force (each at its own angle), pounding if any angle pounds;

then the median over the records of the peak base displacement [in] (plan |u| in 2D), the
probability of pounding [-] (the fraction of records that pounded), the median peak impact force
[kip] over the records that pounded (the force of an impact, given one; a record that did not
pound has no impact force: counting it as 0 would make the median 0 whenever fewer than half
pound), and the records that collapsed (one of the runs behind the record's case reached a
story drift ratio of 10 % or the isolator's 7 in capacity, in plan |u|, or a runaway bound),
out of the records, as the other columns (the run counts stay in table.csv). The criteria do not
stop a run (``[collapse] stop = false``): every peak is over the whole record, in 1D as in 2D,
and a run ends early only at a runaway bound (a story drift of one story height, the isolator at
ten times its capacity). A record with a run that did not finish (a solver failure or an error,
counted under ``failed``) is left out of that case's statistics.
"""

import functools

import numpy as np

LAWS = ("E", "V", "J", "H", "M")
WALLS = ("concrete", "steel")
ANGLES = (0, 15, 30, 45, 60, 75)  # [deg] the distinct orientations, [0, 90) (module docstring)
CASES = {"1d": "1D", "2d_0": "2D 0 deg", "2d_worst": "2D worst"}
"""The table's cases: key (CSV) and label (markdown)."""

QUICK = {"ids": [1, 6, 12], "laws": ("E", "H")}
"""The quick variant: three pairs (whole records, scaled as in the full study: its rows are the
full table's rows of these pairs), two laws."""

_BUILDING = {  # the paper building, stated (femoat.scenario.defaults()'s, Building()'s; story
    # heights 39 in, Building's default)
    "base_weight": 10.0,                       # [kip]
    "floor_weights": [8.0, 8.0, 7.0],          # [kip]
    "story_model": "bilinear",
    "story": {"k0": 42.799, "Fy": 11.556, "b": 0.03},  # [kip/in], [kip], [-]
    "story_damping_ratio": 0.02,               # [-]
    "story_damping_period": 0.30,              # [s]
    "isolator": {"R": 30.0, "mu": 0.06, "u_y": 0.01},  # [in], [-], [in]
    "isolator_capacity": 7.0,                  # [in] (in plan: |u|)
}
_WALL = {"damping": "published", "gap": 4.0}  # [in] clearance to each wall
_COMMON = {
    "solver": {"method": "ark5"},
    # the criteria are marked, the runs go on to the record's end (stop = false): every peak is
    # over the whole record in both suites, however early a criterion was reached
    "collapse": {"drift_ratio": 0.10, "isolator": True, "stop": False},
    "scaling": {"method": "p695", "period": 3.5, "sdc": "Dmax", "multipliers": [1.0]},
    "run": {"solver_failure": "separate"},
}


@functools.lru_cache(maxsize=1)
def full_anchor():
    """SF [-] of the full study's FEMA P695 anchoring (the median Sa(T) of the 44 normalized
    far-field components brought to S_MT): the quick variant scales its pairs by it, so its
    rows preview the full table's for the same records."""
    from femoat.suite.definition import suite_from_dict

    d = definitions()["1d"]
    d = {**d, "variations": {"walls.law": [LAWS[0]], "walls.preset": [WALLS[0]]}}
    return suite_from_dict(d).scaling.anchor


def definitions(quick=False):
    """``{"1d": dict, "2d": dict}``: the two suite definitions (parsed-TOML dicts for
    :func:`femoat.suite.suite_from_dict`); ``quick``: the small variant :data:`QUICK`, its
    records scaled by the full set's SF (:func:`full_anchor`), not re-anchored on its own."""
    laws = QUICK["laws"] if quick else LAWS
    records = {"set": "farfield", "time_scale": 0.5, "extra_time": 2.0}
    common = _COMMON
    if quick:
        records.update(ids=list(QUICK["ids"]))
        common = {**_COMMON, "scaling": {**_COMMON["scaling"], "anchor": full_anchor()}}
    one_d = {"building": dict(_BUILDING), "walls": dict(_WALL, sides="both"),
             "records": dict(records, components=["a", "b"]),
             "variations": {"walls.law": list(laws), "walls.preset": list(WALLS)}}
    two_d = {"building": dict(_BUILDING, plan=True),
             "moat": dict(_WALL, friction=0.0, sides=["+x", "-x", "+y", "-y"]),
             "records": dict(records, pairs=True, angles=list(ANGLES)),
             "variations": {"moat.law": list(laws), "moat.preset": list(WALLS)}}
    return {k: {**common, **d} for k, d in (("1d", one_d), ("2d", two_d))}


def run_study(out, quick=False, workers=None, serial=False, overwrite=False, stream=None):
    """Run (or resume) both suites into ``out/1d`` and ``out/2d``; write ``out/table.csv`` and
    ``out/table.markdown``; return ``(table, markdown)``."""
    from femoat.studies.suites import run_suites, write_table

    tables = run_suites("bidirectional", definitions(quick), out, workers=workers, serial=serial,
                        overwrite=overwrite, stream=stream)
    table = study_table(tables["1d"], tables["2d"])
    markdown = to_markdown(table)
    write_table(out, table, markdown)
    return table, markdown


# ---- the table ---------------------------------------------------------------------------------
FAILED = ("solver_failure", "error")


def per_record(one_d, two_d):
    """One row per (law, wall, case, record): the record's peak base displacement [in], peak
    impact force [kip] and pounding in that case (the module docstring's envelopes), with its
    runs, collapsed and failed runs. ``one_d``, ``two_d``: the suites' run tables
    (:func:`femoat.suite.load_table`)."""
    import pandas as pd

    a = _runs(one_d, "walls")
    b = _runs(two_d, "moat")
    parts = [_envelope(a, "1d"), _envelope(b[b["angle"] == 0.0], "2d_0"),
             _envelope(b, "2d_worst")]
    return pd.concat(parts, ignore_index=True)


def _runs(table, prefix):
    """The columns the study reads, named alike for both suites: law, wall, record (the FEMA
    P695 ID), angle, peak base displacement [in], peak impact force [kip] (the largest over
    the walls), pounding, collapsed, failed."""
    import pandas as pd

    forces = table[[c for c in table.columns if c.startswith("peak_impact_force_")]]
    failed = table["status"].isin(FAILED).to_numpy()
    return pd.DataFrame({
        "law": table[f"{prefix}.law"].astype(str), "wall": table[f"{prefix}.preset"].astype(str),
        "record": table["record_id"].astype(int),
        "angle": table.get("angle", 0.0),
        "displacement": table["peak_base_displacement"].astype(float),
        "force": forces.astype(float).max(axis=1, skipna=True),
        "pounding": table["pounding"].fillna(False).astype(bool),
        "collapsed": table["collapsed"].fillna(False).astype(bool), "failed": failed})


def _envelope(runs, case):
    g = runs.groupby(["law", "wall", "record"], sort=True)
    out = g.agg(displacement=("displacement", "max"), force=("force", "max"),
                pounding=("pounding", "any"), runs=("failed", "size"),
                collapsed=("collapsed", "sum"), record_collapsed=("collapsed", "any"),
                failed=("failed", "sum")).reset_index()
    out.insert(2, "case", case)
    return out


def study_table(one_d, two_d):
    """The study's table: one row per (law, wall, case) in LAWS x WALLS x CASES order, with
    the medians, the pounding probability and the run counts of the module docstring."""
    import pandas as pd

    recs = per_record(one_d, two_d)
    rows = []
    for (law, wall, case), g in recs.groupby(["law", "wall", "case"], sort=False):
        ok = g[g["failed"] == 0]
        pounded = ok[ok["pounding"]]
        rows.append({"law": law, "wall": wall, "case": case, "records": len(ok),
                     "median peak base displacement [in]": _median(ok["displacement"]),
                     "pounding probability [-]": float(ok["pounding"].mean()) if len(ok)
                     else np.nan,
                     "records that pounded": len(pounded),
                     "median peak impact force, pounded [kip]": _median(pounded["force"]),
                     "records that collapsed": int(ok["record_collapsed"].sum()),
                     "runs": int(g["runs"].sum()), "collapsed runs": int(g["collapsed"].sum()),
                     "failed runs": int(g["failed"].sum())})
    table = pd.DataFrame(rows)
    order = {k: i for i, k in enumerate((*LAWS, *WALLS, *CASES))}
    return table.sort_values(["wall", "law", "case"], key=lambda s: s.map(order),
                             ignore_index=True)


def _median(values):
    return float(np.median(values)) if len(values) else np.nan


def to_markdown(table):
    """The table as markdown: one row per law x wall, each quantity for 1D, 2D 0 deg and 2D
    worst side by side; the run counts under it."""
    cases = list(CASES)
    head = (["wall", "law"]
            + [f"u {CASES[c]} [in]" for c in cases]
            + [f"P {CASES[c]} [-]" for c in cases]
            + [f"F {CASES[c]} [kip]" for c in cases]
            + [f"collapsed {CASES[c]}" for c in cases])
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for (wall, law), g in table.groupby(["wall", "law"], sort=False):
        by = g.set_index("case")
        cells = ([wall, law]
                 + [_fmt(by.at[c, "median peak base displacement [in]"], 2) for c in cases]
                 + [_fmt(by.at[c, "pounding probability [-]"], 2) for c in cases]
                 + [_fmt(by.at[c, "median peak impact force, pounded [kip]"], 0) for c in cases]
                 + [f"{by.at[c, 'records that collapsed']}/{by.at[c, 'records']}"
                    for c in cases])
        lines.append("| " + " | ".join(cells) + " |")
    n = table.groupby("case")["records"].agg(["min", "max"])
    failed = int(table["failed runs"].sum())
    lines += ["", "u: median over the records of the peak base displacement (2D: in plan, |u|); "
              "P: probability of pounding (the fraction of records that pounded); F: median "
              "peak impact force over the records that pounded (largest over the walls); "
              "collapsed: records that collapsed / records, enveloped as u, P and F (a record "
              "collapsed when any run behind its case reached a collapse criterion or a "
              "runaway bound: 1D either component, 2D worst any angle; the run counts are in "
              "table.csv); "
              "1D: the envelope of a record's two components run alone; 2D worst: the "
              "envelope of its pair over the angles "
              + ", ".join(f"{a}" for a in ANGLES) + " deg. Records per case: "
              + ", ".join(f"{CASES[c]} {_span(n.loc[c])}" for c in cases)
              + f"; failed runs (left out): {failed}."]
    return "\n".join(lines) + "\n"


def _span(row):
    return f"{row['min']}" if row["min"] == row["max"] else f"{row['min']}-{row['max']}"


def _fmt(x, digits):
    return "-" if np.isnan(x) else f"{x:.{digits}f}"

"""The isolators study (issue 28, item 6): the paper building on a single friction pendulum, a
triple friction pendulum and a lead-rubber bearing designed for the same MCE displacement, in the
paper's moat, under the FEMA P695 far-field pairs at the MCE, in 1D and in plan.

**The isolators** (:func:`isolators`), each carrying the building's weight W = 33 kip:

* ``fp``: the paper's single friction pendulum (R = 30 in, μ = 0.06, u_y = 0.01 in);
* ``tfp``: a triple friction pendulum of a usual geometry at the model's quarter scale (the
  kind's full-scale defaults L1 = 12 in, L2 = L3 = 88 in, d1 = 2 in, d2 = d3 = 16 in times 1/4;
  μ1 = 0.012 < μ2 = 0.052 < μ3 = 0.12; u_y = 0.01 in), its outer radii L2 = L3 tuned;
* ``lrb``: a lead-rubber bearing with the pendulum's strength Q_d = μ·W = 1.98 kip and
  K_u = 10·K_d (η = 1, β = γ = 0.5), its post-yield stiffness K_d tuned;

the tuned parameter chosen so that each bearing's ASCE 7-16 MCE displacement D_M (Eq. 17.5-1,
the bearing's effective period and damping at D_M from its own loop:
:mod:`femoat.structure.isolation_design`) equals the pendulum's. The spectrum is SDC Dmax's
S_M1 = 0.9 g·s at the model's time scale 0.5 (0.45 g·s at the model's periods), the scaling's
own (FEMA P695, anchored at the prototype period T = 3.5 s, one stripe at S_MT, as the
bidirectional study and the headline suite).

**The suites** (:func:`definitions`): every isolator (a variation over the whole
``[building.isolator]`` table), in the paper's concrete moat (law H, 4 in gaps, published
damping), at the MCE: 1D, every component of the 22 pairs alone along the axis of two walls
(each dimension's default method: the fifth-order step); 2D, the building in plan in a square
moat of four such walls under each pair turned by 0° and 45° (each isolator's plan default,
:func:`femoat.run.plan_method`: ark5, each kind's rate form).
The collapse criteria (a story drift ratio of 10 %, the isolator beyond its capacity: the
building's 7 in, or the bearing's own where smaller, in plan |u|) mark runs without stopping
them.

**The table** (:func:`study_table`), per isolator and case (1D: a record's two components
enveloped; 2D: its pair's angles enveloped), over the records: the median peak base
displacement [in] (2D: in plan), the probability of pounding, the median peak impact force over
the records that pounded [kip], the median peak story drift ratio [-] and peak floor
acceleration [g] (the largest over the stories, and in 2D over x and y), and the records that
collapsed. :func:`figure` draws them.
"""

import functools
from pathlib import Path

import numpy as np

WEIGHT = 33.0
"""[kip] the paper building's weight on the isolators (base 10 + floors 8, 8, 7)."""

S_M1 = 0.45
"""[g·s] SDC Dmax's S_M1 = 0.9 g·s at the model's time scale 0.5 (module docstring)."""

ISOLATORS = ("fp", "tfp", "lrb")
ANGLES = (0, 45)  # [deg]
CASES = {"1d": "1D", "2d": "2D"}
QUICK = {"ids": [1, 6, 12]}
"""The quick variant: three pairs, whole records, scaled as in the full study."""

_BUILDING = {  # the paper building (femoat.studies.bidirectional's)
    "base_weight": 10.0, "floor_weights": [8.0, 8.0, 7.0], "story_model": "bilinear",
    "story": {"k0": 42.799, "Fy": 11.556, "b": 0.03}, "story_damping_ratio": 0.02,
    "story_damping_period": 0.30, "isolator_capacity": 7.0,
}
_WALL = {"preset": "concrete", "law": "H", "damping": "published", "gap": 4.0}
_COMMON = {
    "collapse": {"drift_ratio": 0.10, "isolator": True, "stop": False},
    "scaling": {"method": "p695", "period": 3.5, "sdc": "Dmax", "multipliers": [1.0]},
    "run": {"solver_failure": "separate"},
}


@functools.lru_cache(maxsize=1)
def isolators():
    """{key: bearing}: the three one-axis bearings of the module docstring, the TFP's and the
    LRB's tuned parameter solved so that every D_M is the pendulum's; and the design record
    {key: (D_M [in], T_M [s], β_M [-])}."""
    from femoat.bearings.friction_pendulum import FrictionPendulum
    from femoat.bearings.lead_rubber import LeadRubberBearing
    from femoat.bearings.triple_friction_pendulum import TripleFrictionPendulum
    from femoat.structure.isolation_design import match_displacement, mce_displacement

    fp = FrictionPendulum(W=WEIGHT, R=30.0, mu=0.06, u_y=0.01)
    target = mce_displacement(fp, WEIGHT, S_M1)[0]

    def tfp(radius):
        return TripleFrictionPendulum(W=WEIGHT, L1=3.0, L2=radius, L3=radius, d1=0.5, d2=4.0,
                                      d3=4.0, mu1=0.012, mu2=0.052, mu3=0.12, u_y=0.01)

    def lrb(kd):
        return LeadRubberBearing(Q_d=0.06 * WEIGHT, K_d=kd, K_u=10.0 * kd)

    bearings = {"fp": fp,
                "tfp": match_displacement(tfp, target, WEIGHT, S_M1, (8.0, 200.0))[0],
                "lrb": match_displacement(lrb, target, WEIGHT, S_M1, (0.1, 5.0))[0]}
    design = {k: mce_displacement(b, WEIGHT, S_M1) for k, b in bearings.items()}
    return bearings, design


def isolator_table(bearing):
    """The ``[building.isolator]`` table of ``bearing`` (its type and every parameter)."""
    import dataclasses

    from femoat.bearings import registry

    key = registry.module(registry.kind_of(bearing)).KEY
    values = {f.name: getattr(bearing, f.name) for f in dataclasses.fields(bearing)}
    # left out: what a scenario cannot write (None: mu_fast; inf: no capacity) takes the default
    return {"type": key, **{k: float(v) for k, v in values.items()
                            if v is not None and np.isfinite(v)}}


def definitions(quick=False):
    """``{"1d": dict, "2d": dict}``: the two suite definitions (parsed-TOML dicts for
    :func:`femoat.suite.suite_from_dict`); ``quick``: three pairs (:data:`QUICK`), scaled by
    the full set's SF (:func:`femoat.studies.bidirectional.full_anchor`: the same anchoring)."""
    tables = [isolator_table(b) for b in isolators()[0].values()]
    records = {"set": "farfield", "time_scale": 0.5, "extra_time": 2.0}
    common = _COMMON
    if quick:
        from femoat.studies.bidirectional import full_anchor

        records.update(ids=list(QUICK["ids"]))
        common = {**_COMMON, "scaling": {**_COMMON["scaling"], "anchor": full_anchor()}}
    one_d = {"building": dict(_BUILDING), "walls": dict(_WALL, sides="both"),
             "records": dict(records, components=["a", "b"]),
             "variations": {"building.isolator": tables}}
    two_d = {"building": dict(_BUILDING, plan=True),
             "moat": dict(_WALL, friction=0.0, sides=["+x", "-x", "+y", "-y"]),
             "records": dict(records, pairs=True, angles=list(ANGLES)),
             "variations": {"building.isolator": tables}}
    return {k: {**common, **d} for k, d in (("1d", one_d), ("2d", two_d))}


def run_study(out, quick=False, workers=None, serial=False, overwrite=False, stream=None):
    """Run (or resume) both suites into ``out/1d`` and ``out/2d``; write ``out/table.csv``,
    ``out/table.markdown`` and ``out/isolators.png``; return ``(table, markdown)``."""
    from femoat.studies.suites import run_suites, write_table

    tables = run_suites("isolators", definitions(quick), out, workers=workers, serial=serial,
                        overwrite=overwrite, stream=stream)
    table = study_table(tables["1d"], tables["2d"])
    markdown = to_markdown(table)
    write_table(out, table, markdown)
    figure(table, Path(out) / "isolators.png")
    return table, markdown


# ---- the table ---------------------------------------------------------------------------------
FAILED = ("solver_failure", "error")


def _kind(value):
    """The isolator key of a run's ``building.isolator`` cell (the table as its variation)."""
    if isinstance(value, dict):
        return value["type"]
    text = str(value)
    for key in ISOLATORS:
        if f"'type': '{key}'" in text or f'"type": "{key}"' in text:
            return key
    raise ValueError(f"building.isolator = {value!r}: not one of the study's isolators.")


def _largest(table, prefix):
    cols = [c for c in table.columns if c.startswith(prefix) and c[len(prefix):].replace(
        "x_", "").replace("y_", "").isdigit()]
    return table[cols].astype(float).max(axis=1, skipna=True)


def per_record(one_d, two_d):
    """One row per (isolator, case, record): the envelope over the record's runs (1D: its two
    components; 2D: its angles) of the peaks the table reports, with its run counts."""
    import pandas as pd

    parts = []
    for case, table in (("1d", one_d), ("2d", two_d)):
        forces = table[[c for c in table.columns if c.startswith("peak_impact_force_")]]
        runs = pd.DataFrame({
            "isolator": table["building.isolator"].map(_kind),
            "record": table["record_id"].astype(int),
            "displacement": table["peak_base_displacement"].astype(float),
            "force": forces.astype(float).max(axis=1, skipna=True),
            "drift_ratio": table["peak_drift_ratio"].astype(float),
            "acceleration": _largest(table, "peak_floor_acceleration_"),
            "pounding": table["pounding"].fillna(False).astype(bool),
            "collapsed": table["collapsed"].fillna(False).astype(bool),
            "failed": table["status"].isin(FAILED).to_numpy()})
        g = runs.groupby(["isolator", "record"], sort=True)
        env = g.agg(displacement=("displacement", "max"), force=("force", "max"),
                    drift_ratio=("drift_ratio", "max"), acceleration=("acceleration", "max"),
                    pounding=("pounding", "any"), runs=("failed", "size"),
                    record_collapsed=("collapsed", "any"), failed=("failed", "sum")
                    ).reset_index()
        env.insert(1, "case", case)
        parts.append(env)
    return pd.concat(parts, ignore_index=True)


def study_table(one_d, two_d):
    """One row per (isolator, case), in ISOLATORS x CASES order (module docstring)."""
    import pandas as pd

    recs = per_record(one_d, two_d)
    rows = []
    for (iso, case), g in recs.groupby(["isolator", "case"], sort=False):
        ok = g[g["failed"] == 0]
        pounded = ok[ok["pounding"]]
        rows.append({"isolator": iso, "case": case, "records": len(ok),
                     "median peak base displacement [in]": _median(ok["displacement"]),
                     "pounding probability [-]": float(ok["pounding"].mean()) if len(ok)
                     else np.nan,
                     "median peak impact force, pounded [kip]": _median(pounded["force"]),
                     "median peak drift ratio [-]": _median(ok["drift_ratio"]),
                     "median peak floor acceleration [g]": _median(ok["acceleration"]),
                     "records that collapsed": int(ok["record_collapsed"].sum()),
                     "runs": int(g["runs"].sum()), "failed runs": int(g["failed"].sum())})
    table = pd.DataFrame(rows)
    order = {k: i for i, k in enumerate((*ISOLATORS, *CASES))}
    return table.sort_values(["isolator", "case"], key=lambda s: s.map(order),
                             ignore_index=True)


def _median(values):
    return float(np.median(values)) if len(values) else np.nan


def to_markdown(table):
    """The table as markdown, one row per isolator and case, and the isolators' design."""
    head = ["isolator", "case", "u [in]", "P [-]", "F [kip]", "drift ratio [%]", "PFA [g]",
            "collapsed"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for _, r in table.iterrows():
        lines.append("| " + " | ".join([
            r["isolator"], CASES[r["case"]], _fmt(r["median peak base displacement [in]"], 2),
            _fmt(r["pounding probability [-]"], 2),
            _fmt(r["median peak impact force, pounded [kip]"], 0),
            _fmt(100 * r["median peak drift ratio [-]"], 2),
            _fmt(r["median peak floor acceleration [g]"], 2),
            f"{r['records that collapsed']}/{r['records']}"]) + " |")
    bearings, design = isolators()
    lines += ["", "u: median over the records of the peak base displacement (2D: in plan); P: "
              "probability of pounding; F: median peak impact force over the records that "
              "pounded; drift ratio and PFA: medians of the largest peak story drift ratio and "
              "floor acceleration; collapsed: records that collapsed / records. 1D: the "
              "envelope of a record's two components alone; 2D: of its pair at "
              + ", ".join(str(a) for a in ANGLES) + " deg. Failed runs (left out): "
              f"{int(table['failed runs'].sum())}.", "",
              "Design (ASCE 7-16 Eq. 17.5-1, S_M1 = 0.45 g·s at the model's time scale): "
              + "; ".join(f"{k}: D_M = {d:.2f} in, T_M = {t:.2f} s, β_M = {100 * b:.1f} %"
                          for k, (d, t, b) in design.items()) + "."]
    return "\n".join(lines) + "\n"


def _fmt(x, digits):
    return "-" if np.isnan(x) else f"{x:.{digits}f}"


def figure(table, path):
    """A figure of the table: per isolator, 1D and 2D side by side, the median peak base
    displacement, the probability of pounding, the median impact force and the median peak
    floor acceleration."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from femoat.atomic import atomic_path

    quantities = (("median peak base displacement [in]", "peak base displacement [in]"),
                  ("pounding probability [-]", "probability of pounding [-]"),
                  ("median peak impact force, pounded [kip]", "impact force, pounded [kip]"),
                  ("median peak floor acceleration [g]", "peak floor acceleration [g]"))
    fig, axes = plt.subplots(1, len(quantities), figsize=(13, 3.2), constrained_layout=True)
    x = np.arange(len(ISOLATORS))
    for ax, (col, label) in zip(axes, quantities):
        for j, case in enumerate(CASES):
            rows = table.set_index(["isolator", "case"])
            vals = [rows[col].get((iso, case), np.nan) for iso in ISOLATORS]
            ax.bar(x + (j - 0.5) * 0.38, vals, width=0.36, label=CASES[case])
        ax.set_xticks(x, [k.upper() for k in ISOLATORS])
        ax.set_ylabel(label)
    axes[0].legend(frameon=False, loc="lower right")
    fig.suptitle("Paper building on three isolators of equal D_M, FEMA P695 far-field pairs "
                 "at the MCE, concrete moat (law H)")
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=120, format="png")
    plt.close(fig)
    return path

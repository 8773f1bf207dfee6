"""The report of building runs: the summary table (CSV and text), the impact table (CSV), the
figures and a README, for ``femoat paper`` (the study's 10 runs) and ``femoat run`` (one
scenario) alike. Runs are given as ``{(wall, law): RunResult}``.
"""

import csv
import io
from pathlib import Path

import numpy as np

from femoat.atomic import write_text

SUMMARY_COLUMNS = [
    ("wall", "", "{}"), ("law", "", "{}"),
    ("peak_impact_force", "kip", "{:.2f}"), ("peak_impact_force_pos", "kip", "{:.2f}"),
    ("peak_impact_force_neg", "kip", "{:.2f}"), ("impacts_pos", "", "{}"),
    ("impacts_neg", "", "{}"), ("peak_base_displacement", "in", "{:.3f}"),
    ("peak_wall_displacement", "in", "{:.4f}"), ("peak_indentation", "in", "{:.4f}"),
    ("peak_impulse", "kip*s", "{:.3f}"), ("peak_drift_max", "in", "{:.3f}"),
    ("peak_floor_acceleration_max", "g", "{:.3f}"), ("peak_base_acceleration", "g", "{:.2f}"),
    ("energy_residual", "", "{:.1e}"), ("steps", "", "{}"), ("solver_seconds", "s", "{:.4f}"),
    ("compile_seconds", "s", "{:.3f}"),
]
"""Summary columns (key, unit, format). ``solver_seconds`` is the CPU time of the run's compiled
loop; ``compile_seconds`` the start-up (numba compilation or kernel loading) paid before that run,
measured on its own by
:func:`femoat.startup.warmup.warm_up`: non-zero only for a process's first run."""


def summary_rows(runs):
    rows = []
    for (wall, law), r in runs.items():
        p = dict(r.peaks)
        p["wall"], p["law"] = wall, law
        p["peak_drift_max"] = max(p["peak_drift"], default=0.0)
        p["peak_floor_acceleration_max"] = max(p["peak_floor_acceleration"], default=0.0)
        p["solver_seconds"] = p["cpu_seconds"]
        p["compile_seconds"] = r.meta.get("compile_seconds", 0.0)
        rows.append({key: p[key] for key, _, _ in SUMMARY_COLUMNS})
    return rows


def format_table(rows):
    heads = [f"{k}" + (f" [{u}]" if u else "") for k, u, _ in SUMMARY_COLUMNS]
    cells = [[fmt.format(row[k]) for k, _, fmt in SUMMARY_COLUMNS] for row in rows]
    widths = [max(len(h), *(len(c[i]) for c in cells)) for i, h in enumerate(heads)]
    lines = ["  ".join(h.rjust(w) for h, w in zip(heads, widths))]
    lines += ["  ".join(c.rjust(w) for c, w in zip(cell, widths)) for cell in cells]
    return "\n".join(lines)


def write_outputs(runs, motion, folder, damping, figures=True, notes=()):
    """Figures, summary CSV and per-run impact tables into ``folder``; returns the paths.
    ``notes``: lines on the motion for README.txt (e.g. how it was scaled to Sa(T))."""
    folder = Path(folder)
    rows = summary_rows(runs)
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow([k + (f" [{u}]" if u else "") for k, u, _ in SUMMARY_COLUMNS])
    for row in rows:
        w.writerow([row[k] for k, _, _ in SUMMARY_COLUMNS])
    paths = [folder / "summary.csv"]
    write_text(paths[0], buf.getvalue())
    ibuf = io.StringIO()
    iw = csv.writer(ibuf)
    iw.writerow(["wall", "law", "side", "start [s]", "duration [s]", "approach_velocity [in/s]",
                 "peak_force [kip]", "max_indentation [in]", "impulse [kip*s]"])
    for (wall, law), r in runs.items():
        for imp in r.impacts:
            iw.writerow([wall, law, imp["side"], imp["start"], imp["duration"],
                         imp["approach_velocity"], imp["peak_force"], imp["max_indentation"],
                         imp["impulse"]])
    paths.append(folder / "impacts.csv")
    write_text(paths[-1], ibuf.getvalue())
    if figures:
        from femoat.ground_motions import response_spectrum
        from femoat.plotting import paper_figures as pf

        periods = np.linspace(0.0, 3.0, 151)
        spec = response_spectrum(motion, periods, damping=0.05)
        figs = {
            "fig4_ground_motion.png": lambda p: pf.plot_ground_motion(motion, p, (periods, spec.psa)),
            "fig5_impact_forces.png": lambda p: pf.plot_impact_forces(runs, p),
            "fig6_contact_hysteresis.png": lambda p: pf.plot_contact_hysteresis(runs, p),
            "fig7_wall_hysteresis.png": lambda p: pf.plot_wall_hysteresis(runs, p),
            "global_response.png": lambda p: pf.plot_global_response(runs, p),
        }
        for name, make in figs.items():
            make(folder / name)
            paths.append(folder / name)
    write_text(folder / "README.txt", (
        f"femoat paper study, C_imp = {damping}\n"
        f"motion: {motion.name}, PGA {motion.pga:.3f} g, dt {motion.dt} s\n"
        + "".join(f"  {note}\n" for note in notes) +
        "units: kip, in, s; accelerations in g\n"
        "solver_seconds: CPU time of each run's compiled loop; compile_seconds: start-up (numba "
        "compilation or kernel loading) paid once per process, before its first run\n\n"
        + format_table(rows) + "\n"))
    paths.append(folder / "README.txt")
    return paths

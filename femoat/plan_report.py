"""What a plan ``femoat run`` writes besides run.npz and the impact table: summary.csv (one row,
units in the headings, as a 1D run's) and README.txt with the echo of the model it ran (the
moat side by side: law, gap, wall, friction; the pair, its angle and scale), so that a number
quoted from the folder says what it belongs to.
"""

import csv
import io
from pathlib import Path

from femoat.atomic import write_text

SIDE_NAMES = {"+x": "px", "-x": "mx", "+y": "py", "-y": "my"}

COLUMNS = (  # (summary key, unit, what), the walls' columns per wall key after them
    ("angle", "deg", "the pair's orientation"), ("scale", "-", "the pair's amplitude factor"),
    ("peak_plan_base_displacement", "in", "largest |u| of the base mat"),
    ("peak_base_displacement_x", "in", ""), ("peak_base_displacement_y", "in", ""),
    ("peak_drift_ratio_x", "-", "largest over the stories"),
    ("peak_drift_ratio_y", "-", "largest over the stories"),
    ("peak_floor_acceleration_x", "g", "largest over the floors, absolute"),
    ("peak_floor_acceleration_y", "g", "largest over the floors, absolute"),
    ("peak_impact_force", "kip", "over all walls"), ("peak_impulse", "kip*s", "over all walls"),
)
WALL_COLUMNS = (("impacts", "-"), ("peak_impact_force", "kip"), ("peak_wall_displacement", "in"))
TAIL = (("energy_residual", "-"), ("steps", "-"), ("solver_seconds", "s"),
        ("compile_seconds", "s"))


def _largest(value):
    if isinstance(value, (list, tuple)):
        return max((abs(v) for v in value if v is not None), default=None)
    return value


def summary_row(result, pair):
    """{heading with unit: value} of one plan run (its peaks; per wall impacts, peak force,
    peak wall displacement; a wall the moat lacks is empty)."""
    p = dict(result.peaks)
    row = {"record": pair.name}
    values = {"angle": pair.angle, "scale": pair.scale,
              "solver_seconds": p.get("cpu_seconds"),
              "compile_seconds": result.meta.get("compile_seconds", 0.0)}
    for key, unit, _ in COLUMNS:
        row[f"{key} [{unit}]"] = _largest(values.get(key, p.get(key)))
    for side, w in SIDE_NAMES.items():
        for name, unit in WALL_COLUMNS:
            row[f"{name}_{w} [{unit}]"] = p.get(f"{name}_{w}")
    for key, unit in TAIL:
        row[f"{key} [{unit}]"] = values.get(key, p.get(key))
    return row


def model_echo(model, pair, moat_given=True, scaling=None):
    """Lines that say what ran: the building's isolator and weight, each wall of the moat
    (law, gap, wall stiffness and damping, friction), the pair, its angle and scale, and with
    ``scaling`` (a :class:`~femoat.scenario.intensity.SaScaling`) how the scale was found."""
    b = model.building
    lines = [f"building: in plan, {len(b.floor_weights)} stories, weight "
             f"{b.base_weight + sum(b.floor_weights):g} kip; isolator {_isolator(b.isolator)}"]
    if not moat_given:
        lines.append("moat: NOT IN THE FILE ([moat] left out): the default moat below, "
                     "rectangular_moat() (add a [moat] table to choose; sides = [] for none)")
    sides = [w.side for w in model.walls]
    lines.append(f"moat: walls on {', '.join(sides) if sides else 'no side'}"
                 + (f"; none on {', '.join(s for s in SIDE_NAMES if s not in sides)}"
                    if len(sides) < 4 else ""))
    for w in model.walls:
        lines.append(f"  wall {w.side}: law {w.law.kind}, gap {w.gap:g} in, {_wall(w.wall)}, "
                     f"friction {w.friction:g} [-]")
    lines.append(f"pair: {pair.name}, angle {pair.angle:g} deg (from +x toward +y), scale "
                 f"{pair.scale:.4g} [-] on both components; dt {pair.dt:g} s, "
                 f"{pair.x.npts} samples")
    if scaling is not None:
        lines.append(f"  {scaling.describe()}")
    return lines


def _isolator(iso):
    if iso is None:
        return "none"
    fields = [f"{k} = {getattr(iso, k):g} [{unit}]" for k, unit in (("R", "in"), ("mu", "-"))
              if hasattr(iso, k)]
    return f"{type(iso).__name__} ({', '.join(fields)})" if fields else type(iso).__name__


def _wall(wall):
    k, c = getattr(wall, "stiffness", None), getattr(wall, "damping", None)
    if k is None:
        return f"{type(wall).__name__}"
    return f"{type(wall).__name__} K1 = {k:g} kip/in, C_imp = {c:g} kip*s/in"


def figure_title(model, pair):
    """A plan figure's title: the pair, its angle and scale, and the walls' laws."""
    laws = sorted({w.law.kind for w in model.walls})
    law = ("law " + "/".join(laws)) if laws else "no walls"
    return f"{pair.name} at {pair.angle:g} deg, x{pair.scale:.3g}; {law}"


def write_plan_summary(result, model, pair, folder, moat_given=True, written=(), scaling=None):
    """summary.csv and README.txt of a plan run into ``folder``; returns their paths.
    ``written`` the other files of the run (named in the README); ``scaling`` the pair's
    :class:`~femoat.scenario.intensity.SaScaling` (echoed) or None."""
    folder = Path(folder)
    row = summary_row(result, pair)
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(list(row))
    w.writerow(["" if v is None else v for v in row.values()])
    paths = [folder / "summary.csv", folder / "README.txt"]
    write_text(paths[0], buf.getvalue())
    width = max(len(k) for k in row)
    table = "\n".join(f"  {k.ljust(width)}  {_cell(v)}" for k, v in row.items())
    text = ["femoat run: a building in plan", "", *model_echo(model, pair, moat_given, scaling), "",
            "units: kip, in, s; accelerations in g; angles in deg (units in each heading)",
            "walls in the columns: px +x, mx -x, py +y, my -y (empty: no wall on that side)",
            "solver_seconds: CPU time of the compiled loop; compile_seconds: start-up paid "
            "before it", "", "summary.csv:", table, "",
            "files: " + ", ".join(p.name for p in [*written, *paths])]
    write_text(paths[1], "\n".join(text) + "\n")
    return paths


def _cell(v):
    if v is None:
        return "-"
    return f"{v:.4g}" if isinstance(v, float) else str(v)

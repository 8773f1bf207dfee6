"""``femoat run scenario.toml``: one building run described by a scenario file."""

import json
import sys
from pathlib import Path


def add_parser(sub):
    p = sub.add_parser(
        "run",
        help="run a scenario file (building, walls, law, motion, solver)",
        description="Run the scenario described by a TOML file (see femoat.scenario for every "
        "key) and write the results (run.npz), the impact table (impacts.csv) and figures to "
        "the output folder; prints the peaks with their units and every file written.",
    )
    p.add_argument("scenario", type=Path, help="scenario TOML file")
    p.add_argument("--out", type=Path, default=None,
                   help="output folder (default: [output] folder of the scenario)")
    p.add_argument("--json", action="store_true", help="print the peak summary as one JSON object")
    p.add_argument("--no-figures", action="store_true", help="skip the figures")
    return p


# units of the peak summary, by key prefix (longest first); lists hold one value per story/floor
UNITS = (("peak_impact_force", "kip"), ("impacts_", "-"), ("peak_base_displacement", "in"),
         ("peak_plan_base_displacement", "in"),
         ("peak_base_velocity", "in/s"), ("peak_wall_displacement", "in"),
         ("peak_indentation", "in"), ("peak_impulse", "kip*s"), ("peak_drift_ratio", "-"),
         ("peak_drift", "in"), ("peak_floor_acceleration", "g"),
         ("peak_base_acceleration", "g"), ("energy_residual", "- (relative)"),
         ("cpu_seconds", "s"), ("compile_seconds", "s"), ("steps", "-"),
         ("collapse", "s (time each criterion is first reached)"),
         ("runaway", "time in s, bound in in"))


def unit_of(key):
    """The unit of a peak-summary entry, e.g. ``kip`` for ``peak_impact_force_pos``."""
    return next((u for prefix, u in UNITS if key.startswith(prefix)), "-")


def _fmt(value):
    """A value to 4 significant digits (lists and dicts element by element)."""
    if isinstance(value, bool) or value is None:
        return str(value)
    if isinstance(value, float):
        return f"{value:.4g}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_fmt(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {_fmt(v)}" for k, v in value.items()) + "}"
    return str(value)


def _plan_outputs(result, out, figures, title=""):
    """A plan run's impact table (impacts.csv) and figures (the base mat's orbit in the moat,
    the impact force per wall; ``title`` theirs): the paths written."""
    import csv

    from femoat.atomic import atomic_path

    paths = [out / "impacts.csv"]
    with atomic_path(paths[0]) as tmp:
        with open(tmp, "w", newline="") as fh:
            fields = ["side", "start", "duration", "approach_velocity", "peak_force",
                      "max_indentation", "impulse"]
            w = csv.DictWriter(fh, fieldnames=fields)
            w.writeheader()
            w.writerows(result.impacts)
    if figures:
        from femoat.plotting.plan_figures import plot_plan_impact_forces, plot_plan_orbit
        from femoat.plotting.plan_history import PlanHistory

        history = PlanHistory.from_result(result, title=title)
        for plot, name in ((plot_plan_orbit, "plan_orbit.png"),
                           (plot_plan_impact_forces, "plan_impact_forces.png")):
            plot(history, out / name)  # (writes the file, returns the figure)
            paths.append(out / name)
    return paths


def run(args):
    from femoat.collapse import describe_runaway
    from femoat.integration.solve import SolverError
    from femoat.run import run as run_model
    from femoat.scenario import load_scenario

    sc = load_scenario(args.scenario)
    from femoat.startup.bearing_kinds import select_for

    select_for([sc.model])  # the loop of this model's bearing kind (before the first run)
    out = args.out or sc.output_folder
    echo = []
    if sc.plan:  # what runs, before it runs (a default moat said loudly)
        from femoat.plan_report import model_echo

        echo = model_echo(sc.model, sc.motion, "moat" in sc.source, sc.intensity)
        if not args.json:
            print("\n".join(echo))
    elif sc.intensity is not None and not args.json:  # the factor, before the run
        print(f"motion: {sc.motion.name}, {sc.intensity.describe()}")
    from femoat.startup.warmup import warm_up

    startup = warm_up()  # compile / load the kernels outside the run's timed loop
    try:
        result = run_model(sc.model, sc.motion, sc.integrator, extra_time=sc.extra_time,
                           collapse=sc.collapse)
    except SolverError as exc:  # the run could not finish: its sentence, not a traceback
        print(f"femoat run: error: {exc}", file=sys.stderr)
        return 1
    result.meta["compile_seconds"] = startup
    result.save(out / "run.npz")
    if sc.plan:
        from femoat.plan_report import figure_title, write_plan_summary

        paths = _plan_outputs(result, out, figures=sc.figures and not args.no_figures,
                              title=figure_title(sc.model, sc.motion))
        paths += write_plan_summary(result, sc.model, sc.motion, out, "moat" in sc.source,
                                    written=[out / "run.npz", *paths], scaling=sc.intensity)
    else:
        from femoat.report import write_outputs

        law = sc.model.walls[0].law.kind if sc.model.walls else "-"
        wall = sc.wall_label
        # (the figures include global_response.png, drawn once)
        paths = write_outputs({(wall, law): result}, sc.motion, out, "scenario",
                              figures=sc.figures and not args.no_figures,
                              notes=[sc.intensity.describe()] if sc.intensity else ())
    # cpu_seconds is the solver's loop only; compile_seconds the start-up paid before it
    summary = {**result.peaks, "compile_seconds": startup}
    if result.collapse is not None:
        summary["collapse"] = result.collapse
    if result.runaway is not None:
        summary["runaway"] = result.runaway
    written = [out / "run.npz", *paths]
    if args.json:
        print(json.dumps({**summary, "units": {k: unit_of(k) for k in summary},
                          "written": [str(p) for p in written],
                          **({"model": echo} if echo else {}),
                          **({"scaling": sc.intensity._asdict()} if sc.intensity else {})}))
    else:
        for k, v in summary.items():
            if k == "runaway":  # the run ended early: say so in a sentence
                print(f"{k:28s} {describe_runaway(v)}")
            else:
                print(f"{k:28s} {_fmt(v):>12s}  [{unit_of(k)}]")
        for p in written:
            print(f"wrote {p}")
    return 0

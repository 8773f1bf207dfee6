"""``femoat opensees scenario.toml``: run a scenario in femoat and in its OpenSees twin, side by
side (needs the ``verify`` extra: openseespy)."""

import json
import sys
from pathlib import Path

# peak-summary keys printed side by side, with units
_ROWS = [
    ("peak_impact_force", "kip"), ("peak_impact_force_pos", "kip"),
    ("peak_impact_force_neg", "kip"), ("impacts_pos", ""), ("impacts_neg", ""),
    ("peak_base_displacement", "in"), ("peak_wall_displacement", "in"),
    ("peak_indentation", "in"), ("peak_impulse", "kip*s"), ("peak_base_acceleration", "g"),
    ("steps", ""), ("cpu_seconds", "s"),
]


def add_parser(sub):
    p = sub.add_parser(
        "opensees",
        help="cross-check a scenario in OpenSees (fixed step) next to femoat",
        description="Build the OpenSees twin of the scenario's model (zeroLength elements, gap "
        "materials, Parallel(Elastic, ElasticPP) isolator, Steel01/Bilin stories, "
        "UniformExcitation; see femoat.opensees.building), run it at a fixed time step with "
        "Newmark average acceleration and Newton, run femoat on the same scenario, and print "
        "both peak summaries. Needs openseespy (pip install femoat[verify]).",
    )
    p.add_argument("scenario", type=Path, help="scenario TOML file")
    p.add_argument("--dt", type=float, default=1e-4,
                   help="OpenSees fixed time step [s] (default: 1e-4)")
    p.add_argument("--script", type=Path, default=None,
                   help="also write the standalone openseespy script of the model to this file")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object {femoat: peaks, opensees: peaks}")
    return p


def _fmt(value):
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)


def run(args):
    from femoat.opensees.building import OpenSeesFailure, opensees_run, write_opensees_script
    from femoat.run import run as run_model
    from femoat.scenario import load_scenario

    from femoat.opensees.available import import_opensees

    try:
        import_opensees()
    except ImportError as exc:  # whatever openseespy's import raised, with what to install
        print(f"femoat opensees: error: {exc}", file=sys.stderr)
        return 2
    sc = load_scenario(args.scenario)
    from femoat.plan.model import PlanModel

    if isinstance(sc.model, PlanModel):
        print(f"femoat opensees: error: {args.scenario} is a plan scenario ([building] plan = "
              "true); this command compares 1D scenarios. Run the plan model's 3D twin from "
              "Python: femoat.opensees.plan.opensees_plan_run(model, pair, dt) (or set plan = "
              "false for the 1D model).", file=sys.stderr)
        return 2
    from femoat.startup.bearing_kinds import select_for

    select_for([sc.model])  # the loop of this model's bearing kind (before the first run)
    duration = sc.motion.duration + sc.extra_time
    if args.script is not None:
        write_opensees_script(sc.model, sc.motion, args.dt, args.script, duration=duration)
    from femoat.startup.warmup import warm_up

    startup = warm_up()  # femoat's start-up, reported apart from its solver time
    fm = run_model(sc.model, sc.motion, sc.integrator, duration=duration)
    try:
        os_run = opensees_run(sc.model, sc.motion, args.dt, duration=duration)
        os_peaks, failure = os_run["peaks"], None
    except OpenSeesFailure as exc:
        os_peaks, failure = {}, str(exc)
    if args.json:
        from femoat.commands.run import unit_of

        femoat = {**fm.peaks, "compile_seconds": startup}
        units = {k: unit_of(k) for k in {**femoat, **os_peaks}} | {"opensees_dt": "s"}
        print(json.dumps(dict(femoat=femoat, opensees=os_peaks, opensees_dt=args.dt,
                              opensees_failure=failure, units=units)))
    else:
        print(f"{sc.motion.name}, {duration:g} s; femoat rtol = {sc.integrator.rtol:g}, "
              f"OpenSees dt = {args.dt:g} s")
        print(f"{'quantity':28s} {'femoat':>14s} {'OpenSees':>14s}  unit")
        for key, unit in _ROWS:
            print(f"{key:28s} {_fmt(fm.peaks.get(key, '-')):>14s} "
                  f"{_fmt(os_peaks.get(key, '-')):>14s}  {unit}")
        print(f"{'compile_seconds':28s} {_fmt(startup):>14s} {'-':>14s}  s  (femoat start-up, "
              "paid once per process; cpu_seconds is the solver alone)")
        if failure:
            print(f"OpenSees failed: {failure}")
        if args.script is not None:
            print(f"wrote {args.script}")
    return 0 if failure is None else 1

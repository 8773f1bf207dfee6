"""The paper study (Hughes & Mosqueda, 17WCEE 2020): 5 contact laws × 2 walls on the default
building under Erzincan N-S scaled to 0.91 g and time-scaled by 0.5, with Figs. 4-7, the global
response and a summary table."""

import sys

from femoat.contact.laws import PAPER_LAWS, make_law
from femoat.integration.settings import Integrator
from femoat.report import (  # noqa: F401  (the paper study's outputs; their home before)
    SUMMARY_COLUMNS,
    format_table,
    summary_rows,
    write_outputs,
)
from femoat.run import run
from femoat.structure.building import Building
from femoat.structure.pounding import MoatWall, PoundingModel
from femoat.walls.presets import wall_preset

LAWS = PAPER_LAWS
WALLS = ("concrete", "steel")


def paper_model(wall, law, damping="published", calibrate=False, gap=4.0, building=None):
    """The default building between two moat walls of the given preset and contact law."""
    preset = wall_preset(wall, damping=damping)
    contact = make_law(law, preset.contact)
    if calibrate and contact.calibratable:
        from femoat.impact.calibration import calibrate as calibrate_law

        contact = calibrate_law(contact, 10.0)
    walls = tuple(MoatWall(contact, preset.wall, gap, side) for side in (1, -1))
    return PoundingModel(building or Building(), walls)


def paper_motion(quick=False):
    """Erzincan N-S at PGA 0.91 g, time-scaled by 0.5 (quick: the first 4 s, which hold all
    the impacts of the default model)."""
    from femoat.ground_motions import GroundMotion, erzincan_paper

    gm = erzincan_paper()
    if quick:
        n = int(round(4.0 / gm.dt)) + 1
        gm = GroundMotion(gm.accel_g[:n], gm.dt, name=gm.name + " (first 4 s)", source=gm.source)
    return gm


def run_paper_study(damping="published", quick=False, calibrate=False, integrator=None,
                    laws=LAWS, walls=WALLS, progress=True):
    """Run the study; returns (runs {(wall, law): RunResult}, motion).

    The solver's start-up (numba compilation or kernel loading) is paid and timed before the
    first run
    (:func:`femoat.startup.warmup.warm_up`) and kept as ``meta["compile_seconds"]`` of that run
    (0.0 for the others), so that every run's ``cpu_seconds`` is solver time only.
    """
    from femoat.startup.warmup import warm_up

    motion = paper_motion(quick)
    integ = integrator or Integrator()
    startup = warm_up()
    if progress:
        print(f"start-up: solver kernels compiled or loaded in {startup:.3f} s of CPU (once per "
              "process, not counted as solver time)", file=sys.stderr, flush=True)
    runs = {}
    total = len(walls) * len(laws)
    for i, wall in enumerate(walls):
        for j, law in enumerate(laws):
            k = i * len(laws) + j + 1
            model = paper_model(wall, law, damping, calibrate)
            result = run(model, motion, integ, extra_time=1.0 if quick else 2.0)
            result.meta["compile_seconds"], startup = startup, 0.0
            runs[(wall, law)] = result
            if progress:
                p = result.peaks
                print(f"[{k:2d}/{total}] {wall:8s} {law}: peak impact force "
                      f"{p['peak_impact_force']:8.2f} kip, {p['impacts_pos']}+{p['impacts_neg']} "
                      f"impacts, {p['steps']} steps, solver {p['cpu_seconds'] * 1e3:.1f} ms",
                      file=sys.stderr, flush=True)
    return runs, motion

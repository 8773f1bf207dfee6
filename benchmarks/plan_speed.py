"""A plan run against 1D runs of the same record: CPU (the compiled loop, best of N), steps, and
the plan run's worst peak error against a converged plan run, side by side in one run; and the
plan run with and without history (``history=False``, what a suite does): the loop's CPU and the
whole ``run()`` call (wall clock, best of N: with history it also reads the peaks from it).

    python benchmarks/plan_speed.py [--repeat 5] [--pairs 1 5 12] [--seconds 12] [--factor 2]

Each FEMA P695 far-field pair (its first seconds, both components times ``factor``) drives the
paper building in plan in the paper's concrete moat (Hertzdamp, 4 in gaps on all four sides):
the plan run (Newmark, the default of a plan run) against the 1D model along x under the x
component (its default dp5, and Newmark: the same method as the plan run).
"""

import argparse
import time

import numpy as np

from femoat.ground_motions import GroundMotion, RecordPair, fema_p695_pair
from femoat.integration import Integrator
from femoat.plan import PlanModel, rectangular_moat
from femoat.run import run


def first(gm, seconds, factor):
    n = min(gm.npts, int(round(seconds / gm.dt)) + 1)
    return GroundMotion(factor * gm.accel_g[:n], gm.dt, name=gm.name)


def _peaks(pk):
    keys = ["peak_plan_base_displacement", "peak_impact_force_px", "peak_impact_force_mx",
            "peak_impact_force_py", "peak_impact_force_my"]  # (0.0 on a wall never hit)
    vals = [pk[k] for k in keys] + pk["peak_drift_x"] + pk["peak_drift_y"] \
        + pk["peak_floor_acceleration_x"] + pk["peak_floor_acceleration_y"]
    return np.array(vals, dtype=float)


def _best(model, motion, integ, duration, repeat, history=True):
    """(the loop's best CPU [s], the whole run()'s best wall clock [s], the first run)."""
    runs, walls = [], []
    for _ in range(repeat):
        t0 = time.perf_counter()
        runs.append(run(model, motion, integ, duration=duration, history=history))
        walls.append(time.perf_counter() - t0)
    return min(r.peaks["cpu_seconds"] for r in runs), min(walls), runs[0]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--pairs", type=int, nargs="+", default=[1, 5, 12])
    ap.add_argument("--seconds", type=float, default=12.0)
    ap.add_argument("--factor", type=float, default=2.0)
    args = ap.parse_args(argv)
    model = PlanModel(walls=rectangular_moat("concrete", "H", gap=4.0))
    along = model.along("x")
    print(f"{'pair':>4s} {'plan ms':>8s} {'steps':>7s} {'1D dp5 ms':>10s} {'steps':>7s} "
          f"{'1D nm ms':>9s} {'steps':>7s} {'plan/1D dp5':>11s} {'plan/1D nm':>10s} "
          f"{'impacts':>8s} {'worst peak err':>15s} {'no-hist ms':>10s} {'run() ms':>9s} "
          f"{'no-hist run() ms':>16s}")
    for k in args.pairs:
        p = fema_p695_pair("farfield", k)
        pair = RecordPair(first(p.x, args.seconds, args.factor),
                          first(p.y, args.seconds, args.factor))
        duration = pair.duration + 1.0
        run(model, pair, duration=duration)  # compile / load
        t_plan, w_plan, r_plan = _best(model, pair, None, duration, args.repeat)
        t_bare, w_bare, r_bare = _best(model, pair, None, duration, args.repeat, history=False)
        t_dp5, _, r_dp5 = _best(along, pair.x, Integrator(), duration, args.repeat)
        t_nm, _, r_nm = _best(along, pair.x, Integrator(method="newmark"), duration, args.repeat)
        assert r_bare.peaks["steps"] == r_plan.peaks["steps"]  # the same steps, recorded or not
        ref = run(model, pair, Integrator(method="newmark", rtol=1e-8), duration=duration)
        got, want = _peaks(r_plan.peaks), _peaks(ref.peaks)
        err = (np.abs(got - want) / np.maximum(np.abs(want), 1e-12)).max()  # (0 against 0: 0)
        hits = sum(r_plan.peaks[f"impacts_{s}"] for s in ("px", "mx", "py", "my"))
        print(f"{k:4d} {t_plan * 1e3:8.1f} {r_plan.peaks['steps']:7d} {t_dp5 * 1e3:10.1f} "
              f"{r_dp5.peaks['steps']:7d} {t_nm * 1e3:9.1f} {r_nm.peaks['steps']:7d} "
              f"{t_plan / t_dp5:11.2f} {t_plan / t_nm:10.2f} {hits:8d} {err:15.2e} "
              f"{t_bare * 1e3:10.1f} {w_plan * 1e3:9.1f} {w_bare * 1e3:16.1f}")


if __name__ == "__main__":
    main()

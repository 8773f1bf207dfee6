"""A plan run against 1D runs of the same record: CPU (the compiled loop, best of N), steps, and
the plan run's worst peak error against a converged plan run, side by side in one run; and the
plan run with and without history (``history=False``, what a suite does): the loop's CPU and the
whole ``run()`` call (wall clock, best of N: with history it also reads the peaks from it).

    python benchmarks/plan_speed.py [--repeat 5] [--pairs 1 5 12] [--seconds 12] [--factor 2]
                                    [--mce [--angles 0 30]] [--isolator fp|lrb|tfp [--designed]]
                                    [--reference newmark|ark5] [--loop all|own]

Each FEMA P695 far-field pair (its first seconds, both components times ``factor``) drives the
paper building in plan in the paper's concrete moat (Hertzdamp, 4 in gaps on all four sides):
the plan run (ark5, the default of a plan run on a friction pendulum; and Newmark, the plan
default before it) against the 1D model along x under the x component (its default dp5, and
Newmark). The worst peak errors are against the plan run converged (Newmark, rtol 1e-8).
``--mce``: the full pairs at the MCE, time x 0.5, at 0 and 30 degrees (issue 26's targets).
``--isolator lrb`` or ``tfp``: the building on the default lead-rubber bearing or triple friction
pendulum instead (both on ark5, their rate forms); the last four columns then give the single
friction pendulum's plan run of the same pair (the default): its CPU, steps and impacts, and the
ratio of the two CPUs (issue 28's target for the triple pendulum: at most 2); ``--designed``: the TFP or
LRB of ``femoat study isolators``, designed for the pendulum's MCE displacement (the default TFP
pounds more often than the pendulum on some pairs: a contact phase is Newmark's small steps, so
its CPU then compares runs of a different event). ``--reference ark5``: the converged run is ark5
at rtol 1e-9 instead of Newmark at 1e-8. ``--loop own``: compile the loop for the single
pendulum alone when the building stands on it (what ``femoat run`` and the studies compile for
such a model, ``femoat.startup.bearing_kinds``); the default ``all`` is the loop of every bearing
kind, what a Python session gets.
"""

import argparse
import time

import numpy as np

from femoat.ground_motions import GroundMotion, RecordPair, fema_p695_pair
from femoat.integration import Integrator
from femoat.plan import PlanBuilding, PlanModel, rectangular_moat
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


def _pairs(args):
    """(label, RecordPair): the first ``seconds`` of each pair times ``factor``, or with
    ``--mce`` the full pairs at the paper building's MCE (FEMA P695 normalized, the
    bidirectional study's anchoring SF at T = 3.5 s), time x 0.5, at each angle."""
    if not args.mce:
        for k in args.pairs:
            p = fema_p695_pair("farfield", k)
            yield f"{k}", RecordPair(first(p.x, args.seconds, args.factor),
                                     first(p.y, args.seconds, args.factor))
        return
    from femoat.studies.bidirectional import full_anchor

    sf = full_anchor()
    for k in args.pairs:
        for angle in args.angles:
            p = fema_p695_pair("farfield", k, scale=sf, normalized=True)
            pair = RecordPair(p.x.time_scaled(0.5), p.y.time_scaled(0.5),
                              scale=p.scale).rotated(angle)  # (keep NF x SF)
            yield f"{k}@{angle:g}", pair


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--pairs", type=int, nargs="+", default=[1, 5, 12])
    ap.add_argument("--seconds", type=float, default=12.0)
    ap.add_argument("--factor", type=float, default=2.0)
    ap.add_argument("--mce", action="store_true",
                    help="full pairs at the MCE, time x 0.5, at --angles (issue 26's targets)")
    ap.add_argument("--angles", type=float, nargs="+", default=[0.0, 30.0])
    ap.add_argument("--isolator", choices=("fp", "lrb", "tfp"), default="fp",
                    help="the building's bearing: the paper's friction pendulum, the default "
                         "lead-rubber bearing or triple friction pendulum (each on its rate "
                         "form: ark5)")
    ap.add_argument("--designed", action="store_true",
                    help="with --isolator tfp or lrb: the bearing of `femoat study isolators`, "
                         "designed for the pendulum's MCE displacement (the two buildings then "
                         "pound alike), instead of the kind's defaults")
    ap.add_argument("--reference", choices=("newmark", "ark5"), default="newmark",
                    help="the converged run: Newmark at rtol 1e-8 (default) or ark5 at rtol 1e-9")
    ap.add_argument("--loop", choices=("all", "own"), default="all",
                    help="the compiled loop: every bearing kind's (a Python session's, default) "
                         "or the pendulum's alone for --isolator fp (what femoat run compiles)")
    args = ap.parse_args(argv)
    if args.loop == "own" and args.isolator == "fp":
        from femoat.bearings import registry

        registry.select(["fp"])
    building = PlanBuilding()
    if args.designed and args.isolator != "fp":
        from femoat.studies.isolators import isolators

        building = PlanBuilding(isolator=isolators()[0][args.isolator])
    elif args.isolator == "lrb":
        from femoat.bearings.lead_rubber import LeadRubberBearing

        building = PlanBuilding(isolator=LeadRubberBearing())
    elif args.isolator == "tfp":
        from femoat.bearings.triple_friction_pendulum import TripleFrictionPendulum

        building = PlanBuilding(isolator=TripleFrictionPendulum())
    model = PlanModel(building, walls=rectangular_moat("concrete", "H", gap=4.0))
    single = PlanModel(walls=rectangular_moat("concrete", "H", gap=4.0))
    along = model.along("x")
    newmark = Integrator(method="newmark")
    print(f"{'pair':>7s} {'plan ms':>8s} {'steps':>7s} {'1D dp5 ms':>10s} {'steps':>7s} "
          f"{'1D nm ms':>9s} {'steps':>7s} {'plan/1D dp5':>11s} {'plan/1D nm':>10s} "
          f"{'impacts':>8s} {'worst peak err':>15s} {'no-hist ms':>10s} {'run() ms':>9s} "
          f"{'no-hist run() ms':>16s} {'plan nm ms':>10s} {'nm err':>9s}"
          + (f" {'fp plan ms':>10s} {'fp steps':>8s} {'fp hits':>7s} {'/fp':>5s}"
             if args.isolator != "fp" else ""))
    for label, pair in _pairs(args):
        duration = pair.duration + 1.0
        run(model, pair, duration=duration)  # compile / load
        t_plan, w_plan, r_plan = _best(model, pair, None, duration, args.repeat)
        t_bare, w_bare, r_bare = _best(model, pair, None, duration, args.repeat, history=False)
        t_pnm, _, r_pnm = _best(model, pair, newmark, duration, args.repeat)
        t_dp5, _, r_dp5 = _best(along, pair.motion_x, Integrator(), duration, args.repeat)
        t_nm, _, r_nm = _best(along, pair.motion_x, newmark, duration, args.repeat)
        assert r_bare.peaks["steps"] == r_plan.peaks["steps"]  # the same steps, recorded or not
        converged = (Integrator(method="newmark", rtol=1e-8) if args.reference == "newmark" else
                     Integrator(method="ark5", rtol=1e-9))
        ref = run(model, pair, converged, duration=duration)
        want = _peaks(ref.peaks)
        err, err_nm = ((np.abs(_peaks(r.peaks) - want) / np.maximum(np.abs(want), 1e-12)).max()
                       for r in (r_plan, r_pnm))  # (0 against 0: 0)
        hits = sum(r_plan.peaks[f"impacts_{s}"] for s in ("px", "mx", "py", "my"))
        print(f"{label:>7s} {t_plan * 1e3:8.1f} {r_plan.peaks['steps']:7d} {t_dp5 * 1e3:10.1f} "
              f"{r_dp5.peaks['steps']:7d} {t_nm * 1e3:9.1f} {r_nm.peaks['steps']:7d} "
              f"{t_plan / t_dp5:11.2f} {t_plan / t_nm:10.2f} {hits:8d} {err:15.2e} "
              f"{t_bare * 1e3:10.1f} {w_plan * 1e3:9.1f} {w_bare * 1e3:16.1f} "
              f"{t_pnm * 1e3:10.1f} {err_nm:9.2e}", end="")
        if args.isolator != "fp":
            t_fp, _, r_fp = _best(single, pair, None, duration, args.repeat)
            fp_hits = sum(r_fp.peaks[f"impacts_{s}"] for s in ("px", "mx", "py", "my"))
            print(f" {t_fp * 1e3:10.1f} {r_fp.peaks['steps']:8d} {fp_hits:7d} "
                  f"{t_plan / t_fp:5.2f}", end="")
        print(flush=True)


if __name__ == "__main__":
    main()

"""Accuracy of every peak (impact force, base and wall displacement, story drifts, floor and base
accelerations) at several rtol, against femoat converged and against the OpenSees twin.

    python benchmarks/peak_accuracy.py [--rtol 1e-3,1e-4,1e-5,1e-6,1e-7] [--opensees-dt 2e-5]
                                       [--no-opensees] [--quick]

Cases: the paper runs of laws E, V, J, H on both walls (Erzincan N-S, 0.91 g, time scale 0.5;
V pulls in tension here, as OpenSees' ViscoelasticGap does; M differs from OpenSees for the
documented reason), and FEMA P695 far-field records (dt 0.01 s, time scale 0.5, PGA 0.6 g,
paper building, concrete wall, law E: the gap stays open). 'ref' is femoat at rtol 1e-8 with
steps of at most 1e-4 s; 'OS' the OpenSees twin at a fixed step. For each case: ref against OS,
then femoat at each rtol against ref (steps, CPU ms, relative error of each peak), then femoat
at its default rtol against OS. Ends with the worst errors at the default rtol, the figures
issue 9 sets targets on. Prints; nothing is asserted (tests/test_peak_accuracy.py asserts).
"""

import argparse
import time

from femoat.contact.laws import make_law
from femoat.ground_motions import fema_p695_record
from femoat.integration import Integrator
from femoat.paper import paper_model, paper_motion
from femoat.run import run
from femoat.structure.building import Building
from femoat.structure.pounding import MoatWall, PoundingModel
from femoat.walls.presets import wall_preset

KEYS = ["F", "base", "wall", "d1", "d2", "d3", "a1", "a2", "a3", "a0"]
REFERENCE = Integrator(rtol=1e-8, max_step=1e-4)
FEMA_RECORDS = ((1, "a"), (5, "a"), (12, "a"), (3, "b"), (8, "a"), (17, "b"), (21, "a"))


def peaks(p):
    """The peaks of a femoat ``RunResult.peaks`` or an OpenSees twin's ``peaks`` dict."""
    out = dict(F=p["peak_impact_force"], base=p["peak_base_displacement"],
               wall=p["peak_wall_displacement"], a0=p["peak_base_acceleration"])
    out.update({f"d{k + 1}": d for k, d in enumerate(p["peak_drift"])})
    out.update({f"a{k + 1}": a for k, a in enumerate(p["peak_floor_acceleration"])})
    return out


def errors(p, ref):
    """Relative error of each peak that the reference has (a zero peak, e.g. no impact, is
    left out)."""
    return {k: abs(p[k] - ref[k]) / abs(ref[k]) for k in ref if ref[k]}


def twin_model(wall, law):
    """The paper model with the law OpenSees has too (V with tension allowed)."""
    preset = wall_preset(wall, damping="published")
    contact = make_law(law, preset.contact, **({"allow_tension": True} if law == "V" else {}))
    return PoundingModel(Building(), tuple(MoatWall(contact, preset.wall, 4.0, side)
                                           for side in (1, -1)))


def cases(quick=False):
    for wall in ("concrete",) if quick else ("concrete", "steel"):
        for law in "E" if quick else "EVJH":
            yield f"paper/{wall}/{law}", twin_model(wall, law), paper_motion()
    for rid, comp in FEMA_RECORDS[:1] if quick else FEMA_RECORDS:
        gm = fema_p695_record("farfield", rid, comp).scaled_to_pga(0.6).time_scaled(0.5)
        yield f"FEMA-FF{rid}{comp}/concrete/E", paper_model("concrete", "E"), gm


def row(name, label, setting, steps, ms, e):
    cells = "".join(f"{e[k]:8.0e}" if k in e else f"{'-':>8s}" for k in KEYS)
    head = f"{name:28s}{label:>7s}{setting:>9s}{steps:>7s}{ms:>6s} "
    return head + cells + f"{max(e.values()):8.1e}"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rtol", default="1e-3,1e-4,1e-5,1e-6,1e-7")
    ap.add_argument("--opensees-dt", type=float, default=2e-5)
    ap.add_argument("--no-opensees", action="store_true")
    ap.add_argument("--quick", action="store_true", help="one paper run and one FEMA record")
    args = ap.parse_args(argv)
    default = Integrator().rtol
    rtols = sorted({float(x) for x in args.rtol.split(",")} | {default}, reverse=True)
    print(f"relative error of each peak; ref = femoat at rtol {REFERENCE.rtol:g}, max_step "
          f"{REFERENCE.max_step:g} s; OS = OpenSees twin at dt = {args.opensees_dt:g} s; "
          f"default rtol = {default:g}")
    print(f"{'case':28s}{'against':>7s}{'rtol':>9s}{'steps':>7s}{'ms':>6s} "
          + "".join(f"{k:>8s}" for k in KEYS) + f"{'worst':>8s}")
    worst = {"paper drifts vs OS": 0.0, "paper every peak vs OS": 0.0,
             "FEMA every peak vs OS": 0.0, "paper every peak vs ref": 0.0,
             "FEMA every peak vs ref": 0.0}
    run(paper_model("concrete", "E"), paper_motion(quick=True))  # compile outside the timings
    for name, model, motion in cases(args.quick):
        kind = "paper" if name.startswith("paper") else "FEMA"
        ref = peaks(run(model, motion, REFERENCE).peaks)
        twin = None
        if not args.no_opensees:
            from femoat.opensees import opensees_run

            try:
                # V: OpenSees' 1e-10 in increment test stagnates at t = 2.129 s (concrete)
                tol = 1e-8 if name.endswith("/V") else 1e-10
                twin = peaks(opensees_run(model, motion, args.opensees_dt, tol=tol)["peaks"])
                print(row(name, "ref/OS", "", "", "", errors(ref, twin)), flush=True)
            except Exception as exc:  # report, do not stop the table
                print(f"{name:28s} OpenSees failed: {str(exc)[:80]}", flush=True)
        for rtol in rtols:
            t0 = time.process_time()
            r = run(model, motion, Integrator(rtol=rtol))
            ms = f"{(time.process_time() - t0) * 1e3:.0f}"
            steps = str(r.peaks["steps"])
            e = errors(peaks(r.peaks), ref)
            print(row(name, "ref", f"{rtol:.0e}", steps, ms, e), flush=True)
            if rtol != default:
                continue
            worst[f"{kind} every peak vs ref"] = max(worst[f"{kind} every peak vs ref"],
                                                     max(e.values()))
            if twin is not None:
                e = errors(peaks(r.peaks), twin)
                print(row(name, "OS", f"{rtol:.0e}", steps, ms, e), flush=True)
                worst[f"{kind} every peak vs OS"] = max(worst[f"{kind} every peak vs OS"],
                                                        max(e.values()))
                if kind == "paper":
                    worst["paper drifts vs OS"] = max(worst["paper drifts vs OS"],
                                                      *(e[k] for k in ("d1", "d2", "d3")))
    print(f"\nat the default rtol = {default:g} (issue 9's targets: paper drifts vs OS < 3e-4, "
          "FEMA every peak vs OS < 1e-3):")
    for label, value in worst.items():
        if value:
            print(f"  {label:26s} {value:.1e}")


if __name__ == "__main__":
    main()

"""Accuracy of every peak (impact force, base and wall displacement, story drifts, floor and base
accelerations) at several rtol, against femoat converged and against the OpenSees twin.

    python benchmarks/peak_accuracy.py [--rtol 1e-3,1e-4,1e-5,1e-6,1e-7] [--opensees-dt 2e-5]
                                       [--methods newmark,dp5] [--no-opensees] [--quick]

Cases: the paper runs of laws E, V, J, H on both walls (Erzincan N-S, 0.91 g, time scale 0.5;
V pulls in tension here, as OpenSees' ViscoelasticGap does; M differs from OpenSees for the
documented reason), and FEMA P695 far-field records (dt 0.01 s, time scale 0.5, PGA 0.6 g,
paper building, concrete wall, law E: the gap stays open). 'ref' is femoat at rtol 1e-8 with
steps of at most 1e-4 s (Newmark); 'OS' the OpenSees twin at a fixed step. For each case: ref
against OS, then each method at each rtol against ref (steps, CPU ms, relative error of each
peak), then each method at its default rtol against OS. Ends with the worst errors of each
method at its default rtol. Prints; nothing is asserted (tests/test_peak_accuracy.py asserts).
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
REFERENCE = Integrator(method="newmark", rtol=1e-8, max_step=1e-4)
FEMA_RECORDS = ((1, "a"), (5, "a"), (12, "a"), (3, "b"), (8, "a"), (17, "b"), (21, "a"))
NEAR_FIELD = ((1, "a"), (9, "b"))
"""Near-field records (pulse-like) at 0.6 g too, and far-field 5a at 0.15 g and 1a at 1.2 g."""


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
    if quick:
        return
    for rid, comp in NEAR_FIELD:
        gm = fema_p695_record("nearfield_pulse", rid, comp).scaled_to_pga(0.6).time_scaled(0.5)
        yield f"FEMA-NF{rid}{comp}/concrete/E", paper_model("concrete", "E"), gm
    for (rid, comp), pga in (((5, "a"), 0.15), ((1, "a"), 1.2)):
        gm = fema_p695_record("farfield", rid, comp).scaled_to_pga(pga).time_scaled(0.5)
        yield f"FEMA-FF{rid}{comp}@{pga}g/concrete/E", paper_model("concrete", "E"), gm


def row(name, label, setting, steps, ms, e):
    cells = "".join(f"{e[k]:8.0e}" if k in e else f"{'-':>8s}" for k in KEYS)
    head = f"{name:28s}{label:>7s}{setting:>13s}{steps:>7s}{ms:>6s} "
    return head + cells + f"{max(e.values()):8.1e}"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rtol", default="1e-3,1e-4,1e-5,1e-6,1e-7")
    ap.add_argument("--methods", default="newmark,dp5")
    ap.add_argument("--opensees-dt", type=float, default=2e-5)
    ap.add_argument("--no-opensees", action="store_true")
    ap.add_argument("--quick", action="store_true", help="one paper run and one FEMA record")
    args = ap.parse_args(argv)
    methods = args.methods.split(",")
    defaults = {m: Integrator(method=m).rtol for m in methods}
    grid = {m: sorted({float(x) for x in args.rtol.split(",")} | {defaults[m]}, reverse=True)
            for m in methods}
    print(f"relative error of each peak; ref = femoat Newmark at rtol {REFERENCE.rtol:g}, "
          f"max_step {REFERENCE.max_step:g} s; OS = OpenSees twin at dt = {args.opensees_dt:g} "
          f"s; default rtol: " + ", ".join(f"{m} {r:g}" for m, r in defaults.items())
          + f"; Integrator() is {Integrator().method}")
    print(f"{'case':28s}{'against':>7s}{'method/rtol':>13s}{'steps':>7s}{'ms':>6s} "
          + "".join(f"{k:>8s}" for k in KEYS) + f"{'worst':>8s}")
    labels = ("paper drifts vs OS", "paper every peak vs OS", "FEMA every peak vs OS",
              "paper every peak vs ref", "FEMA every peak vs ref", "paper CPU ms (max)",
              "FEMA CPU ms (max)")
    worst = {m: dict.fromkeys(labels, 0.0) for m in methods}
    for m in methods:  # compile outside the timings
        run(paper_model("concrete", "E"), paper_motion(quick=True), Integrator(method=m))
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
        for method in methods:
            for rtol in grid[method]:
                integ = Integrator(method=method, rtol=rtol)
                run(model, motion, integ)  # warm caches; the second run is timed
                t0 = time.process_time()
                r = run(model, motion, integ)
                cpu = (time.process_time() - t0) * 1e3
                steps = str(r.peaks["steps"])
                e = errors(peaks(r.peaks), ref)
                label = f"{method} {rtol:.0e}"
                print(row(name, "ref", label, steps, f"{cpu:.0f}", e), flush=True)
                if rtol != defaults[method]:
                    continue
                w = worst[method]
                w[f"{kind} every peak vs ref"] = max(w[f"{kind} every peak vs ref"],
                                                     max(e.values()))
                w[f"{kind} CPU ms (max)"] = max(w[f"{kind} CPU ms (max)"], cpu)
                if twin is not None:
                    e = errors(peaks(r.peaks), twin)
                    print(row(name, "OS", label, steps, f"{cpu:.0f}", e), flush=True)
                    w[f"{kind} every peak vs OS"] = max(w[f"{kind} every peak vs OS"],
                                                        max(e.values()))
                    if kind == "paper":
                        w["paper drifts vs OS"] = max(w["paper drifts vs OS"],
                                                      *(e[k] for k in ("d1", "d2", "d3")))
    for method in methods:
        print(f"\n{method} at its default rtol = {defaults[method]:g} (targets: every peak "
              "within 1e-3; issue 15: paper CPU <= 5 ms):")
        for label, value in worst[method].items():
            if value:
                print(f"  {label:26s} {value:.3g}" if "CPU" in label else
                      f"  {label:26s} {value:.1e}")


if __name__ == "__main__":
    main()

"""The triple friction pendulum with velocity-dependent friction: the accuracy of its
backward-Euler return on a steady orbit (against the closed form, and OpenSees' element), and
the cost and accuracy of a plan run on it, beside the constant-friction bearing.

    python benchmarks/tfp_velocity.py [--no-opensees] [--twin-run] [--mce] [--suite FOLDER]

Bearing: ``TripleFrictionPendulum(mu1_fast=0.03, mu2_fast=0.08, mu3_fast=0.15, a=1.0)`` (the
defaults' μ as μ_slow). Prints:

* a circle of 0.5 in in 2 s (regime I, the inner slider's surfaces at ~0.8 in/s), 3 turns, at
  125 to 4000 steps a turn: femoat's steady force and its error against the closed form of the
  continuous model (tests/test_bearing_tfp_velocity.py derives it), and OpenSees'
  ``TripleFrictionPendulum`` with ``VelDependent`` friction on the same imposed orbit: its last
  force and how much it swings over the last half turn (a steady orbit's force is constant);
* the paper building in plan on the bearing in the square concrete moat (law H), the first 8 s
  of Erzincan along x and its reversed copy at 0.6 along y, turned by 30°: ark5 (the plan
  default: the rate form) and Newmark (the backward-Euler return), each at its default rtol and
  at 1e-6, 1e-7: steps, loop CPU (best of 3), the worst peak's relative error against each
  method's run at rtol 1e-8; the constant-friction bearing at its default for scale; the same
  (Newmark only) for the 1D model
  along x under the x record (its one-axis kernels read each step's duration from the loop),
  and the 1D run against the plan run on a line (y at rest);
* ``--mce``: far-field pairs 1, 5 and 12 at the MCE (the bidirectional study's scale), 0° and
  30°, in a 4 in moat: ark5 and Newmark at their defaults against both converged;
* ``--twin-run``: that plan run's OpenSees twin (``femoat.opensees.plan``, tol 1e-6; at 1e-8 it
  stops converging) at 0.2, 0.1 and 0.05 ms: its worst peak against femoat at rtol 1e-8 (about
  a minute of OpenSees);
* ``--suite FOLDER``: does the velocity dependence matter for pounding? The isolators study's
  plan suite (``femoat.studies.isolators``: the 22 far-field pairs at the MCE, 0° and 45°, the
  paper's concrete moat) on its triple pendulum with constant friction against the same bearing
  with μ_fast = the study's μ, μ_slow = μ/2 and a = 1.5 s/in (about 0.75 s/in at full scale:
  the model's velocities are half the prototype's), each at its plan default (ark5):
  per isolator, the median peak plan displacement, the probability of pounding, the median
  peak impact force of the records that pounded, the median peak drift ratio, and the CPU.
"""

import argparse
import math
import time

import numpy as np
from scipy.optimize import brentq

from femoat.bearings.orbit import orbit_forces
from femoat.bearings.triple_friction_pendulum import TripleFrictionPendulum
from femoat.ground_motions import GroundMotion, RecordPair
from femoat.integration import Integrator
from femoat.paper import paper_motion
from femoat.plan import PlanBuilding, PlanModel
from femoat.run import run

BEARING = TripleFrictionPendulum(mu1_fast=0.03, mu2_fast=0.08, mu3_fast=0.15, a=1.0)
RADIUS, PERIOD = 0.5, 2.0


def circle(n, turns=3):
    """(path, velocities, dt): a ramp to (RADIUS, 0) in 0.25 s, then ``turns`` turns."""
    dt = PERIOD / n
    n0 = max(1, round(0.25 / dt))
    ramp = np.column_stack([RADIUS * np.arange(1, n0 + 1) / n0, np.zeros(n0)])
    ramp_v = np.column_stack([np.full(n0, RADIUS / (n0 * dt)), np.zeros(n0)])
    om = 2.0 * math.pi / PERIOD
    th = om * dt * np.arange(1, turns * n + 1)
    path = np.vstack([ramp, RADIUS * np.column_stack([np.cos(th), np.sin(th)])])
    vel = np.vstack([ramp_v, RADIUS * om * np.column_stack([-np.sin(th), np.cos(th)])])
    return path, vel, dt


def femoat_forces(path, vel, dt):
    return np.hypot(*orbit_forces(BEARING, path, dt, vel)[0].T)


def closed_form():
    """The steady force [kip] of the continuous model on the circle (the test's derivation)."""
    b = BEARING
    kr, k0 = b.W / b.radii[0], b.sticking_stiffness
    ke, om = k0 - kr, 2.0 * math.pi / PERIOD
    c, alpha = 1.0 + 2.0 * kr / k0, (1.0 + 2.0 * kr / k0) / ke + 2.0 / k0

    def q(rho):
        v = b.rate_factors[0] * om * rho
        return b.W * (b.mu1_fast - (b.mu1_fast - b.mu1) * math.exp(-b.a * v))

    rho = brentq(lambda r: (r * c) ** 2 + (q(r) * alpha) ** 2 - RADIUS ** 2, 0.0, RADIUS,
                 xtol=1e-15, rtol=1e-15)
    return math.hypot(kr * rho, q(rho) * (1.0 + kr / ke))


def opensees_forces(path, dt):
    """OpenSees' element on the imposed orbit, one transient step of dt a point: the force
    magnitudes (None if openseespy is missing or OpenSees fails)."""
    from femoat.opensees.bearing_orbit import orbit_forces

    try:
        return np.hypot(*orbit_forces(BEARING, path, dt).T)
    except (ImportError, RuntimeError):
        return None


def orbit_table(with_opensees):
    exact = closed_form()
    print(f"steady circle r = {RADIUS} in, T = {PERIOD} s (regime I): closed form {exact:.9f} kip")
    print(f"{'steps/turn':>10} {'dt [ms]':>8} {'femoat':>12} {'error':>10} {'opensees':>12} "
          f"{'error':>10} {'swing':>9}")
    for n in (125, 250, 500, 1000, 2000, 4000):
        path, vel, dt = circle(n)
        f = femoat_forces(path, vel, dt)[-1]
        line = f"{n:10d} {1e3 * dt:8.2f} {f:12.9f} {(f - exact) / exact:10.2e}"
        g = opensees_forces(path, dt) if with_opensees else None
        if g is not None:
            line += (f" {g[-1]:12.9f} {(g[-1] - exact) / exact:10.2e} "
                     f"{np.ptp(g[-n // 2:]) / exact:9.1e}")
        print(line, flush=True)


def _first(m, seconds):
    n = int(round(seconds / m.dt)) + 1
    return GroundMotion(m.accel_g[:n], m.dt, name=m.name)


def _peaks(r, plan):
    pk = r.peaks
    if plan:
        tags = ("px", "mx", "py", "my")
        return np.array([pk["peak_plan_base_displacement"],
                         *[pk[f"peak_impact_force_{t}"] for t in tags],
                         *pk["peak_drift_x"], *pk["peak_drift_y"]])
    return np.array([pk["peak_base_displacement"], pk["peak_impact_force_pos"],
                     pk["peak_impact_force_neg"], *pk["peak_drift"]])


def _plan_pair():
    m8 = _first(paper_motion(), 8.0)
    return RecordPair(m8, GroundMotion(-0.6 * m8.accel_g[::-1], m8.dt, name="y"), angle=30.0)


def twin_run_table():
    from femoat.opensees.plan import opensees_plan_run

    pair = _plan_pair()
    model = PlanModel(building=PlanBuilding(isolator=BEARING))
    ref = _peaks(run(model, pair, integrator=Integrator(method="newmark", rtol=1e-8)), True)
    sides = [w.side for w in model.walls]
    order = [("+x", "-x", "+y", "-y").index(s) for s in sides]
    print("\nthe plan run's OpenSees twin (tol 1e-6) against femoat at rtol 1e-8")
    for dt in (2e-4, 1e-4, 5e-5):
        t = time.time()
        tw = opensees_plan_run(model, pair, dt, tol=1e-6)["peaks"]
        forces = np.zeros(4)
        forces[order] = tw["impact_force"]
        d = np.asarray(tw["drift"])
        twin = np.array([tw["plan_base_displacement"], *forces, *d[:, 0], *d[:, 1]])
        err = np.max(np.abs(twin / ref - 1.0))
        print(f"dt {1e3 * dt:.2f} ms: worst peak {err:.3f}, impacts {list(tw['impacts'])}, "
              f"{time.time() - t:.0f} s", flush=True)


def runs_table():
    m = paper_motion()
    m8 = _first(m, 8.0)
    pair = RecordPair(m8, GroundMotion(-0.6 * m8.accel_g[::-1], m8.dt, name="y"), angle=30.0)

    def plan_model(b):
        return PlanModel(building=PlanBuilding(isolator=b))

    def line_model(b):
        return plan_model(b).along("x")

    for label, plan, motion, model, methods in (
            ("plan", True, pair, plan_model, ("ark5", "newmark")),
            ("1D", False, m8, line_model, ("newmark",))):
        run(model(BEARING), motion)  # (load the kernels)
        refs = [_peaks(run(model(BEARING), motion, integrator=Integrator(method=m, rtol=1e-8)),
                       plan) for m in methods]
        print(f"\n{label}: velocity-dependent bearing, the worst peak against each method's run "
              f"at rtol 1e-8 ({', '.join(methods)})")
        print(f"{'method':>8} {'rtol':>8} {'steps':>8} {'CPU [s]':>8} "
              + " ".join(f"{'vs ' + m:>10}" for m in methods))
        for method in methods:
            for rtol in (None, 1e-6, 1e-7):
                integ = Integrator(method=method) if rtol is None else \
                    Integrator(method=method, rtol=rtol)
                best = np.inf
                for _ in range(3):
                    t = time.process_time()
                    r = run(model(BEARING), motion, integrator=integ, history=False)
                    best = min(best, time.process_time() - t)
                errs = " ".join(f"{np.max(np.abs(_peaks(r, plan) / ref - 1.0)):10.1e}"
                                for ref in refs)
                name = "default" if rtol is None else f"{rtol:.0e}"
                print(f"{method:>8} {name:>8} {r.peaks['steps']:8d} {best:8.3f} {errs}",
                      flush=True)
        const = TripleFrictionPendulum()
        run(model(const), motion)
        t = time.process_time()
        r = run(model(const), motion, history=False)
        print(f"constant friction (μ_slow) at its default ({r.meta['info']['method']}): "
              f"{r.peaks['steps']} steps, {time.process_time() - t:.3f} s")
    zero = GroundMotion(0.0 * m8.accel_g, m8.dt, name="zero")
    one = _peaks(run(line_model(BEARING), m8), False)
    both = run(plan_model(BEARING), RecordPair(m8, zero),
               integrator=Integrator(method="newmark")).peaks
    on_line = np.array([both["peak_plan_base_displacement"], both["peak_impact_force_px"],
                        both["peak_impact_force_mx"], *both["peak_drift_x"]])
    print(f"1D run against the plan run on a line (y at rest), both on Newmark at its default: worst peak "
          f"{np.max(np.abs(one / on_line - 1.0)):.1e}")


def mce_table():
    """Far-field pairs 1, 5 and 12 at the bidirectional study's MCE scale (time x 0.5), at 0° and
    30°, the paper building on the bearing in the concrete moat (gap 4 in, law H): ark5 and
    Newmark at their defaults, steps, loop CPU (best of 3), impacts and the worst peak against
    ark5 at rtol 1e-9 and Newmark at rtol 1e-8 (the two converged runs' own agreement first)."""
    from femoat.ground_motions import fema_p695_pair
    from femoat.plan import rectangular_moat
    from femoat.studies.bidirectional import full_anchor

    model = PlanModel(PlanBuilding(isolator=BEARING), walls=rectangular_moat("concrete", "H",
                                                                             gap=4.0))
    sf = full_anchor()
    tags = ("px", "mx", "py", "my")

    def worst(a, b):
        m = np.abs(b) > 1e-9 * np.abs(b).max()
        return np.max(np.abs(a[m] / b[m] - 1.0)) if m.any() else 0.0

    print("\nfar-field pairs at the MCE, the worst peak against ark5 at rtol 1e-9 and Newmark at 1e-8")
    print(f"{'pair':>6} {'method':>8} {'steps':>7} {'CPU [s]':>8} {'vs ark5':>9} "
          f"{'vs newmark':>10}  impacts (+x, -x, +y, -y)")
    for k, angle in ((1, 0.0), (1, 30.0), (5, 0.0), (5, 30.0), (12, 0.0), (12, 30.0)):
        p = fema_p695_pair("farfield", k, scale=sf, normalized=True)
        pair = RecordPair(p.x.time_scaled(0.5), p.y.time_scaled(0.5),
                          scale=p.scale).rotated(angle)
        d = pair.duration + 1.0
        ra = run(model, pair, integrator=Integrator(method="ark5", rtol=1e-9), duration=d)
        rn = run(model, pair, integrator=Integrator(method="newmark", rtol=1e-8), duration=d)
        ref_a, ref_n = _peaks(ra, True), _peaks(rn, True)
        label = f"{k}@{angle:.0f}"
        print(f"{label:>6} converged runs against each other: {worst(ref_a, ref_n):.1e}")
        for method in ("ark5", "newmark"):
            best = np.inf
            for _ in range(3):
                t = time.process_time()
                r = run(model, pair, integrator=Integrator(method=method), duration=d,
                        history=False)
                best = min(best, time.process_time() - t)
            pk = _peaks(r, True)
            print(f"{label:>6} {method:>8} {r.peaks['steps']:7d} {best:8.3f} "
                  f"{worst(pk, ref_a):9.1e} {worst(pk, ref_n):10.1e}  "
                  f"{[r.peaks[f'impacts_{t}'] for t in tags]}", flush=True)


def suite_table(folder):
    import dataclasses

    from femoat.studies import isolators as study
    from femoat.studies.suites import run_suites
    from femoat.suite import load_table

    tfp = study.isolators()[0]["tfp"]
    fast = {f"mu{i}_fast": getattr(tfp, f"mu{i}") for i in (1, 2, 3)}
    rate = dataclasses.replace(tfp, mu1=tfp.mu1 / 2, mu2=tfp.mu2 / 2, mu3=tfp.mu3 / 2, a=1.5,
                               **fast)
    two_d = study.definitions()["2d"]
    two_d["variations"] = {"building.isolator": [study.isolator_table(b) for b in (tfp, rate)]}
    run_suites("tfp velocity", {"2d": two_d}, folder)
    table = load_table(f"{folder}/2d")
    rate_runs = table["building.isolator"].map(lambda v: "mu1_fast" in str(v))
    forces = table[[c for c in table.columns if c.startswith("peak_impact_force_")]]
    print(f"\n{'TFP friction':>16} {'runs':>5} {'median u [in]':>14} {'P(pounding)':>12} "
          f"{'median F [kip]':>15} {'median drift':>13} {'CPU [s]':>8}")
    for label, mask in (("constant", ~rate_runs), ("velocity-dep.", rate_runs)):
        t = table[mask]
        pounded = t.groupby("record_id")["pounding"].any()
        force = forces[mask].astype(float).max(axis=1).groupby(t["record_id"]).max()
        median_force = float(np.median(force[pounded[pounded].index])) if pounded.any() else 0.0
        disp = t.groupby("record_id")["peak_base_displacement"].max()
        drift = t.groupby("record_id")["peak_drift_ratio"].max()
        cpu = float(t["cpu_seconds"].sum()) if "cpu_seconds" in t else float("nan")
        print(f"{label:>16} {len(t):5d} {float(np.median(disp)):14.3f} "
              f"{float(pounded.mean()):12.3f} {median_force:15.2f} "
              f"{float(np.median(drift)):13.4f} {cpu:8.1f}", flush=True)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-opensees", action="store_true")
    ap.add_argument("--twin-run", action="store_true")
    ap.add_argument("--suite", metavar="FOLDER")
    ap.add_argument("--suite-only", action="store_true", help="only the --suite table")
    ap.add_argument("--mce", action="store_true",
                    help="also far-field pairs 1, 5, 12 at the MCE on ark5 and Newmark")
    args = ap.parse_args(argv)
    if not args.suite_only:
        orbit_table(not args.no_opensees)
        runs_table()
        if args.twin_run:
            twin_run_table()
        if args.mce:
            mce_table()
    if args.suite:
        suite_table(args.suite)


if __name__ == "__main__":
    main()

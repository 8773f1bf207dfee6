"""The lead-rubber bearing's chord integration: accuracy against the substep rule, cost per trial,
and the OpenSees twin's convergence (printed).

1. Error in z of the Runge-Kutta rule (femoat.bearings.lead_rubber: substeps at most
   STEP·u_y/max(1, η/cap) and GRADE·|z|·u_y) over random plan chords (the committed z anywhere
   in the cap disk, 0.01-5 u_y long, every direction), against scipy's DOP853 at rtol 1e-13 with
   the end of unloading as an event; the kernels run as Python with STEP and GRADE changed.
2. CPU per compiled plan trial on chords of 0.01-0.3 u_y (a dynamic step's size) from states
   on and inside the cap, for η = 1 (Runge-Kutta), η = 2 (closed form), and the friction
   pendulum's trial for comparison.
3. The 3D OpenSees twin (elastomericBearingBoucWen) on a circle of 120 chords, each cut into m
   backward-Euler steps: the error against this bearing and its rate.

Run: ``PYTHONPATH=. python benchmarks/lrb_bearing.py``.
"""

import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from test_bearing_lrb import (
    circle,
    converged_z,
    drive_plan,
    opensees_plan_forces,
    random_chord,
    refined,
)

from femoat.bearings import friction_pendulum as fp
from femoat.bearings import lead_rubber as lrb
from femoat.compilation.jit import njit

KERNELS = ("_z_path", "_segment", "_piece", "_rk_piece", "_rk4", "_rates", "_unloading_end", "_phi",
           "_linear_piece", "_mobius_piece", "_line_piece", "_rate", "_hyper", "_atanc",
           "_log1pc", "_expc")


def python_z(bearing, s, ux, uy, step, grade):
    """z at the chord's end by the module's kernels run as Python with STEP, GRADE changed."""
    saved = {name: getattr(lrb, name) for name in (*KERNELS, "STEP", "GRADE")}
    try:
        for name in KERNELS:
            setattr(lrb, name, saved[name].py_func)
        lrb.STEP, lrb.GRADE = step, grade
        r = lrb._z_path(bearing.params(), s[0], s[1], s[2], s[3], s[0], s[1], 0.0, 0.0, ux, uy,
                           0.0, 0.0, 0.0)
    finally:
        for name, value in saved.items():
            setattr(lrb, name, value)
    return np.array(r[:2])


def accuracy(lines):
    lines.append("1. error in z of the Runge-Kutta rule (40 random plan chords, worst and median)")
    rng = np.random.default_rng(2)
    for bearing, name in ((lrb.LeadRubberBearing(), "eta = 1"),
                          (lrb.LeadRubberBearing(beta=0.8, gamma=0.2), "eta = 1, beta 0.8"),
                          (lrb.LeadRubberBearing(eta=3.0), "eta = 3")):
        chords = [random_chord(rng, bearing) for _ in range(40)]
        refs = [converged_z(bearing, *c) for c in chords]
        for step, grade in ((0.2, 0.1), (0.1, 0.1), (0.05, 0.1), (0.025, 0.1), (0.05, 1e9),
                            (0.05, 0.05)):
            errs = [np.max(np.abs(python_z(bearing, *c, step, grade) - r))
                    for c, r in zip(chords, refs)]
            tag = "none" if grade > 1e6 else f"{grade}"
            lines.append(f"   {name:18s} STEP {step:5.3f} GRADE {tag:5s}: worst {max(errs):.1e}, "
                         f"median {np.median(errs):.1e}")


@njit
def _trials(trial, p, states, ux, uy, vx, vy, tau, f, k, c):
    """Every step's trial in a compiled loop (start velocity (vy, vx): a curved path)."""
    total = 0.0
    for i in range(ux.size):
        trial(p, states[i], 0.0, 0.0, vy[i], vx[i], ux[i], uy[i], vx[i], vy[i], tau, f, k, c)
        total += f[0]
    return total


def cost(lines):
    lines.append("2. CPU per compiled plan trial (in a compiled loop over 1e5 chords of 0.01-0.3 "
                 "u_y, best of 3)")
    rng = np.random.default_rng(3)
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    yd = lrb.LeadRubberBearing().u_y  # the same displacement steps for all three
    n = 100_000
    states = np.zeros((n, 6))  # [u_c, z_c, ...] in both kinds' plan states
    rho = rng.uniform(0.0, 1.0, n) ** 0.3
    th = rng.uniform(0.0, 2.0 * np.pi, n)
    states[:, 2], states[:, 3] = rho * np.cos(th), rho * np.sin(th)
    length = yd * 10.0 ** rng.uniform(-2.0, math.log10(0.3), n)
    ph = rng.uniform(0.0, 2.0 * np.pi, n)
    ux, uy = length * np.cos(ph), length * np.sin(ph)
    vx, vy = ux / 0.01, uy / 0.01  # end velocity along the chord, start velocity across it
    for bearing, name, trial in (
            (lrb.LeadRubberBearing(), "lrb eta = 1", lrb.plan_trial),
            (lrb.LeadRubberBearing(eta=2.0), "lrb eta = 2", lrb.plan_trial),
            (lrb.LeadRubberBearing(eta=3.0), "lrb eta = 3", lrb.plan_trial),
            (fp.BidirectionalFrictionPendulum(), "friction pendulum", fp.plan_trial)):
        p = bearing.params()
        times = []
        for tau in (0.0, 0.01):  # the chord; a curved step of 0.01 s
            _trials(trial, p, states, ux, uy, vx, vy, tau, f, k, c)  # compile
            best = math.inf
            for _ in range(3):
                t0 = time.process_time()
                _trials(trial, p, states, ux, uy, vx, vy, tau, f, k, c)
                best = min(best, time.process_time() - t0)
            times.append(best / n * 1e9)
        lines.append(f"   {name:18s}: {times[0]:.0f} ns per chord trial, {times[1]:.0f} ns per "
                     "curved step")


def opensees(lines):
    lines.append("3. OpenSees elastomericBearingBoucWen, circle r = 3 in, 120 chords, m steps each")
    try:
        from femoat.opensees.available import import_opensees

        ops = import_opensees()
    except ImportError as exc:
        lines.append(f"   skipped: {exc}")
        return
    for bearing, name in ((lrb.LeadRubberBearing(), "eta = 1"),
                          (lrb.LeadRubberBearing(eta=2.0), "eta = 2")):
        u = circle(3.0, 120, cycles=2)
        ours = drive_plan(bearing, u)[0]
        prev = None
        for m in (1, 2, 4, 8, 16):
            theirs = opensees_plan_forces(ops, bearing, refined(u, m, np.zeros(2)))[m - 1::m]
            err = np.max(np.abs(theirs - ours))
            rate = f", rate {math.log2(prev / err):.2f}" if prev else ""
            lines.append(f"   {name}: m = {m:2d}: max |f - f_OpenSees| = {err:.3e} kip{rate}")
            prev = err


def main():
    lines = [f"lrb_bearing.py, {time.strftime('%Y-%m-%d')}"]
    accuracy(lines)
    cost(lines)
    opensees(lines)
    print("\n".join(lines))


if __name__ == "__main__":
    main()

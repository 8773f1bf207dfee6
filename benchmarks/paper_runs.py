"""Benchmark the 10 paper runs: CPU time, steps, Newton iterations, and accuracy against the same
run at a 10× stricter tolerance. Also the start-up time of a second process (numba cache).

    python benchmarks/paper_runs.py [--rtol 1e-5] [--damping published|consistent]

Prints a table; nothing is asserted (speed is measured here, never in tests).
"""

import argparse
import subprocess
import sys
import time

from femoat.integration import Integrator
from femoat.paper import LAWS, WALLS, paper_model, paper_motion
from femoat.run import run


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rtol", type=float, default=Integrator().rtol)
    ap.add_argument("--damping", default="published")
    ap.add_argument("--repeat", type=int, default=5, help="timing repetitions (best of)")
    args = ap.parse_args(argv)

    motion = paper_motion()
    run(paper_model("concrete", "H"), motion)  # compile / load the numba cache first
    head = (f"{'wall':9s}{'law':4s}{'cpu [ms]':>9s}{'steps':>7s}{'newton':>8s}{'rej':>5s}"
            f"{'F_peak [kip]':>13s}{'err F':>9s}{'err u_b':>9s}{'err w':>9s}{'E resid':>9s}")
    print(f"paper runs at rtol = {args.rtol:g} vs rtol = {args.rtol / 10:g}, C_imp "
          f"{args.damping}; CPU = best of {args.repeat}")
    print(head)
    worst = 0.0
    for wall in WALLS:
        for law in LAWS:
            model = paper_model(wall, law, args.damping)
            best, res = float("inf"), None
            for _ in range(args.repeat):
                r = run(model, motion, Integrator(rtol=args.rtol))
                best = min(best, r.meta["stats"]["cpu_seconds"])
                res = r
            ref = run(model, motion, Integrator(rtol=args.rtol / 10))
            p, q = res.peaks, ref.peaks
            errs = [abs(p[k] / q[k] - 1) for k in ("peak_impact_force", "peak_base_displacement",
                                                    "peak_wall_displacement")]
            worst = max(worst, errs[0])
            st = res.meta["stats"]
            print(f"{wall:9s}{law:4s}{best * 1e3:9.1f}{st['steps']:7d}{st['newton_iterations']:8d}"
                  f"{st['rejected_error'] + st['rejected_newton']:5d}{p['peak_impact_force']:13.3f}"
                  f"{errs[0]:9.1e}{errs[1]:9.1e}{errs[2]:9.1e}{p['energy_residual']:9.1e}")
    print(f"largest peak-force change against the 10x stricter run: {worst:.2e}")

    # A second process: the whole start (interpreter, imports, kernels from numba's on-disk
    # cache, one paper run).
    code = ("import time, sys; t = time.perf_counter(); from femoat.paper import paper_model, "
            "paper_motion; from femoat.run import run; "
            "r = run(paper_model('steel', 'J'), paper_motion()); "
            "print(time.perf_counter() - t)")
    best = None
    for _ in range(3):
        t0 = time.perf_counter()
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                             check=True)
        total = time.perf_counter() - t0
        if best is None or total < best[0]:
            best = (total, float(out.stdout.split()[-1]))
    print(f"second process, numba's cache: {best[0]:.2f} s from process start to a finished "
          f"paper run (imports + run {best[1]:.2f} s; best of 3)")


if __name__ == "__main__":
    main()

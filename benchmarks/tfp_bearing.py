"""The triple friction-pendulum bearing's series solve: Newton iterations per trial and the cost
of a trial, against the single friction pendulum's, in a compiled loop.

    python benchmarks/tfp_bearing.py [--points 20000] [--repeat 5]

Paths (the typical bearing, ``TripleFrictionPendulum()``), each point a trial then a commit:

* one axis, a random history with reversals through every regime and the restrainers;
* plan, a random walk (steps of 0.05 in, kept within the capacity);
* plan, circular orbits of 4 and 31 in (regimes II and IV), 2000 points per turn;
* plan, one step from rest to points past every transition (the robustness of a large step).

Prints, per path: the Newton iterations per solve (mean, largest; a solve that had not
converged would give a NaN force, counted), and the CPU per trial + commit in a compiled loop,
with the single friction pendulum's plan kernels on the same path for scale.
"""

import argparse
import time

import numpy as np

from femoat.bearings import friction_pendulum as fp
from femoat.bearings import triple_friction_pendulum as tfp
from femoat.compilation.jit import njit


@njit(cache=True)
def _drive_tfp(p, s, path, iterations, forces):
    for i in range(path.shape[0]):
        r = tfp.series_solve(p, s, path[i, 0], path[i, 1])
        iterations[i] = r[17]
        forces[i] = r[0]
        tfp.plan_commit(p, s, 0.0, 0.0, 0.0, 0.0, path[i, 0], path[i, 1], 0.0, 0.0, 0.0)


@njit(cache=True)
def _drive_fp(p, s, path, forces, f, k, c):
    for i in range(path.shape[0]):
        fp.plan_trial(p, s, 0.0, 0.0, 0.0, 0.0, path[i, 0], path[i, 1], 0.0, 0.0, 0.0, f, k, c)
        forces[i] = f[0]
        fp.plan_commit(p, s, 0.0, 0.0, 0.0, 0.0, path[i, 0], path[i, 1], 0.0, 0.0, 0.0)


def paths(points, capacity, rng):
    one_axis, u, sign = [], 0.0, 1.0
    while len(one_axis) < points:
        for du in sign * rng.uniform(0.05, 1.0, int(rng.integers(1, 80))) * 0.2:
            if abs(u + du) > 1.005 * capacity:
                break
            u += du
            one_axis.append((u, 0.0))
        sign = -sign
    walk = np.cumsum(rng.normal(0.0, 0.05, (points, 2)), axis=0)
    norm = np.hypot(*walk.T)
    walk *= np.minimum(1.0, 0.98 * capacity / np.maximum(norm, 1e-300))[:, None]
    out = {"one axis, random": np.array(one_axis[:points]), "plan, random walk": walk}
    for radius in (4.0, 31.0):
        n = 2000
        approach = np.column_stack([np.linspace(0, radius, int(radius / 0.01) + 1)[1:],
                                    np.zeros(int(radius / 0.01))])
        phi = 2 * np.pi * np.arange(1, max(points - len(approach), n) + 1) / n
        out[f"plan, circle r = {radius:g} in"] = np.vstack(
            [approach, radius * np.column_stack([np.cos(phi), np.sin(phi)])])
    return out


def main(points, repeat):
    b = tfp.TripleFrictionPendulum()
    single = fp.BidirectionalFrictionPendulum()
    rng = np.random.default_rng(1)
    print(f"{'path':28s} {'points':>7s} {'iter mean':>9s} {'iter max':>8s} {'NaN':>4s} "
          f"{'TFP us/pt':>9s} {'FP us/pt':>8s}")
    for name, path in paths(points, b.capacity, rng).items():
        path = np.ascontiguousarray(path)
        iterations, forces = np.zeros(len(path)), np.zeros(len(path))
        best_tfp = best_fp = np.inf
        for _ in range(repeat):
            s = b.initial_state()
            t0 = time.process_time()
            _drive_tfp(b.params(), s, path, iterations, forces)
            best_tfp = min(best_tfp, time.process_time() - t0)
            s1, f1 = single.initial_state(), np.zeros(len(path))
            f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
            t0 = time.process_time()
            _drive_fp(single.params(), s1, path, f1, f, k, c)
            best_fp = min(best_fp, time.process_time() - t0)
        print(f"{name:28s} {len(path):7d} {iterations.mean():9.2f} {iterations.max():8.0f} "
              f"{int(np.isnan(forces).sum()):4d} {1e6 * best_tfp / len(path):9.2f} "
              f"{1e6 * best_fp / len(path):8.2f}")
    p = b.params()
    worst = 0
    for u in np.linspace(0.01, 1.01 * b.capacity, 400):
        for angle in np.linspace(0.0, np.pi / 2, 7):
            r = tfp.series_solve(p, b.initial_state(), u * np.cos(angle), u * np.sin(angle))
            assert np.isfinite(r[0])
            worst = max(worst, int(r[17]))
    print(f"one step from rest to 0.01 ... {1.01 * b.capacity:.1f} in, 7 directions: "
          f"at most {worst} Newton iterations")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=20000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    main(args.points, args.repeat)

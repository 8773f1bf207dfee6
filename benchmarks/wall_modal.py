"""Time modal extraction (10 modes) of the three wall models. A script, not a test.

    python benchmarks/wall_modal.py

Targets on a 2-core machine: 3D quadratic-hex wall of ~30k DOFs < 10 s (assembly + modes);
beam and 2D models < 0.5 s. BLAS is pinned to one thread (tiny and sparse work thrashes a
threaded BLAS), as in the tests.
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import time  # noqa: E402


def _time(label, build, n_modes=10, repeat=3):
    from femoat.walls.fe.modal import modal_analysis

    best = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        model = build()
        t1 = time.perf_counter()
        result = modal_analysis(model, n_modes)
        t2 = time.perf_counter()
        if best is None or t2 - t0 < best[0]:
            best = (t2 - t0, t1 - t0, t2 - t1)
    total, assemble, modes = best
    print(f"{label:<34s} {model.n_dofs:>7d} DOFs  assemble {assemble:6.3f} s  modes {modes:6.3f} s"
          f"  total {total:6.3f} s  f1 = {result.frequencies[0]:.3f} Hz")
    return total


def main():
    from femoat.walls.fe.beam import beam_model
    from femoat.walls.fe.geometry import WallGeometry
    from femoat.walls.fe.materials import concrete
    from femoat.walls.fe.plane_stress import plane_model
    from femoat.walls.fe.solid import solid_model

    wall = WallGeometry(height=86.0, length=48.0, thickness=3.25, material=concrete(),
                        impact_height=84.0, impact_patch=4.0)
    print("wall: H 86 in, L 48 in, t 3.25 in, concrete; best of 3 runs")
    beam = _time("beam, 40 Hermite elements", lambda: beam_model(wall, n_height=40))
    plane = _time("plane stress, 2 x 40 Q2 quads", lambda: plane_model(wall, 40, 2))
    solid = _time("solid, 2 x 16 x 30 Hex2", lambda: solid_model(wall, 30, 16, 2), repeat=1)
    print(f"targets: beam {beam:.3f} s < 0.5 s: {beam < 0.5}; 2D {plane:.3f} s < 0.5 s: "
          f"{plane < 0.5}; 3D {solid:.2f} s < 10 s: {solid < 10}")


if __name__ == "__main__":
    main()

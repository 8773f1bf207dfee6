"""What lazy evaluation saves: measured, not asserted.

    python benchmarks/lazy.py

1. Wall DOFs eliminated separately while no contact carries force (exact), for the paper's SDOF
   walls and for 10- and 20-mode finite-element walls.
2. Recording only the requested channels, and decimating the open phase.
3. Only as many wall modes as contribute: automatic N against a fixed large N.
"""

import time

import numpy as np

from femoat.integration import Integrator
from femoat.integration.solve import solve
from femoat.paper import paper_model, paper_motion
from femoat.run import run
from femoat.structure.pounding import MoatWall, PoundingModel


def best_cpu(fn, repeat=5):
    best = float("inf")
    out = None
    for _ in range(repeat):
        t0 = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t0)
    return best, out


def modal_model(n_modes):
    from femoat.walls.fe import beam_model, load_geometry
    from femoat.walls.modal import ModalWall

    geom = load_geometry("meshes/concrete_wall.toml")
    sdof = paper_model("concrete", "H").walls[0]
    xi = sdof.wall.damping_ratio
    wall = ModalWall.from_fe(beam_model(geom), n_modes=n_modes, damping_ratio=xi)
    base = paper_model("concrete", "H")
    return PoundingModel(base.building, tuple(MoatWall(w.law, wall, w.gap, w.side)
                                              for w in base.walls)), wall


def main():
    gm = paper_motion()
    dur = gm.duration + 2.0
    run(paper_model("concrete", "H"), gm)  # warm the numba cache
    print("1. lazy wall elimination (CPU ms, best of 5; identical results)")
    print(f"{'walls':28s}{'DOFs':>6s}{'lazy':>9s}{'full':>9s}{'saved':>8s}")
    cases = [("paper SDOF walls", paper_model("concrete", "H"))]
    for n in (10, 20):
        try:
            cases.append((f"{n}-mode beam walls", modal_model(n)[0]))
        except Exception as exc:  # an FE wall needs the meshes/ folder
            print(f"   ({n}-mode walls skipped: {exc})")
    for name, model in cases:
        packed = model.pack()
        t_lazy, a = best_cpu(lambda: solve(packed, gm.accel, gm.dt, dur, Integrator(), lazy=True))
        t_full, b = best_cpu(lambda: solve(packed, gm.accel, gm.dt, dur, Integrator(), lazy=False))
        assert np.allclose(a.arrays["contact_force"].max(0), b.arrays["contact_force"].max(0),
                           rtol=1e-8)
        print(f"{name:28s}{packed.n:6d}{t_lazy * 1e3:9.1f}{t_full * 1e3:9.1f}"
              f"{1 - t_lazy / t_full:8.0%}")

    print("\n2. recorded channels and decimation (paper run, steel, H)")
    model = paper_model("steel", "H")
    for label, ch, every in (("all channels, every step", None, 1),
                             ("displacement + contacts", ("displacement", "contacts"), 1),
                             ("displacement + contacts, every 10th", ("displacement", "contacts"), 10)):
        t, r = best_cpu(lambda: run(model, gm, Integrator(record_every=every), channels=ch))
        nbytes = sum(a.nbytes for a in r.arrays.values())
        print(f"   {label:38s} {t * 1e3:6.1f} ms  {r.time.size:6d} rows  {nbytes / 1e6:6.2f} MB"
              f"  peak F {r.peaks['peak_impact_force']:.4f} kip")

    print("\n3. wall modes: automatic N vs fixed N (concrete beam wall, H law)")
    try:
        from femoat.walls.fe import beam_model, load_geometry
        from femoat.walls.modal import ModalWall, contact_time

        geom = load_geometry("meshes/concrete_wall.toml")
        for n in (None, 40):
            base = paper_model("concrete", "H")
            law = base.walls[0].law
            # the impacting body is the heavy base mat: the reduced mass is about the wall's M1
            t_c = contact_time(law, mass=base.pack().M[0, 0], wall_mass=base.walls[0].wall.mass)
            kw = dict(n_modes=n) if n else dict(contact_duration=t_c)
            wall = ModalWall.from_fe(beam_model(geom), damping_ratio=base.walls[0].wall.damping_ratio,
                                     computed_modes=48, **kw)
            m = PoundingModel(base.building, tuple(MoatWall(w.law, wall, w.gap, w.side)
                                                   for w in base.walls))
            t, r = best_cpu(lambda: run(m, gm), repeat=3)
            print(f"   N = {len(wall.modal_masses):3d} ({'automatic' if n is None else 'fixed'}): "
                  f"{t * 1e3:7.1f} ms, peak F {r.peaks['peak_impact_force']:.3f} kip, "
                  f"peak wall {r.peaks['peak_wall_displacement']:.4f} in")
    except Exception as exc:
        print(f"   skipped: {exc}")


if __name__ == "__main__":
    main()

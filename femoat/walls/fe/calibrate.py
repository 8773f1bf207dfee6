"""Wall dimensions that reproduce a target SDOF wall (K1, M1), e.g. the paper's Table 3 walls.

The search runs on the beam model (milliseconds per evaluation): two free dimensions among
height, length and thickness are solved in log space (scipy.optimize.root) so that the
fundamental impact mode has K1 [kip/in] and M1 [kip·s²/in]. The impact point keeps the
template's distance below the wall top (the base mat sits at a fixed depth below the top).
Optionally the targets are corrected by a continuum model (secant iteration on the ratios
continuum/beam), so that the 2D or 3D wall, not the beam, hits them.

Scaling for a uniform cantilever hit near its top: M1 ≈ ρ·L·t·H/4 and K1 ≈ 3.09·E·L·t³/(12H³),
so at fixed length the solution is unique, and over lengths H ∝ L^(-1/3), t ∝ L^(-2/3).
"""

from dataclasses import dataclass

import numpy as np

from femoat.units import weight_to_mass
from femoat.walls.fe.beam import beam_model
from femoat.walls.fe.modal import modal_analysis

DIMENSIONS = ("height", "length", "thickness")


@dataclass(frozen=True)
class SdofTarget:
    """A target SDOF wall. K1 : float [kip/in]; M1 : float [kip·s²/in]."""

    K1: float
    M1: float
    name: str = "target"

    def __post_init__(self):
        if not (self.K1 > 0 and self.M1 > 0):
            raise ValueError(f"SdofTarget K1 [kip/in] and M1 [kip·s²/in] must be positive, got "
                             f"K1={self.K1!r}, M1={self.M1!r}")


PAPER_CONCRETE = SdofTarget(K1=2.4, M1=weight_to_mass(0.29), name="concrete")
"""Paper Table 3, concrete wall: K1 = 2.4 kip/in, M1·g = 0.29 kip."""
PAPER_STEEL = SdofTarget(K1=100.0, M1=weight_to_mass(0.41), name="steel")
"""Paper Table 3, steel wall: K1 = 100 kip/in, M1·g = 0.41 kip."""


def _trial(template, free, values):
    changes = {name: float(v) for name, v in zip(free, values)}
    below_top = template.height - template.impact_height
    height = changes.get("height", template.height)
    changes["impact_height"] = height - below_top
    return template.with_(**changes)


def _beam_sdof(geometry, n_height, timoshenko):
    r = modal_analysis(beam_model(geometry, n_height=n_height, timoshenko=timoshenko), 1)
    return r.K1, r.M1


def calibrate_beam(template, target, free=("height", "thickness"), n_height=40,
                   timoshenko=False):
    """The template with two ``free`` dimensions changed so the beam model has K1, M1 = target.

    template : WallGeometry  material, fixity, backfill, fixed dimensions, impact depth below top
    target : SdofTarget
    free : two of "height", "length", "thickness"
    """
    from scipy.optimize import root

    free = tuple(free)
    if len(free) != 2 or len(set(free)) != 2 or not set(free) <= set(DIMENSIONS):
        raise ValueError(f"free must name two different dimensions among {DIMENSIONS}, got {free!r}")
    x0 = np.log([getattr(template, name) for name in free])

    def residual(logx):
        K1, M1 = _beam_sdof(_trial(template, free, np.exp(logx)), n_height, timoshenko)
        return [np.log(K1 / target.K1), np.log(M1 / target.M1)]

    try:
        sol = root(residual, x0, method="hybr")
    except ValueError as err:  # a trial left the valid geometry (e.g. patch above the top)
        raise ValueError(f"calibration left the valid geometry ({err}); start from a template "
                         "closer to the target or free other dimensions") from None
    if not sol.success or np.max(np.abs(residual(sol.x))) > 1e-8:
        raise ValueError(f"no wall with free {free} reaches K1 = {target.K1:g} kip/in and "
                         f"M1 = {target.M1:.4g} kip*s^2/in from this template ({sol.message}); "
                         "free other dimensions or change the template")
    return _trial(template, free, np.exp(sol.x))


def calibrate(template, target, free=("height", "thickness"), refine_with=None, n_height=40,
              timoshenko=False, iterations=3, model_options=None):
    """Calibrate on the beam, then optionally correct the targets with a continuum model.

    refine_with : None or a continuum wall kind ("plane", "solid")  model whose K1, M1 should
        hit the target: each iteration re-targets the beam by the continuum/beam ratios (secant
        on a near-constant ratio, converging in 2-3 iterations)
    model_options : dict  mesh divisions passed to the continuum model
    Returns the calibrated WallGeometry.
    """
    geometry = calibrate_beam(template, target, free, n_height, timoshenko)
    if refine_with is None:
        return geometry
    build = _continuum(refine_with)
    beam_target = target
    for _ in range(iterations):
        K1b, M1b = _beam_sdof(geometry, n_height, timoshenko)
        r = modal_analysis(build(geometry, **(model_options or {})), 3)
        beam_target = SdofTarget(beam_target.K1 * target.K1 / r.K1,
                                 beam_target.M1 * target.M1 / r.M1, target.name)
        geometry = calibrate_beam(geometry, beam_target, free, n_height, timoshenko)
    return geometry


def _continuum(kind):
    from femoat.walls.kinds import registered

    row = next((k for k in registered() if k.name == kind), None)
    if row is None or row.dimension == 1:
        raise ValueError(f"refine_with = {kind!r}: refine with a continuum model ("
                         + ", ".join(repr(k.name) for k in registered() if k.dimension > 1)
                         + ") or None")
    return row.build


def write_wall(geometry, stem, model="solid", **mesh_options):
    """Write ``<stem>.vtu`` (the structured mesh of wall kind ``model``, with named boundaries)
    and ``<stem>.toml``."""
    from pathlib import Path

    from femoat.walls.fe.mesh_io import write_mesh
    from femoat.walls.kinds import registered, wall_kind

    stem = Path(stem)
    mesher = wall_kind(model).mesher
    if mesher is None:
        raise ValueError(f"model = {model!r} makes its own mesh: write a kind with a mesher ("
                         + ", ".join(repr(k.name) for k in registered() if k.mesher) + ")")
    mesh = mesher(geometry, **mesh_options)
    write_mesh(stem.with_suffix(".vtu"), mesh)
    geometry.save(stem.with_suffix(".toml"))
    return stem.with_suffix(".vtu"), stem.with_suffix(".toml")


def paper_walls(length=48.0, impact_patch=4.0, refine_with="solid"):
    """The paper's concrete and steel walls at a given length [in], impact patch at the top.

    The base mat (patch side ``impact_patch`` [in]) hits the top edge of the wall: the patch
    spans z = [H - patch, H]. Returns {"concrete": WallGeometry, "steel": WallGeometry}.
    """
    from femoat.walls.fe.geometry import WallGeometry
    from femoat.walls.fe.materials import concrete, steel

    walls = {}
    for target, material, guess in ((PAPER_CONCRETE, concrete(), (86.0, 3.2)),
                                     (PAPER_STEEL, steel(), (43.0, 2.8))):
        template = WallGeometry(height=guess[0], length=length, thickness=guess[1],
                                material=material, impact_height=guess[0] - impact_patch / 2,
                                impact_patch=impact_patch)
        walls[target.name] = calibrate(template, target, refine_with=refine_with)
    return walls


def main():
    """Calibrate the paper's walls, print them with their modes, write meshes/*_wall.*."""
    from femoat.units import G
    from femoat.walls.kinds import registered

    for name, g in paper_walls().items():
        print(f"{name}: H = {g.height:.2f} in, L = {g.length:.1f} in, t = {g.thickness:.3f} in, "
              f"impact at z = {g.impact_height:.2f} in (patch {g.impact_patch:g} in)")
        for kind in registered():
            r = modal_analysis(kind.build(g), 6)
            print(f"  {kind.name:<6s} K1 = {r.K1:8.3f} kip/in  M1*g = {r.M1 * G:.4f} kip  "
                  f"static k = {r.static_stiffness:8.3f} kip/in  f = "
                  + ", ".join(f"{f:.1f}" for f in r.frequencies) + " Hz")
        print("  written:", *write_wall(g, f"meshes/{name}_wall"))


if __name__ == "__main__":
    main()

"""A rectangular moat in plan: up to four walls, +x, −x, +y, −y, each with its own contact.

A wall is named by its outward normal n seen from the base mat: the "+x" wall stands at +gap
along x and is hit when the base mat moves toward +x. Along its normal each wall is the 1D
Masroor chain of :class:`femoat.structure.pounding.MoatWall` (gap, contact law, wall model),
with the indentation δ = n·u_base − gap − Σ φ_i·q_i [in] (the wall's modal coordinates q_i
positive away from the building) and the contact force pushing the base mat along −n.

Wall friction: a Coulomb coefficient μ_w [-] (default 0: frictionless walls, the 1D model) that,
while the wall is in contact with normal force F_n, resists the base mat's sliding along the
wall, t = (−n_y, n_x), with a force of magnitude at most μ_w·F_n. It is part of the model
description; the OpenSees twin has no counterpart and refuses μ_w > 0.

Order: a moat's walls are kept in :data:`SIDES` order (+x, −x, +y, −y), the order of every
per-wall array (docs/plan.md §2).
"""

from femoat.contact.laws import make_law
from femoat.structure.pounding import SIDES, MoatWall, wall_side
from femoat.walls.presets import wall_preset

PlanWall = MoatWall
"""A moat wall in plan: the one wall class, :class:`femoat.structure.pounding.MoatWall` (its side a
normal, "+x", "-x", "+y" or "-y"; its wall friction)."""

__all__ = ["SIDES", "PlanWall", "rectangular_moat", "wall_side"]


def rectangular_moat(preset="concrete", law="H", gap=4.0, damping="published", friction=0.0,
                     sides=SIDES):
    """Walls of one paper preset and one contact law on the given sides (default all four).

    Parameters
    ----------
    preset : str
        "concrete" or "steel" (the paper's Table 3, :func:`femoat.walls.wall_preset`).
    law : str
        Contact law letter or name (E, V, J, H, M); default Hertzdamp, as the scenario files.
    gap : float
        Clearance on every side [in], >= 0 (the paper's 4 in by default).
    damping : str
        "published" or "consistent" C_imp (:func:`femoat.walls.wall_preset`).
    friction : float
        Wall friction coefficient μ_w [-] on every side (module docstring).
    sides : iterable of str
        The walls to build, from :data:`SIDES`.
    """
    walls_preset = wall_preset(preset, damping=damping)
    contact = make_law(law, walls_preset.contact)
    return tuple(PlanWall(contact, walls_preset.wall, gap, side, friction) for side in sides)

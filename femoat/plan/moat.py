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

import math
from dataclasses import dataclass

from femoat.contact.laws import ContactLaw, make_law
from femoat.structure.pounding import MoatWall, wall_modes
from femoat.walls.presets import wall_preset

SIDES = ("+x", "-x", "+y", "-y")
"""The four walls, named by their outward normal, in the order of every per-wall array."""

_NORMALS = {"+x": (1.0, 0.0), "-x": (-1.0, 0.0), "+y": (0.0, 1.0), "-y": (0.0, -1.0)}
_TYPOGRAPHIC = str.maketrans({"\u2212": "-", "\u2013": "-"})  # "−x" (minus sign) reads as "-x"


def wall_side(side):
    """The canonical name ("+x", "-x", "+y" or "-y") of a wall side; a ValueError names the
    four."""
    name = side.strip().translate(_TYPOGRAPHIC).lower() if isinstance(side, str) else side
    if name not in _NORMALS:
        raise ValueError(f"side = {side!r} is not a moat wall: use one of '+x', '-x', '+y', '-y' "
                         "(the wall's outward normal seen from the base mat).")
    return name


@dataclass(frozen=True)
class PlanWall:
    """One wall of a rectangular moat and its contact.

    Parameters
    ----------
    law : ContactLaw
        The contact law between base mat and wall (along the wall's normal).
    wall : SdofWall or ModalWall
        The wall behind the contact spring (femoat.walls), moving along its normal.
    gap : float
        Clearance between base mat and wall at rest [in], >= 0.
    side : str
        "+x", "-x", "+y" or "-y": the wall's outward normal seen from the base mat.
    friction : float
        Coulomb coefficient μ_w [-] >= 0 of the base mat sliding along the wall while in contact
        (tangential force at most μ_w times the contact force); 0 (default) is frictionless.
    """

    law: ContactLaw
    wall: object
    gap: float = 4.0
    side: str = "+x"
    friction: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "side", wall_side(self.side))
        where = f"wall {self.side}"
        if not isinstance(self.law, ContactLaw):
            raise ValueError(f"{where}: law must be a ContactLaw (see femoat.contact.make_law).")
        try:
            wall_modes(self.wall)
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from None
        if not (isinstance(self.gap, (int, float)) and math.isfinite(self.gap) and self.gap >= 0):
            raise ValueError(f"{where}: gap = {self.gap!r} must be a clearance >= 0 [in] (the "
                             "distance from the base mat to the wall at rest).")
        if not (isinstance(self.friction, (int, float)) and math.isfinite(self.friction)
                and self.friction >= 0):
            raise ValueError(f"{where}: friction = {self.friction!r} must be a Coulomb "
                             "coefficient >= 0 [-] (0 for a frictionless wall).")

    @property
    def normal(self):
        """Outward normal n = (n_x, n_y) [-] seen from the base mat."""
        return _NORMALS[self.side]

    @property
    def tangent(self):
        """Direction along the wall t = (−n_y, n_x) [-] (n turned by +90°)."""
        nx, ny = self.normal
        return (-ny, nx)

    @property
    def axis(self):
        """0 for a wall normal to x (+x, −x), 1 for one normal to y."""
        return 0 if self.side[1] == "x" else 1

    @property
    def sign(self):
        """+1 for the wall at +gap along its axis, −1 for the one at −gap."""
        return 1 if self.side[0] == "+" else -1

    def uniaxial(self):
        """This wall along its axis: the 1D :class:`~femoat.structure.pounding.MoatWall`
        (friction dropped: nothing slides along a wall in a 1D model)."""
        return MoatWall(self.law, self.wall, self.gap, self.sign)


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

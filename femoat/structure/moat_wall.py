"""A moat wall: its contact law, the wall behind it, its gap and side, and the wall's modes.

Sign convention: a wall is named by its outward normal n seen from the base mat ("+x", "-x",
"+y", "-y"); the "+x" wall stands at +gap along x. A wall's DOFs are its modal coordinates (one
for the SDOF wall), each positive away from the building along n, so that the indentation is
δ = n·u_base − gap − Σ φ_i·q_i [in] and a positive contact force pushes the base mat back and
the wall away. Wall masses feel the ground acceleration. A 1D model's walls are its "+x" and
"-x" walls (side +1 and −1: at +gap and −gap along its axis).
"""

import math
from dataclasses import dataclass

import numpy as np

from femoat.contact.laws import ContactLaw
from femoat.walls.modal import ModalWall
from femoat.walls.sdof import SdofWall


def wall_modes(wall):
    """(masses [kip·s²/in], stiffnesses [kip/in], dampings [kip·s/in], φ at impact [-],
    ground participation L_i = φ_iᵀ·M·ι [kip·s²/in]) of a wall's modes."""
    if isinstance(wall, SdofWall):
        wall = ModalWall.from_sdof(wall)  # the paper's wall is a one-mode modal wall
    try:
        return (np.asarray(wall.modal_masses, float), np.asarray(wall.modal_stiffnesses, float),
                np.asarray(wall.modal_dampings, float), np.asarray(wall.impact_shape, float),
                np.asarray(wall.ground_participation, float))
    except AttributeError:
        raise ValueError("wall must be an SdofWall or a modal wall (see femoat.walls).") from None


SIDES = ("+x", "-x", "+y", "-y")
"""The four walls of a moat, named by their outward normal seen from the base mat, in the order
of every per-wall array of a plan model."""

_NORMALS = {"+x": (1.0, 0.0), "-x": (-1.0, 0.0), "+y": (0.0, 1.0), "-y": (0.0, -1.0)}
_TANGENTS = {"+x": (0.0, 1.0), "-x": (0.0, -1.0), "+y": (-1.0, 0.0), "-y": (1.0, 0.0)}
"""Each side's t = (−n_y, n_x), written out: no component is a negative zero (a 1D
pack's slip rows are then zeros to the bit)."""
_TYPOGRAPHIC = str.maketrans({"\u2212": "-", "\u2013": "-"})  # "−x" (minus sign) reads as "-x"
_SIGNED = {1: "+x", -1: "-x"}  # a 1D model's sides: +1 and −1 along its axis


def wall_side(side):
    """The canonical name ("+x", "-x", "+y" or "-y") of a wall side; +1 and −1 (a 1D model's
    walls at +gap and −gap) are "+x" and "-x". A ValueError names the choices."""
    if isinstance(side, str):
        name = side.strip().translate(_TYPOGRAPHIC).lower()
    elif isinstance(side, int) and not isinstance(side, bool) and side in _SIGNED:
        name = _SIGNED[side]
    else:
        name = side
    if name not in _NORMALS:
        raise ValueError(f"side = {side!r} is not a moat wall: use one of '+x', '-x', '+y', '-y' "
                         "(the wall's outward normal seen from the base mat; +1 and -1 are "
                         "'+x' and '-x').")
    return name


@dataclass(frozen=True)
class MoatWall:
    """One moat wall and its contact, in a 1D model (its walls at ±gap along x) or in plan (a
    rectangular moat's).

    Parameters
    ----------
    law : ContactLaw
        The contact law between base mat and wall (along the wall's normal).
    wall : SdofWall or modal wall
        The wall behind the contact spring (femoat.walls), moving along its normal.
    gap : float
        Clearance between base mat and wall at rest [in], >= 0.
    side : str or int
        The wall's outward normal seen from the base mat: "+x", "-x", "+y" or "-y"; +1 and −1
        (the wall at +gap and at −gap of a 1D model) are "+x" and "-x". Kept as the name.
    friction : float
        Coulomb coefficient μ_w [-] >= 0 of the base mat sliding along the wall while in contact
        (tangential force at most μ_w times the contact force; a plan model's: nothing slides
        along a wall in a 1D model); 0 (default) is frictionless.
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
        return _TANGENTS[self.side]

    @property
    def axis(self):
        """0 for a wall normal to x (+x, −x), 1 for one normal to y."""
        return 0 if self.side[1] == "x" else 1

    @property
    def sign(self):
        """+1 for the wall at +gap along its axis, −1 for the one at −gap."""
        return 1 if self.side[0] == "+" else -1

    def uniaxial(self):
        """This wall in a 1D model along its axis (the model's axis is its x): "+x" or "-x" by
        its sign, friction dropped (nothing slides along a wall in a 1D model)."""
        return MoatWall(self.law, self.wall, self.gap, self.sign)

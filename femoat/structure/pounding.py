"""A building and its moat walls: the model the time-stepping solver integrates.

Sign convention: all DOFs are horizontal displacements relative to the ground, positive in +x.
A wall on side +1 stands at +gap; on side −1 at −gap. A wall's DOFs are its modal coordinates
(one for the SDOF wall), each positive in the direction away from the building, so that the
indentation is δ = side·u_base − gap − Σ φ_i·q_i and a positive contact force pushes the base mat
back and the wall away. Wall masses feel the ground acceleration.
"""

import math
from dataclasses import dataclass

import numpy as np

from femoat.contact.kernels import N_HISTORY, N_PARAMS
from femoat.contact.laws import ContactLaw
from femoat.structure.building import Building
from femoat.structure.roles import ISOLATOR, STORY, Role
from femoat.units import G
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
        """This wall in a 1D model along its axis (the model's axis is its x): "+x" or "-x" by
        its sign, friction dropped (nothing slides along a wall in a 1D model)."""
        return MoatWall(self.law, self.wall, self.gap, self.sign)


@dataclass(frozen=True)
class PoundingModel:
    """A building with zero, one or two moat walls."""

    building: Building
    walls: tuple = ()

    def __post_init__(self):
        for w in self.walls:
            if not isinstance(w, MoatWall):
                raise ValueError("walls must be MoatWall entries (femoat.structure.pounding).")
            if w.axis != 0 or w.friction != 0.0:
                raise ValueError(f"wall {w.side}: a 1D model's walls stand at ±gap along its "
                                 "axis (side +1 or -1, '+x' or '-x') without wall friction; "
                                 "walls normal to y, or friction along a wall, need a plan model "
                                 "(femoat.plan).")
        sides = [w.side for w in self.walls]
        if len(set(sides)) != len(sides):
            raise ValueError("walls: at most one wall per side (+1 and −1).")

    def dof_names(self):
        names = ["base"] + [f"floor{k + 1}" for k in range(len(self.building.floor_weights))]
        for w in self.walls:
            tag = "pos" if w.sign > 0 else "neg"
            nm = len(wall_modes(w.wall)[0])
            names += [f"wall_{tag}"] if nm == 1 else [f"wall_{tag}_mode{i + 1}" for i in range(nm)]
        return names

    def pack(self):
        """Arrays for the compiled loop (see :mod:`femoat.integration.driver`)."""
        b = self.building
        nf = len(b.floor_weights)
        n_struct = 1 + nf
        modes = [wall_modes(w.wall) for w in self.walls]
        n = n_struct + sum(len(m[0]) for m in modes)
        M = np.zeros((n, n))
        C = np.zeros((n, n))
        K = np.zeros((n, n))
        r = np.zeros(n)
        weights = [b.base_weight, *b.floor_weights]
        for i, w in enumerate(weights):
            M[i, i] = w / G
            r[i] = w / G
        # story dashpots c = β·k0 between floor k and the one below
        beta = b.story_damping_beta
        for k, mat in enumerate(b.stories):
            c = beta * mat.initial_stiffness
            i, j = k + 1, k
            C[i, i] += c
            C[j, j] += c
            C[i, j] -= c
            C[j, i] -= c
        # P-Delta: the geometric stiffness −P/h of each story, a linear spring in K
        for k, kg in enumerate(b.geometric_stiffnesses()):
            i, j = k + 1, k
            K[i, i] += kg
            K[j, j] += kg
            K[i, j] -= kg
            K[j, i] -= kg
        # nonlinear elements: isolator (base–ground), stories
        elements = []
        if b.isolator is not None:
            elements.append((0, -1, b.isolator, Role(ISOLATOR)))
        for k, mat in enumerate(b.stories):
            elements.append((k + 1, k, mat, Role(STORY, k + 1)))
        # walls: modal DOFs and contacts
        contacts = []
        col = n_struct
        for w, (mm, kk, cc, phi, L) in zip(self.walls, modes):
            bvec = np.zeros(n)
            bvec[0] = w.sign
            for i in range(len(mm)):
                M[col, col] = mm[i]
                K[col, col] = kk[i]
                C[col, col] = cc[i]
                # the wall's modal coordinates point away from the building: ground load sign
                r[col] = L[i] * w.sign
                bvec[col] = -phi[i]
                col += 1
            contacts.append((bvec, w))
        return PackedModel(
            M=M, C=C, K=K, r=r, n_struct=n_struct, dof_names=self.dof_names(),
            story_heights=np.array(b.heights, dtype=float),
            el_i=np.array([e[0] for e in elements], dtype=np.int64),
            el_j=np.array([e[1] for e in elements], dtype=np.int64),
            el_code=np.array([e[2].code for e in elements], dtype=np.int64),
            el_P=_stack([e[2].params() for e in elements]),
            el_S=_stack([e[2].initial_state() for e in elements]),
            el_roles=tuple(e[3] for e in elements),
            el_materials=[e[2] for e in elements],
            c_B=np.array([c[0] for c in contacts]).reshape(len(contacts), n),
            c_gap=np.array([c[1].gap for c in contacts], dtype=float),
            c_code=np.array([c[1].law.code for c in contacts], dtype=np.int64),
            c_P=_stack([c[1].law.packed() for c in contacts], width=N_PARAMS),
            c_H=np.zeros((len(contacts), N_HISTORY)),
            c_names=["pos" if c[1].sign > 0 else "neg" for c in contacts],
            walls=self.walls,
        )


def _stack(rows, width=None):
    if not rows:
        return np.zeros((0, width or 1))
    w = max(len(r) for r in rows)
    out = np.zeros((len(rows), w))
    for i, row in enumerate(rows):
        out[i, : len(row)] = row
    return out


@dataclass
class PackedModel:
    """Plain arrays of a :class:`PoundingModel` (mutable copies: the loop updates states)."""

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    r: np.ndarray
    n_struct: int
    dof_names: list
    story_heights: np.ndarray
    el_i: np.ndarray
    el_j: np.ndarray
    el_code: np.ndarray
    el_P: np.ndarray
    el_S: np.ndarray
    el_roles: tuple
    """Each element's :class:`~femoat.structure.roles.Role` (isolator, story k)."""
    el_materials: list
    c_B: np.ndarray
    c_gap: np.ndarray
    c_code: np.ndarray
    c_P: np.ndarray
    c_H: np.ndarray
    c_names: list
    walls: tuple

    @property
    def n(self):
        return self.M.shape[0]

    @property
    def el_names(self):
        """Each element's name (``"isolator"``, ``"story1"``, ...), from its role."""
        return [role.name for role in self.el_roles]

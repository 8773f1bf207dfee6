"""A building and its moat walls: the model the time-stepping solver integrates.

Sign convention: all DOFs are horizontal displacements relative to the ground, positive in +x.
A wall on side +1 stands at +gap; on side −1 at −gap (the walls, their modal coordinates and the
indentation: :mod:`femoat.structure.moat_wall`). Wall masses feel the ground acceleration.
"""

from dataclasses import dataclass

import numpy as np

from femoat.contact.kernels import N_HISTORY, N_PARAMS
from femoat.structure.building import Building
from femoat.structure.moat_wall import (  # noqa: F401  (their home before)
    SIDES,
    MoatWall,
    wall_modes,
    wall_side,
)
from femoat.structure.roles import ISOLATOR, STORY, Role
from femoat.units import G


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

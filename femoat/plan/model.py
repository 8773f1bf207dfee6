"""The plan model: a :class:`~femoat.plan.building.PlanBuilding` in a rectangular moat.

The plan solver integrates this model; the OpenSees twin (:mod:`femoat.opensees.plan`) builds it
in 3D. Conventions (docs/plan.md §2): plan axes x, y, z up, kip, in, s; no torsion.

DOF layout (docs/plan.md §4), node-major: floor k (k = 0 the base mat, then floors bottom to
top) owns ``layout.floor_dofs[k] = (x, y, θ)``, indices into the state vector; θ = −1, since no
floor rotates in this issue (a later torsion model fills that column, nothing else moves). The
walls' modal coordinates follow, wall by wall in :data:`~femoat.plan.moat.SIDES` order, each
positive away from the building along the wall's normal. So n = 2·(floors + 1) + wall modes.

:meth:`PlanModel.pack` gives the plain arrays a solver needs, the 1D
:meth:`~femoat.structure.pounding.PoundingModel.pack` with every uniaxial element acting along a
direction in plan through a gather row b (deformation b·u):

* ``M``, ``C``, ``K`` (n, n): masses on x and y, story dashpots c = β·k0 and P-Delta −P/h per
  direction, the walls' modal masses, stiffnesses and dampings;
* ``R`` (n, 2): the ground load is −R·a_g with a_g = (a_x, a_y) [in/s²]: the masses on their
  axis, a wall mode's participation L_i along its normal (signed: the mode points away);
* uniaxial elements (stories, an Elastic isolator): DOFs i (top) and j (bottom, −1 the ground)
  on the element's axis (``el_axis`` 0 x, 1 y), material code, params, state, role;
* the plan bearing (a kind of :mod:`femoat.bearings`): ``bearing_kind``, ``bearing_dofs`` (the
  base mat's x, y), params and plan state, one row (none when the isolator is an Elastic spring
  or None);
* contacts, one row per wall: ``c_B`` (δ = c_B·u − gap, n at the base mat and −φ_i on the
  wall's modes), ``c_T`` (the base mat's slip along the wall, t at the base mat), gap, law
  code, params, history, friction coefficient, side.
"""

from dataclasses import dataclass, field

import numpy as np

from femoat.contact.kernels import N_HISTORY, N_PARAMS
from femoat.bearings import registry as bearing_registry
from femoat.plan.building import AXES, PlanBuilding
from femoat.plan.moat import SIDES, PlanWall, rectangular_moat
from femoat.structure.pounding import PoundingModel, _stack, wall_modes
from femoat.structure.roles import ISOLATOR, STORY, Role
from femoat.units import G


@dataclass(frozen=True, eq=False)
class PlanLayout:
    """Where each DOF of a plan model sits in the state vector (module docstring).

    floor_dofs : array (floors + 1, 3) of int  (x, y, θ) per floor, base mat first; θ = −1
    wall_dofs : tuple of tuple of int  each wall's modal DOFs, in the model's wall order
    names : tuple of str  one per DOF: "base_x", "floor1_y", "wall_+x", "wall_-y_mode2", ...
    """

    floor_dofs: np.ndarray
    wall_dofs: tuple
    names: tuple

    @property
    def n(self):
        """Number of DOFs."""
        return len(self.names)

    @property
    def n_struct(self):
        """Number of building DOFs (the floors' translations), the first ones."""
        return 2 * self.floor_dofs.shape[0]


@dataclass(frozen=True)
class PlanModel:
    """A plan building and the walls of its rectangular moat.

    Parameters
    ----------
    building : PlanBuilding
        Default: the paper's building in both directions.
    walls : tuple of PlanWall
        At most one wall per side, kept in the order +x, −x, +y, −y whatever the order given;
        default: the paper's concrete wall with the Hertzdamp law and the 4 in gap on all four
        sides (:func:`~femoat.plan.moat.rectangular_moat`); ``()`` for no moat.
    """

    building: PlanBuilding = field(default_factory=PlanBuilding)
    walls: tuple = field(default_factory=rectangular_moat)

    def __post_init__(self):
        if not isinstance(self.building, PlanBuilding):
            raise ValueError("building must be a PlanBuilding (femoat.plan); "
                             "PlanBuilding.from_building turns a 1D Building into one.")
        walls = tuple(self.walls)
        for w in walls:
            if not isinstance(w, PlanWall):
                raise ValueError("walls must be PlanWall entries (femoat.plan), one per side "
                                 "'+x', '-x', '+y', '-y'.")
        sides = [w.side for w in walls]
        doubled = sorted({s for s in sides if sides.count(s) > 1})
        if doubled:
            raise ValueError(f"walls: more than one wall on side {', '.join(doubled)}; give at "
                             "most one wall per side.")
        object.__setattr__(self, "walls", tuple(sorted(walls, key=lambda w: SIDES.index(w.side))))

    def wall(self, side):
        """The wall on ``side`` ("+x", ...), or None where the moat has none."""
        from femoat.plan.moat import wall_side

        side = wall_side(side)
        return next((w for w in self.walls if w.side == side), None)

    def along(self, axis):
        """The 1D :class:`~femoat.structure.pounding.PoundingModel` along ``axis`` ("x" or "y"):
        the building along that axis and the two walls normal to it. Under a ground motion along
        that axis only, with no contact on the other walls, this model is that one exactly."""
        k = AXES.index(axis) if axis in AXES else None
        building = self.building.along(axis)  # also names a bad axis
        return PoundingModel(building, tuple(w.uniaxial() for w in self.walls if w.axis == k))

    def layout(self):
        """The :class:`PlanLayout` of this model's DOFs."""
        nf = len(self.building.floor_weights) + 1
        floor_dofs = np.full((nf, 3), -1, dtype=np.int64)
        floor_dofs[:, 0] = 2 * np.arange(nf)
        floor_dofs[:, 1] = 2 * np.arange(nf) + 1
        names = [f"{floor}_{axis}" for floor in ["base"] + [f"floor{k}" for k in range(1, nf)]
                 for axis in AXES]
        wall_dofs, col = [], 2 * nf
        for w in self.walls:
            nm = len(wall_modes(w.wall)[0])
            wall_dofs.append(tuple(range(col, col + nm)))
            names += ([f"wall_{w.side}"] if nm == 1
                      else [f"wall_{w.side}_mode{i + 1}" for i in range(nm)])
            col += nm
        floor_dofs.setflags(write=False)
        return PlanLayout(floor_dofs, tuple(wall_dofs), tuple(names))

    def dof_names(self):
        """One name per DOF (:class:`PlanLayout`)."""
        return list(self.layout().names)

    def pack(self):
        """Plain arrays for a plan solver (module docstring)."""
        b = self.building
        lay = self.layout()
        n, dofs = lay.n, lay.floor_dofs
        M, C, K, R = np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, 2))
        for k, w in enumerate([b.base_weight, *b.floor_weights]):
            for a in range(2):
                M[dofs[k, a], dofs[k, a]] = w / G
                R[dofs[k, a], a] = w / G
        beta = b.story_damping_beta
        geometric = b.geometric_stiffnesses()
        elements = []
        for a, axis in enumerate(AXES):
            for k, mat in enumerate(getattr(b, f"stories_{axis}")):
                i, j = dofs[k + 1, a], dofs[k, a]
                _add_spring(C, i, j, beta * mat.initial_stiffness)
                _add_spring(K, i, j, geometric[k])
                elements.append((i, j, a, mat, Role(STORY, k + 1)))
        iso = b.isolator
        kind = None if iso is None else bearing_registry.kind_of(iso)
        plan_bearing = kind is not None
        if iso is not None and not plan_bearing:  # an Elastic isolator: one spring per axis
            elements = [(dofs[0, a], -1, a, iso, Role(ISOLATOR)) for a in range(2)] + elements
        contacts = []
        for w, cols in zip(self.walls, lay.wall_dofs):
            mm, kk, cc, phi, L = wall_modes(w.wall)
            row, slip = np.zeros(n), np.zeros(n)
            row[dofs[0, :2]] = w.normal
            slip[dofs[0, :2]] = w.tangent
            for i, col in enumerate(cols):
                M[col, col], K[col, col], C[col, col] = mm[i], kk[i], cc[i]
                R[col, w.axis] = L[i] * w.sign  # the mode points away from the building
                row[col] = -phi[i]
            contacts.append((row, slip, w))
        return PackedPlanModel(
            M=M, C=C, K=K, R=R, layout=lay,
            story_heights=np.array(b.heights, dtype=float),
            el_i=np.array([e[0] for e in elements], dtype=np.int64),
            el_j=np.array([e[1] for e in elements], dtype=np.int64),
            el_axis=np.array([e[2] for e in elements], dtype=np.int64),
            el_code=np.array([e[3].code for e in elements], dtype=np.int64),
            el_P=_stack([e[3].params() for e in elements]),
            el_S=_stack([e[3].initial_state() for e in elements]),
            el_roles=tuple(e[4] for e in elements),
            el_materials=[e[3] for e in elements],
            bearing_kind=np.array([kind] if plan_bearing else [], dtype=np.int64),
            bearing_dofs=np.array([dofs[0, :2]] if plan_bearing else [], dtype=np.int64
                                  ).reshape(-1, 2),
            bearing_P=_stack([iso.params()] if plan_bearing else [],
                             width=bearing_registry.widths()[0]),
            bearing_S=_stack([iso.initial_state_plan()] if plan_bearing else [],
                             width=bearing_registry.widths()[2]),
            c_B=np.array([c[0] for c in contacts]).reshape(len(contacts), n),
            c_T=np.array([c[1] for c in contacts]).reshape(len(contacts), n),
            c_gap=np.array([c[2].gap for c in contacts], dtype=float),
            c_code=np.array([c[2].law.code for c in contacts], dtype=np.int64),
            c_P=_stack([c[2].law.packed() for c in contacts], width=N_PARAMS),
            c_H=np.zeros((len(contacts), N_HISTORY)),
            c_friction=np.array([c[2].friction for c in contacts], dtype=float),
            c_names=[c[2].side for c in contacts],
            walls=self.walls,
        )


def _add_spring(A, i, j, value):
    """Add a spring ``value`` between DOFs i and j (j = −1: the ground) to the matrix A."""
    A[i, i] += value
    if j >= 0:
        A[j, j] += value
        A[i, j] -= value
        A[j, i] -= value


@dataclass
class PackedPlanModel:
    """Plain arrays of a :class:`PlanModel` (mutable copies: a solver updates the states).
    Fields as in :class:`~femoat.structure.pounding.PackedModel`, plus (module docstring):
    ``R`` (n, 2) [kip·s²/in], ``layout``, ``el_axis``, the plan bearings' rows
    ``bearing_kind`` (nb,) (:mod:`femoat.bearings.registry`), ``bearing_dofs`` (nb, 2),
    ``bearing_P`` and ``bearing_S`` (nb, the registry's widest), ``c_T`` and ``c_friction``
    [-]."""

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    R: np.ndarray
    layout: PlanLayout
    story_heights: np.ndarray
    el_i: np.ndarray
    el_j: np.ndarray
    el_axis: np.ndarray
    el_code: np.ndarray
    el_P: np.ndarray
    el_S: np.ndarray
    el_roles: tuple
    el_materials: list
    bearing_kind: np.ndarray
    bearing_dofs: np.ndarray
    bearing_P: np.ndarray
    bearing_S: np.ndarray
    c_B: np.ndarray
    c_T: np.ndarray
    c_gap: np.ndarray
    c_code: np.ndarray
    c_P: np.ndarray
    c_H: np.ndarray
    c_friction: np.ndarray
    c_names: list
    walls: tuple

    @property
    def n(self):
        return self.M.shape[0]

    @property
    def n_struct(self):
        """Number of building DOFs (x, y per floor), the first ones."""
        return self.layout.n_struct

    @property
    def dof_names(self):
        """One name per DOF (:class:`PlanLayout`)."""
        return list(self.layout.names)

    @property
    def r(self):
        """The ground load's influence matrix ``R`` (n, 2) [kip·s²/in]."""
        return self.R

    @property
    def el_names(self):
        """Each uniaxial element's name and axis (``"story1_x"``, ``"isolator_y"``, ...)."""
        return [f"{role.name}_{AXES[a]}" for role, a in zip(self.el_roles, self.el_axis)]

    @property
    def dof_axis(self):
        """(n,) the plan axis (0 x, 1 y) each DOF moves along (a wall mode: its normal's)."""
        axis = np.zeros(self.n, dtype=np.int64)
        axis[self.layout.floor_dofs[:, 1]] = 1
        for w, cols in zip(self.walls, self.layout.wall_dofs):
            axis[list(cols)] = w.axis
        return axis

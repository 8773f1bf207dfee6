"""The plan model: a :class:`~femoat.plan.building.PlanBuilding` in a rectangular moat.

The plan solver integrates this model; the OpenSees twin (:mod:`femoat.opensees.plan`) builds it
in 3D. Conventions (docs/plan.md §2): plan axes x, y, z up, kip, in, s; no torsion.

DOF layout (docs/plan.md §4, :mod:`femoat.structure.layout`), node-major: floor k (k = 0 the
base mat, then floors bottom to top) owns ``layout.floor_dofs[k] = (x, y, θ)``, indices into the
state vector; θ = −1, since no floor rotates in this issue. The walls' modal coordinates follow,
wall by wall in :data:`~femoat.plan.moat.SIDES` order. So n = 2·(floors + 1) + wall modes.

:meth:`PlanModel.pack` is the one pack path (:mod:`femoat.structure.packing`) on two axes: the
1D :meth:`~femoat.structure.pounding.PoundingModel.pack` with every uniaxial element acting
along its axis, the ground load ``R`` (n, 2) one column per ground component, the plan bearing
(a kind of :mod:`femoat.bearings`, one row; none when the isolator is an Elastic spring, one
element per axis, or None), each wall's slip row ``c_T`` and friction coefficient. The fields:
:class:`~femoat.structure.packed.PackedModel`.
"""

from dataclasses import dataclass, field

from femoat.bearings import registry as bearing_registry
from femoat.plan.building import PlanBuilding
from femoat.plan.moat import SIDES, PlanWall, rectangular_moat
from femoat.structure import packing
from femoat.structure.layout import AXES, Layout, dof_layout
from femoat.structure.packed import PackedModel
from femoat.structure.pounding import PoundingModel

PlanLayout = Layout
"""The DOF layout of a plan model: the one :class:`~femoat.structure.layout.Layout` (two
axes)."""

PackedPlanModel = PackedModel
"""The packed plan model: the one :class:`~femoat.structure.packed.PackedModel` (two axes)."""


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
        """The :class:`~femoat.structure.layout.Layout` of this model's DOFs: two axes, the
        walls in :data:`~femoat.plan.moat.SIDES` order."""
        return dof_layout(len(self.building.floor_weights), 2, self.walls)

    def dof_names(self):
        """One name per DOF ("base_x", "floor1_y", "wall_+x", ...)."""
        return list(self.layout().names)

    def pack(self):
        """The :class:`~femoat.structure.packed.PackedModel` for the compiled loop (module
        docstring)."""
        b = self.building
        kind = None if b.isolator is None else bearing_registry.kind_of(b.isolator)
        return packing.pack(b, (b.stories_x, b.stories_y), self.layout(), self.walls,
                            bearing=kind)

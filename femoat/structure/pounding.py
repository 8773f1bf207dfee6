"""A building and its moat walls along one axis: the model the time-stepping solver integrates
in 1D (:mod:`femoat.plan` is the model in plan).

Sign convention: all DOFs are horizontal displacements relative to the ground, positive in +x.
A wall on side +1 ("+x") stands at +gap; on side −1 ("-x") at −gap (the walls:
:mod:`femoat.structure.moat_wall`). The DOF layout (:mod:`femoat.structure.layout`) is the plan
model's on one axis, and :meth:`PoundingModel.pack` the one pack path
(:mod:`femoat.structure.packing`) on it.
"""

from dataclasses import dataclass

from femoat.structure.building import Building
from femoat.structure.layout import dof_layout
from femoat.structure.moat_wall import (  # noqa: F401  (their home before)
    SIDES,
    MoatWall,
    wall_modes,
    wall_side,
)
from femoat.structure.packed import PackedModel  # noqa: F401  (its home before)
from femoat.structure import packing


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

    def layout(self):
        """The :class:`~femoat.structure.layout.Layout` of this model's DOFs: one axis, the
        walls in their given order."""
        return dof_layout(len(self.building.floor_weights), 1, self.walls)

    def dof_names(self):
        """One name per DOF ("base", "floor1", ..., "wall_pos", "wall_neg_mode2", ...)."""
        return list(self.layout().names)

    def pack(self):
        """The :class:`~femoat.structure.packed.PackedModel` for the compiled loop (see
        :mod:`femoat.integration.driver`): on one axis, the isolator one of its elements."""
        return packing.pack(self.building, (self.building.stories,), self.layout(), self.walls)

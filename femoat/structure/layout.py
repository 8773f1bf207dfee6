"""Where each DOF of a model sits in the state vector: one layout for a model on one axis
(:class:`~femoat.structure.pounding.PoundingModel`) and a model in plan
(:class:`~femoat.plan.model.PlanModel`).

Node-major (docs/plan.md §4): floor k (k = 0 the base mat, then the floors bottom to top) owns
``floor_dofs[k] = (x, y, θ)``, indices into the state vector, −1 where the model has no such
DOF: y on one axis, θ always (no floor rotates yet; a torsion model fills that column, nothing
else moves). The walls' modal coordinates follow, wall by wall in the model's wall order, each
positive away from the building along the wall's normal. So n = axes·(floors + 1) + wall modes.

Names: in plan a DOF's name carries its axis and a wall is named by its side ("base_x",
"floor1_y", "wall_+x", "wall_-y_mode2"); on one axis the axis is left out and a wall is named by
its sign ("base", "floor1", "wall_pos", "wall_neg_mode2"), as a 1D run's results have always
named them.
"""

from dataclasses import dataclass

import numpy as np

from femoat.structure.moat_wall import wall_modes

AXES = ("x", "y")
"""The plan axes, in the order of every (x, y) column; a model on one axis moves along the
first (its own x)."""


@dataclass(frozen=True, eq=False)
class Layout:
    """Where each DOF of a model sits in the state vector (module docstring).

    floor_dofs : array (floors + 1, 3) of int  (x, y, θ) per floor, base mat first; −1 where
        the model has no such DOF
    wall_dofs : tuple of tuple of int  each wall's modal DOFs, in the model's wall order
    names : tuple of str  one per DOF: "base_x", "floor1_y", "wall_+x", ... ("base", "floor1",
        "wall_pos", ... on one axis)
    wall_names : tuple of str  one per wall: its side "+x", ... ("pos" or "neg" on one axis)
    """

    floor_dofs: np.ndarray
    wall_dofs: tuple
    names: tuple
    wall_names: tuple

    @property
    def n(self):
        """Number of DOFs."""
        return len(self.names)

    @property
    def axes(self):
        """The axes the floors translate along: ("x",) or ("x", "y")."""
        return tuple(a for k, a in enumerate(AXES) if self.floor_dofs[0, k] >= 0)

    @property
    def n_struct(self):
        """Number of building DOFs (the floors' translations), the first ones."""
        return len(self.axes) * self.floor_dofs.shape[0]


def dof_layout(floors, n_axes, walls):
    """The :class:`Layout` of a base mat and ``floors`` floors translating along the first
    ``n_axes`` (1 or 2) of :data:`AXES`, and ``walls`` (:class:`MoatWall` entries, in the
    model's order)."""
    if n_axes not in (1, 2):
        raise ValueError(f"n_axes = {n_axes!r}: a model moves along one axis or two (plan).")
    plan = n_axes == 2
    nodes = floors + 1
    floor_dofs = np.full((nodes, 3), -1, dtype=np.int64)
    for a in range(n_axes):
        floor_dofs[:, a] = n_axes * np.arange(nodes) + a
    floor_names = ["base"] + [f"floor{k}" for k in range(1, nodes)]
    names = [f"{floor}_{axis}" if plan else floor for floor in floor_names
             for axis in AXES[:n_axes]]
    wall_names = tuple(w.side if plan else ("pos" if w.sign > 0 else "neg") for w in walls)
    wall_dofs, col = [], n_axes * nodes
    for w, tag in zip(walls, wall_names):
        nm = len(wall_modes(w.wall)[0])
        wall_dofs.append(tuple(range(col, col + nm)))
        names += [f"wall_{tag}"] if nm == 1 else [f"wall_{tag}_mode{i + 1}" for i in range(nm)]
        col += nm
    floor_dofs.setflags(write=False)
    return Layout(floor_dofs, tuple(wall_dofs), tuple(names), wall_names)

"""The space an OpenSees twin is written in: on one axis ``-ndm 1 -ndf 1`` (every node moves
along x only), in plan ``-ndm 3 -ndf 6`` (x, y, z and three rotations per node, the ones a node
does not use fixed). :mod:`femoat.opensees.twin` and :mod:`femoat.opensees.wall_chain` write
their nodes, fixes, masses and loads through it, so neither branches on the dimension.

Axes are numbered as femoat's (0 x, 1 y) and, for a slider's axial DOF, 2 (z); OpenSees' DOF and
``-dir`` numbers are these plus one.
"""

from dataclasses import dataclass


@dataclass(frozen=True)
class Frame:
    """An OpenSees model space: ``ndm`` coordinates and ``ndf`` DOFs per node."""

    ndm: int
    ndf: int

    def model(self):
        """The ``model basic`` command of this space."""
        return ("model", "basic", "-ndm", self.ndm, "-ndf", self.ndf)

    def node(self, tag, position=0.0, axis=0):
        """A node at ``position`` [in] along ``axis``, at the origin on the others."""
        where = [0.0] * self.ndm
        where[axis] = position
        return ("node", tag, *where)

    def fix(self, tag, free=()):
        """The ``fix`` of node ``tag`` that leaves the DOFs of ``free`` (axes 0, 1, 2) free and
        holds the others: a list of one command, or none when every DOF is free."""
        fixed = [0 if d in free else 1 for d in range(self.ndf)]
        return [("fix", tag, *fixed)] if any(fixed) else []

    def vector(self, values):
        """A node vector (mass [kip·s²/in] or load [kip]) of ``values`` ({axis: value}), zero on
        the other DOFs."""
        out = [0.0] * self.ndf
        for axis, value in values.items():
            out[axis] = value
        return out


ONE_AXIS = Frame(ndm=1, ndf=1)
"""The 1D twin's space: a :class:`~femoat.structure.pounding.PoundingModel`."""

PLAN = Frame(ndm=3, ndf=6)
"""The 3D twin's space: a :class:`~femoat.plan.model.PlanModel` (z for a slider's normal
force)."""


def frame_of(n_axes):
    """The space of a model whose floors translate along ``n_axes`` axes (1 or 2)."""
    return ONE_AXIS if n_axes == 1 else PLAN

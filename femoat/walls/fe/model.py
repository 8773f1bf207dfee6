"""What every wall model hands to the modal analysis, the mesh writer and the solver.

Units: stiffness [kip/in], mass [kip·s²/in], DOFs are displacements [in] (and rotations [rad] in
the beam model). The frame is the one of :mod:`femoat.walls.fe.geometry`.
"""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True, eq=False)
class WallModel:
    """An assembled wall, before supports are applied.

    kind : str  the name of its wall kind (:mod:`femoat.walls.kinds`)
    geometry : WallGeometry  the wall it was built from
    stiffness : scipy.sparse.csr_matrix  [kip/in], all DOFs (supports not yet applied)
    mass : scipy.sparse.csr_matrix  [kip·s²/in], consistent mass, all DOFs
    impact : ndarray  [-], interpolation vector: the impact-point displacement is ``impact @ u``
        [in]. It is also the load vector of a unit impact force [kip] (reciprocity): in the 2D/3D
        models it spreads the force uniformly over the impact patch and ``impact @ u`` is the
        patch-averaged horizontal displacement u_x.
    fixed : ndarray[int]  supported DOFs (zero displacement)
    ground : ndarray  [-], influence vector of a unit horizontal (x) rigid-body displacement
    mesh : skfem.Mesh  the discretisation, with named boundaries "base", "impact" (and "back")
    vertex_dofs : ndarray[int], shape (3, n_vertices)  DOF of u_x, u_y, u_z at each mesh vertex,
        -1 where the model has no such component (used to write mode shapes as point data)
    """

    kind: str
    geometry: object
    stiffness: object
    mass: object
    impact: np.ndarray
    fixed: np.ndarray
    ground: np.ndarray
    mesh: object
    vertex_dofs: np.ndarray

    @property
    def n_dofs(self):
        return self.stiffness.shape[0]

    @property
    def free(self):
        """Unsupported DOFs, ascending."""
        return np.setdiff1d(np.arange(self.n_dofs), self.fixed)

    def vertex_vectors(self, u):
        """Displacement vectors at the mesh vertices, shape (n_vertices, 3) [in], from a DOF vector."""
        u = np.asarray(u)
        out = np.zeros((self.vertex_dofs.shape[1], 3))
        for k in range(3):
            have = self.vertex_dofs[k] >= 0
            out[have, k] = u[self.vertex_dofs[k, have]]
        return out

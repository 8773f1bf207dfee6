"""The wall as a 3D continuum: quadratic (27-node) hexahedra.

Mesh coordinates are (x, y, z) as in :mod:`femoat.walls.fe.geometry`. Named boundaries:
"base" (z = 0), "back" (x = t) and "impact", the square patch of side ``impact_patch`` centred at
(y = L/2, z = impact_height) on x = 0. The impact force is spread uniformly over the patch and
the "impact-point displacement" is the patch-averaged horizontal displacement u_x (positive
toward the backfill): the two are work-conjugate, so K⁻¹ on that load read with the same average
gives the patch flexibility.
"""

import numpy as np

from femoat.walls.fe._continuum import assemble_continuum
from femoat.walls.fe._grid import axis_coordinates


def solid_mesh(geometry, n_height=16, n_length=8, n_thickness=2):
    """Structured hex mesh with element edges on the patch outline."""
    from skfem import MeshHex1

    g = geometry
    y0, y1 = g.patch_y
    z0, z1 = g.patch_z
    x = axis_coordinates(g.thickness, n_thickness, (), "n_thickness")
    y = axis_coordinates(g.length, n_length, [y0, y1], "n_length")
    z = axis_coordinates(g.height, n_height, [z0, z1], "n_height")
    tol = 1e-9 * max(g.height, g.length)
    return MeshHex1.init_tensor(x, y, z).with_boundaries({
        "base": lambda p: np.abs(p[2]) < tol,
        "back": lambda p: np.abs(p[0] - g.thickness) < tol,
        "impact": lambda p: ((np.abs(p[0]) < tol) & (p[1] > y0) & (p[1] < y1)
                             & (p[2] > z0) & (p[2] < z1)),
    })


def solid_model(geometry, n_height=16, n_length=8, n_thickness=2, mesh=None):
    """Assemble the 3D wall (ElementHex2 on hexes, ElementTetP2 on tets, intorder 4).

    geometry : WallGeometry
    n_height, n_length, n_thickness : int  element divisions of the structured mesh
    mesh : skfem 3D mesh with boundaries "base", "impact" (and "back"), optional
    Returns a :class:`WallModel` (kind "solid").
    """
    from skfem.models.elasticity import lame_parameters

    if mesh is None:
        mesh = solid_mesh(geometry, n_height, n_length, n_thickness)
    mat = geometry.material
    lame = lame_parameters(mat.youngs_modulus, mat.poisson_ratio)
    return assemble_continuum("solid", geometry, mesh, lame, width=1.0)

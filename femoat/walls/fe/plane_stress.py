"""The wall as a 2D plane-stress section: height × thickness, out-of-plane width = wall length.

Mesh coordinates are (x, z): x across the thickness (0 = impact face, t = back), z up. The
impact load is spread uniformly over the patch z ∈ [impact_height ± patch/2] on x = 0, and the
impact-point displacement is the patch-averaged u_x. Plane stress with width L is the right
idealisation for a narrow wall; a long wall bending in cylindrical bending is closer to plane
strain (about E/(1-ν²) stiffer), which the 3D model captures.
"""

import numpy as np

from femoat.walls.fe._continuum import assemble_continuum
from femoat.walls.fe._grid import axis_coordinates


def plane_mesh(geometry, n_height=20, n_thickness=2):
    """Structured quad mesh with boundaries "base" (z = 0), "back" (x = t) and "impact"."""
    from skfem import MeshQuad1

    g = geometry
    z0, z1 = g.patch_z
    x = axis_coordinates(g.thickness, n_thickness, (), "n_thickness")
    z = axis_coordinates(g.height, n_height, [z0, z1], "n_height")
    tol = 1e-9 * g.height
    return MeshQuad1.init_tensor(x, z).with_boundaries({
        "base": lambda p: np.abs(p[1]) < tol,
        "back": lambda p: np.abs(p[0] - g.thickness) < tol,
        "impact": lambda p: (np.abs(p[0]) < tol) & (p[1] > z0) & (p[1] < z1),
    })


def plane_model(geometry, n_height=20, n_thickness=2, mesh=None):
    """Assemble the plane-stress wall (9-node quadratic quads, or P2 triangles on a tri mesh).

    geometry : WallGeometry
    n_height, n_thickness : int  element divisions of the structured mesh
    mesh : skfem 2D mesh in (x, z) with boundaries "base", "impact" (and "back"), optional
    Returns a :class:`WallModel` (kind "plane").
    """
    from skfem.models.elasticity import plane_stress

    if mesh is None:
        mesh = plane_mesh(geometry, n_height, n_thickness)
    mat = geometry.material
    lame = plane_stress(mat.youngs_modulus, mat.poisson_ratio)
    return assemble_continuum("plane", geometry, mesh, lame, width=geometry.length)

"""Assembly shared by the 2D (plane stress) and 3D (solid) wall models.

Quadratic Lagrange elements (linear ones shear-lock in bending). ``intorder=4`` integrates the
stiffness and mass of quadratic quads/hexes on box-shaped (affine) cells exactly with 3 Gauss
points per direction, and is exact for P2 triangles/tets; scikit-fem's default (2 × maxdeg)
would use 5-7 points per direction.
"""

import numpy as np

INTORDER = 4


def element_for(mesh):
    """The scalar quadratic element for a mesh type (quad/hex: Q2, triangle/tet: P2)."""
    import skfem

    table = {
        skfem.MeshQuad1: skfem.ElementQuad2, skfem.MeshQuad2: skfem.ElementQuad2,
        skfem.MeshTri1: skfem.ElementTriP2, skfem.MeshTri2: skfem.ElementTriP2,
        skfem.MeshHex1: skfem.ElementHex2, skfem.MeshHex2: skfem.ElementHex2,
        skfem.MeshTet1: skfem.ElementTetP2, skfem.MeshTet2: skfem.ElementTetP2,
    }
    if type(mesh) not in table:
        raise ValueError(f"no wall element for a {type(mesh).__name__}: use quad or triangle "
                         "meshes (2D) or hexahedron or tetrahedron meshes (3D)")
    return table[type(mesh)]()


def assemble_continuum(kind, geometry, mesh, lame, width):
    """K, M, impact vector, supports and influence vector of a continuum wall.

    kind : str  the wall kind (:mod:`femoat.walls.kinds`): the wall-frame axes of the mesh
        coordinates and of the displacement components; x (the impact direction) comes first
    lame : (λ, μ) [ksi]  Lamé parameters (the plane-stress ones in 2D)
    width : float  [in] out-of-plane width multiplying 2D forms (the wall length); 1 in 3D
    The mesh must carry boundaries "base" and "impact" (and "back" if there is a backfill).
    The vertical axis is the mesh's last coordinate; x (the first) is normal to the wall.
    """
    from skfem import Basis, FacetBasis, LinearForm, asm

    from femoat.walls.fe import _assembly
    from femoat.walls.fe.model import WallModel
    from femoat.walls.kinds import kind_of_mesh

    axes = kind_of_mesh(mesh, kind).axes
    if axes[0] != 0:
        raise ValueError(f"{kind} wall: a continuum kind's first mesh axis must be x (0, the "
                         f"impact direction), not {axes[0]}")
    g = geometry
    names = set(mesh.boundaries or {})
    needed = {"base", "impact"} | ({"back"} if g.subgrade_modulus > 0 else set())
    if not needed <= names:
        raise ValueError(f"{kind} wall mesh lacks named boundaries {sorted(needed - names)}; "
                         "tag them (gmsh physical groups or with_boundaries)")
    elem = element_for(mesh)  # scalar quadratic element; vector DOF of (s, i) is dim*s + i
    dim = mesh.dim()
    basis = Basis(mesh, elem, intorder=INTORDER)
    n_dofs = dim * basis.N
    stiffness = width * _assembly.elasticity(basis, *lame)
    mass = width * _assembly.mass(basis, g.material.density)
    if g.subgrade_modulus > 0:
        back = FacetBasis(mesh, elem, facets=mesh.boundaries["back"], intorder=INTORDER)
        stiffness = stiffness + width * _assembly.normal_spring(back, g.subgrade_modulus)

    patch = FacetBasis(mesh, elem, facets=mesh.boundaries["impact"], intorder=INTORDER)
    impact = np.zeros(n_dofs)
    impact[0::dim] = asm(LinearForm(lambda v, w: v), patch) / patch.dx.sum()

    base = basis.get_dofs("base").all()
    if g.base == "pinned":
        # A hinge: hold only the base nodes on the line closest to the base centre x = t/2.
        x = basis.doflocs[0, base]
        mid = 0.5 * (x.min() + x.max())
        base = base[np.isclose(np.abs(x - mid), np.abs(x - mid).min(), atol=1e-9 * g.thickness)]
    fixed = np.sort(_assembly.vector_dofs(base, dim).ravel())
    ground = np.zeros(n_dofs)
    ground[0::dim] = 1.0
    vertex_dofs = np.full((3, mesh.nvertices), -1)
    nodal = _assembly.vector_dofs(basis.nodal_dofs[0], dim).T
    vertex_dofs[list(axes)] = nodal
    return WallModel(kind, g, stiffness.tocsr(), mass.tocsr(), impact, fixed, ground, mesh,
                     vertex_dofs)

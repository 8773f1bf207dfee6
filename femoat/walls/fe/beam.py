"""The wall as a vertical cantilever beam: two-node cubic (Hermite) elements.

The whole wall length L is one beam bending about its long axis: section b = L by h = thickness,
I = L·t³/12 [in⁴], A = L·t [in²] (for a strip per unit length, use length = 1 in).
DOFs per node: w, the horizontal displacement u_x [in], then θ = dw/dz [rad]; node i holds DOFs
2i and 2i+1, nodes ascend in z from the base. Euler-Bernoulli by default; ``timoshenko=True``
adds shear deformation (κ = 5/6) and rotary inertia with the exact-static two-node element of
Friedman & Kosmatka (1993, Computers & Structures 47(3)), which reduces to Euler-Bernoulli as
Φ = 12EI/(κGAl²) → 0. The Winkler backfill is a distributed spring k_s·L [kip/in²] over the
full height, with the consistent (translational-mass-shaped) matrix.
"""

import numpy as np
import scipy.sparse as sp

from femoat.walls.fe._grid import axis_coordinates
from femoat.walls.fe.model import WallModel

SHEAR_COEFFICIENT = 5.0 / 6.0
"""κ of a rectangular section [-]."""


def _stiffness(EI, l, phi):
    """Element bending (+ shear) stiffness [kip/in, kip, kip·in]."""
    return EI / ((1.0 + phi) * l**3) * np.array([
        [12.0, 6 * l, -12.0, 6 * l],
        [6 * l, (4 + phi) * l**2, -6 * l, (2 - phi) * l**2],
        [-12.0, -6 * l, 12.0, -6 * l],
        [6 * l, (2 - phi) * l**2, -6 * l, (4 + phi) * l**2],
    ])


def _translational(m, l, phi):
    """∫ m·NᵀN dz for the cubic displacement shape functions; m per unit height [kip·s²/in²]."""
    p2 = phi * phi
    a = 70 * p2 + 147 * phi + 78
    b = (35 * p2 + 77 * phi + 44) * l / 4
    c = 35 * p2 + 63 * phi + 27
    d = (35 * p2 + 63 * phi + 26) * l / 4
    e = (7 * p2 + 14 * phi + 8) * l**2 / 4
    f = (7 * p2 + 14 * phi + 6) * l**2 / 4
    return m * l / (210 * (1 + phi) ** 2) * np.array([
        [a, b, c, -d],
        [b, e, d, -f],
        [c, d, a, -b],
        [-d, -f, -b, e],
    ])


def _rotary(rI, l, phi):
    """Rotary inertia ∫ ρI·N_θᵀN_θ dz; ρI per unit height [kip·s²]."""
    g = (15 * phi - 3) * l
    e = (10 * phi**2 + 5 * phi + 4) * l**2
    f = (5 * phi**2 - 5 * phi - 1) * l**2
    return rI / (30 * (1 + phi) ** 2 * l) * np.array([
        [36.0, -g, -36.0, -g],
        [-g, e, g, f],
        [-36.0, g, 36.0, g],
        [-g, f, g, e],
    ])


def _assemble(blocks, n_dofs):
    rows, cols, vals = [], [], []
    for i, block in enumerate(blocks):
        idx = np.arange(2 * i, 2 * i + 4)
        rows.append(np.repeat(idx, 4))
        cols.append(np.tile(idx, 4))
        vals.append(block.ravel())
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n_dofs, n_dofs))


def beam_model(geometry, n_height=40, timoshenko=False, mesh=None):
    """Assemble the cantilever-beam wall.

    geometry : WallGeometry
    n_height : int  elements over the height (a node is added at the impact height)
    timoshenko : bool  shear deformation and rotary inertia (thick walls)
    mesh : skfem.MeshLine1, optional  node heights z [in] (e.g. read from a file); its
        "impact" boundary, if any, marks the impact node, else the node nearest impact_height
    Returns a :class:`WallModel` (kind "beam"); ``impact`` is the unit vector of w at the impact
    node (the beam takes the impact at a point: the patch size does not enter).
    """
    from skfem import MeshLine1

    g, mat = geometry, geometry.material
    if mesh is None:
        z = axis_coordinates(g.height, n_height, [g.impact_height], "n_height")
        mesh = MeshLine1.init_tensor(z)
    z = mesh.p[0]
    order = np.argsort(z)
    if not np.array_equal(order, np.arange(len(z))) or not np.allclose(
            mesh.t, np.vstack([np.arange(len(z) - 1), np.arange(1, len(z))])):
        raise ValueError("beam mesh must be a chain of nodes ascending from the base; "
                         "build it with MeshLine1(sorted heights)")
    if abs(z[0]) > 1e-9 * g.height or abs(z[-1] - g.height) > 1e-6 * g.height:
        raise ValueError(f"beam mesh spans z = [{z[0]:g}, {z[-1]:g}] in but the geometry height "
                         f"is {g.height:g} in: use a mesh from 0 to the wall height")

    E, G = mat.youngs_modulus, mat.shear_modulus
    A = g.length * g.thickness
    I = g.length * g.thickness**3 / 12.0
    mline = mat.density * A
    lengths = np.diff(z)
    phis = (12 * E * I / (SHEAR_COEFFICIENT * G * A * lengths**2) if timoshenko
            else np.zeros_like(lengths))
    n_dofs = 2 * len(z)
    stiffness = _assemble([_stiffness(E * I, l, p) for l, p in zip(lengths, phis)], n_dofs)
    mass_blocks = [_translational(mline, l, p) for l, p in zip(lengths, phis)]
    if timoshenko:
        mass_blocks = [m + _rotary(mat.density * I, l, p)
                       for m, l, p in zip(mass_blocks, lengths, phis)]
    mass = _assemble(mass_blocks, n_dofs)
    if g.subgrade_modulus > 0:
        ks = g.subgrade_modulus * g.length
        stiffness = stiffness + _assemble(
            [_translational(ks, l, p) for l, p in zip(lengths, phis)], n_dofs)

    if mesh.boundaries and "impact" in mesh.boundaries:
        node = int(mesh.facets[0, mesh.boundaries["impact"][0]])
    else:
        node = int(np.argmin(np.abs(z - g.impact_height)))
        if abs(z[node] - g.impact_height) > 1e-9 * g.height:
            raise ValueError(f"no beam node at impact_height {g.impact_height:g} in (nearest "
                             f"{z[node]:g} in): add one to the mesh")
    mesh = mesh.with_boundaries({
        "base": lambda x: np.isclose(x[0], 0.0),
        "impact": np.array([np.nonzero(mesh.facets[0] == node)[0][0]]),
    }, boundaries_only=False)
    impact = np.zeros(n_dofs)
    impact[2 * node] = 1.0
    ground = np.zeros(n_dofs)
    ground[0::2] = 1.0
    fixed = np.array([0, 1] if g.base == "fixed" else [0])
    vertex_dofs = np.full((3, len(z)), -1)
    vertex_dofs[0] = 2 * np.arange(len(z))
    return WallModel("beam", g, stiffness.tocsr(), mass.tocsr(), impact, fixed, ground, mesh,
                     vertex_dofs)

"""Vectorised assembly of the three bilinear forms the continuum walls need.

scikit-fem evaluates a form once per pair of local DOFs (81² = 6561 Python calls for a 27-node
vector hexahedron) and builds the vector basis by evaluating every scalar function once per
component; that takes seconds on a few hundred cells. Here everything comes from the *scalar*
basis: the element stiffness of isotropic elasticity is one batched matrix product per chunk of
cells, the mass is kron(scalar mass, I). The results equal scikit-fem's
``asm(linear_elasticity(λ, μ), Basis(mesh, ElementVector(e)))`` etc. to round-off
(tests/test_wall_fe_models.py).

DOF numbering is scikit-fem's ElementVector numbering: component i of scalar DOF s is global
DOF ``dim*s + i``.
"""

import numpy as np
import scipy.sparse as sp

CHUNK = 256
"""Cells per batched product (bounds each temporary to CHUNK·(27·3)²·8 bytes = 13 MB)."""


def vector_dofs(scalar_dofs, dim):
    """Global vector DOFs (..., dim) of scalar DOFs: dim*s + i."""
    return dim * np.asarray(scalar_dofs)[..., None] + np.arange(dim)


def _coo(blocks, element_dofs, n):
    """Sum element blocks (cell, p, q) into an n×n CSR; element_dofs is (p, cell)."""
    nd = element_dofs.shape[0]
    rows = np.repeat(element_dofs.T, nd, axis=1).ravel()
    cols = np.tile(element_dofs.T, (1, nd)).ravel()
    return sp.csr_matrix((blocks.ravel(), (rows, cols)), shape=(n, n))


def elasticity(basis, lam, mu):
    """Stiffness of λ·div u·div v + 2μ·ε(u):ε(v) from a scalar Lagrange CellBasis.

    Block (a, i; b, j) of a cell is λ·A[a,i,b,j] + μ·A[a,j,b,i] + μ·δ_ij·Σ_k A[a,k,b,k] with
    A[a,i,b,j] = ∫ ∂_i N_a ∂_j N_b dx.
    """
    dim = basis.mesh.dim()
    n_local = len(basis.basis)
    grads = np.array([basis.basis[a][0].grad for a in range(n_local)])  # (a, i, cell, qp)
    nd = n_local * dim
    blocks = np.empty((basis.nelems, nd, nd))
    eye = np.eye(dim)[None, None, :, None, :]
    for s in range(0, basis.nelems, CHUNK):
        c = slice(s, s + CHUNK)
        g = grads[:, :, c].transpose(2, 0, 1, 3).reshape(-1, nd, grads.shape[-1])  # (e, ai, q)
        A = np.matmul(g * basis.dx[c][:, None, :], g.transpose(0, 2, 1))
        A = A.reshape(-1, n_local, dim, n_local, dim)  # (e, a, i, b, j)
        trace = np.einsum("eakbk->eab", A)[:, :, None, :, None]
        blocks[c] = (lam * A + mu * A.transpose(0, 1, 4, 3, 2) + mu * trace * eye).reshape(-1, nd, nd)
    element_dofs = vector_dofs(basis.element_dofs.T, dim).reshape(basis.nelems, nd).T
    return _coo(blocks, element_dofs, dim * basis.N)


def mass(basis, density):
    """Consistent mass of ρ·u·v from a scalar Lagrange CellBasis: kron(∫ρN_aN_b, I_dim)."""
    values = np.array([np.asarray(phi[0]) for phi in basis.basis])  # (a, cell, qp)
    blocks = density * np.einsum("aeq,beq,eq->eab", values, values, basis.dx)
    scalar = _coo(blocks, basis.element_dofs, basis.N)
    return sp.kron(scalar, sp.identity(basis.mesh.dim()), format="csr")


def normal_spring(facet_basis, stiffness):
    """k·(u·n)(v·n) from a scalar Lagrange FacetBasis; k per unit area."""
    dim = facet_basis.mesh.dim()
    values = np.array([np.asarray(phi[0]) for phi in facet_basis.basis])  # (a, facet, qp)
    n = facet_basis.normals  # (i, facet, qp)
    blocks = stiffness * np.einsum("aeq,beq,ieq,jeq,eq->eaibj", values, values, n, n,
                                   facet_basis.dx, optimize=True)
    nd = values.shape[0] * dim
    element_dofs = vector_dofs(facet_basis.element_dofs.T, dim).reshape(-1, nd).T
    return _coo(blocks.reshape(-1, nd, nd), element_dofs, dim * facet_basis.N)

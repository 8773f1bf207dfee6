"""The stored energies of the energy balance, element by element in one compiled call each (the
Python side sums them exactly: :func:`femoat.integration.solve.solve`'s balance)."""

from femoat.bearings.dispatch import bearing_plan_commit, bearing_plan_energy
from femoat.compilation.jit import njit
from femoat.contact.kernels import contact_stored_energy
from femoat.structure.materials.kernels import material_commit, material_recoverable_energy


@njit(cache=True)
def initial_element_energies(el_i, el_j, el_code, el_P, el_S, u, s_tmp, out,
                             b_kind, b_dofs, b_P, b_S, v, b_tmp, b_out):
    """Into ``out``: each element's recoverable energy [kip·in] with its virgin state
    (``el_S``, not changed) committed at the deformation of the displacements ``u`` [in]; into
    ``b_out`` each plan bearing's, its virgin state (``b_S``, not changed) committed at ``u``
    and the velocities ``v`` [in/s] (``s_tmp``, ``b_tmp``: scratch of a state's width)."""
    for e in range(el_code.size):
        i, j = el_i[e], el_j[e]
        d = u[i] - (u[j] if j >= 0 else 0.0)
        for k in range(s_tmp.size):
            s_tmp[k] = el_S[e, k]
        material_commit(el_code[e], el_P[e], s_tmp, d, 0.0)
        out[e] = material_recoverable_energy(el_code[e], el_P[e], s_tmp)
    for e in range(b_kind.size):
        ix, iy = b_dofs[e, 0], b_dofs[e, 1]
        for k in range(b_tmp.size):
            b_tmp[k] = b_S[e, k]
        # a path of no duration (tau = 0): one return from the virgin state
        bearing_plan_commit(b_kind[e], b_P[e], b_tmp, 0.0, 0.0, 0.0, 0.0, u[ix], u[iy], v[ix],
                            v[iy], 0.0)
        b_out[e] = bearing_plan_energy(b_kind[e], b_P[e], b_tmp)


@njit(cache=True)
def stored_energies(el_code, el_P, el_S, c_code, c_P, c_H, c_d, c_closed, el_out, c_out,
                    b_kind, b_P, b_S, b_out):
    """Into ``el_out`` each element's recoverable energy, into ``c_out`` each closed contact's
    stored energy (0 when open) and into ``b_out`` each plan bearing's recoverable energy
    [kip·in] at the committed states."""
    for e in range(el_code.size):
        el_out[e] = material_recoverable_energy(el_code[e], el_P[e], el_S[e])
    for c in range(c_code.size):
        c_out[c] = contact_stored_energy(c_code[c], c_P[c], c_H[c], c_d[c]) if c_closed[c] else 0.0
    for e in range(b_kind.size):
        b_out[e] = bearing_plan_energy(b_kind[e], b_P[e], b_S[e])

"""Accepting a step: energies, element and contact states, the episodes a step opens or
closes, the kinematics."""

from femoat.bearings.dispatch import bearing_plan_commit, bearing_plan_rate_commit
from femoat.compilation.jit import njit
from femoat.contact.kernels import step_commit
from femoat.integration.codes import E_INPUT, E_VISCOUS
from femoat.integration.events import close_episode, open_episode
from femoat.integration.forces import contact_rate, ground_load
from femoat.structure.materials.kernels import material_commit


@njit(cache=True, inline="always")
def accept(hh, ag1, landing, explicit_step, model, state, settings, work):
    """Commit the trial step: energies, element, bearing and contact states, episode changes (a closure
    within gap_tol, the located separation of contact ``landing``), kinematics. Returns
    (an episode opened or closed, the largest approach velocity of the closures).

    Energies: input and viscous by the trapezoidal rule of the Newmark step, or the explicit
    step's own quadrature (``work.de``) when ``explicit_step``; element work by the trapezoidal
    rule for both (exact on a branch that is linear in the deformation), and for the plan
    bearings and the walls' friction."""
    C, r, c_B = model.C, model.r, model.c_B
    u, v, a, Fn = state.u, state.v, state.a, state.F
    energy = state.energy
    gap_tol = settings.gap_tol
    ag0 = state.ag_now
    n = u.size
    if explicit_step:
        energy[E_INPUT] += work.de[E_INPUT]
        energy[E_VISCOUS] += work.de[E_VISCOUS]
    else:
        for i in range(n):
            du_i = work.u[i] - u[i]
            energy[E_INPUT] += 0.5 * (ground_load(r, i, ag0) + ground_load(r, i, ag1)) * du_i
            cv0 = 0.0
            cv1 = 0.0
            for j in range(n):
                cv0 += C[i, j] * v[j]
                cv1 += C[i, j] * work.v[j]
            energy[E_VISCOUS] += 0.5 * (cv0 + cv1) * du_i
    el_i, el_j = model.el_i, model.el_j
    el_f, el_d, w_ef, w_ed = state.el_f, state.el_d, work.ef, work.ed
    for e in range(el_f.size):
        # the trapezoidal rule is the exact work of a piecewise-linear branch, and no step
        # changes branch (kinks and turning points are landed on)
        state.el_W[e] += 0.5 * (el_f[e] + w_ef[e]) * (w_ed[e] - el_d[e])
        i, j = el_i[e], el_j[e]
        dv = work.v[i] - (work.v[j] if j >= 0 else 0.0)
        material_commit(model.el_code[e], model.el_P[e], state.el_S[e], w_ed[e], dv)
        el_f[e] = w_ef[e]
        el_d[e] = w_ed[e]
    b_f, w_bf, b_dofs = state.b_f, work.bf, model.b_dofs
    for e in range(b_f.shape[0]):
        ix, iy = b_dofs[e, 0], b_dofs[e, 1]
        state.b_W[e] += 0.5 * ((b_f[e, 0] + w_bf[e, 0]) * (work.u[ix] - u[ix])
                               + (b_f[e, 1] + w_bf[e, 1]) * (work.u[iy] - u[iy]))
        if work.b_rate[e] != 0:  # the step carried its friction state (ark5): commit it
            bearing_plan_rate_commit(model.b_kind[e], model.b_P[e], state.b_S[e], work.u[ix],
                                     work.u[iy], work.v[ix], work.v[iy], work.bz[e])
            work.b_rate[e] = 0
        else:
            bearing_plan_commit(model.b_kind[e], model.b_P[e], state.b_S[e], u[ix], u[iy],
                                v[ix], v[iy], work.u[ix], work.u[iy], work.v[ix], work.v[iy], hh)
        b_f[e, 0] = w_bf[e, 0]
        b_f[e, 1] = w_bf[e, 1]
    toggled = False
    v_close = 0.0
    c_f, c_d, w_cf, w_cd, c_closed = state.c_f, state.c_d, work.cf, work.cd, state.c_closed
    for c in range(c_f.size):
        state.c_W[c] += 0.5 * (c_f[c] + w_cf[c]) * (w_cd[c] - c_d[c])
        if model.c_mu[c] > 0.0:  # the wall friction's work along the slip t·u
            slip = 0.0
            for i in range(n):
                slip += model.c_T[c, i] * (work.u[i] - u[i])
            state.c_Wt[c] += 0.5 * (state.c_ft[c] + work.cft[c]) * slip
            state.c_ft[c] = work.cft[c]
        step_commit(model.c_code[c], model.c_P[c], state.c_H[c], w_cd[c])
        c_f[c] = w_cf[c]
        c_d[c] = w_cd[c]
        dd1 = contact_rate(c_B, c, work.v)
        if not c_closed[c] and w_cd[c] >= -gap_tol and w_cd[c] <= 0.0 and dd1 > 0.0:
            open_episode(c, dd1, state)
            v_close = max(v_close, dd1)
            toggled = True
        elif c_closed[c] and landing == c and w_cd[c] <= gap_tol and dd1 < 0.0:
            # separation only at the located crossing (the step was shortened onto it; a
            # closed contact whose trial step ends below −gap_tol never gets here, the event
            # search shortens the step or opens it at the committed state). A contact
            # resting within ±gap_tol of δ = 0 stays closed (it carries no force there)
            # instead of opening and closing at every step.
            close_episode(c, state)
            toggled = True
    for i in range(n):
        u[i] = work.u[i]
        v[i] = work.v[i]
        a[i] = work.a[i]
        Fn[i] = work.F[i]
    for k in range(ag1.size):
        state.ag_now[k] = ag1[k]
    return toggled, v_close

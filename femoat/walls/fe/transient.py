"""The full finite-element wall in time: a mass hits the impact patch through a contact law.

The reference that the SDOF and modal walls are checked against. Units kip, in, s.

    m·ẍ = −f(δ, δ̇),     M·ü + C·u̇ + K·u = c·f,     δ = x − cᵀu,

with (K, M) the wall's sparse stiffness and consistent mass on the free DOFs, c the impact vector
(load vector of a unit impact force, spread over the patch; cᵀu is the patch-averaged horizontal
displacement), x the mass position and f the contact force of any femoat contact law. The mass
meets the wall at t = 0 with speed v0 (gap closed, δ = 0, δ̇ = v0), the wall at rest; the run
stops at the first separation, like :func:`femoat.impact.simulate_impact`.

Integration: Newmark average acceleration (β = 1/4, γ = 1/2: unconditionally stable, no
numerical damping) with a fixed step h. The effective matrix K̂ = K + (2/h)·C + (4/h²)·M is
factorised once (scipy.sparse.linalg.splu); the contact enters through the single vector c, so
each step condenses the wall onto the contact: u_{n+1} = u_p + g·f with u_p = K̂⁻¹·r̂_n and
g = K̂⁻¹·c (computed once), which makes δ and δ̇ affine in the scalar f,

    δ = δ_p − A·f,   A = h²/(4m) + cᵀg;     δ̇ = δ̇_p − B·f,   B = h/(2m) + (2/h)·cᵀg,

and f = F(δ_p − A·f, δ̇_p − B·f) is one scalar equation, solved by Newton safeguarded by
bisection on [0, F(δ_p, δ̇_p)] (its residual is increasing in f for every femoat law). One
sparse solve per step.

Damping (optional): Rayleigh C = αM + βK (sparse), and/or the same ratio ξ in every mode of a
set of mass-normalised modes Φ: C = MΦ·diag(2ξω_i)·ΦᵀM, a rank-r term handled by the
Sherman-Morrison-Woodbury identity on the factorised sparse part. With ``damped_modes`` = all
modes this is the uniform modal damping of :meth:`femoat.walls.ModalWall.from_fe`.

Energy: average acceleration conserves ½u̇ᵀMu̇ + ½uᵀKu exactly up to the work of the
(trapezoidal) external force and the dissipation (h/4)·(u̇_n + u̇_{n+1})ᵀC(u̇_n + u̇_{n+1}) per
step, so the balance ½mv0² = ½mv² + E_wall + E_contact + E_dashpot closes to round-off and
``energy_residual`` checks the implementation, not the accuracy. Accuracy is set by the step:
the period error of average acceleration is (ωh)²/12, so the default ``steps_per_contact`` =
2000 over the contact's rigid-stop half period keeps it near 1e-6 at the contact frequency.
"""

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
import scipy.sparse.linalg as sla

from femoat.contact import kernels
from femoat.contact.history import H_V0
from femoat.contact.laws import ContactLaw
from femoat.contact.episode import ContactDidNotEndError, ImpactResult


@dataclass(frozen=True)
class FeImpactResult(ImpactResult):
    """An :class:`~femoat.impact.ImpactResult` (target "fe") with the finite-element extras.

    dt : float  fixed time step [s]
    steps : int  steps taken
    n_dofs : int  free wall DOFs
    peak_field : ndarray  wall displacement (all DOFs, supports = 0) at the peak force [in]
    peak_time : float  time of the peak force [s]
    """

    dt: float = 0.0
    steps: int = 0
    n_dofs: int = 0
    peak_field: np.ndarray | None = field(default=None, repr=False)
    peak_time: float = 0.0


def _damping_operator(model, free, M, K, damping_ratio, damped_modes):
    """(U, D) with C_modal = U·diag(D)·Uᵀ, U = MΦ for the mass-normalised modes Φ [√(kip·s²/in)]."""
    from femoat.walls.fe.modal import modal_analysis

    n = len(free)
    if damped_modes is None:
        if n > 3000:
            raise ValueError(f"damping_ratio on all {n} modes needs a dense eigensolution: give "
                             "damped_modes (e.g. 100) or use rayleigh")
        lam, phi = scipy.linalg.eigh(K.toarray(), M.toarray())
    else:
        if int(damped_modes) != damped_modes or damped_modes < 1:
            raise ValueError(f"damped_modes = {damped_modes!r} must be a positive integer or None "
                             "(all modes)")
        res = modal_analysis(model, int(damped_modes))
        lam, phi = res.angular_frequencies**2, res.shapes[free]
    phi = phi / np.sqrt(np.einsum("im,im->m", phi, M @ phi))
    return M @ phi, 2.0 * damping_ratio * np.sqrt(lam)


def fe_impact(model, law, v0, mass=None, damping_ratio=0.0, damped_modes=None, rayleigh=None,
              dt=None, steps_per_contact=2000, t_max=None, record_every=1):
    """A mass at ``v0`` hits the finite-element wall ``model`` through ``law``.

    Parameters
    ----------
    model : WallModel
        The wall (beam, plane or solid model; supports applied from ``model.fixed``).
    law : ContactLaw
        Contact law between the mass and the impact patch.
    v0 : float
        Impact speed [in/s], > 0.
    mass : float or None
        Impacting mass [kip·s²/in]; defaults to the law's m_eff.
    damping_ratio : float
        ξ [-] in every damped mode (see ``damped_modes``); 0 for none.
    damped_modes : int or None
        Number of lowest modes that get ``damping_ratio``; None: all modes (dense, small models).
    rayleigh : (float, float) or None
        (α [1/s], β [s]) of a Rayleigh damping C = αM + βK, added to the modal damping.
    dt : float or None
        Fixed time step [s]; default: π·√(min(m, m_eff)/k_eff) / steps_per_contact.
    steps_per_contact : int
        Steps per rigid-stop contact half period when ``dt`` is None.
    t_max : float or None
        Give up (ContactDidNotEndError) after this time [s]; default: 200 rigid-stop contact
        times plus 20 fundamental wall periods.
    record_every : int
        Keep every k-th step in the histories (peaks and the separation use every step).
    """
    if not isinstance(law, ContactLaw):
        raise ValueError("law must be a ContactLaw (see femoat.contact.make_law).")
    if not (isinstance(v0, (int, float)) and math.isfinite(v0) and v0 > 0):
        raise ValueError(f"v0 = {v0!r} must be a positive impact speed [in/s].")
    m = law.params.m_eff if mass is None else mass
    if not (isinstance(m, (int, float)) and math.isfinite(m) and m > 0):
        raise ValueError(f"mass = {mass!r} must be a positive mass [kip·s²/in].")
    if not (isinstance(damping_ratio, (int, float)) and math.isfinite(damping_ratio)
            and damping_ratio >= 0):
        raise ValueError(f"damping_ratio = {damping_ratio!r} must be a ratio >= 0 [-].")
    if int(steps_per_contact) != steps_per_contact or steps_per_contact < 10:
        raise ValueError(f"steps_per_contact = {steps_per_contact!r} must be an integer >= 10.")
    if int(record_every) != record_every or record_every < 1:
        raise ValueError(f"record_every = {record_every!r} must be a positive integer.")
    k_eff = law.params.k_eff
    t_est = math.pi * math.sqrt(min(m, law.params.m_eff) / k_eff)
    h = t_est / steps_per_contact if dt is None else dt
    if not (isinstance(h, (int, float)) and math.isfinite(h) and h > 0):
        raise ValueError(f"dt = {dt!r} must be a positive time step [s] or None.")

    free = model.free
    K = model.stiffness[free][:, free].tocsc()
    M = model.mass[free][:, free].tocsc()
    c = np.asarray(model.impact, float)[free]
    C = None
    if rayleigh is not None:
        try:
            alpha, beta = (float(x) for x in rayleigh)
        except (TypeError, ValueError):
            raise ValueError("rayleigh must be a pair (alpha [1/s], beta [s])") from None
        if not (alpha >= 0 and beta >= 0 and math.isfinite(alpha) and math.isfinite(beta)):
            raise ValueError(f"rayleigh = {rayleigh!r}: alpha [1/s] and beta [s] must be >= 0")
        C = (alpha * M + beta * K).tocsc()
    U = D = None
    if damping_ratio > 0:
        U, D = _damping_operator(model, free, M, K, damping_ratio, damped_modes)

    # Newmark average acceleration constants
    a0, a1 = 4.0 / h**2, 2.0 / h
    Khat = K + a0 * M + (a1 * C if C is not None else 0.0 * M)
    try:
        lu = sla.splu(Khat.tocsc(), permc_spec="MMD_AT_PLUS_A")
    except RuntimeError as err:
        raise ValueError(f"the wall's effective matrix is singular ({err}): check the supports "
                         "(base='fixed' or a backfill)") from None
    if U is not None:
        # (K̂₀ + a1·U·diag(D)·Uᵀ)⁻¹ by Woodbury: W = K̂₀⁻¹U, S = diag(1/(a1·D)) + UᵀW
        W = lu.solve(np.asfortranarray(U))
        S = scipy.linalg.lu_factor(np.diag(1.0 / (a1 * D)) + U.T @ W)

        def solve(b):
            y = lu.solve(b)
            return y - W @ scipy.linalg.lu_solve(S, U.T @ y)

        def damp(v):
            return U @ (D * (U.T @ v)) + (C @ v if C is not None else 0.0)
    else:
        solve = lu.solve

        def damp(v):
            return C @ v
    damped = C is not None or U is not None

    g = solve(c)
    cg = float(c @ g)
    A = h * h / (4.0 * m) + cg
    B = h / (2.0 * m) + a1 * cg

    if t_max is None:
        from femoat.walls.fe.modal import modal_analysis

        t_max = 200.0 * t_est + 20.0 / modal_analysis(model, 1).frequencies[0]
    n_steps_max = int(math.ceil(t_max / h))

    spec = law.resolved()
    code, p = law.code, spec.params()
    hist = np.zeros(kernels.N_HISTORY)
    kernels.contact_closure(hist, float(v0))

    def raw(d, dd):
        # unclipped force indicator of the laws that separate by force (as in simulate_impact)
        return spec.separation_indicator(d, dd, hist[H_V0])

    n = len(free)
    u, v, a = np.zeros(n), np.zeros(n), np.zeros(n)
    # The force just after closure: c_eff·v0 for Kelvin-Voigt (a jump), 0 for the other laws.
    f_old = kernels.contact_force(code, p, hist, np.finfo(float).tiny, float(v0))[0]
    x, xd, xa = 0.0, float(v0), -f_old / m
    if f_old > 0.0:
        a = sla.splu(M, permc_spec="MMD_AT_PLUS_A").solve(c * f_old)
    d_old, dd_old, w_old = 0.0, float(v0), 0.0
    e_contact = e_dashpot = 0.0
    ts, fs, ds, dds, ws = [0.0], [f_old], [0.0], [float(v0)], [0.0]
    peak_f, peak_u, peak_t = -1.0, np.zeros(n), 0.0
    t_end = None
    step = 0
    for step in range(1, n_steps_max + 1):
        t = step * h
        # predictor: everything at f = 0
        rhat = M @ (a0 * u + 4.0 / h * v + a)
        if damped:
            rhat += damp(a1 * u + v)
        up = solve(rhat)
        wp = c @ up
        x_p = x + h * xd + 0.25 * h * h * xa
        d_p = x_p - wp
        # δ̇: ẋ_{n+1} − cᵀu̇_{n+1}, u̇_{n+1} = a1(u_{n+1} − u_n) − u̇_n
        dd_p = (xd + 0.5 * h * xa) - (a1 * (wp - c @ u) - c @ v)
        f = _solve_contact(code, p, hist, d_p, dd_p, A, B)
        u_new = up + g * f
        v_new = a1 * (u_new - u) - v
        a_new = a0 * (u_new - u) - 4.0 / h * v - a
        xa_new = -f / m
        x_new = x_p + 0.25 * h * h * xa_new
        xd_new = xd + 0.5 * h * (xa + xa_new)
        d_new = x_new - c @ u_new
        dd_new = xd_new - c @ v_new
        e_contact += 0.5 * (f_old + f) * (d_new - d_old)
        if damped:
            vs = v + v_new
            e_dashpot += 0.25 * h * float(vs @ damp(vs))
        if f > peak_f:
            peak_f, peak_u, peak_t = f, u_new, t
        u, v, a = u_new, v_new, a_new
        x, xd, xa = x_new, xd_new, xa_new
        kernels.contact_commit(code, hist, d_new)
        separated = d_new <= 0.0 or (f == 0.0 and raw(d_new, dd_new) <= 0.0)
        if separated:
            # locate the separation by linear interpolation of δ (or of the raw force); the
            # histories end there, interpolated (force zero)
            if d_new <= 0.0:
                s = d_old / (d_old - d_new)
            else:
                r0, r1 = raw(d_old, dd_old), raw(d_new, dd_new)
                s = r0 / (r0 - r1) if r0 > r1 else 1.0
            s = min(max(s, 0.0), 1.0)
            t_end = (step - 1 + s) * h
            ts.append(t_end)
            fs.append(0.0)
            ds.append(d_old + s * (d_new - d_old))
            dds.append(dd_old + s * (dd_new - dd_old))
            ws.append(w_old + s * (c @ u_new - w_old))
            break
        if step % record_every == 0:
            ts.append(t)
            fs.append(f)
            ds.append(d_new)
            dds.append(dd_new)
            ws.append(c @ u_new)
        f_old, d_old, dd_old, w_old = f, d_new, dd_new, c @ u_new
    if t_end is None:
        raise ContactDidNotEndError(
            f"The contact through law {law.kind} did not end within {t_max:.3g} s; raise t_max "
            "or check the wall supports and the law.")

    wall_energy = 0.5 * float(v @ (M @ v)) + 0.5 * float(u @ (K @ u))
    e_in = 0.5 * m * v0 * v0
    e_out = 0.5 * m * xd * xd + wall_energy + e_contact + e_dashpot
    field_at_peak = np.zeros(model.n_dofs)
    field_at_peak[free] = peak_u
    time = np.array(ts)
    return FeImpactResult(
        law=law.kind, target="fe", v0=float(v0), peak_force=float(peak_f),
        max_indentation=float(max(ds)), contact_duration=float(t_end),
        restitution=float(-xd / v0), dissipated_energy=float(e_contact),
        wall_dissipated_energy=float(e_dashpot), wall_energy=wall_energy,
        peak_wall_displacement=float(max(ws)),
        energy_residual=float(abs(e_in - e_out) / e_in), damping=law.damping_parameter(),
        time=time, indentation=np.array(ds), indentation_rate=np.array(dds), force=np.array(fs),
        wall_displacement=np.array(ws), dt=float(h), steps=step, n_dofs=n,
        peak_field=field_at_peak, peak_time=float(peak_t),
    )


def _solve_contact(code, p, hist, d_p, dd_p, A, B, tol=1e-13, max_iter=60):
    """The contact force f [kip] with f = F(d_p − A·f, dd_p − B·f) (A [in/kip], B [in/(kip·s)]).

    The residual r(f) = f − F(d_p − A f, dd_p − B f) has r' = 1 + A·F_δ + B·F_δ̇ >= 1 (every law's
    tangents are >= 0), so its root is unique and lies in [0, F(d_p, dd_p)].
    """
    f_hi = kernels.contact_force(code, p, hist, d_p, dd_p)[0]
    if f_hi <= 0.0:
        return 0.0
    lo, hi = 0.0, f_hi
    f = f_hi
    for _ in range(max_iter):
        F, Fd, Fv = kernels.contact_force(code, p, hist, d_p - A * f, dd_p - B * f)
        r = f - F
        if r > 0:
            hi = f
        else:
            lo = f
        if abs(r) <= tol * f_hi:
            return f
        step = r / (1.0 + A * Fd + B * Fv)
        f_new = f - step
        if not (lo < f_new < hi):
            f_new = 0.5 * (lo + hi)
        if abs(f_new - f) <= 1e-15 * f_hi:
            return f_new
        f = f_new
    return f


def impact_errors(result, reference):
    """Errors of an impact ``result`` against a ``reference`` (e.g. the FE wall) [-].

    Relative, signed: ``peak_force``, ``max_indentation``, ``peak_wall_displacement``,
    ``contact_duration`` ((result − reference)/reference). Absolute: ``restitution``
    (result − reference; e can be near zero or negative when the wall runs away from the mass).
    ``force_history``: ‖f − f_ref‖₂/‖f_ref‖₂ over the reference's time samples after t = 0 (the
    result's force interpolated there, zero after its separation).
    """
    out = {key: getattr(result, key) / getattr(reference, key) - 1.0
           for key in ("peak_force", "max_indentation", "peak_wall_displacement",
                       "contact_duration")}
    out["restitution"] = result.restitution - reference.restitution
    t, f_ref = reference.time[1:], reference.force[1:]
    f = np.interp(t, result.time, result.force, right=0.0)
    out["force_history"] = float(np.sqrt(np.trapezoid((f - f_ref) ** 2, t)
                                         / np.trapezoid(f_ref**2, t)))
    return out

"""A precise single impact: a mass at speed v0 hits a rigid stop, a Masroor SDOF wall or a
modal wall.

This is femoat's reference for one contact episode. The equations of motion

    m ẍ = −f(δ, δ̇),      M1 ẅ = f − K1·w − C_imp·ẇ,      δ = x − w,

(for a modal wall of N modes, m_i·q̈_i = φ_i·f − k_i·q_i − c_i·q̇_i and w = Σ φ_i·q_i, with the
arrays of :func:`femoat.structure.pounding.wall_modes`) are integrated with scipy's 8th-order Dormand-Prince method (DOP853) at tight tolerances. Contact
starts at t = 0 (gap closure, δ = 0, δ̇ = v0; Hertzdamp captures δ̇₀ = v0 there). The events that
change a law's regime are located inside the step and the integration is restarted on them:

* a turning point δ̇ = 0 (the bilinear law records its largest indentation; Jankowski's dashpot
  switches off or on);
* the force falling to zero while δ > 0 (Kelvin-Voigt without tension, Hertzdamp): separation;
* δ returning to zero: separation.

Only the first contact episode is simulated. Two extra states integrate the work done on the
contact spring, ∫f·δ̇ dt, and the energy dissipated in the wall dashpots, ∫Σc_i·q̇_i² dt (C_imp·ẇ²
for the SDOF wall), so that the energy balance ½mv0² = ½mv² + E_wall + E_contact + E_dashpot, with
E_wall = Σ(½m_i·q̇_i² + ½k_i·q_i²), is an independent accuracy check.

A modal wall whose dashpots make the equations stiff (fastest modal root c_i/m_i or ω_i far beyond
the contact time scale) is integrated with the implicit Radau IIA method and an analytic Jacobian
instead of DOP853; the events and the energy states are the same.
"""

import math

import numpy as np
from scipy.integrate import solve_ivp

from femoat.contact import kernels
from femoat.contact.episode import ContactDidNotEndError, ImpactResult
from femoat.contact.history import H_DMAX, H_V0
from femoat.contact.laws import ContactLaw
from femoat.walls.sdof import SdofWall


def simulate_impact(law, v0, wall=None, mass=None, rtol=1e-11, samples_per_phase=2000):
    """Simulate one impact of a mass at ``v0`` [in/s] through ``law``.

    Parameters
    ----------
    law : ContactLaw
        The contact law (with its parameters).
    v0 : float
        Impact (approach) speed [in/s], > 0.
    wall : SdofWall, ModalWall or None
        The wall behind the contact spring; ``None`` for a rigid stop. Any object with the
        modal arrays of :func:`femoat.structure.pounding.wall_modes` is a modal wall.
    mass : float or None
        Impacting mass [kip·s²/in]; defaults to the law's m_eff.
    rtol : float
        Relative tolerance of the integrator (absolute tolerances are scaled from it).
    samples_per_phase : int
        Dense-output samples per regime for the returned histories and the peak force.
    """
    if not isinstance(law, ContactLaw):
        raise ValueError("law must be a ContactLaw (see femoat.contact.make_law).")
    if not (isinstance(v0, (int, float)) and math.isfinite(v0) and v0 > 0):
        raise ValueError(f"v0 = {v0!r} must be a positive impact speed [in/s].")
    m = law.params.m_eff if mass is None else mass
    if not (math.isfinite(m) and m > 0):
        raise ValueError(f"mass = {mass!r} must be a positive mass [kip·s²/in].")
    modal = wall is not None and not isinstance(wall, SdofWall)
    if modal:
        modes = _modal_arrays(wall)
    if not (0 < rtol < 1e-3):
        raise ValueError(f"rtol = {rtol!r} must be in (0, 1e-3).")

    spec = law.resolved()
    code, p = law.code, spec.params()
    h = np.zeros(kernels.N_HISTORY)
    kernels.contact_closure(h, float(v0))
    rigid = wall is None
    if modal:
        mm, kk, cc, phi = modes
        n = mm.size
    else:
        K1, M1, C = (0.0, 1.0, 0.0) if rigid else (wall.stiffness, wall.mass, wall.damping)
        n = 1
    # State: x, ẋ, the wall coordinates (w or q_1..q_N), their rates, ∫f·δ̇ dt, ∫Σc·q̇² dt.
    iq, iqd, iec = slice(2, 2 + n), slice(2 + n, 2 + 2 * n), 2 + 2 * n

    if modal:
        def wall_of(y):
            return phi @ y[iq], phi @ y[iqd]

        def rhs(t, y):
            q, qd = y[iq], y[iqd]
            dd = y[1] - phi @ qd
            f = kernels.contact_force(code, p, h, y[0] - phi @ q, dd)[0]
            out = np.empty_like(y)
            out[0], out[1] = y[1], -f / m
            out[iq] = qd
            out[iqd] = (phi * f - kk * q - cc * qd) / mm
            out[iec], out[iec + 1] = f * dd, cc @ (qd * qd)
            return out

        def jac(t, y):
            q, qd = y[iq], y[iqd]
            d, dd = y[0] - phi @ q, y[1] - phi @ qd
            f, fd, fv = kernels.contact_force(code, p, h, d, dd)
            J = np.zeros((y.size, y.size))
            # ∂f/∂(x, ẋ, q, q̇) = (f_δ, f_δ̇, −f_δ·φ, −f_δ̇·φ)
            df = np.concatenate(([fd, fv], -fd * phi, -fv * phi))
            J[0, 1] = 1.0
            J[1, :iec] = -df / m
            J[iq, iqd] = np.eye(n)
            J[iqd, :iec] = np.outer(phi / mm, df)
            J[iqd, iq] -= np.diag(kk / mm)
            J[iqd, iqd] -= np.diag(cc / mm)
            ddd = np.concatenate(([0.0, 1.0], np.zeros(n), -phi))  # ∂δ̇/∂(x, ẋ, q, q̇)
            J[iec, :iec] = df * dd + f * ddd
            J[iec + 1, iqd] = 2.0 * cc * qd
            return J
    else:
        def wall_of(y):
            return y[2], y[3]

        def rhs(t, y):
            x, v, w, wd = y[0], y[1], y[2], y[3]
            d, dd = x - w, v - wd
            f = kernels.contact_force(code, p, h, d, dd)[0]
            if rigid:
                return (v, -f / m, 0.0, 0.0, f * dd, 0.0)
            return (v, -f / m, wd, (f - K1 * w - C * wd) / M1, f * dd, C * wd * wd)

    def separation(t, y):
        return y[0] - wall_of(y)[0]

    separation.terminal, separation.direction = True, -1

    def raw_force(t, y):
        # The unclipped force of the laws that can pull: zero crossing = separation by force.
        w, wd = wall_of(y)
        d, dd = y[0] - w, y[1] - wd
        return spec.separation_indicator(d, dd, h[H_V0])

    raw_force.terminal, raw_force.direction = True, -1

    def turning(t, y):
        return y[1] - wall_of(y)[1]

    turning.terminal = True

    # Scales for tolerances and time limits from the linear estimate of the contact.
    k_est = law.params.k_eff
    t_est = math.pi * math.sqrt(m / k_est)
    d_scale = v0 * t_est
    e_in = 0.5 * m * v0 * v0
    atol = rtol * np.concatenate([[d_scale, v0], np.full(n, d_scale), np.full(n, v0),
                                  [e_in, e_in]]) * 1e-2
    method, options = "DOP853", {}
    if rigid:
        t_limit = 200.0 * t_est
    elif not modal:
        t_limit = 200.0 * t_est + 20.0 * wall.period
    else:
        t_limit = 200.0 * t_est + 20.0 * float(np.max(np.maximum(2 * np.pi * np.sqrt(mm / kk),
                                                                   cc / kk)))
        if _is_stiff(mm, kk, cc, t_est):
            method, options = "Radau", {"jac": jac}

    y = np.zeros(4 + 2 * n)
    y[1] = float(v0)
    t = 0.0
    loading = True
    ts, ys = [np.array([0.0])], [y[:, None]]
    while True:
        turning.direction = -1 if loading else 1
        sol = solve_ivp(rhs, (t, t_limit), y, method=method, rtol=rtol, atol=atol,
                        events=(separation, raw_force, turning), dense_output=True,
                        max_step=t_est / 20.0, **options)
        if sol.status == -1:
            raise RuntimeError(f"The impact integration failed at t = {t:.3e} s: {sol.message}")
        t_new, y = sol.t[-1], sol.y[:, -1].copy()
        tt = np.union1d(np.linspace(t, t_new, samples_per_phase), sol.t)[1:]
        ts.append(tt)
        ys.append(sol.sol(tt))
        t = t_new
        if sol.status == 0:
            raise ContactDidNotEndError(
                f"The contact through law {law.kind} did not end within {t_limit:.3g} s "
                "(the wall keeps the bodies pressed together); check K1, C_imp and the law."
            )
        fired = [len(ev) > 0 for ev in sol.t_events]
        if fired[0] or fired[1]:
            break
        # turning point: the bilinear law remembers its largest indentation
        kernels.contact_commit(code, h, y[0] - wall_of(y)[0])
        loading = not loading

    time = np.concatenate(ts)
    Y = np.concatenate(ys, axis=1)
    if modal:
        w_hist, wd_hist = phi @ Y[iq], phi @ Y[iqd]
    else:
        w_hist, wd_hist = Y[2], Y[3]
    d_hist, dd_hist = Y[0] - w_hist, Y[1] - wd_hist
    # Force history with the history variables valid at each sample (δ_m grows monotonically,
    # so re-evaluating with the running maximum reproduces the committed history).
    dmax_run = np.maximum.accumulate(np.maximum(d_hist, 0.0))
    force = np.empty_like(time)
    hh = h.copy()
    for i in range(time.size):
        hh[H_DMAX] = dmax_run[i]
        force[i] = kernels.contact_force(code, p, hh, d_hist[i], dd_hist[i])[0]

    v_end, e_contact, e_dashpot = y[1], y[iec], y[iec + 1]
    if modal:
        q_end, qd_end = y[iq], y[iqd]
        wall_energy = float(0.5 * mm @ qd_end**2 + 0.5 * kk @ q_end**2)
    else:
        w_end, wd_end = y[2], y[3]
        wall_energy = 0.0 if rigid else 0.5 * M1 * wd_end**2 + 0.5 * K1 * w_end**2
    e_out = 0.5 * m * v_end**2 + wall_energy + e_contact + e_dashpot
    return ImpactResult(
        law=law.kind,
        target="rigid" if rigid else ("modal" if modal else "sdof"),
        v0=float(v0),
        peak_force=float(force.max()),
        max_indentation=float(d_hist.max()),
        contact_duration=float(t),
        restitution=float(-v_end / v0),
        dissipated_energy=float(e_contact),
        wall_dissipated_energy=float(e_dashpot),
        wall_energy=float(wall_energy),
        peak_wall_displacement=float(w_hist.max()),
        energy_residual=float(abs(e_in - e_out) / e_in),
        damping=law.damping_parameter(),
        time=time,
        indentation=d_hist,
        indentation_rate=dd_hist,
        force=force,
        wall_displacement=w_hist,
        modal_displacement=Y[iq].T if modal else None,
    )


STIFFNESS_RATIO = 100.0
"""A modal wall is integrated with Radau when its fastest decaying root exceeds this multiple
of the fastest oscillation (the contact's π/t_est or an underdamped mode's ω)."""


def _is_stiff(mm, kk, cc, t_est):
    """Do overdamped modes make the wall equations stiff on the contact time scale?"""
    omega2 = kk / mm
    half = cc / (2.0 * mm)
    over = half * half > omega2
    fast = np.where(over, half + np.sqrt(np.maximum(half * half - omega2, 0.0)), 0.0)
    reference = max(math.pi / t_est, float(np.max(np.sqrt(omega2[~over]), initial=0.0)))
    return float(fast.max()) > STIFFNESS_RATIO * reference


def _modal_arrays(wall):
    """(m, k, c, φ) of a modal wall, checked; ValueError naming the problem otherwise."""
    from femoat.structure.pounding import wall_modes

    try:
        mm, kk, cc, phi, _ = wall_modes(wall)
    except ValueError:
        raise ValueError("wall must be an SdofWall, a ModalWall (femoat.walls.ModalWall) or None "
                         "(rigid stop).") from None
    n = mm.size
    if n == 0 or any(a.shape != (n,) for a in (kk, cc, phi)):
        raise ValueError("wall: modal_masses, modal_stiffnesses, modal_dampings and impact_shape "
                         "must be 1-D arrays of the same length (one value per mode).")
    if not (np.all(mm > 0) and np.all(kk > 0) and np.all(cc >= 0) and np.all(np.isfinite(phi))):
        raise ValueError("wall: modal masses [kip·s²/in] and stiffnesses [kip/in] must be > 0 "
                         "and modal dampings [kip·s/in] >= 0.")
    return mm, kk, cc, phi

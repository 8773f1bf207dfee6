"""Response spectrum: exact for piecewise-linear excitation."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from femoat.ground_motions import GroundMotion, response_spectrum
from femoat.units import G


def _synthetic(npts=600, dt=0.01, seed=3):
    rng = np.random.default_rng(seed)
    return GroundMotion(0.2 * rng.standard_normal(npts), dt, name="noise")


def test_matches_solve_ivp_for_several_periods():
    # Independent reference: u'' + 2ζω u' + ω² u = -a_g with a_g linear between samples, solved by
    # solve_ivp (DOP853, tight tolerances) one sample interval at a time so that no kink in a_g
    # falls inside a step; all periods ride in one state vector [u_1, v_1, u_2, v_2, ...].
    # The recurrence is exact for piecewise-linear input, even on this coarse grid (dt = 0.02 s).
    gm = _synthetic(npts=100, dt=0.02)
    periods, zeta = np.array([0.05, 0.3, 1.0, 4.0]), 0.05
    omega = 2 * np.pi / periods
    dt = gm.dt

    y, peak = np.zeros(2 * periods.size), np.zeros(periods.size)
    for n in range(gm.npts - 1):
        a0, a1 = gm.accel[n], gm.accel[n + 1]

        def rhs(s, y, a0=a0, a1=a1):
            u, v = y[0::2], y[1::2]
            a = a0 + (a1 - a0) * s / dt
            return np.column_stack([v, -(omega**2) * u - 2 * zeta * omega * v - a]).ravel()

        y = solve_ivp(rhs, (0, dt), y, method="DOP853", rtol=1e-10, atol=1e-14).y[:, -1]
        peak = np.maximum(peak, np.abs(y[0::2]))
    spec = response_spectrum(gm, periods, damping=zeta)
    np.testing.assert_allclose(spec.sd, peak, rtol=1e-6)
    # PSA = ω² SD, in g
    np.testing.assert_allclose(spec.psa, omega**2 * peak / G, rtol=1e-6)


def test_rigid_limit_is_pga():
    gm = _synthetic()
    spec = response_spectrum(gm, [0.0, 1e-4])
    # T = 0 is a rigid oscillator: the mass moves with the ground, PSA = PGA, SD = 0
    assert spec.psa[0] == gm.pga
    assert spec.sd[0] == 0.0
    # Quasi-static expansion for ω -> ∞: ω² u = -a_g + (2ζ/ω) a_g' + O(1/ω²), so
    # |PSA - PGA| <= (2ζ/ω) max|a_g'| with max|a_g'| = max|Δa| / dt (Chopra §6.8 limits).
    omega = 2 * np.pi / 1e-4
    bound = 2 * 0.05 / omega * np.max(np.abs(np.diff(gm.accel_g))) / gm.dt
    assert abs(spec.psa[1] - gm.pga) <= bound + 1e-12


def test_undamped_harmonic_closed_form_converges_at_second_order():
    # u'' + ω² u = -A sin(Ω t), u(0) = u'(0) = 0 (Chopra, Dynamics of Structures, eq. 3.1.3):
    #   u(t) = -A / (ω² - Ω²) · (sin Ω t - (Ω/ω) sin ω t)
    # The sampled sine is only piecewise linear, so the peak converges as O(dt²).
    A, Omega, period, t_end = 0.3, 2 * np.pi / 0.9, 0.4, 4.0
    omega = 2 * np.pi / period
    errors = []
    for dt in (0.01, 0.005, 0.0025):
        n = int(round(t_end / dt)) + 1
        t = np.arange(n) * dt
        gm = GroundMotion(A * np.sin(Omega * t), dt)
        shape = np.sin(Omega * t) - Omega / omega * np.sin(omega * t)
        exact = A * G / (omega**2 - Omega**2) * shape
        sd = response_spectrum(gm, period, damping=0.0).sd
        errors.append(abs(sd - np.max(np.abs(exact))) / np.max(np.abs(exact)))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    np.testing.assert_allclose(rates, 2.0, atol=0.1)
    assert errors[-1] < 1e-4


def test_shapes_and_validation():
    gm = _synthetic(npts=50)
    spec = response_spectrum(gm, [[0.1, 0.2], [0.3, 0.0]])
    assert spec.psa.shape == spec.sd.shape == (2, 2)
    psa, sd = response_spectrum(gm, 0.5)  # a NamedTuple unpacks
    assert psa.shape == () and sd.shape == ()
    with pytest.raises(ValueError, match="periods"):
        response_spectrum(gm, [-0.1, 1.0])
    with pytest.raises(ValueError, match="damping"):
        response_spectrum(gm, 1.0, damping=-0.05)
    with pytest.raises(TypeError, match="GroundMotion"):
        response_spectrum(gm.accel_g, 1.0)


def test_one_period_on_floats_is_the_vectorised_recurrence_to_the_bit(monkeypatch):
    # A few periods run the Nigam-Jennings recurrence on Python floats, more run it vectorised
    # over periods: the same IEEE operations in the same order, so the same bits (a suite's
    # scale factors, and with them its stored runs, depend on them).
    from femoat.ground_motions import fema_p695_record
    from femoat.ground_motions import spectrum

    periods = [0.2, 1.0, 3.5]
    for record, component in ((1, "a"), (12, "b")):
        gm = fema_p695_record("farfield", record, component)
        floats = [spectrum.response_spectrum(gm, t).psa for t in periods]
        monkeypatch.setattr(spectrum, "SCALAR_PERIODS", 0)
        vectorised = [spectrum.response_spectrum(gm, t).psa for t in periods]
        monkeypatch.setattr(spectrum, "SCALAR_PERIODS", 4)
        assert floats == vectorised
        assert spectrum.response_spectrum(gm, periods).psa.tolist() == [float(x) for x in floats]

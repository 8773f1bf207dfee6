"""The triple friction pendulum's velocity-dependent friction (femoat.bearings.
triple_friction_pendulum, ``mu1_fast``, ``mu2_fast``, ``mu3_fast``, ``a``): each series element
an elastic-viscoplastic friction disk whose strength follows Constantinou's law at its surface's
sliding speed, stepped by backward Euler over the step's duration.

Notation as in the module: series elements i = 1, 2, 3 of radius L̄ = 2·L1, L2 − L1, L3 − L1,
restoring stiffness kr_i = W/L̄_i, sticking stiffness k_0 = 3·μ1·W/u_y, elastic disk stiffness
k_e,i = k_0 − kr_i, surface speed fact_i·(slip rate), fact = 1/2, L2/(L2 − L1), L3/(L3 − L1).
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from femoat.bearings import triple_friction_pendulum as tfp
from femoat.bearings.orbit import orbit_forces
from femoat.bearings.triple_friction_pendulum import TripleFrictionPendulum

FAST = dict(mu1_fast=0.03, mu2_fast=0.08, mu3_fast=0.15, a=1.0)
BEARING = TripleFrictionPendulum(**FAST)


def mu_of(b, i, speed):
    """Surface i's (1, 2, 3) friction coefficient [-] at its sliding speed [in/s]."""
    slow, fast = b.frictions[i - 1], getattr(b, f"mu{i}_fast")
    return fast - (fast - slow) * math.exp(-b.a * speed)


def drive(b, path, dt, velocities):
    """Trial then commit the plan kernels along ``path`` (n, 2) [in], one step of ``dt`` [s] per
    point, the velocities (n, 2) [in/s] at the points, from rest at the origin
    (``femoat.bearings.orbit``): the force magnitudes (n,) [kip] and the final state."""
    forces, s = orbit_forces(b, path, dt, velocities)
    return np.hypot(*forces.T), s


def orbit(radius, period, n_per_turn, turns):
    """A radial ramp to (radius, 0) in 0.25 s, then ``turns`` turns of the circle of ``radius``
    [in] and ``period`` [s], ``n_per_turn`` steps a turn: (path, velocities, dt)."""
    dt = period / n_per_turn
    n0 = max(1, round(0.25 / dt))
    ramp = np.column_stack([radius * np.arange(1, n0 + 1) / n0, np.zeros(n0)])
    ramp_v = np.column_stack([np.full(n0, radius / (n0 * dt)), np.zeros(n0)])
    ramp_v[-1] = 0.0, 0.0
    om = 2.0 * math.pi / period
    th = om * dt * np.arange(1, turns * n_per_turn + 1)
    circle = radius * np.column_stack([np.cos(th), np.sin(th)])
    circle_v = radius * om * np.column_stack([-np.sin(th), np.cos(th)])
    return np.vstack([ramp, circle]), np.vstack([ramp_v, circle_v]), dt


def steady_circle_force(b, radius, period):
    """The steady force magnitude [kip] on a circle of ``radius`` [in] run at constant speed
    with only the inner element sliding (elements 2, 3 sticking: d = F/k_0 each), the
    continuous model. In the frame turning with the orbit (complex amplitudes), element 1's
    slip p = ρ·e^(iφ) turns at ω, so its slip rate is ω·ρ along i·p, and its friction force,
    along the slip rate, is Q = i·q·e^(iφ), q = μ1(fact_1·ω·ρ)·W. Its displacement
    d_1 = p + Q/k_e, the force F = kr·d_1 + Q, and u = d_1 + 2·F/k_0 = r:
        r = e^(iφ)·(ρ·c + i·q·α),  c = 1 + 2·kr/k_0,  α = c/k_e + 2/k_0,
    so r² = (ρ·c)² + (q·α)² fixes ρ (the left side grows with ρ: one root) and
    |F| = |kr·ρ + i·q·(1 + kr/k_e)|."""
    kr, k0 = b.W / b.radii[0], b.sticking_stiffness
    ke = k0 - kr
    om = 2.0 * math.pi / period
    c, alpha = 1.0 + 2.0 * kr / k0, (1.0 + 2.0 * kr / k0) / ke + 2.0 / k0

    def q(rho):
        return b.W * mu_of(b, 1, b.rate_factors[0] * om * rho)

    rho = brentq(lambda r: (r * c) ** 2 + (q(r) * alpha) ** 2 - radius ** 2, 0.0, radius,
                 xtol=1e-15, rtol=1e-15)
    return math.hypot(kr * rho, q(rho) * (1.0 + kr / ke)), q(rho)


def test_a_steady_orbit_converges_at_first_order_to_its_closed_form():
    # A circle of 0.5 in in 2 s (the inner slider's surfaces at ~0.8 in/s, μ1 ≈ 0.022, between
    # its μ_slow 0.012 and μ_fast 0.03; the outer elements stick: |Q_2| = F·(1 − kr_2/k_0)
    # < μ2·W = 1.72 kip), after four turns, at 500 to 2000 steps a turn: the backward-Euler
    # return is first order, so the error halves with the step (measured 7.4e-4, 3.7e-4,
    # 1.8e-4 kip: ratios 2.00), and the first-order term extrapolates out (Richardson: 2·f(h/2)
    # − f(h) within 2e-6 of the closed form's 0.986 kip).
    force, q = steady_circle_force(BEARING, 0.5, 2.0)
    assert BEARING.mu1 * BEARING.W < q < BEARING.mu1_fast * BEARING.W
    assert force * (1.0 - BEARING.W / BEARING.radii[1] / BEARING.sticking_stiffness) \
        < BEARING.mu2 * BEARING.W
    errors = []
    for n in (500, 1000, 2000):
        path, vel, dt = orbit(0.5, 2.0, n, 4)
        f, _ = drive(BEARING, path, dt, vel)
        assert np.ptp(f[-n // 2:]) < 1e-9 * force  # steady
        errors.append(f[-1] - force)
    assert 0.0 < errors[-1] < 2e-4
    for coarse, fine in zip(errors, errors[1:]):
        assert coarse / fine == pytest.approx(2.0, rel=0.02)
    assert abs(2.0 * errors[-1] - errors[-2]) < 2e-6 * force


@pytest.mark.parametrize("radius", [0.5, 4.0, 20.0])
def test_equal_slow_and_fast_friction_is_the_constant_friction_bearing(radius):
    # μ_fast = μ on every surface: μ(v) is constant, and the backward-Euler return with a
    # constant strength is the radial return of the constant-friction elements (the slip
    # |Q_tr| − q over k_e): the same forces to round-off, along a radial ramp and two turns of
    # a circle of this radius (regimes I, II and III).
    same = TripleFrictionPendulum(mu1_fast=0.012, mu2_fast=0.052, mu3_fast=0.12, a=2.0)
    path, vel, dt = orbit(radius, 2.0, 400, 2)
    f_rate, s_rate = drive(same, path, dt, vel)
    f_const, s_const = drive(TripleFrictionPendulum(), path, dt, vel)
    np.testing.assert_allclose(f_rate, f_const, rtol=0.0, atol=1e-10 * f_const.max())
    np.testing.assert_allclose(s_rate[:12], s_const[:12], rtol=0.0, atol=1e-10 * radius)


def test_slow_and_fast_limits_are_the_constant_friction_bearings():
    # Along one axis, 2 in out and back in regimes I-II. Run slowly (steps of 0.005 in in 2.5 s:
    # every slip rate ≤ 0.002 in/s, the surfaces' speeds fact·w ≤ 0.001, 0.0023, 0.0023 in/s, so
    # μ_i within a·fact_i·w·(μ_fast,i − μ_i) = 1.8e-5, 6.5e-5, 6.9e-5 of μ_slow) it is the
    # bearing of constant friction μ_slow within W·Σ of those = 5.0e-3 kip (measured 1.3e-3),
    # and the rate effect is there (above 1e-4 kip: first order in the speed). Run fast with a
    # huge a (every slip rate ≫ 1/a, μ = μ_fast) it is the bearing of constant friction μ_fast
    # (and the same sticking stiffness) within 1e-6 (a slip rate of a few 1e-6 in/s already
    # reaches μ_fast: e^(−a·w) → 0).
    u = np.concatenate([np.linspace(0.0, 2.0, 401)[1:], np.linspace(2.0, -0.5, 501)[1:]])
    path = np.column_stack([u, np.zeros_like(u)])
    slow_b = TripleFrictionPendulum(**FAST)
    const_slow = TripleFrictionPendulum()
    fast_b = TripleFrictionPendulum(**{**FAST, "a": 1e6})
    # (the same sticking stiffness k_0 = 3·μ1_slow·W/u_y: the u_y of μ_fast's bearing scaled)
    const_fast = TripleFrictionPendulum(mu1=0.03, mu2=0.08, mu3=0.15, u_y=0.01 * 0.03 / 0.012)
    dt_slow = 1000.0 / 400  # [s] a step: 0.005 in in 2.5 s
    f, _ = drive(slow_b, path, dt_slow, np.zeros_like(path))
    g, _ = drive(const_slow, path, dt_slow, np.zeros_like(path))
    bound = slow_b.W * slow_b.a * 0.002 * sum(
        fact * (getattr(slow_b, f"mu{i}_fast") - mu) for i, (fact, mu) in
        enumerate(zip(slow_b.rate_factors, slow_b.frictions), start=1))
    assert 1e-4 < np.max(np.abs(f - g)) < bound
    f, _ = drive(fast_b, path, 1e-3, np.zeros_like(path))
    g, _ = drive(const_fast, path, 1e-3, np.zeros_like(path))
    assert np.max(np.abs(f - g)) < 1e-6 * g.max()


def test_the_tangent_is_the_derivative_of_the_force():
    # The consistent tangent of one series solve with velocity-dependent elements (each
    # k_e·(γ·n nᵀ + |Q|/|Q_tr|·(I − n nᵀ)) in series, γ = q′/(q′ + k_e·τ)) against central
    # differences of its force, at trial points of a 2 ms step from a state sliding in
    # regime II (one piece: a path's tangent is its last piece's).
    b = BEARING
    p, s = b.params(), b.initial_state_plan()
    path, vel, dt = orbit(3.0, 2.0, 400, 1)
    u0, v0 = np.zeros(2), np.zeros(2)
    for j in range(300):
        tfp.plan_commit(p, s, *u0, *v0, *path[j], *vel[j], dt)
        u0, v0 = path[j], vel[j]
    assert math.hypot(*s[8:10]) > 1.0  # element 2 slides, faster than at rest

    def solve(u):
        return tfp._path(p, s, *u0, *v0, *u, *v0, dt, 1)

    for du in ([0.01, 0.0], [0.004, -0.007], [-0.002, 0.003]):
        u = u0 + np.array(du)
        r = solve(u)
        k = np.array([[r[2], r[3]], [r[3], r[4]]])
        h = 1e-7
        numeric = np.zeros((2, 2))
        for col in range(2):
            e = np.zeros(2)
            e[col] = h
            plus, minus = solve(u + e), solve(u - e)
            numeric[:, col] = (np.array(plus[:2]) - np.array(minus[:2])) / (2.0 * h)
        np.testing.assert_allclose(k, numeric, rtol=0.0, atol=1e-5 * np.abs(k).max())


def _sliding_state(radius, period):
    """The committed state after two turns of the circle of ``radius`` [in] and ``period`` [s]
    (2000 steps a turn), the rate form's carried elements marked as at a step's start: (p, s,
    u, v)."""
    b = BEARING
    path, vel, dt = orbit(radius, period, 2000, 2)
    _, s = drive(b, path, dt, vel)
    p = b.params()
    assert tfp.plan_rate_active(p, s, *vel[-1])
    return p, s, path[-1], vel[-1]


def test_the_slip_rate_inverts_the_friction_law():
    # _slip_rate(|z|) is the w with μ_i(fact_i·w)/μ_i = |z| (the law read back to 1e-12), zero in
    # the disk (sticking), and beyond a·fact·w = RATE_CAP it goes on along its tangent: value
    # and slope continuous there.
    p = BEARING.params()
    for i in range(3):
        q, qf, b = p[tfp._E0 + 4 * i + 1], p[tfp._RATE + 2 * i], p[tfp._RATE + 2 * i + 1]
        r = qf / q
        assert tfp._slip_rate(p, i, 0.999) == (0.0, 0.0) and tfp._slip_rate(p, i, 1.0) == (0.0, 0.0)
        for x in (1e-9, 0.3, 0.9, 0.999999):
            rho = 1.0 + x * (r - 1.0)
            w, _ = tfp._slip_rate(p, i, rho)
            assert (qf - (qf - q) * math.exp(-b * w)) / q == pytest.approx(rho, rel=1e-12)
        tail = math.exp(-tfp.RATE_CAP)
        cap = 1.0 + (1.0 - tail) * (r - 1.0)
        lo, hi = cap * (1.0 - 1e-15), cap * (1.0 + 1e-15)
        below, slope = tfp._slip_rate(p, i, lo)
        above, slope_above = tfp._slip_rate(p, i, hi)
        assert abs(below - tfp.RATE_CAP / b) <= 2.0 * slope * (cap - lo)
        # the tangent at the switch, w′ = 1/(b·(r − 1)·e^-30); w′ grows towards it (∝ 1/(1 − x)),
        # so the difference quotient across lies between the slopes at its two ends
        assert slope_above == pytest.approx(1.0 / (b * (r - 1.0) * tail), rel=1e-9)
        assert slope < (above - below) / (hi - lo) < slope_above * 1.01


@pytest.mark.parametrize("radius, period", [(0.5, 2.0), (6.0, 3.0)])
def test_the_rate_jacobian_is_its_derivative(radius, period):
    # plan_rate's ∂g/∂z for velocity-dependent friction (exact with the compliances held,
    # which they are without restrainer contact) against central differences of its g, at a
    # state sliding on the inner element (0.5 in, regime I) and on two elements (6 in; |z_1|
    # 2.35, |z_2| 1.54 of μ_fast/μ_slow 2.5 and 1.54: the law's steep end, ∂g/∂z up to 3e6/s):
    # each column within 1e-6 of its largest entry (measured 1e-8).
    p, s, u, v = _sliding_state(radius, period)
    z = s[6:12].copy()
    g, J = np.zeros(6), np.zeros((6, 6))
    tfp.plan_rate(p, s, *u, *v, z, g, J)
    carried = [i for i in range(3) if int(s[tfp._CARRY]) >> i & 1]
    assert carried == ([0] if radius < 1.0 else [0, 1])
    assert np.all(g[[2 * i for i in carried]] != 0.0)
    for col in range(6):
        h = 1e-9 * max(1.0, abs(z[col]))
        plus, minus, scratch = np.zeros(6), np.zeros(6), np.zeros((6, 6))
        zp, zm = z.copy(), z.copy()
        zp[col] += h
        zm[col] -= h
        tfp.plan_rate(p, s, *u, *v, zp, plus, scratch)
        tfp.plan_rate(p, s, *u, *v, zm, minus, scratch)
        numeric = (plus - minus) / (2.0 * h)
        np.testing.assert_allclose(J[:, col], numeric, rtol=0.0,
                                   atol=1e-6 * max(1.0, np.abs(J[:, col]).max()))


def test_the_rate_is_the_limit_of_the_return():
    # The rate form and the backward-Euler return are one model: from a committed state sliding
    # in regime I, the return over a straight step of τ at the bearing's velocity moves z by
    # τ·g + O(τ²): the difference quotient tends to plan_rate's g at first order (measured
    # errors 0.0306, 0.0154, 0.0077 /s against |g| 5.7 /s: ratios 2.00).
    p, s, u, v = _sliding_state(0.5, 2.0)
    g, J = np.zeros(6), np.zeros((6, 6))
    tfp.plan_rate(p, s, *u, *v, s[6:12].copy(), g, J)
    errors = []
    for tau in (1e-4, 5e-5, 2.5e-5):
        s1 = s.copy()
        end = u + v * tau
        tfp.plan_commit(p, s1, *u, *v, *end, *v, tau)
        errors.append(np.abs((s1[6:8] - s[6:8]) / tau - g[:2]).max())
    assert errors[-1] < 2e-3 * np.abs(g).max()
    for coarse, fine in zip(errors, errors[1:]):
        assert coarse / fine == pytest.approx(2.0, rel=0.05)


def test_a_slider_keeps_its_rate_strength_at_the_committed_state():
    # A zero step (τ = 0, the committed state itself, as an event evaluates it) returns the
    # committed friction force, above μ_slow·W while the slider was fast: the force is
    # continuous across a commit.
    b = BEARING
    p, s = b.params(), b.initial_state_plan()
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    u0 = np.zeros(2)
    for j in range(1, 201):  # out along x at 10 in/s
        u = np.array([0.005 * j, 0.0])
        tfp.plan_trial(p, s, *u0, 10.0, 0.0, *u, 10.0, 0.0, 5e-4, f, k, c)
        tfp.plan_commit(p, s, *u0, 10.0, 0.0, *u, 10.0, 0.0, 5e-4)
        u0 = u
    moving = f.copy()
    tfp.plan_trial(p, s, *u0, 0.0, 0.0, *u0, 0.0, 0.0, 0.0, f, k, c)
    np.testing.assert_allclose(f, moving, rtol=1e-12)
    assert math.hypot(*s[6:8]) > 1.5  # the inner element's friction, over μ_slow·W


def test_a_vanishing_rate_parameter_is_the_constant_friction_bearing():
    # a → 0: μ(v) → μ_slow at every finite speed. The return's dissipated energy τ·D(w),
    # D(w) = μ_f·W·w − (μ_f − μ_s)·W·(1 − e^(−b·w))/b, must not cancel (b·w ~ 1e-12 here: expm1)
    # or the energy's gradient would leave the force and the line search fail (NaN forces):
    # a 6 in orbit with a = 1e-12 s/in gives the constant bearing's forces within 1e-9.
    tiny = TripleFrictionPendulum(**{**FAST, "a": 1e-12})
    path, vel, dt = orbit(6.0, 2.0, 400, 2)
    f, _ = drive(tiny, path, dt, vel)
    g, _ = drive(TripleFrictionPendulum(), path, dt, vel)
    assert np.all(np.isfinite(f))
    np.testing.assert_allclose(f, g, rtol=0.0, atol=1e-9 * g.max())


def test_the_opensees_twin_commands_carry_the_velocity_dependence():
    # Without OpenSees: the twin's three friction models are VelDependent with μ_slow and
    # μ_fast each scaled by k_0/(k_0 − W/L̄_i) (the hardening-element equivalence of the
    # constant-friction twin) and the rate a; on the asymmetric bearing whose outer surfaces the
    # twin lists in reverse (d3/L3 > d2/L2), the fast values follow their surfaces.
    b = TripleFrictionPendulum(W=50.0, L2=70.0, L3=100.0, d2=12.0, d3=20.0, mu2=0.06, mu3=0.09,
                               u_y=0.02, mu1_fast=0.02, mu2_fast=0.1, mu3_fast=0.12, a=0.7)
    commands, _ = tfp.opensees_plan_element(b, 1, 1, 2, 1)
    models = [c for c in commands if c[0] == "frictionModel"]
    assert [m[1] for m in models] == ["VelDependent"] * 3
    k0 = b.sticking_stiffness
    # listed: inner (L̄ = 2·L1), then the surface of L3 (larger d/L) as OpenSees' second
    expected = [(b.mu1, b.mu1_fast, 2.0 * b.L1), (b.mu3, b.mu3_fast, b.L3 - b.L1),
                (b.mu2, b.mu2_fast, b.L2 - b.L1)]
    for m, (slow, fast, radius) in zip(models, expected):
        scale = k0 / (k0 - b.W / radius)
        assert m[3:] == pytest.approx((slow * scale, fast * scale, 0.7), rel=1e-15)
    element = next(c for c in commands if c[0] == "element")
    assert element[13:15] == (b.L3, b.L2)  # (OpenSees' L2, L3: the reversed outer surfaces)


@pytest.mark.parametrize(("changes", "name"), [
    ({"mu1_fast": 0.03}, "mu2_fast"),
    ({**FAST, "mu3_fast": None}, "mu3_fast"),
    ({**FAST, "mu2_fast": 0.04}, "mu2_fast"),
    ({**FAST, "mu1_fast": 1.0}, "mu1_fast"),
    ({**FAST, "a": 0.0}, "a"),
    ({**FAST, "a": float("nan")}, "a"),
    ({"a": 1.0}, "a"),
])
def test_invalid_velocity_dependence_names_the_parameter(changes, name):
    with pytest.raises(ValueError, match=rf"^{name} = "):
        TripleFrictionPendulum(**changes)


def test_along_one_axis_the_plan_bearing_is_the_axis_bearing():
    # The one-axis kernels are the plan element at (u, 0) reached in the duration the state
    # row's last entry holds (the loop writes it there: materials.kernels.DURATION): along x at
    # varying speeds (steps of 1-4 ms, two reversals, through regimes I-III), the same forces,
    # tangents and internal states to the bit.
    from femoat.structure.materials.kernels import DURATION

    b = BEARING
    p = b.params()
    sa, sp = b.initial_state_axis(), b.initial_state_plan()
    assert sa.size == sp.size + 1 and sa[DURATION] == 0.0
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    rng = np.random.default_rng(7)
    u0 = 0.0
    points = np.concatenate([np.linspace(0.0, 12.0, 300)[1:], np.linspace(12.0, -8.0, 300)[1:],
                             np.linspace(-8.0, 3.0, 200)[1:]])
    for u in points:
        tau = float(rng.uniform(1e-3, 4e-3))
        sa[DURATION] = tau
        fa, ka, ca = tfp.axis_trial(p, sa, u, 0.0)
        tfp.plan_trial(p, sp, u0, 0.0, 0.0, 0.0, u, 0.0, 0.0, 0.0, tau, f, k, c)
        assert (fa, ka, ca) == (f[0], k[0, 0], 0.0) and f[1] == 0.0
        tfp.axis_commit(p, sa, u, 0.0)
        tfp.plan_commit(p, sp, u0, 0.0, 0.0, 0.0, u, 0.0, 0.0, 0.0, tau)
        np.testing.assert_array_equal(sa[:12], sp[:12])
        assert sa[DURATION] == tau  # (the kernels never write it)
        u0 = u
    assert np.max(np.abs(sa[6:12:2])) > 1.0  # the elements slid faster than at rest


def test_the_design_loop_reads_the_friction_at_its_nominal_speed():
    # isolation_design.effective_properties cycles a one-axis bearing at 1 in/s; a
    # velocity-dependent bearing is stepped with each step's duration at that speed. With a
    # huge rate parameter (a = 1e6 s/in: μ = μ_fast at any slip rate above ~1e-5 in/s) its
    # loop is the constant bearing's at μ_fast (but for the first instants of each slip, whose
    # rate starts from 0: to 1e-7); with a vanishing one (1e-12 s/in) the constant bearing's at
    # μ_slow (to 1e-9; the same sticking stiffness 3·μ1·W/u_y in all); a = 1 s/in, whose
    # surfaces slide at fact_i times their share of 1 in/s, lies strictly between.
    from femoat.structure.isolation_design import effective_properties

    amp = 10.0
    slow = effective_properties(TripleFrictionPendulum(), amp)
    k0 = TripleFrictionPendulum().sticking_stiffness
    fast_const = TripleFrictionPendulum(mu1=0.03, mu2=0.08, mu3=0.15,
                                        u_y=3.0 * 0.03 * 33.0 / k0)
    fast = effective_properties(fast_const, amp)
    np.testing.assert_allclose(effective_properties(  # (measured 1.7e-8: each slip's onset)
        TripleFrictionPendulum(**{**FAST, "a": 1e6}), amp), fast, rtol=1e-7)
    np.testing.assert_allclose(effective_properties(
        TripleFrictionPendulum(**{**FAST, "a": 1e-12}), amp), slow, rtol=1e-9)
    k, beta = effective_properties(BEARING, amp)
    assert slow[0] < k < fast[0] and slow[1] < beta < fast[1]


def test_a_1d_run_takes_newmark_and_agrees_with_the_plan_run_on_a_line():
    # A 1D building on the bearing runs on Newmark's step by default (whose solve writes each
    # step's duration into the element states) and refuses the other methods, whose stages
    # would take the return over their offsets. The paper building in the concrete moat under
    # Erzincan (first 6 s, law H): within 1e-3 of its run at rtol 1e-8 on every peak with the
    # same impacts (measured 7.1e-4, a drift), its energy balance closed (the work done on the
    # bearing = its recoverable energy + what the returns dissipated; measured 3.0e-14 of the
    # input, 2e-9 before a restart after a contact event stamped a zero duration), and within
    # 1e-3 of the plan model along x on Newmark's step (like for like: its default is ark5)
    # under the same record and a zero y
    # component (not the same steps: the plan run lands on the bearing's branch changes, the
    # 1D kink search skips a bearing whose tangent depends on the step; measured 2.7e-5), the
    # same impacts.
    from femoat.ground_motions import GroundMotion, RecordPair
    from femoat.integration import Integrator
    from femoat.paper import paper_motion
    from femoat.plan import PlanBuilding, PlanModel
    from femoat.run import run

    m = paper_motion()
    n = int(round(6.0 / m.dt)) + 1
    m = GroundMotion(m.accel_g[:n], m.dt, name=m.name)
    plan = PlanModel(building=PlanBuilding(isolator=BEARING))
    line = plan.along("x")
    one = run(line, m)
    assert one.meta["info"]["method"] == "newmark"
    converged = run(line, m, integrator=Integrator(method="newmark", rtol=1e-8))
    both = run(plan, RecordPair(m, GroundMotion(0.0 * m.accel_g, m.dt, name="zero")),
               integrator=Integrator(method="newmark"))

    def peaks(r):
        pk = r.peaks
        return [pk["peak_base_displacement"], pk["peak_impact_force_pos"],
                pk["peak_impact_force_neg"], *pk["peak_drift"]]

    assert one.peaks["impacts_pos"] + one.peaks["impacts_neg"] > 0
    assert [one.peaks["impacts_pos"], one.peaks["impacts_neg"]] == \
        [converged.peaks["impacts_pos"], converged.peaks["impacts_neg"]]
    np.testing.assert_allclose(peaks(one), peaks(converged), rtol=1e-3)
    energy = one.meta["energy"]
    assert energy["residual"] < 1e-12  # (relative to the input)
    assert [one.peaks["impacts_pos"], one.peaks["impacts_neg"]] == \
        [both.peaks["impacts_px"], both.peaks["impacts_mx"]]
    np.testing.assert_allclose(
        peaks(one),
        [both.peaks["peak_plan_base_displacement"], both.peaks["peak_impact_force_px"],
         both.peaks["peak_impact_force_mx"], *both.peaks["peak_drift_x"]], rtol=1e-3)
    # the velocity dependence acts in 1D: both constant-friction bearings (at μ_slow, and at
    # μ_fast with the same sticking stiffness) are far off on some peak (measured 22 % and 7.9 %)
    for other in (TripleFrictionPendulum(),
                  TripleFrictionPendulum(mu1=0.03, mu2=0.08, mu3=0.15, u_y=0.025)):
        r = run(PlanModel(building=PlanBuilding(isolator=other)).along("x"), m)
        assert np.max(np.abs(np.array(peaks(r)) / peaks(converged) - 1.0)) > 0.03
    for method in ("dp5", "ark5", "tsit5"):
        with pytest.raises(ValueError, match=rf"method = '{method}' on a 1D isolator with "
                                             "velocity-dependent friction.*'newmark'"):
            run(line, m, integrator=Integrator(method=method))


def test_a_plan_run_defaults_to_ark5_and_a_surface_at_constant_friction_to_newmark():
    # The rate form covers velocity-dependent friction with μ_fast > μ on every surface (the
    # law's inverse, the slip rate, exists on each); a bearing with one surface at μ_fast = μ
    # (allowed: its friction is constant there) runs on Newmark and refuses ark5 by name.
    from femoat.ground_motions import GroundMotion, RecordPair
    from femoat.integration import Integrator
    from femoat.plan import PlanBuilding, PlanModel
    from femoat.run import plan_method, run

    assert plan_method(PlanModel(building=PlanBuilding(isolator=BEARING))) == "ark5"
    assert tfp.rate_form_covers(BEARING.params())
    mixed = TripleFrictionPendulum(**{**FAST, "mu1_fast": BEARING.mu1})
    assert not tfp.rate_form_covers(mixed.params())
    model = PlanModel(building=PlanBuilding(isolator=mixed))
    assert plan_method(model) == "newmark"
    quiet = GroundMotion(np.zeros(10), 0.01, name="zero")
    with pytest.raises(ValueError, match="velocity-dependent friction.*newmark.*μ_fast > μ"):
        run(model, RecordPair(quiet, quiet), integrator=Integrator(method="ark5"))


def test_scenario_and_suite_files_take_the_velocity_dependence():
    # [building.isolator] type = "tfp" with the μ_fast and a: a plan scenario builds the
    # bearing (ark5 by default, Newmark on request) and a 1D one (Newmark by default, another
    # method refused naming the fix); a suite may vary mu2_fast like any isolator field.
    from femoat.run import plan_method
    from femoat.scenario import model_from_dict
    from femoat.scenario.document import integrator_for
    from femoat.suite.model import build_variation
    from femoat.suite.variations import allowed_keys, apply, variations_from_dict

    iso = {"type": "tfp", **FAST}
    plan = model_from_dict({"building": {"plan": True, "isolator": iso}})
    assert plan.building.isolator.velocity_dependent
    assert plan.building.isolator.rate_factors == (0.5, 88.0 / 76.0, 88.0 / 76.0)
    assert plan_method(plan) == "ark5"
    assert integrator_for(plan, {}).method == "ark5"  # a [solver] table without a method
    assert integrator_for(plan, {"method": "newmark"}).method == "newmark"
    one_axis = model_from_dict({"building": {"isolator": iso}})
    assert integrator_for(one_axis, {}).method == "newmark"
    assert integrator_for(one_axis, {"rtol": 1e-6}).rtol == 1e-6
    with pytest.raises(ValueError, match=r"^\[solver\] method = 'dp5'.*method = \"newmark\""):
        integrator_for(one_axis, {"method": "dp5"})
    assert integrator_for(model_from_dict({}), {}).method == "dp5"  # (the default kept)
    assert {"mu1_fast", "mu2_fast", "mu3_fast", "a"} <= allowed_keys()["building.isolator"]
    _, combos = variations_from_dict({"building.isolator.mu2_fast": [0.06, 0.1]})
    base = {"building": {"plan": True, "isolator": iso}}
    isos = [build_variation(apply(base, c)).pounding.building.isolator for c in combos]
    assert [b.mu2_fast for b in isos] == [0.06, 0.1]
    assert [b.params()[tfp._RATE + 2] for b in isos] == [0.06 * 33.0, 0.1 * 33.0]
    # (a 1D suite's runs take Newmark too: a suite reads its [solver] as a scenario does)
    line = build_variation(apply({"building": {"isolator": iso}}, combos[0]))
    assert line.integrator.method == "newmark" and line.pounding.building.isolator.mu2_fast == 0.06


# ---- OpenSees' TripleFrictionPendulum with VelDependent friction ------------------------------


def opensees_orbit_forces(b, path, dt):
    """OpenSees' TripleFrictionPendulum (tfp.opensees_plan_element: VelDependent friction
    models) under ``path`` (n, 2) [in] imposed one transient step of ``dt`` [s] per point (its
    friction reads |Δd_i|/Δt, the analysis' step), N = W from a static step first
    (``femoat.opensees.bearing_orbit``): the shear force magnitudes (n,) [kip]."""
    from conftest import opensees_or_skip
    from femoat.opensees.bearing_orbit import orbit_forces

    opensees_or_skip()
    return np.hypot(*orbit_forces(b, path, dt).T)


@pytest.mark.opensees
def test_opensees_twin_converges_to_the_same_steady_orbit():
    # The steady circle of the first test (0.5 in in 2 s, regime I) at 125, 250 and 500 steps a
    # turn (16, 8, 4 ms): both are first-order steps of the same model (OpenSees reads each
    # friction law at its element's whole deformation rate |Δd|/Δt, femoat at the slip rate;
    # on this orbit they differ by ~(q/k_e)²/ρ² ~ 1e-4 of the rate), so each one's Richardson
    # extrapolation 2·f(h/2) − f(h) tends to the closed form: OpenSees' within 6.3e-5 and
    # 2.5e-5 of it (measured), femoat's within 3.1e-6 and 8e-7. femoat's error is the smaller
    # at each step (7.4e-4 against 3.0e-3 at 4 ms). (Smaller steps are not comparable: at
    # 2 ms and below OpenSees' force oscillates from step to step on this orbit by up to 8 %:
    # its friction coefficient lags one iteration behind the velocity, a fixed point whose
    # factor W·μ′·fact/(k_0·Δt/2) passes 1 below ~2.3 ms here: benchmarks/tfp_velocity.py.)
    exact, _ = steady_circle_force(BEARING, 0.5, 2.0)
    ours, twin = [], []
    for n in (125, 250, 500):
        path, vel, dt = orbit(0.5, 2.0, n, 3)
        f, _ = drive(BEARING, path, dt, vel)
        g = opensees_orbit_forces(BEARING, path, dt)
        assert np.ptp(g[-n // 2:]) < 1e-9 * exact  # steady in OpenSees too
        ours.append(f[-1])
        twin.append(g[-1])
    for a, b in zip(ours, twin):
        assert 0.0 < a - exact < b - exact
    for seq, bound in ((twin, 1e-4), (ours, 5e-6)):
        for coarse, fine in zip(seq, seq[1:]):
            assert abs(2.0 * fine - coarse - exact) < bound * exact


def test_a_plan_run_converges_and_the_velocity_dependence_acts():
    # The paper building in plan on the bearing (the square concrete moat, law H), the first
    # 8 s of Erzincan along x and its reversed copy at 0.6 along y, turned by 30°. Two
    # discretisations of one model: the rate form on the coupled-friction step (the default,
    # ark5) and the backward-Euler return on Newmark's (first order in the friction). The
    # default within 1e-3 of Newmark at rtol 1e-8 on every peak (measured 8.2e-5; Newmark at its
    # default 2.0e-4, also asserted), the same impacts on every wall; ark5 and Newmark, both at
    # rtol 1e-8, within 1e-4 of each other (measured 2.3e-5, Newmark's own error). The energy
    # balance closes on Newmark's step (the work done on the bearing = its recoverable energy
    # + friction dissipated, the returns' incremental potentials: measured residual 3.6e-14 of
    # the input) and to the pair's quadrature on ark5's (measured 1.4e-5; the constant-friction
    # bearing's ark5 run: 9.5e-6). The friction acts at speed: the peaks differ from both
    # constant-friction bearings', at μ_slow and at μ_fast (with the same sticking stiffness),
    # by far more than the run's error (the impact forces by 12-14 % and 4-7 %).
    from femoat.ground_motions import GroundMotion, RecordPair
    from femoat.integration import Integrator
    from femoat.paper import paper_motion
    from femoat.plan import PlanBuilding, PlanModel
    from femoat.run import run

    m = paper_motion()
    n = int(round(8.0 / m.dt)) + 1
    m = GroundMotion(m.accel_g[:n], m.dt, name=m.name)
    pair = RecordPair(m, GroundMotion(-0.6 * m.accel_g[::-1], m.dt, name="y"), angle=30.0)

    def model(b):
        return PlanModel(building=PlanBuilding(isolator=b))

    tags = ("px", "mx", "py", "my")

    def peaks(r):
        pk = r.peaks
        return np.array([pk["peak_plan_base_displacement"],
                         *[pk[f"peak_impact_force_{t}"] for t in tags],
                         *pk["peak_drift_x"], *pk["peak_drift_y"]])

    default = run(model(BEARING), pair)
    assert default.meta["info"]["method"] == "ark5"
    newmark = run(model(BEARING), pair, integrator=Integrator(method="newmark"))
    converged = run(model(BEARING), pair, integrator=Integrator(method="newmark", rtol=1e-8))
    tight = run(model(BEARING), pair, integrator=Integrator(method="ark5", rtol=1e-8))
    for r in (default, newmark, tight):
        assert [r.peaks[f"impacts_{t}"] for t in tags] == \
            [converged.peaks[f"impacts_{t}"] for t in tags]
        np.testing.assert_allclose(peaks(r), peaks(converged), rtol=1e-3)
    np.testing.assert_allclose(peaks(tight), peaks(converged), rtol=1e-4)
    assert newmark.meta["energy"]["residual"] < 1e-12  # (relative to the input)
    assert default.meta["energy"]["residual"] < 1e-4
    slow = run(model(TripleFrictionPendulum()), pair)
    fast = run(model(TripleFrictionPendulum(mu1=0.03, mu2=0.08, mu3=0.15, u_y=0.025)), pair)
    for other in (slow, fast):
        assert np.max(np.abs(peaks(other) / peaks(converged) - 1.0)) > 0.03

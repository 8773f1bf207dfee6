"""The triple friction-pendulum bearing (femoat.bearings.triple_friction_pendulum): the series
model's backbone and loops against closed forms, Fenz & Constantinou's regimes as u_y → 0, the
plan element on one axis, steady circular orbits, and OpenSees' TripleFrictionPendulum as twin.

Notation as in the module: L1 inner, L2/L3 outer radii; series elements i = 1, 2, 3 of radius
L̄ = 2·L1, L2 − L1, L3 − L1, friction force q_i = μ_i·W, restoring stiffness kr_i = W/L̄_i,
sticking stiffness k_0 = 3·μ1·W/u_y (each element, and each restrainer), element yield
displacement u_y,i = q_i/(k_0 − kr_i), gaps g_i.
"""

import itertools
import math
import re

import numpy as np
import pytest
from scipy.optimize import brentq

from femoat.bearings import triple_friction_pendulum as tfp
from femoat.bearings.triple_friction_pendulum import TripleFrictionPendulum

BEARING = TripleFrictionPendulum()
# Outer surfaces of different radius, capacity and friction, d3/L3 = 0.2 > d2/L2 = 0.171 (the
# inner gap then uses d2/L2, where OpenSees' formula would use d3/L3), a larger u_y and W.
ASYMMETRIC = TripleFrictionPendulum(W=50.0, L2=70.0, L3=100.0, d2=12.0, d3=20.0, mu2=0.06,
                                    mu3=0.09, u_y=0.02)
BEARINGS = pytest.mark.parametrize("b", [BEARING, ASYMMETRIC], ids=["typical", "asymmetric"])


# ---------------------------------------------------------------------------------- drivers


def drive_axis(b, u):
    """Trial then commit the one-axis kernels at every displacement of ``u`` [in]: forces,
    tangents, and the final state."""
    p, s = b.params(), b.initial_state_axis()
    f, k = np.zeros(len(u)), np.zeros(len(u))
    for i, ui in enumerate(u):
        f[i], k[i], c = tfp.axis_trial(p, s, ui, 0.0)
        assert c == 0.0
        tfp.axis_commit(p, s, ui, 0.0)
    return f, k, s


def drive_plan(b, path):
    """Trial then commit the plan kernels at every point of ``path`` (n, 2) [in]: forces (n, 2),
    tangents (n, 2, 2), and the final state."""
    p, s = b.params(), b.initial_state_plan()
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    forces, tangents = np.zeros((len(path), 2)), np.zeros((len(path), 2, 2))
    for i, (ux, uy) in enumerate(path):
        tfp.plan_trial(p, s, 0.0, 0.0, 0.0, 0.0, ux, uy, 0.0, 0.0, 0.0, f, k, c)
        tfp.plan_commit(p, s, 0.0, 0.0, 0.0, 0.0, ux, uy, 0.0, 0.0, 0.0)
        forces[i], tangents[i] = f, k
    return forces, tangents, s


def elements(b):
    """(kr_i [kip/in], q_i [kip], u_y,i [in], g_i [in]) of the three series elements."""
    return [(b.W / r, mu * b.W, uy, g) for r, mu, uy, g in
            zip(b.radii, b.frictions, b.element_yield_displacements, b.gaps)]


# ------------------------------------------------------------------ the backbone on one axis


def element_displacement(b, e, force):
    """Series element ``e``'s displacement [in] at ``force`` [kip] on virgin monotonic loading:
    sticking F/k_0 or sliding (F − q)/kr, whichever is larger (it slides from F = k_0·u_y,i on,
    where both are u_y,i), and past its gap g (reached sliding: F_c = kr·g + q) the restrainer
    k_0 in parallel: g + (F − F_c)/(kr + k_0)."""
    kr, q, _, g = e
    d = max(force / b.sticking_stiffness, (force - q) / kr)
    if d > g:
        d = g + (force - kr * g - q) / (kr + b.sticking_stiffness)
    return d


def backbone_u(b, force):
    """The series model's virgin backbone u(F) [in] = Σ d_i(F) (exact with u_y > 0)."""
    return sum(element_displacement(b, e, force) for e in elements(b))


def breakpoints(b):
    """The forces [kip] where an element starts sliding (k_0·u_y,i) or reaches its gap."""
    k0 = b.sticking_stiffness
    return sorted([k0 * uy for _, _, uy, _ in elements(b)]
                  + [kr * g + q for kr, q, _, g in elements(b)])


def backbone_force(b, u):
    """F(u) [kip] on the backbone: u(F) is linear between breakpoints, so F is the linear
    interpolation between the bracketing breakpoints (exact up to rounding)."""
    fs = [0.0, *breakpoints(b)]
    fs.append(fs[-1] + 10.0 * b.W)
    us = [backbone_u(b, f) for f in fs]
    j = int(np.searchsorted(us, u)) - 1
    j = min(max(j, 0), len(fs) - 2)
    return fs[j] + (u - us[j]) * (fs[j + 1] - fs[j]) / (us[j + 1] - us[j])


def fenz_constantinou(b, u):
    """Fenz & Constantinou's rigid-plastic backbone F(u) [kip] (module docstring), and its
    transition displacements u*, u**, u_dr1, u_dr4, u_ult [in]."""
    w, l1, l2, l3 = b.W, b.L1, b.L2, b.L3
    m1, m2, m3 = b.frictions
    u1 = 2 * l1 * (m2 - m1)
    u2 = u1 + (l1 + l2) * (m3 - m2)
    f_dr1, f_dr4 = w * (m2 + b.d2 / l2), w * (m3 + b.d3 / l3)
    u3 = u2 + (l2 + l3) * (f_dr1 / w - m3)
    u4 = u3 + (l1 + l3) * (f_dr4 - f_dr1) / w
    u5 = u4 + 2 * l1 * (w * (m1 + b.d1 / l1 + min(b.d2 / l2, b.d3 / l3)) - f_dr4) / w
    if u <= u1:
        force = m1 * w + w * u / (2 * l1)
    elif u <= u2:
        force = m2 * w + w * (u - u1) / (l1 + l2)
    elif u <= u3:
        force = m3 * w + w * (u - u2) / (l2 + l3)
    elif u <= u4:
        force = f_dr1 + w * (u - u3) / (l1 + l3)
    else:
        force = f_dr4 + w * (u - u4) / (2 * l1)
    return force, (u1, u2, u3, u4, u5)


@BEARINGS
def test_backbone_is_the_series_closed_form_in_every_regime(b):
    # Monotonic loading from rest to past the capacity: every element's z only grows, so each
    # committed point is on the backbone u(F) = Σ d_i(F) (element_displacement), whatever kinks
    # lie between the points; F(u) is its exact inverse. The five regimes and the stiffening
    # past the capacity all lie on the path.
    u = np.linspace(0.0, 1.01 * b.capacity, 1500)[1:]
    f, k, _ = drive_axis(b, u)
    expected = np.array([backbone_force(b, ui) for ui in u])
    np.testing.assert_allclose(f, expected, rtol=1e-12)
    # The tangent: inside each regime (a point away from the breakpoints) the series
    # stiffness 1/Σ(1/k_i), with k_i = k_0 sticking, kr_i sliding, kr_i + k_0 past the gap.
    _, (u1, u2, u3, u4, u5) = fenz_constantinou(b, 0.0)
    (kr1, _, _, _), (kr2, _, _, _), (kr3, _, _, _) = elements(b)
    k0 = b.sticking_stiffness
    outer_first = (b.d2 / b.L2 + b.mu2) <= (b.d3 / b.L3 + b.mu3)
    ka, kb = (kr2, kr3) if outer_first else (kr3, kr2)
    regimes = [  # (a displacement inside the regime, the series stiffness there)
        (0.5 * u1, 1 / (1 / kr1 + 2 / k0)),
        (0.5 * (u1 + u2), 1 / (1 / kr1 + 1 / kr2 + 1 / k0)),
        (0.5 * (u2 + u3), 1 / (1 / kr1 + 1 / kr2 + 1 / kr3)),
        (0.5 * (u3 + u4), 1 / (1 / kr1 + 1 / (ka + k0) + 1 / kb)),
        (0.5 * (u4 + u5), 1 / (1 / kr1 + 1 / (kr2 + k0) + 1 / (kr3 + k0))),
        (1.005 * b.capacity, 1 / (1 / (kr1 + k0) + 1 / (kr2 + k0) + 1 / (kr3 + k0))),
    ]
    for ui, stiffness in regimes:
        i = int(np.argmin(abs(u - ui)))
        assert k[i] == pytest.approx(stiffness, rel=1e-12), ui
    # F&C's regime stiffnesses W/(2·L1), W/(L1 + L2), W/(L2 + L3), W/(L1 + L3), W/(2·L1) are
    # these with k_0 → ∞ (the sticking and restrainer compliances 1/k_0 dropped).


def test_backbone_tends_to_fenz_constantinou_at_first_order_in_u_y():
    # At F&C's transitions and inside each regime, the force differs from their rigid-plastic
    # closed form by the elastic compliance of the sticking elements and restrainers (each
    # 1/k_0 ∝ u_y) and the onset shift of sliding (k_0·u_y,i − q_i ∝ u_y): first order in u_y,
    # so halving u_y halves the largest difference.
    errors = []
    for u_y in (4e-3, 2e-3, 1e-3):
        b = TripleFrictionPendulum(u_y=u_y)
        _, transitions = fenz_constantinou(b, 0.0)
        probes = sorted([*transitions[:-1], *(0.5 * (a + c) for a, c in
                                              zip((0.0, *transitions[:-1]), transitions))])
        f, _, _ = drive_axis(b, np.array(probes))  # monotonic: each point on the backbone
        expected = np.array([fenz_constantinou(b, ui)[0] for ui in probes])
        errors.append(np.max(np.abs(f - expected)) / (b.mu1 * b.W))
    assert errors[0] < 0.05
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all((ratios > 1.9) & (ratios < 2.1)), ratios


def test_fenz_constantinou_transitions_of_the_typical_bearing():
    # The class docstring's numbers: u* = 2·12·0.04 = 0.96 in, u** = 0.96 + 100·0.068 = 7.76 in,
    # F_dr1/W = 0.052 + 16/88, u_dr1 = 7.76 + 176·(F_dr1/W − 0.12) = 27.78 in,
    # u_dr4 = u_dr1 + 100·0.068 = 34.58 in, and u_ult = 2·2 + 2·16 = 36 in = the capacity.
    _, (u1, u2, u3, u4, u5) = fenz_constantinou(BEARING, 0.0)
    assert (u1, u2) == (pytest.approx(0.96, rel=1e-14), pytest.approx(7.76, rel=1e-14))
    assert u3 == pytest.approx(7.76 + 176 * (0.052 + 16 / 88 - 0.12), rel=1e-14)
    assert u4 == pytest.approx(u3 + 6.8, rel=1e-14)
    assert u5 == pytest.approx(36.0, rel=1e-14) and BEARING.capacity == pytest.approx(36.0)


def test_capacity_is_where_the_inner_slider_reaches_its_restrainer():
    # Symmetric: 2·d1 + d2 + d3. Asymmetric with d3/L3 > d2/L2: the inner slider meets its
    # restrainer on the surface next to L2 first, at 2·d1 + d2 + d3 − L1·(d3/L3 − d2/L2),
    # below OpenSees' formula 2·d1 + d2 + d3 + L1·d3/L3 − L1·d2/L2 by 2·L1·(d3/L3 − d2/L2).
    assert BEARING.capacity == pytest.approx(2 * 2 + 16 + 16, rel=1e-15)
    b = ASYMMETRIC
    physical = 2 * b.d1 + b.d2 + b.d3 - b.L1 * (b.d3 / b.L3 - b.d2 / b.L2)
    opensees = 2 * b.d1 + b.d2 + b.d3 + b.L1 * b.d3 / b.L3 - b.L1 * b.d2 / b.L2
    assert b.capacity == pytest.approx(physical, rel=1e-15)
    assert opensees - b.capacity == pytest.approx(2 * b.L1 * (b.d3 / b.L3 - b.d2 / b.L2))
    swapped = TripleFrictionPendulum(W=50.0, L2=100.0, L3=70.0, d2=20.0, d3=12.0, mu2=0.06,
                                     mu3=0.09, u_y=0.02)  # now d3/L3 < d2/L2: OpenSees' formula
    assert swapped.capacity == pytest.approx(
        2 * 2 + 20 + 12 + 12 * 12 / 70 - 12 * 20 / 100, rel=1e-14)
    # The bearing first slides at 3·u_y,1 ≈ u_y (three elements of stiffness k_0 in series).
    assert BEARING.yield_deformation == pytest.approx(
        3 * 0.012 * 33 / (3 * 0.012 * 33 / 0.01 - 33 / 24), rel=1e-14)


def test_branches_along_the_backbone_and_the_turning_direction():
    # Branch code Σ sliding_i·2^i + contact_i·2^(3+i): along the backbone of the typical bearing
    # the elements start to slide in the order 1, 2, 3 (0 → 1 → 3 → 7), then the restrainers of
    # elements 2, 3 and 1 are reached (7 + 16 = 23, + 32 = 55, + 8 = 63).
    b = BEARING
    p, s = b.params(), b.initial_state()
    seen = []
    for u in [0.005, *np.linspace(0.0, 36.5, 3000)[1:]]:  # 0.005 in: before it slides
        branch = tfp.plan_branch(p, s, u, 0.0)
        if not seen or seen[-1] != branch:
            seen.append(branch)
        tfp.plan_commit(p, s, 0.0, 0.0, 0.0, 0.0, u, 0.0, 0.0, 0.0, 0.0)
        if branch & 1:  # sliding: the turning direction is the friction direction, +x
            assert tfp.plan_turn_direction(s) == (1.0, 0.0)
    assert seen == [0, 1, 3, 7, 23, 55, 63]
    # Back a little: every element sticks (the force drops by less than 2·k_0·u_y,1).
    tfp.plan_commit(p, s, 0.0, 0.0, 0.0, 0.0, 36.5 - 0.001, 0.0, 0.0, 0.0, 0.0)
    assert tfp.plan_turn_direction(s) == (0.0, 0.0)


# ------------------------------------------------------------------------- loops and energy


def loop_energy_closed(b, amplitude):
    """Energy [kip·in] dissipated per steady cycle ±``amplitude`` [in] on one axis.

    The cycle's force amplitude F_A is the backbone's (at u = ±A every element that slid is on
    its sliding branch, the others elastic: Σ d_i(F_A) = A). Element i's friction disk works
    q_i·|Δp| with z = ±1 while its plastic slip p = d − u_y,i·z moves, and its springs and
    restrainer are elastic: per half cycle d runs from −D_i to D_i, D_i = d_i(F_A), of which
    2·u_y,i is the disk's elastic travel, so E = Σ_i 4·q_i·(D_i − u_y,i)₊."""
    fa = backbone_force(b, amplitude)
    return sum(4 * e[1] * max(element_displacement(b, e, fa) - e[2], 0.0) for e in elements(b))


def loop_energy_numeric(b, amplitude, step):
    """∮F du over the cycle A → −A → A (after loading 0 → A), by trapezoids between committed
    points at most ``step`` apart, each step landed just past any change of branch (located by
    bisection to 2^-60 of the step) so that F is linear between points: the trapezoids are then
    exact up to rounding (and a kink in the first 2^-20 of a step, ~1e-12 of the work). Also
    returns the recoverable energy at A before and after."""
    p, s = b.params(), b.initial_state()
    u_now = 0.0
    work = 0.0
    energies = []
    for target, count in ((amplitude, False), (-amplitude, True), (amplitude, True)):
        n = max(1, math.ceil(abs(target - u_now) / step))
        for end in np.linspace(u_now, target, n + 1)[1:]:
            while u_now != end:
                # the branch just into the step (2^-20 of it: at the committed point itself an
                # element may sit on the boundary of two branches, to rounding)
                lo, hi = 2.0**-20, 1.0
                branch0 = tfp.plan_branch(p, s, u_now + lo * (end - u_now), 0.0)
                if tfp.plan_branch(p, s, end, 0.0) != branch0:
                    for _ in range(60):
                        mid = 0.5 * (lo + hi)
                        if tfp.plan_branch(p, s, u_now + mid * (end - u_now), 0.0) == branch0:
                            lo = mid
                        else:
                            hi = mid
                u_next = end if hi == 1.0 else u_now + hi * (end - u_now)
                f0 = tfp.axis_trial(p, s, u_now, 0.0)[0]
                f1 = tfp.axis_trial(p, s, u_next, 0.0)[0]
                if count:
                    work += 0.5 * (f0 + f1) * (u_next - u_now)
                tfp.axis_commit(p, s, u_next, 0.0)
                u_now = u_next
        if target > 0:
            energies.append(tfp.axis_energy(p, s))
    return work, energies


@pytest.mark.parametrize("amplitude", [0.5, 4.0, 15.0, 31.0, 35.5],
                         ids=["I", "II", "III", "IV", "V"])
def test_energy_per_cycle_in_each_regime(amplitude):
    # Closed form (loop_energy_closed); the loop closes: the recoverable energy at +A is the
    # same before and after the cycle, so the work is all dissipated.
    b = BEARING
    work, (before, after) = loop_energy_numeric(b, amplitude, step=0.25)
    expected = loop_energy_closed(b, amplitude)
    assert work == pytest.approx(expected, rel=1e-10)
    assert after == pytest.approx(before, rel=1e-12)
    # In regime I only the inner slider slips, by A less the elastic travel of the two sticking
    # elements (2·F_A/k_0) and of its own disk (u_y,1): 4·μ1·W·(A − 2·F_A/k_0 − u_y,1), F&C's
    # 4·μ1·W·A as u_y → 0 (here 4 % less).
    if amplitude == 0.5:
        slip = amplitude - 2 * backbone_force(b, amplitude) / b.sticking_stiffness \
            - b.element_yield_displacements[0]
        assert expected == pytest.approx(4 * b.mu1 * b.W * slip, rel=1e-12)


# ----------------------------------------------------------------------------------- in plan


def cyclic_path(rng, n=2500, largest=1.5):
    """A random one-axis history [in] with reversals: runs of 1-60 steps of up to ``largest``
    (one run in three of up to 0.006 in, so that the bearing also sticks after reversals), kept
    within ±36.3 in (every regime and the restrainers)."""
    steps, sign, u = [], 1.0, 0.0
    while len(steps) < n:
        size = 0.006 if rng.uniform() < 1 / 3 else largest
        for du in sign * rng.uniform(0.05, 1.0, int(rng.integers(1, 60))) * size:
            if abs(u + du) > 36.3:
                break
            u += du
            steps.append(u)
        sign = -sign
    return np.array(steps[:n])


@pytest.mark.parametrize("axis", [0, 1], ids=["x", "y"])
def test_along_one_axis_the_plan_bearing_is_the_axis_bearing(axis):
    # The axis kernels are the plan core at (u, 0): along x the same arithmetic (bitwise);
    # along y the roles of x and y swap in formulas symmetric in them, with the other
    # component exactly 0: bitwise too. Nothing acts across the axis.
    b = BEARING
    u = cyclic_path(np.random.default_rng(3 + axis))
    path = np.zeros((len(u), 2))
    path[:, axis] = u
    f, k, s_plan = drive_plan(b, path)
    f1, k1, s_axis = drive_axis(b, u)
    np.testing.assert_array_equal(f[:, axis], f1)
    np.testing.assert_array_equal(k[:, axis, axis], k1)
    if axis == 0:  # (the one-axis state ends with the step's duration, kernels.DURATION)
        np.testing.assert_array_equal(s_plan, s_axis[:tfp.N_STATE_PLAN])
    assert np.all(f[:, 1 - axis] == 0.0) and np.all(k[:, 0, 1] == 0.0)
    p = b.params()
    assert tfp.plan_energy(p, s_plan) == pytest.approx(tfp.axis_energy(p, s_axis), rel=1e-12)
    # The history visits sticking (k ≥ k_0/3), regimes I-III and the restrainers (k > k_0/2).
    k0 = b.sticking_stiffness
    assert np.sum(k1 > 0.3 * k0) > 100 and np.sum(k1 < 0.02 * k0) > 100
    assert np.max(np.abs(u)) > b.capacity


def test_straight_motion_in_any_direction_is_the_axis_bearing_along_it():
    # The elements are isotropic: along a line at 30° every internal vector stays on it, and the
    # force is the one-axis force along it.
    d = np.array([math.cos(math.radians(30.0)), math.sin(math.radians(30.0))])
    u = cyclic_path(np.random.default_rng(9), n=800)
    f, k, _ = drive_plan(BEARING, np.outer(u, d))
    f1, k1, _ = drive_axis(BEARING, u)
    np.testing.assert_allclose(f, np.outer(f1, d), rtol=1e-11, atol=1e-11 * BEARING.W)
    np.testing.assert_allclose(np.einsum("i,nij,j->n", d, k, d), k1, rtol=1e-9)


def test_one_step_from_rest_is_the_monotonic_backbone():
    # From rest along a straight line every element loads monotonically, so one trial from the
    # virgin state to any point (here past every transition, 30 in, and past the capacity) is
    # the backbone there: the series solve is robust to large steps.
    b = BEARING
    p = b.params()
    d = np.array([0.6, 0.8])
    for u in (0.005, 3.0, 30.0, 36.4):
        r = tfp.series_solve(p, b.initial_state(), u * d[0], u * d[1])
        assert r[17] < tfp.MAX_ITERATIONS
        np.testing.assert_allclose(r[:2], backbone_force(b, u) * d, rtol=1e-12)


def test_far_trials_are_solved_and_a_nan_trial_gives_nan():
    # Far past the capacity every restrainer carries the excess (one trial from rest and from a
    # loaded state: finite, on the backbone along the line); a NaN trial gives a NaN force (the
    # solver's signal), at once.
    b = BEARING
    p = b.params()
    r = tfp.series_solve(p, b.initial_state(), 300.0, -400.0)
    np.testing.assert_allclose(r[:2], backbone_force(b, 500.0) * np.array([0.6, -0.8]),
                               rtol=1e-12)
    s = b.initial_state()
    tfp.plan_commit(p, s, 0.0, 0.0, 0.0, 0.0, 20.0, 5.0, 0.0, 0.0, 0.0)
    assert np.all(np.isfinite(tfp.series_solve(p, s, -300.0, 400.0)[:5]))
    r = tfp.series_solve(p, s, np.nan, 0.0)
    assert np.isnan(r[0]) and np.isnan(r[2]) and r[17] == 1


@pytest.mark.parametrize("size", [0.01, 0.3, 3.0])
def test_a_carried_solve_in_closed_form_is_the_newton_minimum(size):
    # A carried solve (the rate form's stage force: the carried elements slide at a given z,
    # the others from the committed state) is affine while every other element sticks and no
    # restrainer is reached: f_i = k_i·d_i + c_i with scalar k_i, so F = (u + Σ c_i/k_i)/Σ 1/k_i
    # (tfp._carried_affine). The series energy is convex, so that is the minimum the Newton
    # solve approaches: they agree to its tolerance (1e-14 of |u| + the capacity; measured
    # below 1e-13, 1e-12 asserted) and on the branch, and where the closed form declines, the
    # Newton answer indeed has an uncarried element sliding or a restrainer touched. Committed states from random walks, each sliding
    # element carried at its z turned by a random angle, increments of ``size`` [in]. The Newton
    # solve reads the same committed state from the path's scratch slots (o = _PIECE), where the
    # closed form is not tried.
    b = TripleFrictionPendulum()
    p = b.params()
    rng = np.random.default_rng(7)
    used = declined = 0
    for _ in range(300):
        s = b.initial_state_plan()
        u = np.zeros(2)
        for _ in range(rng.integers(1, 8)):
            u = u + rng.normal(0.0, 1.5, 2)
            tfp._store(s, 0, tfp.series_solve(p, s, u[0], u[1]))
        z = s[6:12].copy()
        carry = 0
        for i in range(3):
            if z[2 * i] ** 2 + z[2 * i + 1] ** 2 >= 1.0 - 1e-9:
                carry |= 1 << i
                turn = rng.normal(0.0, 0.05)
                c, sn = np.cos(turn), np.sin(turn)
                zx, zy = z[2 * i], z[2 * i + 1]
                z[2 * i], z[2 * i + 1] = c * zx - sn * zy, sn * zx + c * zy
        if carry == 0:
            continue
        ux, uy = u + rng.normal(0.0, size, 2)
        s[tfp._PIECE:tfp._PIECE + 12] = s[:12]
        newton = np.array(tfp._series(p, s, tfp._PIECE, ux, uy, carry, z, 0.0))
        ok, closed = tfp._carried_affine(p, s, ux, uy, carry, z)
        assert np.array_equal(np.array(tfp._series(p, s, 0, ux, uy, carry, z, 0.0)),
                              np.array(closed) if ok else newton)
        if ok:
            used += 1
            assert closed[18] == newton[18] == carry  # carried slide, the others stick
            np.testing.assert_allclose(np.array(closed)[:17], newton[:17], rtol=0, atol=1e-12)
        else:
            declined += 1
            sliding, contact = int(newton[18]) & 7, int(newton[18]) >> 3
            assert sliding & ~carry or contact
    assert used > 50 and (declined > 20 or size < 1.0), (used, declined)


def test_tangent_is_the_derivative_of_the_force():
    # The condensed tangent (Σ C_i)⁻¹ against central differences of the force from the same
    # committed state, at states along a random plan walk (sticking, sliding, restrainers).
    b = BEARING
    p, s = b.params(), b.initial_state()
    rng = np.random.default_rng(4)
    u = np.zeros(2)
    checked = 0
    for _ in range(400):
        u = u + rng.normal(0.0, 0.6, 2)
        u *= min(1.0, 36.2 / np.hypot(*u))
        tfp.plan_commit(p, s, 0.0, 0.0, 0.0, 0.0, u[0], u[1], 0.0, 0.0, 0.0)
        step = rng.normal(0.0, 0.3, 2)
        trial = u + step
        r = tfp.series_solve(p, s, *trial)
        h = 1e-6
        for j in range(2):
            e = np.eye(2)[j] * h
            fp = np.array(tfp.series_solve(p, s, *(trial + e))[:2])
            fm = np.array(tfp.series_solve(p, s, *(trial - e))[:2])
            if tfp.plan_branch(p, s, *(trial + e)) != tfp.plan_branch(p, s, *(trial - e)):
                continue  # a kink within ±h
            column = np.array([r[2], r[3]]) if j == 0 else np.array([r[3], r[4]])
            np.testing.assert_allclose(column, (fp - fm) / (2 * h), rtol=1e-5,
                                       atol=1e-6 * b.sticking_stiffness)
            checked += 1
    assert checked > 700


def circle_closed(b, radius):
    """Steady circular orbit of ``radius`` [in], continuous model: (|F| [kip], F_t [kip]), the
    force's magnitude and its component along the motion.

    In steady rotation |F| = Φ is constant. A sticking element carries d = F/k_0. A sliding one
    slips on a circle: p = P·p̂, z = t̂ = i·p̂ (the motion's direction), d = p + u_y,i·z with
    |d| = ρ = sqrt(P² + u_y,i²), and F = κ·d + q·t̂ with κ = kr + k_0·(1 − g/ρ)₊ (the restrainer
    past the gap): F = κ·P·p̂ + (κ·u_y,i + q)·t̂, so Φ² = (κ·P)² + (κ·u_y,i + q)² fixes P, and in
    the frame of F (F real) d = (P + i·u_y,i)·e^(−iψ), tan ψ = (κ·u_y,i + q)/(κ·P). Then
    radius = |Σ d_i(Φ)| fixes Φ; the work per turn, Σ q_i·2π·P_i, is 2π·radius·F_t."""
    k0 = b.sticking_stiffness

    def element(phi, kr, q, uy, g):
        if phi <= k0 * uy:
            return complex(phi / k0), 0.0

        def kappa(pp):
            return kr + k0 * max(0.0, 1.0 - g / math.hypot(pp, uy))

        pp = brentq(lambda x: math.hypot(kappa(x) * x, kappa(x) * uy + q) - phi, 0.0, phi / kr,
                    xtol=1e-15, rtol=1e-15)
        ka = kappa(pp)
        psi = math.atan2(ka * uy + q, ka * pp)
        return complex(pp, uy) * complex(math.cos(psi), -math.sin(psi)), q * pp

    def orbit(phi):
        return sum(element(phi, *e)[0] for e in elements(b))

    phi = brentq(lambda x: abs(orbit(x)) - radius, 1e-9, 10.0 * b.W, xtol=1e-15, rtol=1e-15)
    return phi, sum(element(phi, *e)[1] for e in elements(b)) / radius


def circle(radius, n, turns=3):
    """Out from the centre along +x to ``radius`` [in] (steps of 0.01 in), then counterclockwise
    around the circle, n points per turn."""
    approach = np.column_stack([np.linspace(0.0, radius, int(radius / 0.01) + 1), 0.0 * np.zeros(
        int(radius / 0.01) + 1)])[1:]
    phi = 2.0 * np.pi * np.arange(1, turns * n + 1) / n
    return np.vstack([approach, radius * np.column_stack([np.cos(phi), np.sin(phi)])]), phi


def steady(b, radius, n):
    """(|F|, F_t) [kip] averaged over the last of three turns of :func:`circle`."""
    path, phi = circle(radius, n)
    f, _, _ = drive_plan(b, path)
    last = slice(len(path) - n, len(path))
    tangent = np.column_stack([-np.sin(phi), np.cos(phi)])[-n:]
    return np.mean(np.hypot(*f[last].T)), np.mean(np.sum(f[last] * tangent, axis=1))


@pytest.mark.parametrize("radius", [0.5, 4.0, 15.0, 31.0, 35.5],
                         ids=["I", "II", "III", "IV", "V"])
def test_steady_force_on_a_circle_in_each_regime(radius):
    # The single return per step follows the chord, a first-order error in the step's turn
    # α = 2π/n (the friction direction lags by about α/2): at n = 4000 the steady |F| and F_t
    # are within 1e-3 of the continuous closed form (circle_closed), and F_t is the dissipation
    # per unit path, Σ q_i·P_i/r: the sliding elements' frictions weighted by their slip radii.
    b = BEARING
    magnitude, tangential = circle_closed(b, radius)
    got = steady(b, radius, 4000)
    assert got[0] == pytest.approx(magnitude, rel=1e-3)
    assert got[1] == pytest.approx(tangential, rel=1e-3)
    if radius == 0.5:  # regime I: only the inner slider slips, F_t ≈ μ1·W
        assert tangential == pytest.approx(b.mu1 * b.W, rel=0.05)


def test_circle_error_is_first_order_in_the_step():
    # Doubling the points per turn halves the difference from the continuous steady force.
    b, radius = BEARING, 15.0
    _, tangential = circle_closed(b, radius)
    errors = [abs(steady(b, radius, n)[1] / tangential - 1.0) for n in (1000, 2000, 4000)]
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all((ratios > 1.8) & (ratios < 2.2)), (errors, ratios)


# ------------------------------------------------------------------------ the path of a step


def orbit(radius, step, eight=False):
    """Step ends on a spiral from rest onto a circle of ``radius`` [in] (or a figure eight of
    that size), growing over two turns then steady for two, with their exact velocities [in/s]
    at unit angular rate: (points (n, 2), velocities (n, 2), the steps' durations tau [s] (n,)),
    about ``step`` [in] of orbit per step."""
    dth = step / (1.21 * radius if eight else radius)
    th = dth * np.arange(1, round(8.0 * np.pi / dth) + 1)
    g = np.minimum(th / (4.0 * np.pi), 1.0)
    a = radius * smoothstep(g)
    da = np.where(th < 4.0 * np.pi, radius * 6.0 * g * (1.0 - g) / (4.0 * np.pi), 0.0)
    if eight:
        u = np.column_stack([a * np.sin(th), 0.5 * a * np.sin(2.0 * th)])
        v = np.column_stack([da * np.sin(th) + a * np.cos(th),
                             0.5 * da * np.sin(2.0 * th) + a * np.cos(2.0 * th)])
    else:
        u = np.column_stack([a * np.cos(th), a * np.sin(th)])
        v = np.column_stack([da * np.cos(th) - a * np.sin(th), da * np.sin(th) + a * np.cos(th)])
    return u, v, np.full(len(th), dth)


def drive_path(b, u, v, tau, pieces=None):
    """Each step from the previous point (rest at the centre first) along its Hermite path to
    the next point of ``u`` with the velocities ``v`` over ``tau``: the trial's force (n, 2),
    then the commit. ``pieces`` None: the plan kernels (:data:`tfp.PIECES`); else the path cut
    into that many pieces (1: the chord)."""
    p, s = b.params(), b.initial_state_plan()
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    forces = np.zeros((len(u), 2))
    u0 = v0 = np.zeros(2)
    for i in range(len(u)):
        args = (*u0, *v0, *u[i], *v[i], tau[i])
        if pieces is None:
            tfp.plan_trial(p, s, *args, f, k, c)
            forces[i] = f
            tfp.plan_commit(p, s, *args)
        else:
            r = tfp._path(p, s, *args, pieces)
            forces[i] = r[:2]
            s[:12] = r[5:17]
        u0, v0 = u[i], v[i]
    return forces


@pytest.mark.parametrize(("radius", "step", "eight"), [(4.0, 0.1, False), (4.0, 0.5, False),
                                                       (15.0, 0.5, False), (4.0, 0.2, True)],
                         ids=["II-0.1", "II-0.5", "III-0.5", "eight-II-0.2"])
def test_a_curved_step_follows_its_path(radius, step, eight):
    # On an orbit of curved steps (imposed Hermite paths 0.1-0.5 in long, turns of 1.4° to 7°),
    # against the same paths cut into 256 pieces: the chord (one return per step) is off by Y,
    # 1.7 to 2.4 times the inner friction force times the step's turn (measured), and the plan
    # kernels' PIECES pieces by Y/PIECES: each piece's return is a backward-Euler step of the
    # friction rule, whose friction directions lag by half the piece's turn, an error of first
    # order in the piece (measured ratios 0.247 on the circles, 0.26 on the figure eight, for 4
    # pieces; the reference itself is off by Y/256: within 4e-3·Y of 1024 pieces).
    b = BEARING
    u, v, tau = orbit(radius, step, eight)
    reference = drive_path(b, u, v, tau, 256)
    chord = np.max(np.hypot(*(drive_path(b, u, v, tau, 1) - reference).T))
    path = np.max(np.hypot(*(drive_path(b, u, v, tau) - reference).T))
    turn = step / radius
    assert 1.0 < chord / (b.mu1 * b.W * turn) < 3.0
    assert 0.8 / tfp.PIECES < path / chord < 1.25 / tfp.PIECES, path / chord


def test_a_straight_step_is_the_chord_bit_for_bit():
    # Along one axis with velocities along it (the solver's plan run under one component), and
    # at tau = 0 whatever the velocities, the path is the chord: the plan kernels are the one-
    # axis kernels to the bit (as at tau = 0 in test_along_one_axis_...), and a trial at tau = 0
    # is the series solve at its end point.
    b = BEARING
    p = b.params()
    u = cyclic_path(np.random.default_rng(5), n=1500)
    f1, k1, s_axis = drive_axis(b, u)
    velocity = np.gradient(u, 0.01)
    for axis in (0, 1):
        s = b.initial_state_plan()
        f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
        prev = np.zeros(4)
        for i, (ui, vi) in enumerate(zip(u, velocity)):
            now = np.zeros(4)
            now[axis], now[2 + axis] = ui, vi
            args = (*prev[:2], *prev[2:], *now[:2], *now[2:], 0.01)
            tfp.plan_trial(p, s, *args, f, k, c)
            assert f[axis] == f1[i] and k[axis, axis] == k1[i] and f[1 - axis] == 0.0
            tfp.plan_commit(p, s, *args)
            prev = now
        if axis == 0:
            np.testing.assert_array_equal(s[:12], s_axis[:12])
    # tau = 0 on a curved orbit: the chord
    uo, vo, _ = orbit(4.0, 0.2)
    s = b.initial_state_plan()
    for i in range(1, 300):
        tfp.plan_commit(p, s, *uo[i - 1], *vo[i - 1], *uo[i], *vo[i], 0.2 / 4.0)
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    tfp.plan_trial(p, s, *uo[299], *vo[299], *uo[300], *vo[300], 0.0, f, k, c)
    r = tfp.series_solve(p, s, *uo[300])
    assert (f[0], f[1], k[0, 0], k[0, 1], k[1, 1]) == r[:5]


def test_a_path_is_pieces_of_series_solves_in_the_scratch_slots():
    # A curved step is PIECES series solves, each from the previous one's end state, at equal
    # steps of the Hermite parameter: the commit is the walk by hand (chord commits at those
    # points) to the bit, the trial's force the last piece's; a trial writes only the scratch
    # slots (the committed part of the state is unchanged).
    b = BEARING
    p = b.params()
    uo, vo, tau = orbit(4.0, 0.3)
    s = b.initial_state_plan()
    for i in range(1, 200):
        tfp.plan_commit(p, s, *uo[i - 1], *vo[i - 1], *uo[i], *vo[i], tau[i])
    committed = s.copy()
    args = (*uo[199], *vo[199], *uo[200], *vo[200], tau[200])
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    tfp.plan_trial(p, s, *args, f, k, c)
    np.testing.assert_array_equal(s[:12], committed[:12])
    by_hand = committed.copy()
    for n in range(1, tfp.PIECES):
        q = [tfp._hermite(n / tfp.PIECES, tau[200], uo[199, j], vo[199, j], uo[200, j],
                          vo[200, j]) for j in (0, 1)]
        tfp.plan_commit(p, by_hand, 0.0, 0.0, 0.0, 0.0, *q, 0.0, 0.0, 0.0)
    r = tfp.series_solve(p, by_hand, *uo[200])
    assert (f[0], f[1], k[0, 0], k[0, 1], k[1, 1]) == r[:5]
    tfp.plan_commit(p, by_hand, 0.0, 0.0, 0.0, 0.0, *uo[200], 0.0, 0.0, 0.0)
    tfp.plan_commit(p, s, *args)
    np.testing.assert_array_equal(s[:12], by_hand[:12])
    chord = tfp.series_solve(p, committed, *uo[200])
    assert np.all(np.isfinite(f)) and np.hypot(f[0] - chord[0], f[1] - chord[1]) > 0.0


# ---------------------------------------------------------------------------- OpenSees twin


def opensees_forces(b, path):
    """OpenSees' TripleFrictionPendulum (built by tfp.opensees_plan_element) between a fixed
    node and a node loaded by −W in z, its x and y displacements imposed along ``path`` (n, 2)
    [in] one static step per point: the element's shear forces (n, 2) [kip]
    (``femoat.opensees.bearing_orbit``)."""
    from conftest import opensees_or_skip
    from femoat.opensees.bearing_orbit import orbit_forces

    opensees_or_skip()
    return orbit_forces(b, path)


def smoothstep(x):
    return x * x * (3.0 - 2.0 * x)


@BEARINGS
def test_opensees_twin_on_one_axis(b):
    # A history with reversals through regimes I-V and the restrainers, steps of 0.01 in (≤ 3·u_y
    # from rest: OpenSees' element returns a wrong state after a larger first step). On one axis
    # both solve the same piecewise-linear series equations exactly: equal to rounding (with
    # the twin's tol = 1e-7; at OpenSees' usual 1e-5 a step across a transition leaves a lasting
    # offset of 1.2e-9 of the peak force from its internal split, measured).
    points = [0.0, 6.0, -3.0, 30.0, -34.0, 36.2, -36.2, 10.0]
    u = np.concatenate([np.linspace(a, c, int(abs(c - a) / 0.01) + 1)[1:]
                        for a, c in itertools.pairwise(points)])
    path = np.column_stack([u, np.zeros_like(u)])
    twin = opensees_forces(b, path)
    f, _, _ = drive_plan(b, path)
    peak = np.max(np.abs(twin))
    np.testing.assert_allclose(f, twin, rtol=0.0, atol=1e-11 * peak)


@BEARINGS
@pytest.mark.parametrize("radius", [5.0, 31.0])
def test_opensees_twin_in_plan(b, radius):
    # Smooth orbits from rest, growing over two turns: a spiral onto a circle and a figure
    # eight, 1000 points per turn. Most points agree to 1e-8 of the peak force; at some steps
    # OpenSees' series iteration ends with its three elements' forces disagreeing by up to
    # ~1e-6 of the force (checked against this module's elements at its internal
    # displacements; the same for tol from 1e-5 to 1e-9), so single points differ by up to a
    # few 1e-7 (measured 2.7e-7), and the difference fades as the orbit goes on.
    n = 1000
    th = 2.0 * np.pi * np.arange(1, 4 * n + 1) / n
    a = radius * smoothstep(np.minimum(th / (4.0 * np.pi), 1.0))
    for path in (np.column_stack([a * np.cos(th), a * np.sin(th)]),
                 np.column_stack([a * np.sin(th), 0.5 * a * np.sin(2.0 * th)])):
        twin = opensees_forces(b, path)
        f, _, _ = drive_plan(b, path)
        error = np.max(np.abs(f - twin), axis=1) / np.max(np.abs(twin))
        assert np.max(error) < 1e-6
        assert np.median(error) < 3e-8


# ------------------------------------------------------------------------------ bad input


@pytest.mark.parametrize(("changes", "name"), [
    ({"W": 0.0}, "W"), ({"W": float("nan")}, "W"),
    ({"L1": -1.0}, "L1"), ({"L2": 12.0}, "L2"), ({"L3": 10.0}, "L3"),
    ({"d1": 0.0}, "d1"), ({"d2": -16.0}, "d2"), ({"d3": float("inf")}, "d3"),
    ({"mu1": 0.0}, "mu1"), ({"mu1": 0.06}, "mu2"), ({"mu3": 0.05}, "mu3"),
    ({"mu2": 1.2}, "mu2"), ({"u_y": 0.0}, "u_y"), ({"u_y": 1.0}, "u_y"),
    ({"mu1": "0.01"}, "mu1"),
])
def test_invalid_parameters_name_the_parameter(changes, name):
    with pytest.raises(ValueError, match=rf"^{name} = "):
        TripleFrictionPendulum(**changes)


def test_the_kind_provides_the_contract():
    # The names femoat.bearings' docstring lists; the one class is both faces.
    from femoat.bearings import registry

    mod = registry.check_kind("femoat.bearings.triple_friction_pendulum")
    assert mod.KEY == "tfp" and mod.AXIS_CLASS is mod.PLAN_CLASS is TripleFrictionPendulum
    assert BEARING.params().shape == (tfp.N_PARAMS,)
    assert BEARING.initial_state_axis().shape == (tfp.N_STATE_AXIS,)
    assert BEARING.initial_state_plan().shape == (tfp.N_STATE_PLAN,)


# ----------------------------------------------------------- the manufacturer's geometry

# A bearing given as a manufacturer gives it (OpenSees' indices: 1 the inner surfaces, 2 and 3
# the outer ones), by hand: L_i = R_i − h_i and d_i = d_i,nominal·L_i/R_i (module docstring)
#   inner:  R1 = 16,  h1 = 4  ->  L1 = 12;  d1 = 2·12/16   = 1.5
#   outer:  R2 = 96,  h2 = 8  ->  L2 = 88;  d2 = 18·88/96  = 16.5
#   outer:  R3 = 100, h3 = 4  ->  L3 = 96;  d3 = 20·96/100 = 19.2
GEOMETRY = {"R1": 16.0, "R2": 96.0, "R3": 100.0, "h1": 4.0, "h2": 8.0, "h3": 4.0,
            "d1_nominal": 2.0, "d2_nominal": 18.0, "d3_nominal": 20.0}
EFFECTIVE = {"L1": 12.0, "L2": 88.0, "L3": 96.0, "d1": 1.5, "d2": 16.5, "d3": 19.2}


def test_from_geometry_gives_effective_radii_and_actual_capacities():
    b = TripleFrictionPendulum.from_geometry(**GEOMETRY, mu1=0.01, mu2=0.04, mu3=0.08,
                                             u_y=0.02, W=50.0)
    for name, value in EFFECTIVE.items():
        assert getattr(b, name) == pytest.approx(value, rel=1e-15), name
    assert (b.mu1, b.mu2, b.mu3, b.u_y, b.W) == (0.01, 0.04, 0.08, 0.02, 50.0)
    # ultimate displacement 2·d1 + d2 + d3 − L1·|d2/L2 − d3/L3|
    #   = 3 + 16.5 + 19.2 − 12·|0.1875 − 0.2| = 38.7 − 0.15 = 38.55 in
    # (the nominal capacities would have said 2·2 + 18 + 20 = 42 in)
    assert b.capacity == pytest.approx(38.55, rel=1e-14)
    # friction, u_y and W left out: the dataclass's defaults
    assert TripleFrictionPendulum.from_geometry(**GEOMETRY) == TripleFrictionPendulum(
        **EFFECTIVE)


@pytest.mark.parametrize(("changes", "name"), [
    ({"R1": 0.0}, "R1"), ({"R3": float("inf")}, "R3"), ({"R2": "96"}, "R2"),
    ({"h1": 0.0}, "h1"), ({"h3": -1.0}, "h3"),
    ({"h2": 96.0}, "h2"), ({"h1": 20.0}, "h1"),  # h >= R: no effective radius
    ({"d1_nominal": 0.0}, "d1_nominal"), ({"d2_nominal": float("nan")}, "d2_nominal"),
    ({"R2": 20.0}, "R2 − h2"),  # L2 = 12 = L1: the outer surface not the flatter one
    ({"R1": 100.0, "h1": 2.0}, "R2 − h2"),  # L1 = 98 > L2 = 88: inner and outer swapped
    ({"mu2": 0.005}, "mu2"),  # the dataclass's own checks on the effective bearing
])
def test_from_geometry_refuses_bad_geometry_by_name(changes, name):
    with pytest.raises(ValueError, match=rf"^{re.escape(name)} = "):
        TripleFrictionPendulum.from_geometry(**{**GEOMETRY, **changes})


def _isolator_model(iso, plan=False):
    from femoat.scenario import model_from_dict

    return model_from_dict({"building": {"plan": plan, "isolator": {"type": "tfp", **iso}}})


@pytest.mark.parametrize("plan", [False, True], ids=["1D", "plan"])
def test_a_scenario_takes_the_geometry_for_the_effective_keys(plan):
    # The same model, W the building's weight in both (not given); friction keys beside the
    # geometry are the class's fields as usual.
    assert _isolator_model(GEOMETRY, plan) == _isolator_model(EFFECTIVE, plan)
    mu = {"mu1": 0.01, "mu2": 0.04, "mu3": 0.08}
    assert _isolator_model({**GEOMETRY, **mu}, plan) == _isolator_model({**EFFECTIVE, **mu},
                                                                          plan)


@pytest.mark.parametrize(("iso", "message"), [
    ({**GEOMETRY, "L2": 88.0, "d3": 19.2}, r"L2, d3 with R1, .*remove L2, d3"),  # mixed
    ({**EFFECTIVE, "R1": 16.0}, r"L1, L2, L3, d1, d2, d3 with R1: "),  # mixed the other way
    ({k: v for k, v in GEOMETRY.items() if k != "h2"}, r"h2: missing"),  # no defaults
    ({**GEOMETRY, "h2": 96.0}, r"h2 = 96\.0 \[in\]: must be < R2"),  # the class's message
    ({**GEOMETRY, "R2": "96"}, r"R2 = '96': expected a number"),
    ({**GEOMETRY, "R": 30.0}, r": unknown key\(s\) \['R'\]; allowed: \['R1', "),
])
def test_a_scenario_refuses_a_mixed_or_bad_geometry_table(iso, message):
    with pytest.raises(ValueError, match=r"^\[building\.isolator\] ?" + message):
        _isolator_model(iso)


def test_a_suite_may_vary_the_geometry_keys():
    from femoat.suite.model import build_variation
    from femoat.suite.variations import allowed_keys, apply, variations_from_dict

    assert set(tfp.GEOMETRY_KEYS) <= allowed_keys()["building.isolator"]
    _, combos = variations_from_dict({"building.isolator.h2": [8.0, 16.0]})
    base = {"building": {"isolator": {"type": "tfp", **GEOMETRY}}}
    isos = [build_variation(apply(base, c)).pounding.building.isolator for c in combos]
    # h2 = 16: L2 = 96 − 16 = 80, d2 = 18·80/96 = 15
    assert [(b.L2, b.d2) for b in isos] == [(88.0, 16.5), (80.0, 15.0)]

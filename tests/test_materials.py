"""Structural materials: closed forms, consistency of tangents and energies, input validation."""

import math

import numpy as np
import pytest
from numba import njit

from femoat.structure.materials import (
    BILINEAR,
    ELASTIC,
    FRICTION_PENDULUM,
    IMK,
    Bilinear,
    Elastic,
    FrictionPendulum,
    IMKBilinear,
    material_commit,
    material_recoverable_energy,
    material_trial,
    param_size,
    state_size,
)


def segments(points, step):
    """Piecewise-linear displacement path through ``points`` with increments ≤ ``step`` [in]."""
    path = [float(points[0])]
    for a, b in zip(points[:-1], points[1:]):
        n = max(1, math.ceil(abs(b - a) / step))
        path.extend(np.linspace(a, b, n + 1)[1:])
    return np.array(path)


def drive(material, path, velocities=None):
    """Trial then commit every point of ``path``; returns forces, tangents, final state."""
    p, s = material.params(), material.initial_state()
    forces, tangents = np.empty(len(path)), np.empty(len(path))
    for i, u in enumerate(path):
        v = 0.0 if velocities is None else velocities[i]
        forces[i], tangents[i], _ = material_trial(material.code, p, s, u, v)
        material_commit(material.code, p, s, u, v)
    return forces, tangents, s


def dissipated(material, path):
    """Hysteretic energy [kip·in] over ``path``: ∫f du (trapezoids) − Δ recoverable energy."""
    p, s = material.params(), material.initial_state()
    f_prev, work = 0.0, 0.0
    e0 = None
    for i, u in enumerate(path):
        f, _, _ = material_trial(material.code, p, s, u, 0.0)
        material_commit(material.code, p, s, u, 0.0)
        if i == 0:
            e0 = material_recoverable_energy(material.code, p, s)
        else:
            work += 0.5 * (f + f_prev) * (u - path[i - 1])
        f_prev = f
    return work - (material_recoverable_energy(material.code, p, s) - e0)


ALL = [
    Elastic(k=42.799),
    Bilinear(),
    IMKBilinear(theta_p=0.6, theta_pc=2.0, Lambda=40.0),
    FrictionPendulum(),
    FrictionPendulum(mu=0.04, mu_fast=0.10, a=0.5),
]


# --------------------------------------------------------------------------------- interface


@pytest.mark.parametrize("m", ALL, ids=lambda m: type(m).__name__)
def test_array_sizes_and_codes(m):
    assert m.code in (ELASTIC, BILINEAR, IMK, FRICTION_PENDULUM)
    assert m.params().dtype == np.float64 and len(m.params()) == param_size(m.code)
    assert m.initial_state().dtype == np.float64
    assert len(m.initial_state()) == state_size(m.code)


def test_unknown_code_is_refused():
    with pytest.raises(ValueError, match="code"):
        state_size(99)


@pytest.mark.parametrize("m", ALL, ids=lambda m: type(m).__name__)
def test_trial_leaves_committed_state_alone(m):
    p, s = m.params(), m.initial_state()
    for u in segments([0.0, 1.5, -0.8], 0.05):
        material_commit(m.code, p, s, u, 1.0)
    before = s.copy()
    for u in (-3.0, -0.1, 0.0, 0.7, 2.5):
        material_trial(m.code, p, s, u, -2.0)
    np.testing.assert_array_equal(s, before)


@njit(cache=True)
def _compiled_history(codes, params, states, path, dt):
    """What a compiled time-stepping loop does: trial, then commit, for every element."""
    out = np.empty((len(codes), len(path)))
    for j in range(len(codes)):
        u_prev = 0.0
        for i in range(len(path)):
            v = (path[i] - u_prev) / dt
            f, _, _ = material_trial(codes[j], params[j], states[j], path[i], v)
            material_commit(codes[j], params[j], states[j], path[i], v)
            out[j, i] = f
            u_prev = path[i]
    return out


def test_kernels_run_inside_a_compiled_loop():
    # Ragged params/states travel as numba typed lists of float64 arrays.
    from numba.typed import List

    path = segments([0.0, 1.2, -0.9, 0.4], 0.01)
    codes = np.array([m.code for m in ALL], dtype=np.int64)
    params, states = List([m.params() for m in ALL]), List([m.initial_state() for m in ALL])
    compiled = _compiled_history(codes, params, states, path, 0.01)
    for j, m in enumerate(ALL):
        v = np.diff(path, prepend=0.0) / 0.01
        expected, _, _ = drive(m, path, v)
        np.testing.assert_array_equal(compiled[j], expected)


# ------------------------------------------------------------------------- friction pendulum


def test_friction_pendulum_quasi_static_loop():
    fp = FrictionPendulum(W=33.0, R=30.0, u_y=0.01, mu=0.06)
    path = segments([0.0, 3.0, -3.0, 3.0], 0.005)
    forces, _, _ = drive(fp, path)
    direction = np.sign(np.diff(path, prepend=0.0))
    reversal = path[0]
    checked = 0
    for i in range(1, len(path)):
        if direction[i] != direction[i - 1]:
            reversal = path[i - 1]
        if abs(path[i] - reversal) > 2.0 * fp.u_y + 1e-12:
            # Sliding, away from the reversal by more than the elastic recovery 2·u_y:
            # f = (W/R)·u + μ·W·sign(v)  (single FP bearing, e.g. Zayas et al., 1990).
            expected = fp.W / fp.R * path[i] + fp.mu * fp.W * direction[i]
            assert forces[i] == pytest.approx(expected, rel=1e-12, abs=1e-12)
            checked += 1
        else:
            # Sticking: the friction force never exceeds its capacity μ·W.
            assert abs(forces[i] - fp.W / fp.R * path[i]) <= fp.mu * fp.W + 1e-12
    assert checked > 0.9 * len(path)


def test_friction_coefficient_velocity_dependence():
    fp = FrictionPendulum(mu=0.04, mu_fast=0.10, a=0.5, v_reg=1e-3)
    p, s = fp.params(), fp.initial_state()
    for u in segments([0.0, 1.0], 0.01):  # sliding with z = +1
        material_commit(fp.code, p, s, u, 0.0)
    u = 1.2
    for v in (0.0, 2.0, 50.0):
        f, _, dfdv = material_trial(fp.code, p, s, u, v)
        # μ(v) = μ_fast − (μ_fast − μ_slow)·exp(−a|v|), |v| smoothed by at most v_reg
        mu = 0.10 - 0.06 * math.exp(-0.5 * v)
        assert f == pytest.approx(fp.W / fp.R * u + mu * fp.W, abs=0.06 * 0.5 * 1e-3 * fp.W)
    # The |v| kink is smoothed: ∂f/∂v is continuous and zero at v = 0.
    assert material_trial(fp.code, p, s, u, 0.0)[2] == 0.0
    left = material_trial(fp.code, p, s, u, -1e-6)[2]
    right = material_trial(fp.code, p, s, u, 1e-6)[2]
    assert abs(left) < 1e-3 and abs(right) < 1e-3


def test_friction_pendulum_recoverable_energy():
    fp = FrictionPendulum()
    p, s = fp.params(), fp.initial_state()
    for u in segments([0.0, 2.0], 0.01):
        material_commit(fp.code, p, s, u, 0.0)
    # (W/R)u²/2 + (μW)²/(2μW/u_y) at u = 2 while sliding (brief formula)
    expected = 0.5 * 33.0 / 30.0 * 4.0 + (0.06 * 33.0) ** 2 / (2 * 0.06 * 33.0 / 0.01)
    assert material_recoverable_energy(fp.code, p, s) == pytest.approx(expected, rel=1e-12)


# -------------------------------------------------------------------------- tangents (FD)


@pytest.mark.parametrize("m", ALL, ids=lambda m: type(m).__name__)
def test_tangents_match_central_differences(m):
    rng = np.random.default_rng(7)
    p = m.params()
    h = 1e-6
    checked = 0
    for history in ([0.0, 1.3], [0.0, 1.8, -0.4], [0.0, -2.2, 1.1, 0.3], [0.0, 0.05]):
        s = m.initial_state()
        for u in segments(history, 0.02):
            material_commit(m.code, p, s, u, 3.0)
        for _ in range(25):
            u = s[0] + rng.uniform(-3.0, 3.0)
            v = rng.choice([0.0, rng.uniform(-20.0, 20.0), rng.uniform(-1e-3, 1e-3)])
            f, dfdu, dfdv = material_trial(m.code, p, s, u, v)
            fp_, kp, _ = material_trial(m.code, p, s, u + h, v)
            fm, km, _ = material_trial(m.code, p, s, u - h, v)
            if not (kp == dfdu == km):  # the difference would straddle a kink
                continue
            # central difference: (f(u+h) − f(u−h)) / 2h, exact to O(h²) on a smooth branch
            assert dfdu == pytest.approx((fp_ - fm) / (2 * h), rel=1e-6, abs=1e-6)
            gp, _, _ = material_trial(m.code, p, s, u, v + h)
            gm, _, _ = material_trial(m.code, p, s, u, v - h)
            assert dfdv == pytest.approx((gp - gm) / (2 * h), rel=1e-5, abs=1e-7)
            checked += 1
    assert checked >= 50


# ---------------------------------------------------------------------------------- energy


@pytest.mark.parametrize(
    "m, amplitude",
    [
        (Elastic(k=42.799), 2.0),
        (Bilinear(), 0.9 * Bilinear().uy),
        (IMKBilinear(theta_p=0.6, theta_pc=2.0, Lambda=40.0), 0.2),
        (FrictionPendulum(), 0.9 * FrictionPendulum().u_y),
    ],
    ids=["elastic", "bilinear", "imk", "friction_pendulum"],
)
def test_closed_elastic_cycle_dissipates_nothing(m, amplitude):
    path = segments([0.0, amplitude, -amplitude, 0.0], amplitude / 50)
    # A closed cycle on a linear path stores and returns the same energy: dissipation 0.
    assert dissipated(m, path) == pytest.approx(0.0, abs=1e-10)


def test_bilinear_cycle_dissipates_the_parallelogram():
    b = Bilinear()
    a = 2.0
    path = segments([-a, a, -a], 1e-3)
    p, s = b.params(), b.initial_state()
    for u in segments([0.0, a, -a], 1e-3):  # bring the loop to its stable shape
        material_commit(b.code, p, s, u, 0.0)
    e0 = material_recoverable_energy(b.code, p, s)
    work, f_prev = 0.0, s[1]
    for u0, u in zip(path[:-1], path[1:]):
        f, _, _ = material_trial(b.code, p, s, u, 0.0)
        material_commit(b.code, p, s, u, 0.0)
        work += 0.5 * (f + f_prev) * (u - u0)
        f_prev = f
    loss = work - (material_recoverable_energy(b.code, p, s) - e0)
    # Parallelogram between the yield lines f = b·k0·u ± (1 − b)·Fy (2(1 − b)·Fy apart) over
    # the plastic span 2(a − u_y): area 4·(1 − b)·Fy·(a − u_y)  (kinematic hardening loop).
    expected = 4.0 * (1.0 - b.b) * b.Fy * (a - b.uy)
    assert loss == pytest.approx(expected, rel=1e-5)


# ----------------------------------------------------------------------------------- IMK


def test_imk_without_capping_or_deterioration_is_the_bilinear_spring():
    imk = IMKBilinear(theta_p=1e6, theta_pc=1e6, K0=42.799, My=11.556, alpha_s=0.03)
    path = segments([0.0, 0.4, -0.7, 1.5, -2.0, 2.0, 0.3], 0.01)
    f_imk, k_imk, _ = drive(imk, path)
    f_bil, k_bil, _ = drive(Bilinear(k0=42.799, Fy=11.556, b=0.03), path)
    # Same rules by construction (module docstring): the bilinear model's forces exactly.
    np.testing.assert_allclose(f_imk, f_bil, rtol=0, atol=1e-9)
    np.testing.assert_allclose(k_imk, k_bil, rtol=0, atol=1e-12)


def test_imk_monotonic_backbone():
    m = IMKBilinear(theta_p=0.6, theta_pc=2.0, res=0.4)
    path = segments([0.0, 3.0], 0.01)
    forces, _, _ = drive(m, path)
    f = dict(zip(np.round(path, 6), forces))
    f_cap = m.My + m.alpha_s * m.K0 * m.theta_p  # capping force My + as·K0·θp
    u_cap = m.uy + m.theta_p
    # capping point, then the post-capping line that reaches zero θpc later, then Res·My
    assert f[round(u_cap, 2)] == pytest.approx(m.My + m.alpha_s * m.K0 * (round(u_cap, 2) - m.uy))
    assert max(forces) == pytest.approx(f_cap, rel=1e-3)
    assert f[1.5] == pytest.approx(f_cap * (1.0 - (1.5 - u_cap) / m.theta_pc))
    assert f[3.0] == pytest.approx(m.res * m.My)


def test_imk_deterioration_shrinks_strength_and_stops_at_residual():
    strong = IMKBilinear(theta_p=0.6, theta_pc=2.0, Lambda=5.0, res=0.4)
    path = segments([0.0] + [1.0, -1.0] * 15, 0.02)
    forces, _, s = drive(strong, path)
    peaks = [abs(f) for f, u in zip(forces, path) if abs(abs(u) - 1.0) < 1e-12]
    # Each cycle dissipates energy, so each peak is lower than the one before it...
    assert all(b <= a + 1e-12 for a, b in zip(peaks[:-1], peaks[1:]))
    # ...until the strength on both sides has fallen to the residual Res·My, where it stays.
    assert peaks[-2:] == pytest.approx([0.4 * strong.My] * 2, rel=1e-9)


def test_imk_fracture_is_permanent():
    m = IMKBilinear(theta_p=0.6, theta_pc=2.0, theta_u=2.5)
    path = segments([0.0, 2.6, -1.0, 1.0], 0.05)
    forces, tangents, _ = drive(m, path)
    torn = np.argmax(path >= m.theta_u)  # first point at θu: no force from then on
    assert forces[torn - 1] > 0.0
    assert np.all(forces[torn:] == 0.0) and np.all(tangents[torn:] == 0.0)


# ------------------------------------------------------------------------------ validation


@pytest.mark.parametrize(
    "make, name",
    [
        (lambda: Elastic(k=-1.0), "k"),
        (lambda: Elastic(k=math.nan), "k"),
        (lambda: Bilinear(k0=0.0), "k0"),
        (lambda: Bilinear(Fy=-2.0), "Fy"),
        (lambda: Bilinear(b=1.0), "b"),
        (lambda: IMKBilinear(theta_p=0.0, theta_pc=1.0), "theta_p"),
        (lambda: IMKBilinear(theta_p=1.0, theta_pc=-1.0), "theta_pc"),
        (lambda: IMKBilinear(theta_p=1.0, theta_pc=1.0, K0=math.inf), "K0"),
        (lambda: IMKBilinear(theta_p=1.0, theta_pc=1.0, My=0.0), "My"),
        (lambda: IMKBilinear(theta_p=1.0, theta_pc=1.0, alpha_s=-0.1), "alpha_s"),
        (lambda: IMKBilinear(theta_p=1.0, theta_pc=1.0, res=1.0), "res"),
        (lambda: IMKBilinear(theta_p=1.0, theta_pc=1.0, theta_u=0.1), "theta_u"),
        (lambda: IMKBilinear(theta_p=1.0, theta_pc=1.0, Lambda=0.0), "Lambda"),
        (lambda: IMKBilinear(theta_p=1.0, theta_pc=1.0, c=0.0), "c"),
        (lambda: IMKBilinear(theta_p=1.0, theta_pc=1.0, D=1.5), "D"),
        (lambda: FrictionPendulum(W=0.0), "W"),
        (lambda: FrictionPendulum(R=-30.0), "R"),
        (lambda: FrictionPendulum(u_y=0.0), "u_y"),
        (lambda: FrictionPendulum(mu=1.2), "mu"),
        (lambda: FrictionPendulum(mu_fast=0.1), "a"),
        (lambda: FrictionPendulum(mu_fast=-0.1, a=1.0), "mu_fast"),
        (lambda: FrictionPendulum(v_reg=0.0), "v_reg"),
    ],
)
def test_bad_input_names_the_parameter(make, name):
    with pytest.raises(ValueError, match=rf"^{name} = "):
        make()

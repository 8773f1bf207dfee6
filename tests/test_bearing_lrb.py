"""The lead-rubber bearing kind (femoat.bearings.lead_rubber): a biaxial Bouc-Wen bearing, once
for one axis and plan. Closed forms of the Bouc-Wen law, the plan kernels restricted to one axis,
accuracy against converged integrations, and the OpenSees twins (elastomericBearingBoucWen in 3D,
uniaxialMaterial BoucWen in 1D) converging at their backward-Euler order."""

import itertools
import math

import numpy as np
import pytest
from conftest import opensees_or_skip
from scipy.integrate import quad, solve_ivp
from scipy.special import digamma

from femoat.bearings import lead_rubber as lrb
from femoat.bearings import registry

DEFAULT = lrb.LeadRubberBearing()  # η = 1, β = γ = 0.5: Q_d = 2 kip, u_y = 2/4.05 in
QUADRATIC = lrb.LeadRubberBearing(eta=2.0)  # the closed form in plan
UNEQUAL = lrb.LeadRubberBearing(beta=0.8, gamma=0.2)  # unloading is not elastic (γ − β < 0)
SHARP = lrb.LeadRubberBearing(eta=3.0, beta=0.7, gamma=0.4)  # Runge-Kutta, cap (1/1.1)^(1/3)
BEARINGS = [DEFAULT, QUADRATIC, UNEQUAL, SHARP]
IDS = ["default", "eta2", "beta-gamma", "eta3"]


def drive_plan(bearing, u):
    """Trial then commit at every point of a plan path u (n, 2) [in]: forces (n, 2), ∂f/∂u
    (n, 2, 2), committed z (n, 2)."""
    p, s = bearing.params(), bearing.initial_state_plan()
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    out = np.zeros((len(u), 2)), np.zeros((len(u), 2, 2)), np.zeros((len(u), 2))
    for i, (ux, uy) in enumerate(u):
        lrb.plan_trial(p, s, 0.0, 0.0, 0.0, 0.0, ux, uy, 0.0, 0.0, 0.01, f, k, c)
        lrb.plan_commit(p, s, 0.0, 0.0, 0.0, 0.0, ux, uy, 0.0, 0.0, 0.01)
        out[0][i], out[1][i], out[2][i] = f, k, s[2:4]
    return out


def drive_axis(bearing, u, v=None):
    """The one-axis kernels along u [in] (velocities v [in/s]): force, df/du, df/dv per point."""
    v = np.zeros_like(u) if v is None else v
    p, s = bearing.params(), bearing.initial_state_axis()
    out = np.zeros((len(u), 3))
    for i, (ui, vi) in enumerate(zip(u, v)):
        out[i] = lrb.axis_trial(p, s, ui, vi)
        lrb.axis_commit(p, s, ui, vi)
    return out.T


def plan_trial(bearing, s, ux, uy):
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    lrb.plan_trial(bearing.params(), s, 0.0, 0.0, 0.0, 0.0, ux, uy, 0.0, 0.0, 0.0, f, k, c)
    return f, k, c


def cyclic_path(rng, n=1500):
    """A random cyclic path [in] and velocities [in/s]: runs of 1-60 steps between reversals,
    steps up to 0.3 in or, one run in three, 0.02 in (elastic recoveries, u_y ≈ 0.49 in)."""
    steps, sign = [], 1.0
    while len(steps) < n:
        run = int(rng.integers(1, 60))
        largest = 0.02 if rng.uniform() < 1 / 3 else 0.3
        steps += list(sign * rng.uniform(0.1, 1.0, run) * largest)
        sign = -sign
    return np.cumsum(steps[:n]), rng.uniform(-30.0, 30.0, n)


def random_chord(rng, bearing):
    """A committed plan state (z anywhere in the cap disk) and a trial 0.01-5 u_y away in any
    direction (loading, unloading, or unloading then loading along the chord)."""
    r = bearing.z_cap * rng.uniform(0.0, 1.0) ** 0.3
    th, ph = rng.uniform(0.0, 2.0 * np.pi, 2)
    s = bearing.initial_state_plan()
    s[:4] = rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0), r * np.cos(th), r * np.sin(th)
    length = bearing.u_y * 10.0 ** rng.uniform(-2.0, 0.7)
    return s, s[0] + length * np.cos(ph), s[1] + length * np.sin(ph)


def converged_z(bearing, s, ux, uy):
    """z at the end of the chord by scipy's DOP853 at rtol 1e-13 on u_y·dz/dσ = A·Δu −
    c·|z|^(η−2)·(z·Δu)·z, c = γ − β until z·Δu = 0 (an event), then β + γ."""
    du = np.array([ux - s[0], uy - s[1]])
    eta = bearing.eta

    def rate(_, z, c):
        rho = math.hypot(*z)
        if rho == 0.0:
            return du / bearing.u_y
        return (du - c * rho ** (eta - 2.0) * (z @ du) * z) / bearing.u_y

    def turns(_, z, c):
        return z @ du

    turns.terminal, turns.direction = True, 1
    opts = {"rtol": 1e-13, "atol": 1e-15, "method": "DOP853"}
    z0, t0 = s[2:4].copy(), 0.0
    if z0 @ du < 0.0:
        sol = solve_ivp(rate, (0.0, 1.0), z0, args=(bearing.gamma - bearing.beta,),
                        events=turns, **opts)
        if sol.status != 1:
            return sol.y[:, -1]
        t0, z0 = sol.t_events[0][0], sol.y_events[0][0]
    return solve_ivp(rate, (t0, 1.0), z0, args=(bearing.beta + bearing.gamma,), **opts).y[:, -1]


# ----------------------------------------------------------------------- the contract, the inputs


def test_the_kind_provides_the_contract():
    mod = registry.check_kind("femoat.bearings.lead_rubber")
    b = DEFAULT
    assert mod.KEY == "lrb" and mod.AXIS_CLASS is mod.PLAN_CLASS is lrb.LeadRubberBearing
    assert b.params().shape == (lrb.N_PARAMS,)
    assert b.initial_state().shape == b.initial_state_axis().shape == (lrb.N_STATE_AXIS,)
    assert b.initial_state_plan().shape == (lrb.N_STATE_PLAN,)
    # u_y = Q_d/(K_u − K_d) = 2/(4.5 − 0.45); no capacity of its own unless given
    assert b.yield_deformation == pytest.approx(2.0 / 4.05, rel=1e-15)
    assert b.capacity == math.inf and lrb.LeadRubberBearing(capacity=12.0).capacity == 12.0
    # the defaults under the paper building (W = 33 kip): Q_d ≈ 0.06 W, T_d = 2π sqrt(W/(g K_d))
    # between 2.5 and 3 s, K_u = 10 K_d
    assert b.Q_d == pytest.approx(0.06 * 33.0, rel=0.02)
    assert 2.5 < 2.0 * math.pi * math.sqrt(33.0 / (386.09 * b.K_d)) < 3.0
    assert b.K_u == pytest.approx(10.0 * b.K_d)
    # the reversal criterion is the 1D solver's for materials
    from femoat.integration.kinks import KINK_RATIO

    assert lrb.TURN_RATIO == KINK_RATIO


@pytest.mark.parametrize(
    ("kwargs", "key"),
    [
        ({"Q_d": 0.0}, "Q_d"),
        ({"Q_d": -2.0}, "Q_d"),
        ({"Q_d": math.nan}, "Q_d"),
        ({"K_d": -0.1}, "K_d"),
        ({"K_u": 0.0}, "K_u"),
        ({"K_u": 0.45}, "K_u"),  # not above K_d
        ({"K_u": 0.3}, "K_u"),
        ({"beta": 0.0}, "beta"),
        ({"beta": -0.5}, "beta"),
        ({"gamma": -0.5}, "gamma"),  # β + γ = 0: z unbounded
        ({"gamma": math.inf}, "gamma"),
        ({"eta": 0.5}, "eta"),
        ({"eta": 200.0}, "eta"),
        ({"capacity": 0.0}, "capacity"),
        ({"capacity": -3.0}, "capacity"),
    ],
)
def test_bad_parameters_are_named(kwargs, key):
    with pytest.raises(ValueError, match=rf"^{key} = .*: must"):
        lrb.LeadRubberBearing(**kwargs)


# ----------------------------------------------------------------- one axis: Bouc-Wen's closed forms


@pytest.mark.parametrize(("beta", "gamma"), [(0.5, 0.5), (0.8, 0.2), (0.3, 0.7)])
def test_one_axis_branch_is_the_exponential(beta, gamma):
    # η = 1 on one axis: u_y·dz/du = 1 − (β·sgn(z·du) + γ)·|z| is linear in z on each branch.
    # Loading (z du > 0) from z0: z = z∞ + (z0 − z∞)·exp(−(β+γ)·Δu/u_y), z∞ = 1/(β+γ);
    # moving up with z < 0: u_y dz/du = 1 + (γ−β)·z: z = −1/(γ−β) + (z0 + 1/(γ−β))·
    # exp((γ−β)·Δu/u_y) (z0 + Δu/u_y for γ = β) until z = 0, then the loading branch from 0.
    b = lrb.LeadRubberBearing(beta=beta, gamma=gamma)
    yd, c_load, c_back = b.u_y, beta + gamma, gamma - beta

    def branch(z0, du):
        if z0 >= 0.0:
            return 1.0 / c_load + (z0 - 1.0 / c_load) * math.exp(-c_load * du / yd)
        if c_back == 0.0:
            rest = du + z0 * yd  # path left after z reaches 0
            return z0 + du / yd if rest <= 0.0 else branch(0.0, rest)
        rest = du - yd * math.log(1.0 / (1.0 - c_back * -z0)) / c_back  # where z reaches 0
        if rest <= 0.0:
            return -1.0 / c_back + (z0 + 1.0 / c_back) * math.exp(c_back * du / yd)
        return branch(0.0, rest)

    p = b.params()
    for z0 in (-0.9, -0.3, 0.0, 0.4, 0.95):
        for du in (0.003, 0.2, 0.6, 2.5):
            s = np.array([1.0, z0])
            f, _, _ = lrb.axis_trial(p, s, 1.0 + du, 0.0)
            z = (f - b.K_d * (1.0 + du)) / b.Q_d
            assert z == pytest.approx(branch(z0, du), abs=1e-12)
            # rate-independent and exact: ten commits on the way give the same z
            for k in range(1, 11):
                lrb.axis_commit(p, s, 1.0 + du * k / 10, 0.0)
            assert s[1] == pytest.approx(branch(z0, du), abs=1e-12)


def test_loop_area_tends_to_the_bilinear_as_the_exponent_grows():
    # Imposed cycles u = u0 sin(2πt), u0 = 10 u_y, β = γ = 1/2. The bilinear loop (elastic K_u
    # to u_y = Q_d/(K_u − K_d), then K_d) encloses 4 Q_d (u0 − u_y). Bouc-Wen: unloading is
    # elastic (γ − β = 0) down to z = 0, then loading follows du = u_y dz/(1 − z^η); per
    # branch ∫(1 − z) du exceeds the bilinear's u_y/2 by u_y ∫0^1 (1 − ζ) ζ^η/(1 − ζ^η) dζ
    # = u_y Σ_k 1/((kη + 1)(kη + 2)) = (u_y/η)(ψ(1 + 2/η) − ψ(1 + 1/η)) (ψ the digamma), so
    #   area(η) = 4 Q_d (u0 − u_y) − 2 Q_d u_y S(η),  S(η) ≈ π²/(6η²) for large η,
    # up to the unsaturated part of z at the reversals, exp(−19) for η = 1.
    b0 = DEFAULT
    u0, n = 10.0 * b0.u_y, 2000
    bilinear = 4.0 * b0.Q_d * (u0 - b0.u_y)
    t = np.arange(0, 2 * n + 1) / n
    u = u0 * np.sin(2.0 * np.pi * t)
    errors = []
    for eta in (1.0, 2.0, 5.0, 10.0, 20.0, 50.0):
        f = drive_axis(lrb.LeadRubberBearing(eta=eta), u)[0]
        area = np.sum(0.5 * (f[n + 1:] + f[n:-1]) * np.diff(u[n:]))  # the second cycle
        series = (digamma(1.0 + 2.0 / eta) - digamma(1.0 + 1.0 / eta)) / eta
        closed = bilinear - 2.0 * b0.Q_d * b0.u_y * series
        assert area == pytest.approx(closed, rel=2e-6)  # the trapezoid rule's error
        errors.append((bilinear - area) / bilinear)
    # the loop converges to the bilinear one, at second order in 1/η: the relative error is
    # 2 Q_d u_y S(η)/(4 Q_d (u0 − u_y)) = S(η)/18 → π²/(108 η²) (3.7e-5 at η = 50, 6 % at η = 1)
    assert all(e1 > e2 > 0.0 for e1, e2 in itertools.pairwise(errors))
    assert errors[-1] < 4e-5
    assert 50.0 ** 2 * errors[-1] == pytest.approx(math.pi ** 2 / 108.0, rel=0.05)


# --------------------------------------------------------------------- plan restricted to one axis


@pytest.mark.parametrize("bearing", BEARINGS, ids=IDS)
@pytest.mark.parametrize("axis", [0, 1], ids=["x", "y"])
def test_along_one_axis_it_is_the_1d_bearing(bearing, axis):
    # Written once: the one-axis kernels are the plan core with the y components zero, and a
    # motion along one axis keeps z on it; force and tangent along the axis are the 1D ones
    # (measured: to the bit), nothing acts across it. With velocities along the axis the step's
    # path is straight: the chord, whatever tau.
    u, v = cyclic_path(np.random.default_rng(11 + axis))
    plan_u, plan_v = np.zeros((len(u), 2)), np.zeros((len(u), 2))
    plan_u[:, axis], plan_v[:, axis] = u, v
    f, k, z = drive_plan(bearing, plan_u)
    f_path, k_path = drive_path(bearing, plan_u, plan_v, 0.01)  # a straight path: the chord
    np.testing.assert_array_equal(f_path, f)
    np.testing.assert_array_equal(k_path, k)
    f1, k1, c1 = drive_axis(bearing, u, v)
    np.testing.assert_allclose(f[:, axis], f1, rtol=1e-12, atol=1e-12 * bearing.Q_d)
    np.testing.assert_allclose(k[:, axis, axis], k1, rtol=1e-12)
    assert not np.any(c1)
    other = 1 - axis
    assert not np.any(f[:, other]) and not np.any(z[:, other])
    assert not np.any(k[:, other, axis]) and not np.any(k[:, axis, other])
    # and it does reverse and yield: z reaches 0.95 of its cap both ways
    assert z[:, axis].max() > 0.95 * bearing.z_cap and z[:, axis].min() < -0.95 * bearing.z_cap


# --------------------------------------------------------- accuracy: converged references, tangent


@pytest.mark.parametrize(("bearing", "tol"),
                         [(DEFAULT, 1e-7), (QUADRATIC, 1e-12), (UNEQUAL, 1e-7), (SHARP, 1e-8),
                          (lrb.LeadRubberBearing(eta=2.0, beta=0.9, gamma=0.3), 1e-12)],
                         ids=["default", "eta2", "beta-gamma", "eta3", "eta2-unequal"])
def test_chords_match_a_converged_integration(bearing, tol):
    # Random plan chords, the committed z anywhere in the disk, 0.01-5 u_y long, in every
    # direction. η = 2 is the closed form (a Riccati equation along the chord): to rounding.
    # Otherwise Runge-Kutta 4 with substeps ≤ 0.05 u_y and ≤ 0.1 |z| u_y: measured worst 5e-8
    # (η = 1), 3e-9 (η = 3) against DOP853 at rtol 1e-13 (module docstring); asked below tol.
    rng = np.random.default_rng(5)
    worst = 0.0
    for _ in range(40):
        s, ux, uy = random_chord(rng, bearing)
        f, _, _ = plan_trial(bearing, s, ux, uy)
        z = (f - bearing.K_d * np.array([ux, uy])) / bearing.Q_d
        worst = max(worst, np.max(np.abs(z - converged_z(bearing, s, ux, uy))))
    assert worst < tol


@pytest.mark.parametrize("bearing", BEARINGS, ids=IDS)
def test_tangents_match_central_differences(bearing):
    # ∂f/∂u is the derivative of the update itself (closed forms differentiated, the Runge-Kutta
    # stages carried with their derivatives): central differences (h = 1e-6 u_y, error ~1e-10)
    # agree to the integration error; ∂f/∂v = 0 (rate-independent).
    rng = np.random.default_rng(8)
    worst = 0.0
    for _ in range(25):
        s, ux, uy = random_chord(rng, bearing)
        _, k, c = plan_trial(bearing, s, ux, uy)
        assert not np.any(c)
        h = 1e-6 * bearing.u_y
        fd = np.zeros((2, 2))
        for j in range(2):
            e = h * np.eye(2)[j]
            fd[:, j] = (plan_trial(bearing, s, ux + e[0], uy + e[1])[0]
                        - plan_trial(bearing, s, ux - e[0], uy - e[1])[0]) / (2.0 * h)
        worst = max(worst, np.max(np.abs(k - fd)) / np.max(np.abs(k)))
    assert worst < 2e-6


def test_zero_increment_tangent_follows_the_velocity():
    # At the committed point the tangent of the next increment is the loading one (K_d +
    # Q_d (1 − (β+γ)|z|^η)/u_y along z) if the velocity loads (z·v > 0), else the unloading
    # one (K_u for β = γ); across z it is elastic, K_u.
    b = DEFAULT
    s = b.initial_state_plan()
    s[:4] = 1.0, 0.0, 0.8, 0.0
    p = b.params()
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    lrb.plan_trial(p, s, 0, 0, 0, 0, 1.0, 0.0, 5.0, 0.0, 0.0, f, k, c)
    assert k[0, 0] == pytest.approx(b.K_d + b.Q_d * (1.0 - 0.8) / b.u_y, rel=1e-14)
    assert k[1, 1] == pytest.approx(b.K_u, rel=1e-14) and k[0, 1] == k[1, 0] == 0.0
    lrb.plan_trial(p, s, 0, 0, 0, 0, 1.0, 0.0, -5.0, 0.0, 0.0, f, k, c)
    assert k[0, 0] == pytest.approx(b.K_u, rel=1e-14)
    np.testing.assert_allclose(f, [b.K_d * 1.0 + b.Q_d * 0.8, 0.0], rtol=1e-15)


# -------------------------------------------------------------------------- plan: circular orbits


def circle(r, n, cycles):
    """Out from the centre to (r, 0) in n/4 steps, then ``cycles`` turns counter-clockwise in
    n steps each."""
    ramp = np.column_stack([np.linspace(0.0, r, n // 4 + 1)[1:], np.zeros(n // 4)])
    phi = 2.0 * np.pi * np.arange(1, n * cycles + 1) / n
    return np.vstack([ramp, r * np.column_stack([np.cos(phi), np.sin(phi)])])


@pytest.mark.parametrize("bearing", [QUADRATIC, DEFAULT, SHARP], ids=["eta2", "default", "eta3"])
def test_steady_circular_orbit(bearing):
    # On a circle of radius r (counter-clockwise, arc length s, tangent t, outward normal n)
    # a steady z turns with the orbit: z = ρ·(cos φ t + sin φ n), dz/ds = (ρ/r)·(z rotated by
    # 90°). In u_y dz/ds = A t − c (z·t) ρ^(η−2) z, the part along z gives 0 = A cos φ −
    # c ρ^η cos φ: ρ = (A/(β+γ))^(1/η), the cap, for any η; the part across z gives
    # u_y ρ/r = A sin φ: z lags the velocity by φ = asin(ρ u_y/(A r)), leaning outwards. So
    #   f = (K_d r + Q_d ρ sin φ) n + Q_d ρ cos φ t,
    # |f| = sqrt((K_d r + Q_d ρ sin φ)² + (Q_d ρ cos φ)²). The driven orbit is a polygon of n
    # chords: |z| stays on the cap (it is invariant), the lag and |f| differ from the circle's
    # by O(1/n²) (measured 3.9e-5 rad and 1.6e-5 at n = 720, a quarter at 1440).
    r = 3.0
    rho = bearing.z_cap
    phi = math.asin(rho * bearing.u_y / (lrb.A * r))
    steady = math.hypot(bearing.K_d * r + bearing.Q_d * rho * math.sin(phi),
                        bearing.Q_d * rho * math.cos(phi))
    lag_errors, force_errors = [], []
    for n in (360, 720):
        u = circle(r, n, cycles=3)
        f, _, z = drive_plan(bearing, u)
        normal = u[-n:] / np.linalg.norm(u[-n:], axis=1)[:, None]
        tangent = np.column_stack([-normal[:, 1], normal[:, 0]])
        z_last = z[-n:]
        np.testing.assert_allclose(np.linalg.norm(z_last, axis=1), rho, rtol=1e-8)
        lag = np.arctan2(np.sum(z_last * normal, axis=1), np.sum(z_last * tangent, axis=1))
        lag_errors.append(np.max(np.abs(lag - phi)))
        force_errors.append(np.max(np.abs(np.linalg.norm(f[-n:], axis=1) / steady - 1.0)))
        # the tangential force is the dissipating one: Q_d ρ cos φ
        np.testing.assert_allclose(np.sum(f[-n:] * tangent, axis=1),
                                   bearing.Q_d * rho * math.cos(phi), rtol=4.0 * 360.0 / n * 1e-4)
    assert lag_errors[1] < 5e-5 and force_errors[1] < 2e-5
    assert math.log2(lag_errors[0] / lag_errors[1]) == pytest.approx(2.0, abs=0.05)
    assert math.log2(force_errors[0] / force_errors[1]) == pytest.approx(2.0, abs=0.05)
    # the turning direction is z's (on the cap a reversal is a kink); the branch is the phase
    # at the chord's end: loading ahead (z·Δu > 0), still unloading on a chord straight back
    # along z shorter than the unloading's length, loading beyond it. Straight back along z
    # the rule is one-axis: u_y·d|z|/ds = −(A − (γ − β)·|z|^η) until z = 0 (a = z·d = 0), a
    # length L = u_y·∫₀^ρ dr/(A − (γ − β)·r^η) (ρ·u_y/A for β = γ), integrated by quad here
    p, s = bearing.params(), bearing.initial_state_plan()
    for ux, uy in u:
        lrb.plan_commit(p, s, 0, 0, 0, 0, ux, uy, 0, 0, 0.01)
    np.testing.assert_allclose(lrb.plan_turn_direction(s), z_last[-1] / np.linalg.norm(z_last[-1]),
                               rtol=1e-12)
    zc = s[2:4]
    assert lrb.plan_branch(p, s, 3.0 + 0.1 * zc[0], 0.1 * zc[1]) == 1  # ahead: loading
    length = bearing.u_y * quad(lambda r: 1.0 / (lrb.A - (bearing.gamma - bearing.beta)
                                                  * r ** bearing.eta), 0.0, rho)[0]
    back = -length
    for frac, phase in ((0.5, 0), (0.99, 0), (1.01, 1), (5.0, 1)):
        assert lrb.plan_branch(p, s, 3.0 + frac * back * zc[0] / rho,
                               frac * back * zc[1] / rho) == phase
    # along z the same chord ends unloading at z = 0, with a continuous tangent: no kink, 1
    s_axis = s.copy()
    s_axis[1] = 0.0
    s_axis[2:4] = (rho, 0.0)
    assert lrb.plan_branch(p, s_axis, 3.0 - 0.5 * length, 0.0) == 1


def circle_with_velocities(r, n, cycles, dt):
    """:func:`circle` with its velocities [in/s] (one turn in n·dt seconds; the ramp's zero)."""
    u = circle(r, n, cycles)
    omega = 2.0 * np.pi / (n * dt)
    v = np.column_stack([-u[:, 1], u[:, 0]]) * omega
    v[: n // 4] = 0.0
    return u, v


def drive_path(bearing, u, v, dt):
    """Trial then commit along u with velocities v, each step's path its cubic Hermite (the
    solver's): forces and the trials' ∂f/∂u."""
    p, s = bearing.params(), bearing.initial_state_plan()
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    forces, tangents = np.zeros_like(u), np.zeros((len(u), 2, 2))
    u0, v0 = np.zeros(2), np.zeros(2)
    for i in range(len(u)):
        args = (u0[0], u0[1], v0[0], v0[1], u[i, 0], u[i, 1], v[i, 0], v[i, 1], dt)
        lrb.plan_trial(p, s, *args, f, k, c)
        lrb.plan_commit(p, s, *args)
        forces[i], tangents[i] = f, k
        u0, v0 = u[i], v[i]
    return forces, tangents


@pytest.mark.parametrize("bearing", [DEFAULT, QUADRATIC], ids=["default", "eta2"])
def test_curved_steps_follow_the_path(bearing):
    # The steady circle (closed form above) driven in 60 steps per turn (0.31 in each, 0.64
    # u_y): along chords the orbit is a polygon and |f| errs by O(step²) (measured 2.2e-3);
    # along each step's cubic Hermite path (the circle's own velocities, cut into pieces of at
    # most 0.05 u_y) the error is the pieces' (measured 1.4e-5), whatever the step: 1.1e-5 at
    # 120 steps per turn.
    r, n, dt = 3.0, 60, 0.01
    rho = bearing.z_cap
    phi = math.asin(rho * bearing.u_y / (lrb.A * r))
    steady = math.hypot(bearing.K_d * r + bearing.Q_d * rho * math.sin(phi),
                        bearing.Q_d * rho * math.cos(phi))
    u, v = circle_with_velocities(r, n, 3, dt)
    along_path, _ = drive_path(bearing, u, v, dt)
    chords, _ = drive_path(bearing, u, v, 0.0)  # tau = 0: the chord
    path_error = np.max(np.abs(np.linalg.norm(along_path[-n:], axis=1) / steady - 1.0))
    chord_error = np.max(np.abs(np.linalg.norm(chords[-n:], axis=1) / steady - 1.0))
    assert path_error < 3e-5 and chord_error > 50.0 * path_error


def test_tangent_along_a_curved_path_matches_central_differences():
    # The trial's derivative in its end displacement, the end velocity and tau held: each piece
    # of the Hermite path moves with the end point by its Hermite weight 3θ² − 2θ³.
    b = DEFAULT
    p = b.params()
    rng = np.random.default_rng(4)
    worst = 0.0
    for _ in range(20):
        s = b.initial_state_plan()
        r, th = rng.uniform(0.0, 1.0) ** 0.3, rng.uniform(0.0, 2.0 * np.pi)
        s[2:4] = r * np.cos(th), r * np.sin(th)
        v0, v1, dt = rng.uniform(-30.0, 30.0, 2), rng.uniform(-30.0, 30.0, 2), 0.01
        end = 0.5 * dt * (v0 + v1) + rng.uniform(-0.02, 0.02, 2)

        def trial(x, y, s=s, v0=v0, v1=v1, dt=dt):
            f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
            lrb.plan_trial(p, s, 0.0, 0.0, v0[0], v0[1], x, y, v1[0], v1[1], dt, f, k, c)
            return f, k

        _, k = trial(*end)
        h = 1e-6 * b.u_y
        fd = np.column_stack([(trial(*(end + h * e))[0] - trial(*(end - h * e))[0]) / (2 * h)
                              for e in np.eye(2)])
        worst = max(worst, np.max(np.abs(k - fd)) / np.max(np.abs(k)))
    assert worst < 1e-6


def test_turning_direction_only_where_a_reversal_is_a_kink():
    # Reversing at |z| changes the tangent from K_d + (Q_d/u_y)(1 − |z|) (loading, η = 1,
    # β = γ) to K_u: a kink for the solver when the change exceeds half the larger, i.e.
    # Q_d |z|/u_y > K_u/2: |z| > K_u u_y/(2 Q_d) = 4.5·0.4938/4 = 0.556.
    b = DEFAULT
    p = b.params()
    for zx, expected in ((0.5, (0.0, 0.0)), (0.6, (0.6, 0.8)), (0.9, (0.6, 0.8))):
        s = b.initial_state_plan()
        s[2:4] = zx * 0.6, zx * 0.8
        lrb.plan_commit(p, s, 0, 0, 0, 0, 0.0, 0.0, 0, 0, 0.0)
        np.testing.assert_allclose(lrb.plan_turn_direction(s), expected, rtol=1e-14)


def test_recoverable_energy():
    # K_d |u|²/2 + Q_d u_y |z|²/2 at the committed state (the lead's spring unloaded at Q_d/u_y),
    # the same on one axis and in plan.
    b = DEFAULT
    p = b.params()
    s = b.initial_state_plan()
    s[:4] = 1.5, -2.0, 0.3, 0.4
    assert lrb.plan_energy(p, s) == pytest.approx(
        0.5 * b.K_d * 6.25 + 0.5 * b.Q_d * b.u_y * 0.25, rel=1e-15)
    assert lrb.axis_energy(p, np.array([1.5, 0.3])) == pytest.approx(
        0.5 * b.K_d * 2.25 + 0.5 * b.Q_d * b.u_y * 0.09, rel=1e-15)


# --------------------------------------------------------------------------- the OpenSees twins


def run_commands(ops, commands):
    for name, *args in commands:
        getattr(ops, name)(*args)


def opensees_plan_forces(ops, bearing, u):
    """Shear forces [kip] of the 3D twin (elastomericBearingBoucWen between a fixed node and a
    node driven through the plan path u (n, 2) [in] by imposed displacements, a static
    analysis, one step per point)."""
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(1, 0.0, 0.0, 0.0)
    ops.node(2, 0.0, 0.0, 0.0)
    ops.fix(1, 1, 1, 1, 1, 1, 1)
    ops.fix(2, 0, 0, 0, 1, 1, 1)  # vertical held by the axial spring
    commands, _ = lrb.opensees_plan_element(bearing, 1, 1, 2, 1)
    run_commands(ops, commands)
    for dof in (1, 2):  # t = i + 1: path point i (a Path series is 0 past its end)
        ops.timeSeries("Path", dof, "-dt", 1.0, "-values", 0.0, *u[:, dof - 1], u[-1, dof - 1])
        ops.pattern("Plain", dof, dof)
        ops.sp(2, dof, 1.0)
    ops.constraints("Transformation")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", 1e-12, 20)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    forces = np.zeros((len(u), 2))
    for i in range(len(u)):
        assert ops.analyze(1) == 0
        forces[i] = ops.eleForce(1)[6:8]
    ops.wipe()
    return forces


def opensees_axis_forces(ops, bearing, u):
    """Forces [kip] of the 1D twin (uniaxialMaterial BoucWen) strained through u [in]."""
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    commands, _ = lrb.opensees_axis_material(bearing, 1)
    run_commands(ops, commands)
    ops.testUniaxialMaterial(1)
    forces = np.zeros(len(u))
    for i, x in enumerate(u):
        ops.setStrain(float(x))  # sets and commits
        forces[i] = ops.getStress()
    ops.wipe()
    return forces


def refined(u, m, start):
    """The path u with each increment cut into m equal ones along its chord."""
    points = np.concatenate([start[None], u])
    return np.concatenate([points[i] + np.outer(np.arange(1, m + 1) / m, points[i + 1] - points[i])
                           for i in range(len(u))])


def figure_eight(r, n, cycles=2):
    phi = 2.0 * np.pi * np.arange(1, n * cycles + 1) / n
    return r * np.column_stack([np.sin(phi), 0.5 * np.sin(2.0 * phi)])


@pytest.mark.opensees
@pytest.mark.parametrize("bearing", [DEFAULT, QUADRATIC, UNEQUAL], ids=["default", "eta2",
                                                                          "beta-gamma"])
@pytest.mark.parametrize("orbit", ["circle", "figure-eight"])
def test_matches_opensees_elastomeric_bearing_in_3d(bearing, orbit):
    # The same plan path, each increment one chord. OpenSees takes one backward-Euler step per
    # increment (Newton on z, the sign from the trial z): first-order accurate in the
    # increment. Cutting each increment into m on its chord, its error halves as m doubles
    # (measured rates 0.95-0.99 from m = 1 to 8) and its limit is this bearing, which integrates
    # each chord exactly; the two-point (Richardson) extrapolation of the last pair is much
    # closer still. The strength is Q_d (OpenSees 3.7 reads qd as Q_d).
    ops = opensees_or_skip()
    u = circle(3.0, 120, cycles=2) if orbit == "circle" else figure_eight(3.0, 160)
    ours = drive_plan(bearing, u)[0]
    errors, last = [], None
    for m in (1, 2, 4, 8):
        theirs = opensees_plan_forces(ops, bearing, refined(u, m, np.zeros(2)))[m - 1::m]
        errors.append(np.max(np.abs(theirs - ours)))
        if m == 8:
            richardson = np.max(np.abs(2.0 * theirs - last - ours))
        last = theirs
    rates = np.log2(np.array(errors[:-1]) / errors[1:])
    assert np.all((rates > 0.85) & (rates < 1.15)), rates
    assert errors[0] < 0.1 * bearing.Q_d  # one step per increment: about 5 % of Q_d
    assert richardson < 0.1 * errors[-1]
    # and the orbit yields in plan: both components of z = (f − K_d u)/Q_d reach 0.99 of its cap
    z = (ours - bearing.K_d * u) / bearing.Q_d
    assert np.all(np.max(np.abs(z), axis=0) > 0.99 * bearing.z_cap)


@pytest.mark.opensees
@pytest.mark.parametrize("bearing", [DEFAULT, QUADRATIC, UNEQUAL, lrb.LeadRubberBearing(eta=5.0)],
                         ids=["default", "eta2", "beta-gamma", "eta5"])
def test_matches_opensees_bouc_wen_material_on_one_axis(bearing):
    # uniaxialMaterial BoucWen with z in displacement units (Z = u_y z: gamma = γ/u_y^η,
    # beta = β/u_y^η, A0 = 1, no degradation) is the same law; it too takes one backward-Euler
    # step per increment: cycles of growing then steady amplitude 3 in, 100 increments per
    # cycle, each cut into m: first order towards this bearing.
    ops = opensees_or_skip()
    t = np.arange(1, 301) / 100.0
    u = 3.0 * np.sin(2.0 * np.pi * t) * np.minimum(1.0, t)
    ours = drive_axis(bearing, u)[0]
    errors = []
    for m in (1, 2, 4, 8):
        theirs = opensees_axis_forces(ops, bearing, refined(u[:, None], m, np.zeros(1))[:, 0])
        errors.append(np.max(np.abs(theirs[m - 1::m] - ours)))
    rates = np.log2(np.array(errors[:-1]) / errors[1:])
    assert np.all((rates > 0.85) & (rates < 1.15)), rates
    assert errors[0] < 0.1 * bearing.Q_d

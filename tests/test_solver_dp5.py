"""The fifth-order open-phase method (``Integrator(method="dp5")``): measured order against closed
forms, the walls' exact propagation, stick-slip turning points, energy balance, and agreement
with Newmark on the paper runs."""

import math

import numpy as np
import pytest
from conftest import shear_chain
from scipy import signal
from scipy.linalg import eigh

from femoat.ground_motions import GroundMotion, fema_p695_record
from femoat.integration import Integrator
from femoat.paper import LAWS, WALLS, paper_model, paper_motion
from femoat.run import run
from femoat.structure.building import Building
from femoat.structure.materials import Elastic, FrictionPendulum
from femoat.structure.pounding import PoundingModel
from femoat.units import G


def fixed_dp5(h, method="dp5"):
    # rtol at its loosest so that the error control never shortens a step: fixed steps h
    return Integrator(method=method, rtol=0.099, max_step=h)


PAIRS = ("dp5", "tsit5")
"""The explicit 5(4) pairs on the one compiled step (Dormand-Prince, Tsitouras): the order
tests hold for both (a wrong coefficient of either tableau drops its order to at most 1-2)."""


def _slope(steps, errors):
    return np.polyfit(np.log(steps), np.log(errors), 1)[0]


def _rooted_trees(order):
    """Every rooted tree with ``order`` nodes, as a sorted tuple of its subtrees."""
    if order == 1:
        return [()]
    found = set()

    def children(left, smallest):
        # multisets of subtrees whose node counts sum to ``left``, in non-decreasing order
        if left == 0:
            yield ()
            return
        for n in range(smallest[0], left + 1):
            for t in _rooted_trees(n):
                if (n, t) < smallest:
                    continue
                for rest in children(left - n, (n, t)):
                    yield (t,) + rest

    for kids in children(order - 1, (1, ())):
        found.add(tuple(sorted(kids)))
    return sorted(found)


def _size(t):
    return 1 + sum(_size(u) for u in t)


def _density(t):
    """γ(t): the tree's order times its subtrees' densities."""
    return _size(t) * math.prod(_density(u) for u in t)


def _stage_weights(A, t):
    """Φ_i(t) of every stage i: the product over the subtrees u of Σ_j a_ij·Φ_j(u)."""
    out = np.ones(A.shape[0])
    for u in t:
        out = out * (A @ _stage_weights(A, u))
    return out


@pytest.mark.parametrize("method", PAIRS)
def test_the_pairs_tableau_meets_the_order_conditions(method):
    # Butcher's order conditions Σ_i b_i·Φ_i(t) = 1/γ(t) over every rooted tree t: all 17 trees
    # of up to five nodes for the fifth-order weights b (the last row of A), all 8 of up to
    # four for the embedded weights b̂ = b − E over the seven stages (the last one the step's
    # end), and b̂ misses order five (an embedded pair that met it would estimate nothing).
    # Also c_s = Σ_j a_sj, and E sums to zero (both solutions are consistent). In double
    # precision: Tsitouras' coefficients reach 13 in size, so the sums round to ~1e-14; a wrong
    # digit anywhere shows far above 1e-13.
    from femoat.integration import methods

    A6, C, B, E = methods.module(method).PAIR
    A = np.zeros((7, 7))
    A[:, :6] = A6  # a_sj, j < s; the seventh stage's row is b (first same as last)
    b = A[6].copy()
    b_hat = b - E
    np.testing.assert_allclose(A.sum(axis=1), C, atol=1e-13)
    np.testing.assert_allclose(B, b[:6], atol=0)
    assert abs(E.sum()) < 1e-13
    trees = {n: _rooted_trees(n) for n in range(1, 6)}
    assert [len(trees[n]) for n in trees] == [1, 1, 2, 4, 9]
    for n, ts in trees.items():
        for t in ts:
            phi = _stage_weights(A, t)
            assert b @ phi == pytest.approx(1.0 / _density(t), abs=1e-13), (n, t)
            if n <= 4:
                assert b_hat @ phi == pytest.approx(1.0 / _density(t), abs=1e-13), (n, t)
    misses = [abs(b_hat @ _stage_weights(A, t) - 1.0 / _density(t)) for t in trees[5]]
    assert max(misses) > 1e-4


@pytest.mark.parametrize("method", PAIRS)
def test_measured_order_with_analytic_forcing(method):
    # A linear 3-DOF chain (base mat + 2 floors, undamped) from an initial velocity under a
    # ground acceleration that is exactly linear in time, a_g = ȧ·t (analytic forcing: no
    # sample's kink anywhere). Modal closed form with mass-normalised modes φ_n:
    #   q̈_n + ω_n²·q_n = −L_n·ȧ·t,  L_n = φ_nᵀ·M·1
    #   q_n(t) = −L_n·ȧ·t/ω_n² + q̇₀·... : q_n = A·cos ω_n t + B·sin ω_n t − L_n·ȧ·t/ω_n²,
    #   A = q_n(0) = 0, B·ω_n = q̇_n(0) + L_n·ȧ/ω_n².
    # Both pairs keep their fifth-order solution: the global error falls as h⁵
    # (slope ≥ 3.8 is the bound for a method of at least fourth order).
    b = Building(isolator=Elastic(2.0), stories=(Elastic(42.799),) * 2,
                 floor_weights=(20.0, 20.0), story_damping_ratio=0.0)
    m, K = shear_chain([b.base_weight, *b.floor_weights], [2.0, 42.799, 42.799])
    w2, phi = eigh(K, m)
    w = np.sqrt(w2)
    v_init = np.array([2.0, 1.0, -0.5])
    rate = 50.0  # ȧ [in/s³]
    duration = 1.0
    steps, errors = [8e-3, 4e-3, 2e-3, 1e-3], []
    for h in steps:
        t = np.arange(0.0, duration + h / 2, h)
        motion = GroundMotion(rate * t / G, h, name="ramp")
        res = run(PoundingModel(b), motion, fixed_dp5(h, method), duration=duration,
                  v0=v_init)
        assert res.meta["stats"]["rejected_error"] == 0  # really fixed steps
        L = phi.T @ m @ np.ones(3)
        qd0 = phi.T @ m @ v_init
        tt = res.time[None, :]
        q = ((qd0 + L * rate / w2)[:, None] / w[:, None] * np.sin(w[:, None] * tt)
             - (L * rate / w2)[:, None] * tt)
        errors.append(np.max(np.abs(res.displacement - (phi @ q).T)))
    slope = _slope(steps, errors)
    assert slope >= 3.8, (slope, errors)
    assert errors[-1] < 1e-9


@pytest.mark.parametrize("method", PAIRS)
def test_measured_order_with_a_record_when_steps_end_on_samples(method):
    # The same chain, damped, under a piecewise-linear record (samples every 0.01 s), steps of
    # 1/k of a sample so that every step ends on a sample. scipy's lsim with a first-order hold
    # is exact for that input (a matrix exponential per sample), the reference.
    b = Building(isolator=Elastic(2.0), stories=(Elastic(42.799),) * 2,
                 floor_weights=(20.0, 20.0), story_damping_ratio=0.02)
    rng = np.random.default_rng(7)
    dt = 0.01
    n = 201
    ag_g = 0.3 * np.cumsum(rng.standard_normal(n)) / np.sqrt(n)
    motion = GroundMotion(ag_g, dt, name="random walk")
    pk = PoundingModel(b).pack()
    M, C, K = pk.M, pk.C, pk.K.copy()
    for e, (i, j) in enumerate(zip(pk.el_i, pk.el_j)):
        k = b.isolator.k if j < 0 else b.stories[0].k
        K[i, i] += k
        if j >= 0:
            K[j, j] += k
            K[i, j] -= k
            K[j, i] -= k
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((3, 3)), np.eye(3)], [-Minv @ K, -Minv @ C]])
    B = np.concatenate([np.zeros(3), -Minv @ pk.r])[:, None]
    t = np.arange(n) * dt
    _, y, _ = signal.lsim(signal.StateSpace(A, B, np.eye(6)[:3], np.zeros((3, 1))),
                          ag_g * G, t, interp=True)
    steps, errors = [], []
    for k in (1, 2, 4, 8):
        res = run(PoundingModel(b), motion, fixed_dp5(dt / k, method), duration=t[-1])
        on_samples = np.isin(np.round(res.time / dt * k).astype(int) % k, [0])
        u = res.displacement[on_samples]
        assert u.shape[0] == n
        steps.append(dt / k)
        errors.append(np.max(np.abs(u - y)))
    slope = _slope(steps, errors)
    assert slope >= 3.8, (slope, errors)


def test_a_wall_decays_exactly_while_the_gap_is_open():
    # The paper's concrete wall is an overdamped SDOF (c/m ≈ 4,400 1/s, ω ≈ 56 rad/s): the
    # explicit step would need steps below 1 ms for it; instead it is propagated exactly.
    # Free decay from u₀ (roots λ₁,₂ of m·λ² + c·λ + k = 0, real and distinct):
    #   u(t) = (λ₁·e^{λ₂t} − λ₂·e^{λ₁t})/(λ₁ − λ₂)·u₀.
    model = paper_model("concrete", "E", gap=1000.0)
    pk = model.pack()
    i = pk.n_struct  # the first wall's DOF
    m, c, k = pk.M[i, i], pk.C[i, i], pk.K[i, i]
    disc = math.sqrt(c * c - 4 * m * k)
    l1 = (-c - disc) / (2 * m)
    l2 = k / (m * l1)  # the product of the roots is k/m (no cancellation)
    u0 = np.zeros(pk.n)
    u0[i] = 0.2
    still = GroundMotion(np.zeros(201), 0.005, name="still")
    res = run(model, still, Integrator(method="dp5"), duration=1.0, u0=u0)
    t = res.time
    exact = (l1 * np.exp(l2 * t) - l2 * np.exp(l1 * t)) / (l1 - l2) * 0.2
    assert np.max(np.abs(res.displacement[:, i] - exact)) < 1e-12


def test_a_wall_under_the_record_matches_the_exact_linear_response():
    # The wall DOF alone under a piecewise-linear record: lsim with a first-order hold (exact)
    # against femoat's particular-solution-plus-propagator step, to round-off.
    model = paper_model("steel", "E", gap=1000.0)
    pk = model.pack()
    i = pk.n_struct
    m, c, k, r = pk.M[i, i], pk.C[i, i], pk.K[i, i], pk.r[i]
    rng = np.random.default_rng(3)
    dt, n = 0.005, 401
    ag_g = 0.5 * np.sin(np.arange(n) * 0.3) + 0.1 * rng.standard_normal(n)
    res = run(model, GroundMotion(ag_g, dt, name="noise"), Integrator(method="dp5"),
              duration=(n - 1) * dt)
    t = np.arange(n) * dt
    _, y, _ = signal.lsim(signal.StateSpace([[0, 1], [-k / m, -c / m]], [[0], [-r / m]],
                                            [[1, 0]], [[0]]), ag_g * G, t, interp=True)
    u = np.interp(t, res.time, res.displacement[:, i])
    assert np.max(np.abs(u - y)) < 1e-9 * np.max(np.abs(y))


def test_a_sliding_bearing_turns_back_on_a_sample():
    # A rigid block on a friction pendulum pushed at v0: it slides against friction μW and the
    # restoring (W/R)·u until its velocity turns, then sticks (at the turn (W/R)·u < μW), the
    # elastic-perfectly-plastic friction unloading with stiffness μW/u_y. Every stage of a step
    # is evaluated from the state committed at the step's start, so the turn must be a step
    # end: at the first sign change of the velocity some sample has |v| < v0·2^-12, and there
    # the force is still the sliding one, (W/R)·u + μW; the next sample's is less.
    W, R, mu, uy = 100.0, 40.0, 0.06, 0.01
    bearing = FrictionPendulum(W=W, R=R, mu=mu, u_y=uy)
    model = PoundingModel(Building(base_weight=W, floor_weights=(), stories=(),
                                   isolator=bearing), ())
    still = GroundMotion(np.zeros(201), 0.005, name="still")
    v0 = 10.0
    res = run(model, still, Integrator(method="dp5"), duration=1.0, v0=[v0])
    v = res.velocity[:, 0]
    first_negative = int(np.argmax(v < 0.0))
    assert first_negative > 0
    k = first_negative - 1 if abs(v[first_negative - 1]) < abs(v[first_negative]) \
        else first_negative
    assert abs(v[k]) < v0 * 2.0 ** -12
    # energy at the turn: ½·m·v0² = μW·(u − u_y) + ½·μW·u_y + ½·(W/R)·u² (friction work while
    # sliding, the friction spring's stored ½·μW·u_y, the pendulum's restoring energy), so
    # ½·(W/R)·u² + μW·u − (½·m·v0² + ½·μW·u_y) = 0 (converged runs agree to 1e-10)
    m = W / G
    c = 0.5 * m * v0 ** 2 + 0.5 * mu * W * uy
    u_turn = (-mu * W + math.sqrt((mu * W) ** 2 + 2.0 * (W / R) * c)) / (W / R)
    assert res.displacement[k, 0] == pytest.approx(u_turn, rel=1e-5)
    f = res.element_force[:, 0]
    assert f[k] == pytest.approx(W / R * res.displacement[k, 0] + mu * W, rel=1e-6)
    assert f[k + 1] < f[k]


@pytest.fixture(scope="module")
def paper_pairs():
    motion = paper_motion()
    out = {}
    for wall in WALLS:
        for law in LAWS:
            model = paper_model(wall, law)
            out[(wall, law)] = tuple(run(model, motion, Integrator(method=m))
                                     for m in ("newmark", "dp5"))
    return out


def test_paper_runs_have_newmarks_contact_episodes(paper_pairs):
    # The same impacts on every one of the 10 paper runs (positive and negative side counts),
    # at the same instants to well within a record sample (2.5 ms).
    for key, (nm, dp) in paper_pairs.items():
        assert (dp.peaks["impacts_pos"], dp.peaks["impacts_neg"]) == \
            (nm.peaks["impacts_pos"], nm.peaks["impacts_neg"]), key
        starts_nm = sorted(i["start"] for i in nm.impacts)
        starts_dp = sorted(i["start"] for i in dp.impacts)
        assert np.max(np.abs(np.subtract(starts_nm, starts_dp))) < 1e-4, key


def test_paper_runs_energy_balance_closes(paper_pairs):
    # Newmark's trapezoidal rule balances energy to round-off by construction (1e-13); the
    # fifth-order step balances it to its truncation error (the stages' powers integrated by
    # the method's own weights, the walls exactly), far below any physical term.
    for key, (nm, dp) in paper_pairs.items():
        assert nm.energy["residual"] < 1e-10, key
        assert dp.energy["residual"] < 1e-7, key


def test_paper_runs_cost_fewer_steps(paper_pairs):
    # The open phase takes about one step per record sample (4,955 in 12.39 s at 2.5 ms):
    # fewer than half of Newmark's steps on every paper run.
    for key, (nm, dp) in paper_pairs.items():
        assert dp.peaks["steps"] < 0.5 * nm.peaks["steps"], key


def test_energy_terms_of_building_and_walls_match_a_converged_newmark_run():
    # The walls' input and dashpot work come from their exact propagation (∫p·du = p₁u₁ − p₀u₀
    # − ṗ·∫u, dashpot = input − stored), the building's from the fifth-order quadrature of the
    # stages' powers. Far-away walls (no impact) under a real record, against Newmark at steps
    # of 1e-4 s (converged): the totals within 1e-5 (measured 4e-6), and the walls' own share
    # (the run minus the same building without walls: 8e-4 of the input, 1.2e-3 of the
    # dashpot work here; the building's motion does not depend on the walls while the gaps
    # are open) within 1e-3 of Newmark's share: a sign error in ∫u, or a wall term left out,
    # misses that by far.
    gm = fema_p695_record("farfield", 12, "a").scaled_to_pga(0.6).time_scaled(0.5)
    model = paper_model("steel", "E", gap=1000.0)
    bare = PoundingModel(model.building, ())
    fine = Integrator(method="newmark", rtol=1e-8, max_step=1e-4)
    runs = {(name, m): run(mod, gm, integ, duration=4.0).energy
            for name, integ in (("fine", fine), ("dp5", Integrator(method="dp5")))
            for m, mod in (("walls", model), ("bare", bare))}
    for key in ("input", "viscous", "kinetic", "friction"):
        assert runs["dp5", "walls"][key] == pytest.approx(runs["fine", "walls"][key], rel=1e-5)
    for key in ("input", "viscous"):
        share = {k: runs[k, "walls"][key] - runs[k, "bare"][key] for k in ("fine", "dp5")}
        assert share["fine"] > 5e-4 * runs["fine", "walls"][key]
        assert share["dp5"] == pytest.approx(share["fine"], rel=1e-3), key

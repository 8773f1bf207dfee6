"""The bidirectional friction pendulum bearing (issue 18): friction coupled in plan."""

import math

import numpy as np
import pytest
from conftest import opensees_or_skip

from femoat.plan import (
    BidirectionalFrictionPendulum,
    plan_friction_pendulum_commit,
    plan_friction_pendulum_energy,
    plan_friction_pendulum_trial,
)
from femoat.structure.materials import material_commit, material_trial

CONSTANT = BidirectionalFrictionPendulum(W=33.0, R=30.0, u_y=0.01, mu=0.06)
VELOCITY = BidirectionalFrictionPendulum(W=33.0, R=30.0, u_y=0.01, mu=0.04, mu_fast=0.10, a=0.5)
BEARINGS = pytest.mark.parametrize("bearing", [CONSTANT, VELOCITY], ids=["constant", "velocity"])


def drive(bearing, u, v=None):
    """Trial then commit at every point of a plan path u (n, 2) [in] with velocities v (n, 2):
    forces (n, 2), tangents ∂f/∂u and ∂f/∂v (n, 2, 2), committed z (n, 2)."""
    v = np.zeros_like(u) if v is None else v
    p, s = bearing.params(), bearing.initial_state()
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    out = np.zeros((len(u), 2)), np.zeros((len(u), 2, 2)), np.zeros((len(u), 2, 2))
    z = np.zeros((len(u), 2))
    for i, ((ux, uy), (vx, vy)) in enumerate(zip(u, v)):
        plan_friction_pendulum_trial(p, s, ux, uy, vx, vy, f, k, c)
        plan_friction_pendulum_commit(p, s, ux, uy, vx, vy)
        out[0][i], out[1][i], out[2][i], z[i] = f, k, c, s[2:4]
    return (*out, z)


def drive_1d(material, u, v):
    """The 1D bearing along the same path: force, ∂f/∂u, ∂f/∂v per point."""
    p, s = material.params(), material.initial_state()
    out = np.zeros((len(u), 3))
    for i, (ui, vi) in enumerate(zip(u, v)):
        out[i] = material_trial(material.code, p, s, ui, vi)
        material_commit(material.code, p, s, ui, vi)
    return out.T


def cyclic_path(rng, n=3000):
    """A random cyclic path [in] with velocities [in/s]: runs of 1-80 steps between reversals,
    steps of up to 0.05 in or, in one run out of three, up to 0.003 in (so that the bearing
    also sticks after reversals, within the elastic recovery 2·u_y = 0.02 in)."""
    steps, sign = [], 1.0
    while len(steps) < n:
        run = int(rng.integers(1, 80))
        largest = 0.003 if rng.uniform() < 1 / 3 else 0.05
        steps += list(sign * rng.uniform(0.1, 1.0, run) * largest)
        sign = -sign
    u = np.cumsum(steps[:n])
    v = rng.uniform(-30.0, 30.0, n) * (rng.uniform(size=n) > 0.1)  # some exactly at rest
    return u, v


# ----------------------------------------------------------------- the 1D bearing as a special case


@BEARINGS
@pytest.mark.parametrize("axis", [0, 1], ids=["x", "y"])
def test_along_one_axis_it_is_the_1d_bearing(bearing, axis):
    # Motion along one axis keeps z on that axis: |z_trial| = |z_trial,axis| and z/|z| = ±1, so
    # force, ∂f/∂u and ∂f/∂v along the axis are the 1D bearing's (the same formulas), and
    # nothing acts across it.
    u, v = cyclic_path(np.random.default_rng(11 + axis))
    plan_u, plan_v = np.zeros((len(u), 2)), np.zeros((len(u), 2))
    plan_u[:, axis], plan_v[:, axis] = u, v
    f, k, c, _ = drive(bearing, plan_u, plan_v)
    f1, k1, c1 = drive_1d(bearing.uniaxial(), u, v)
    mu_w = bearing.mu * bearing.W
    np.testing.assert_allclose(f[:, axis], f1, rtol=1e-12, atol=1e-12 * mu_w)
    np.testing.assert_allclose(k[:, axis, axis], k1, rtol=1e-12)
    np.testing.assert_allclose(c[:, axis, axis], c1, rtol=1e-12, atol=1e-12 * mu_w)
    other = 1 - axis
    assert np.all(f[:, other] == 0.0)
    assert np.all(k[:, axis, other] == 0.0) and np.all(k[:, other, axis] == 0.0)
    assert np.all(c[:, other] == 0.0) and np.all(c[:, :, other] == 0.0)
    # The path exercises both states: sticking (k = W/R + μW/u_y) and sliding (k = W/R).
    k_r = bearing.W / bearing.R
    assert np.sum(np.isclose(k1, k_r, rtol=1e-12)) > 0.5 * len(u)
    assert np.sum(k1 > 2.0 * k_r) > 50


@BEARINGS
def test_straight_diagonal_motion_is_the_1d_bearing_along_that_line(bearing):
    # u = s·d, v = ṡ·d with d at 30° keeps z parallel to d, with the 1D value ζ(s): the force is
    # F1D(s)·d, and the stiffness along the line d·K·d is the 1D tangent.
    d = np.array([math.cos(math.radians(30.0)), math.sin(math.radians(30.0))])
    s, sdot = cyclic_path(np.random.default_rng(5))
    f, k, c, _ = drive(bearing, np.outer(s, d), np.outer(sdot, d))
    f1, k1, c1 = drive_1d(bearing.uniaxial(), s, sdot)
    mu_w = bearing.mu * bearing.W
    np.testing.assert_allclose(f, np.outer(f1, d), rtol=1e-12, atol=1e-12 * mu_w)
    np.testing.assert_allclose(np.einsum("i,nij,j->n", d, k, d), k1, rtol=1e-12)
    np.testing.assert_allclose(np.einsum("i,nij,j->n", d, c, d), c1, rtol=1e-12,
                               atol=1e-12 * mu_w)


# ----------------------------------------------------------------------------- coupled friction


def circle(r, n_per_cycle, cycles=3):
    """Out from the centre along +x to radius r [in], then around the circle counterclockwise
    at constant speed, n_per_cycle points per turn."""
    approach = np.column_stack([np.linspace(0.0, r, 201), np.zeros(201)])
    phi = 2.0 * np.pi * np.arange(1, cycles * n_per_cycle + 1) / n_per_cycle
    return np.vstack([approach, r * np.column_stack([np.cos(phi), np.sin(phi)])]), 201


def test_friction_on_a_circle_is_mu_w_not_sqrt2_mu_w():
    # Around a circle the bearing slides all the time (z_trial gains Δu/u_y >> |z| on top of a
    # unit z), so z is a unit vector and the friction force F − (W/R)·u has magnitude μW at every
    # point. Two uncoupled 1D bearings (one per axis) would resist with μW per axis: at 45° on the
    # circle both slide (each moved 0.29·r >> 2·u_y since its last reversal), √2·μW in all.
    r, n = 4.0, 720
    u, start = circle(r, n)
    b = CONSTANT
    f, _, _, z = drive(b, u)
    mu_w, k_r = b.mu * b.W, b.W / b.R
    friction = f - k_r * u
    on_circle = slice(start, None)
    np.testing.assert_allclose(np.hypot(*friction[on_circle].T), mu_w, rtol=1e-14)
    np.testing.assert_allclose(np.hypot(*z[on_circle].T), 1.0, rtol=1e-15)
    uncoupled = b.uniaxial()
    zero = np.zeros(len(u))
    fx = drive_1d(uncoupled, u[:, 0], zero)[0] - k_r * u[:, 0]
    fy = drive_1d(uncoupled, u[:, 1], zero)[0] - k_r * u[:, 1]
    at_45 = start + n + n // 8 - 1  # second turn, φ = 45°
    assert u[at_45] == pytest.approx(r * np.array([1.0, 1.0]) / math.sqrt(2.0), rel=1e-12)
    assert math.hypot(fx[at_45], fy[at_45]) == pytest.approx(math.sqrt(2.0) * mu_w, rel=1e-14)
    assert math.hypot(*friction[at_45]) == pytest.approx(mu_w, rel=1e-14)


@pytest.mark.parametrize(("r", "n"), [(4.0, 90), (4.0, 1000), (1.0, 8000)])
def test_work_per_cycle_on_a_circle_is_mu_w_times_the_slip_path(r, n):
    # Continuous model, steady circular orbit of radius r: z rotates with the displacement and
    # |z| = 1, so ż ⊥ z and the plastic slip u_p = u − u_y·z (with z·u_p' = |u_p'|) runs on a
    # circle of radius sqrt(r² − u_y²); the friction work per turn ∮F·du is the dissipation
    # μW·2π·sqrt(r² − u_y²) (the restoring force is conservative): μW times the slip path,
    # which is the orbit's length 2πr to (u_y/r)²/2 = 3e-6 at r = 4 in.
    # The radial return is that rule's backward Euler step; its steady state on n points per turn
    # (α = 2π/n) is exact too: z_n at angle φ_n + β with cos(β + α/2) = u_y·cos(α/2)/r (z_n plus
    # the chord 2r·sin(α/2)/u_y must point along z_{n+1}), and the trapezoidal work per step,
    # μW·(z_n + z_{n+1})/2·Δu, is μW·r·sin α·sin β (the restoring part cancels exactly on a
    # circle: (u_n + u_{n+1})·(u_{n+1} − u_n) = |u_{n+1}|² − |u_n|² = 0).
    b = CONSTANT
    u, start = circle(r, n)
    f, _, _, _ = drive(b, u)
    third = slice(start + 2 * n - 1, start + 3 * n)  # φ = 0 to 2π, third turn (steady)
    work = np.sum(0.5 * (f[third][1:] + f[third][:-1]) * np.diff(u[third], axis=0))
    mu_w, alpha = b.mu * b.W, 2.0 * np.pi / n
    beta = math.acos(b.u_y * math.cos(alpha / 2) / r) - alpha / 2
    assert work == pytest.approx(n * mu_w * r * math.sin(alpha) * math.sin(beta), rel=1e-12)
    continuous = mu_w * 2.0 * np.pi * math.sqrt(r * r - b.u_y**2)
    # Expanding for small α: n·sin α/2π = 1 − α²/6 and, with cos γ = u_y·cos(α/2)/r,
    # sin β/sin β_∞ = cos(α/2)·(sin γ − (u_y/r)·sin(α/2))/sin β_∞ = 1 − α²/8 − (α/2)·(u_y/r)
    # to leading orders (sin γ/sin β_∞ = 1 + O(α²·(u_y/r)²)): the discrete work falls short of
    # the continuous one by (7/24)·α² + (α/2)·(u_y/r), first order in the step.
    shortfall = 7.0 / 24.0 * alpha**2 + alpha / 2.0 * b.u_y / r
    assert 1.0 - work / continuous == pytest.approx(shortfall, rel=1e-2)


def test_work_per_cycle_converges_at_first_order_to_the_continuous_value():
    # Halving the step halves the error of the backward Euler radial return (fine steps,
    # chord/u_y < 1): the ratio of successive errors tends to 2.
    b, r = CONSTANT, 1.0
    continuous = b.mu * b.W * 2.0 * np.pi * math.sqrt(r * r - b.u_y**2)
    errors = []
    for n in (4000, 8000, 16000):
        u, start = circle(r, n, cycles=2)
        f, _, _, _ = drive(b, u)
        turn = slice(start + n - 1, start + 2 * n)
        work = np.sum(0.5 * (f[turn][1:] + f[turn][:-1]) * np.diff(u[turn], axis=0))
        errors.append(abs(work / continuous - 1))
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all((ratios > 1.9) & (ratios < 2.3)), ratios


def test_radial_return_keeps_z_in_the_unit_disk():
    # z = z_trial/|z_trial| when |z_trial| > 1: on the unit circle up to rounding (one unit in
    # the last place of 1.0, 2^-52), however long the random plan walk, with no drift.
    rng = np.random.default_rng(1)
    u = np.cumsum(rng.normal(0.0, 0.02, (20000, 2)), axis=0)
    _, _, _, z = drive(CONSTANT, u)
    norm = np.hypot(*z.T)
    assert norm.max() <= 1.0 + 2.0**-52
    sliding = norm > 1.0 - 1e-12
    assert 0.2 < sliding.mean() < 0.999  # both states occur
    assert np.all(np.abs(norm[sliding] - 1.0) <= 2.0**-52)


def test_friction_depends_on_the_speed_not_on_each_component():
    # Sliding at speed V in any direction: μ(V) = μ_fast − (μ_fast − μ_slow)·exp(−a·V) (speed
    # smoothed by at most v_reg), the same in every direction; the force stays μ(V)·W in
    # magnitude (not μ(V_x) on x and μ(V_y) on y).
    b = VELOCITY
    p = b.params()
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    V = 8.0
    mu = 0.10 - 0.06 * math.exp(-0.5 * V)
    for angle in (0.0, 30.0, 45.0, 120.0):
        d = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
        s = b.initial_state()
        for step in np.linspace(0.0, 1.0, 101)[1:]:  # slide 1 in along d
            plan_friction_pendulum_commit(p, s, *(step * d), *(V * d))
        plan_friction_pendulum_trial(p, s, *(1.01 * d), *(V * d), f, k, c)
        friction = f - b.W / b.R * 1.01 * d
        assert np.linalg.norm(friction) == pytest.approx(mu * b.W, abs=0.06 * 0.5 * 1e-3 * b.W)
        np.testing.assert_allclose(friction / np.linalg.norm(friction), d, atol=1e-14)


def test_recoverable_energy_on_the_circle():
    # Sliding on a circle of radius r: |u| = r and |z| = 1, so the stored energy is
    # (W/R)·r²/2 + μ·W·u_y/2 (the 1D formula with vectors).
    b, r = CONSTANT, 2.0
    u, _ = circle(r, 400, cycles=1)
    p, s = b.params(), b.initial_state()
    for ux, uy in u:
        plan_friction_pendulum_commit(p, s, ux, uy, 0.0, 0.0)
    expected = 0.5 * b.W / b.R * r * r + 0.5 * b.mu * b.W * b.u_y
    assert plan_friction_pendulum_energy(p, s) == pytest.approx(expected, rel=1e-12)


# ------------------------------------------------------------------------ tangents (differences)


@BEARINGS
def test_tangents_match_central_differences(bearing):
    # ∂f/∂u and ∂f/∂v against central differences of the trial force, at trial points from
    # committed states along random plan walks, sticking and sliding; a difference that
    # straddles the yield circle (|z_trial| = 1 between u − h and u + h) is skipped.
    rng = np.random.default_rng(3)
    p = bearing.params()
    f, k, c = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
    plus, minus, scratch = np.zeros(2), np.zeros(2), np.zeros((2, 2))
    h, checked, sliding = 1e-7, 0, 0
    for _ in range(20):
        s = bearing.initial_state()
        for ux, uy in np.cumsum(rng.normal(0.0, 0.01, (int(rng.integers(1, 60)), 2)), axis=0):
            plan_friction_pendulum_commit(p, s, ux, uy, 0.0, 0.0)

        def slides(u, s=s):
            return np.hypot(*(s[2:4] + (u - s[:2]) / bearing.u_y)) > 1.0

        for _ in range(10):
            u = s[:2] + rng.normal(0.0, rng.choice([0.003, 0.03]), 2)
            v = rng.normal(0.0, 5.0, 2) * rng.choice([0.0, 1.0])
            steps = h * np.eye(2)
            if any(slides(u + e) != slides(u - e) for e in steps):
                continue
            plan_friction_pendulum_trial(p, s, *u, *v, f, k, c)
            numeric_k, numeric_c = np.zeros((2, 2)), np.zeros((2, 2))
            for j, e in enumerate(steps):
                plan_friction_pendulum_trial(p, s, *(u + e), *v, plus, scratch, scratch)
                plan_friction_pendulum_trial(p, s, *(u - e), *v, minus, scratch, scratch)
                numeric_k[:, j] = (plus - minus) / (2 * h)
                plan_friction_pendulum_trial(p, s, *u, *(v + e), plus, scratch, scratch)
                plan_friction_pendulum_trial(p, s, *u, *(v - e), minus, scratch, scratch)
                numeric_c[:, j] = (plus - minus) / (2 * h)
            stiffness = bearing.W / bearing.R + bearing.mu * bearing.W / bearing.u_y
            np.testing.assert_allclose(k, numeric_k, rtol=0, atol=1e-6 * stiffness)
            np.testing.assert_allclose(c, numeric_c, rtol=0, atol=1e-6 * bearing.W)
            checked += 1
            sliding += bool(slides(u))
    assert checked > 150 and 20 < sliding < checked - 20


# ------------------------------------------------------------------------------------ bad input


@pytest.mark.parametrize(
    ("kwargs", "key"),
    [
        ({"W": -33.0}, "W"),
        ({"R": 0.0}, "R"),
        ({"R": -30.0}, "R"),
        ({"mu": -0.06}, "mu"),
        ({"u_y": 0.0}, "u_y"),
        ({"u_y": -0.01}, "u_y"),
        ({"mu": 0.04, "mu_fast": 0.1}, "a"),
    ],
)
def test_bad_parameters_are_named(kwargs, key):
    with pytest.raises(ValueError, match=rf"^{key} = .*: must"):
        BidirectionalFrictionPendulum(**kwargs)


def test_params_are_the_1d_bearings():
    b = VELOCITY
    np.testing.assert_array_equal(b.params(), b.uniaxial().params())
    assert b.initial_state().shape == (6,) and not b.initial_state().any()


# ----------------------------------------------------------------------- the OpenSees twin (3D)


def opensees_forces(ops, b, u):
    """Horizontal forces [kip] of OpenSees' flatSliderBearing (Coulomb, kInit = μW/u_y, axial
    load W on the slider from a gravity step) in parallel with a W/R spring in x and y, the slider
    node driven through the plan path u (n, 2) [in] by imposed displacements; and its N [kip]."""
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(1, 0.0, 0.0, 0.0)  # the sliding surface (ground)
    ops.node(2, 0.0, 0.0, 0.0)  # the slider (base mat)
    ops.fix(1, 1, 1, 1, 1, 1, 1)
    ops.fix(2, 0, 0, 0, 1, 1, 1)  # rotations held: they would tilt the surface (N and V)
    ops.frictionModel("Coulomb", 1, b.mu)
    ops.uniaxialMaterial("Elastic", 1, 1.0e6)  # axial and rotational springs [kip/in]
    ops.uniaxialMaterial("Elastic", 2, b.W / b.R)  # the pendulum's restoring stiffness
    # local x along global z (the bearing's axis), local y along global x: shear y, z = x, y
    ops.element("flatSliderBearing", 1, 1, 2, 1, b.mu * b.W / b.u_y, "-P", 1, "-T", 1, "-My", 1,
                "-Mz", 1, "-orient", 0.0, 0.0, 1.0, 1.0, 0.0, 0.0)
    ops.element("zeroLength", 2, 1, 2, "-mat", 2, 2, "-dir", 1, 2)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 0.0, 0.0, -b.W, 0.0, 0.0, 0.0)
    for dof in (1, 2):  # t = 1: the gravity step at u = 0; t = 2 + i: path point i (a Path
        # series is 0 at its last time, hence the last point once more at the end)
        values = [0.0, 0.0, *u[:, dof - 1], u[-1, dof - 1]]
        ops.timeSeries("Path", 1 + dof, "-dt", 1.0, "-values", *values)
        ops.pattern("Plain", 1 + dof, 1 + dof)
        ops.sp(2, dof, 1.0)
    ops.constraints("Transformation")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", 1e-12, 20)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    assert ops.analyze(1) == 0
    normal = -ops.eleResponse(1, "basicForce")[0]
    forces = np.zeros((len(u), 2))
    for i in range(len(u)):
        assert ops.analyze(1) == 0
        assert ops.nodeDisp(2, 1) == pytest.approx(u[i, 0], abs=1e-14)
        assert ops.nodeDisp(2, 2) == pytest.approx(u[i, 1], abs=1e-14)
        slider, spring = ops.eleForce(1), ops.eleForce(2)
        forces[i] = slider[6] + spring[6], slider[7] + spring[7]
    ops.wipe()
    return forces, normal


def figure_eight(r, n):
    phi = 2.0 * np.pi * np.arange(1, 2 * n + 1) / n
    return r * np.column_stack([np.sin(phi), 0.5 * np.sin(2.0 * phi)])


@pytest.mark.opensees
@pytest.mark.parametrize("orbit", ["circle", "figure-eight"])
def test_matches_opensees_flat_slider_with_restoring_springs(orbit):
    ops = opensees_or_skip()
    b = CONSTANT
    u = circle(3.0, 240, cycles=2)[0] if orbit == "circle" else figure_eight(3.0, 320)
    theirs, normal = opensees_forces(ops, b, u)
    ours, _, _, _ = drive(b, u)
    assert normal == pytest.approx(b.W, rel=1e-12)  # N from the gravity step
    # Same circular surface, radial return and N = W: asked within 1e-3 of the largest force;
    # the two agree to rounding (measured 1e-14 kip), so hold them to 1e-9.
    assert np.max(np.abs(ours - theirs)) <= 1e-9 * np.max(np.abs(ours))
    # and the orbit slides in plan: the friction force turns (both components reach ±0.9 μW)
    friction = ours - b.W / b.R * u
    assert np.all(np.max(np.abs(friction), axis=0) > 0.9 * b.mu * b.W)

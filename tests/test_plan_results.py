"""The result of a plan run (femoat.results.plan): peaks per direction and in plan from closed-form
histories, the impact table per wall, save/load, bad input, and the OpenSees twin's run read the
same way."""

import math

import numpy as np
import pytest
from conftest import opensees_or_skip

from femoat.ground_motions import GroundMotion, RecordPair, fema_p695_pair
from femoat.plan import PlanModel, rectangular_moat
from femoat.results.plan import ARRAY_UNITS, PlanRunResult, hermite_norm_max
from femoat.plotting.plan_history import PlanHistory
from femoat.units import G

W = 2.0 * math.pi  # one revolution per second [rad/s]


def arrays_for(packed, t):
    """Zero histories of the right shapes for ``packed`` at the times t (no friction pendulum
    force recorded)."""
    m, n, ne, nc = t.size, packed.n, len(packed.el_roles), len(packed.c_names)
    return dict(time=t, displacement=np.zeros((m, n)), velocity=np.zeros((m, n)),
                acceleration=np.zeros((m, n)), ground_acceleration=np.zeros((m, 2)),
                element_force=np.zeros((m, ne)), element_deformation=np.zeros((m, ne)),
                bearing_force=np.zeros((m, 0)), contact_force=np.zeros((m, nc)),
                indentation=np.zeros((m, nc)), indentation_rate=np.zeros((m, nc)),
                contact_closed=np.zeros((m, nc), dtype=np.int8))


def meta_for(impacts=()):
    return dict(impacts=list(impacts), stats=dict(steps=100, cpu_seconds=0.5),
                energy=dict(residual=1e-9), info=dict(method="newmark"))


def set_floor(arrays, packed, k, x, vx, y, vy):
    """Floor k (0 the base mat) moves as (x, y) with velocities (vx, vy)."""
    ix, iy = packed.layout.floor_dofs[k, :2]
    arrays["displacement"][:, ix], arrays["velocity"][:, ix] = x, vx
    arrays["displacement"][:, iy], arrays["velocity"][:, iy] = y, vy


def sample_times(per_revolution, revolutions=3, phase=0.3):
    """Samples every 1/N s, shifted by a fraction ``phase`` of a step so that no sample falls on
    a crest of cos or sin."""
    return (np.arange(revolutions * per_revolution + 1) + phase) / per_revolution


def test_plan_crest_between_samples_is_found_to_the_hermite_accuracy():
    # Ellipse u = (a·cos ωt, b·sin ωt), a = 3 > b = 1 in: |u| is largest, a, at ωt = 0, π.
    # Sampled 7 times per revolution off the crests, the samples miss it. The cubic Hermite
    # interpolant through (u, u̇) has the error e(t) = f⁗(ξ)/4!·(t − t₀)²(t − t₁)² per
    # component, at most h⁴/384·max|f⁗| (the product peaks at h⁴/16 mid-interval); |x⁗| ≤ aω⁴,
    # |y⁗| ≤ bω⁴, so |e| ≤ √(a² + b²)·(hω)⁴/384 and the interpolant's crest is within that of a.
    # With hω = 2π/7: (0.8976)⁴/384 = 1.690e-3, times √10: 5.35e-3 in.
    a, b = 3.0, 1.0
    errors = []
    for n in (7, 14, 28, 56):
        t = sample_times(n)
        u = np.c_[a * np.cos(W * t), b * np.sin(W * t)]
        v = W * np.c_[-a * np.sin(W * t), b * np.cos(W * t)]
        bound = math.hypot(a, b) * (W / n) ** 4 / 384.0
        peak = hermite_norm_max(t, u, v)
        assert abs(peak - a) <= bound
        if n == 7:
            sampled = np.hypot(*u.T).max()
            assert sampled < a - 5.0 * bound  # measured 2.96 in: 0.043 in short of the crest
            assert peak > sampled + 0.03
        errors.append(abs(peak - a))
    # the crest's error falls as h⁴ (the interpolant's order): slope of log error against
    # log h between the two finest samplings, measured 4.0
    slope = math.log(errors[-2] / errors[-1]) / math.log(2.0)
    assert 3.7 < slope < 4.3


def test_circular_orbit_peaks_in_plan_and_per_direction():
    # Base mat on the circle u = r(cos ωt, sin ωt), 7 samples per revolution. Every sample has
    # |u| = r, and the Hermite arc between two samples lies inside the circle: written as a
    # Bézier curve its control points sit h·|u̇|/3 = r·φ/3 along the tangents (φ = hω the arc's
    # angle), shorter than the r·(4/3)·tan(φ/4) of the arc that best follows the circle
    # (0.2992·r against 0.3043·r at φ = 2π/7), so the curve bends inside it and the plan peak is
    # r, reached at the samples. Per direction the crests of cos and sin fall between samples:
    # the sampled maxima are below r, the Hermite crests within r·(hω)⁴/384 = 3.4e-3 in of it.
    # The crests of ±cos and ±sin are at quarter revolutions j/4, the samples at (k + p)/7: they
    # are |4(k + p) − 7j|/28 rev apart, at least 0.5/28 rev with p = 1/8 (4p = 1/2), an angle of
    # 0.112 rad: the sampled maxima are r·cos(0.112) = r − 0.0126 in at most.
    r, n = 2.0, 7
    t = sample_times(n, phase=0.125)
    packed = PlanModel().pack()
    arrays = arrays_for(packed, t)
    c, s = np.cos(W * t), np.sin(W * t)
    set_floor(arrays, packed, 0, r * c, -r * W * s, r * s, r * W * c)
    result = PlanRunResult.from_arrays(arrays, packed, meta_for())
    p = result.peaks
    assert p["peak_plan_base_displacement"] == pytest.approx(r, rel=1e-12)
    np.testing.assert_allclose(result.plan_base_displacement, r, rtol=1e-12)
    bound = r * (W / n) ** 4 / 384.0
    for axis, k in (("x", 0), ("y", 1)):
        assert abs(p[f"peak_base_displacement_{axis}"] - r) <= bound
        assert np.abs(result.base_displacement[:, k]).max() < r - 3.0 * bound
    assert p["peak_impact_force"] == 0.0 and p["impacts_px"] == 0


def test_drifts_and_floor_accelerations_per_direction():
    # The paper building (3 floors, 39 in stories). Base at rest; floor 1 at
    # (A1·sin ωt, B1·cos ωt), floor 2 = floor 1 + (A2·sin ωt, B2·cos ωt), floor 3 = floor 2.
    # Drifts: story 1 (A1 sin, B1 cos), story 2 (A2 sin, B2 cos), story 3 zero: peaks A1, A2, 0
    # in x and B1, B2, 0 in y (Hermite crests within A·(hω)⁴/384 of the amplitudes, 8 samples
    # per revolution: 9.4e-4·A; the y crests fall on samples, exactly).
    # Accelerations (relative ü = −ω²u, recorded at the samples; a Newmark run's peaks are the
    # samples'), ground (0, c): along y the base mat's absolute acceleration is c, floor 1's
    # c − ω²B1·cos ωt, largest at cos ωt = −1 (t = 1/2 s, a sample): c + ω²B1; along x floor 2's
    # −ω²(A1 + A2)·sin ωt, largest at the samples nearest the crests: ω²(A1 + A2)·|sin| there.
    a1, a2, b1, b2, c = 0.5, 0.3, 0.2, 0.4, 50.0
    n = 8
    t = np.arange(2 * n + 1) / n
    packed = PlanModel().pack()
    arrays = arrays_for(packed, t)
    sn, cs = np.sin(W * t), np.cos(W * t)
    for k, (ax, ay) in enumerate([(0.0, 0.0), (a1, b1), (a1 + a2, b1 + b2), (a1 + a2, b1 + b2)]):
        set_floor(arrays, packed, k, ax * sn, ax * W * cs, ay * cs, -ay * W * sn)
        ix, iy = packed.layout.floor_dofs[k, :2]
        arrays["acceleration"][:, ix] = -W**2 * ax * sn
        arrays["acceleration"][:, iy] = -W**2 * ay * cs
    arrays["ground_acceleration"][:, 1] = c
    result = PlanRunResult.from_arrays(arrays, packed, meta_for())
    p = result.peaks
    np.testing.assert_allclose(result.story_drifts("x")[:, 0], a1 * sn, atol=1e-15)
    np.testing.assert_allclose(p["peak_drift_x"], [a1, a2, 0.0], atol=a1 * (W / n) ** 4 / 384)
    np.testing.assert_allclose(p["peak_drift_y"], [b1, b2, 0.0], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(p["peak_drift_ratio_y"], [b1 / 39.0, b2 / 39.0, 0.0], rtol=1e-12)
    assert p["peak_base_acceleration_y"] == pytest.approx(c / G, rel=1e-12)
    assert p["peak_floor_acceleration_y"][0] == pytest.approx((c + W**2 * b1) / G, rel=1e-12)
    assert p["peak_base_acceleration_x"] == 0.0
    assert p["peak_floor_acceleration_x"][1] == pytest.approx(
        W**2 * (a1 + a2) * np.abs(sn).max() / G, rel=1e-12)
    with pytest.raises(ValueError, match="axis = 'z'"):
        result.story_drifts("z")


def test_impacts_and_wall_peaks_per_side():
    # A moat with walls at +x and −y only. The impact table has two +x episodes (peaks 30 and
    # 80 kip) and one −y (55 kip): impacts_px = 2, impacts_my = 1, peak forces 80 and 55 kip,
    # the largest 80 kip and the largest impulse 0.4 kip·s; the absent walls' entries are None.
    # The +x wall's modal coordinate q = 0.01·sin ωt (φ = 1 for an SDOF wall): its peak
    # displacement 0.01 in at the crest t = 1/4 s, a sample.
    model = PlanModel(walls=rectangular_moat("steel", "J", sides=("-y", "+x")))
    packed = model.pack()
    assert list(packed.c_names) == ["+x", "-y"]
    t = np.arange(17) / 16.0
    arrays = arrays_for(packed, t)
    q = packed.layout.wall_dofs[0][0]
    arrays["displacement"][:, q] = 0.01 * np.sin(W * t)
    arrays["velocity"][:, q] = 0.01 * W * np.cos(W * t)
    row = dict(duration=0.01, approach_velocity=10.0, max_indentation=0.05)
    impacts = [dict(side="+x", start=0.1, peak_force=30.0, impulse=0.1, **row),
               dict(side="−y", start=0.2, peak_force=55.0, impulse=0.4, **row),
               dict(side="+x", start=0.3, peak_force=80.0, impulse=0.2, **row)]
    result = PlanRunResult.from_arrays(arrays, packed, meta_for(impacts))
    p = result.peaks
    assert (p["impacts_px"], p["impacts_my"]) == (2, 1)
    assert (p["peak_impact_force_px"], p["peak_impact_force_my"]) == (80.0, 55.0)
    assert p["peak_impact_force"] == 80.0 and p["peak_impulse"] == 0.4
    for key in ("mx", "py"):
        assert p[f"impacts_{key}"] is None and p[f"peak_impact_force_{key}"] is None
        assert p[f"peak_wall_displacement_{key}"] is None
    assert p["peak_wall_displacement_px"] == pytest.approx(0.01, rel=1e-12)
    assert p["peak_wall_displacement_my"] == 0.0
    assert result.impacts[1]["side"] == "-y"  # the typographic minus read as "-y"
    # the wall's spring and dashpot force: k·q + c·q̇ (φ = 1)
    k, cc = packed.K[q, q], packed.C[q, q]
    np.testing.assert_allclose(result.wall_force("+x"), k * arrays["displacement"][:, q]
                               + cc * arrays["velocity"][:, q], rtol=1e-12)
    with pytest.raises(ValueError, match="no wall there"):
        result.wall_displacement("+y")


def test_save_load_round_trip_and_the_figures_history(tmp_path):
    r, n = 2.0, 7
    t = sample_times(n)
    packed = PlanModel().pack()
    arrays = arrays_for(packed, t)
    set_floor(arrays, packed, 0, r * np.cos(W * t), -r * W * np.sin(W * t),
              r * np.sin(W * t), r * W * np.cos(W * t))
    arrays["contact_force"][3:5, 0] = [10.0, 5.0]
    impacts = [dict(side="+x", start=t[3], duration=t[5] - t[3], approach_velocity=4.0,
                    peak_force=10.0, max_indentation=0.1, impulse=0.5)]
    result = PlanRunResult.from_arrays(arrays, packed, meta_for(impacts))
    path = tmp_path / "sub" / "plan.npz"
    result.save(path)
    back = PlanRunResult.load(path)
    assert back.meta == result.meta
    for name in ARRAY_UNITS:
        np.testing.assert_array_equal(getattr(back, name), getattr(result, name))
    assert back.contact_closed.dtype == np.int8
    h = PlanHistory.from_result(back, "circle")
    assert isinstance(h, PlanHistory) and h.sides == ("+x", "-x", "+y", "-y")
    np.testing.assert_array_equal(h.base, result.base_displacement)
    assert list(h.impacts()) == [1, 0, 0, 0]
    assert list(h.gaps) == [4.0] * 4
    (tmp_path / "bad.npz").write_bytes(b"not a zip")
    with pytest.raises(ValueError, match="not a femoat plan result file"):
        PlanRunResult.load(tmp_path / "bad.npz")


def test_bad_input_names_the_array_or_key():
    packed = PlanModel().pack()
    t = np.linspace(0.0, 1.0, 5)
    good = arrays_for(packed, t)
    missing = {k: v for k, v in good.items() if k != "velocity"}
    with pytest.raises(ValueError, match="missing 'velocity'"):
        PlanRunResult.from_arrays(missing, packed, meta_for())
    for name, bad in (("displacement", np.zeros((5, 11))), ("contact_force", np.zeros((4, 4))),
                      ("ground_acceleration", np.zeros(5)), ("indentation", np.zeros((5, 0)))):
        with pytest.raises(ValueError, match=rf"arrays\['{name}'\] has shape"):
            PlanRunResult.from_arrays({**good, name: bad}, packed, meta_for())
    nan = good["displacement"].copy()
    nan[2, 0] = np.nan
    with pytest.raises(ValueError, match=r"arrays\['displacement'\] holds values that are not"):
        PlanRunResult.from_arrays({**good, "displacement": nan}, packed, meta_for())
    with pytest.raises(ValueError, match=r"arrays\['time'\]"):
        PlanRunResult.from_arrays({**good, "time": t[::-1]}, packed, meta_for())
    with pytest.raises(ValueError, match="meta is missing 'stats'"):
        PlanRunResult.from_arrays(good, packed, dict(impacts=[], energy={}, info={}))
    row = dict(side="+z", start=0.0, duration=0.0, approach_velocity=0.0, peak_force=1.0,
               max_indentation=0.0, impulse=0.0)
    with pytest.raises(ValueError, match="side = '\\+z'"):
        PlanRunResult.from_arrays(good, packed, meta_for([row]))
    with pytest.raises(ValueError, match=r"meta\['impacts'\]\[0\] must be a dict"):
        PlanRunResult.from_arrays(good, packed, meta_for([dict(side="+x")]))
    walled = PlanModel(walls=rectangular_moat(sides=("+x",))).pack()
    with pytest.raises(ValueError, match="side '-x' is not a wall of the model"):
        PlanRunResult.from_arrays(arrays_for(walled, t), walled,
                                  meta_for([dict(row, side="-x")]))
    # an unrecorded channel is an (m, 0) array; its accessors then say so
    result = PlanRunResult.from_arrays({**good, "acceleration": np.zeros((5, 0))}, packed,
                                       meta_for())
    assert result.peaks["peak_floor_acceleration_x"] is None
    with pytest.raises(ValueError, match="acceleration channel was not recorded"):
        result.absolute_acceleration("x")


def first_seconds(gm, seconds):
    n = int(round(seconds / gm.dt)) + 1
    return GroundMotion(gm.accel_g[:n], gm.dt, name=gm.name)


@pytest.mark.opensees
def test_the_opensees_twin_read_as_a_plan_result():
    opensees_or_skip()
    from femoat.opensees.plan import opensees_plan_run

    # The first 6 s of FEMA P695 far-field pair 1 at twice its size, steel walls (Jankowski) at
    # 3 in on all four sides: the base mat hits every wall (tests/test_opensees_plan.py).
    p = fema_p695_pair("farfield", 1)
    pair = RecordPair(first_seconds(p.x, 6.0), first_seconds(p.y, 6.0), scale=2.0)
    model = PlanModel(walls=rectangular_moat("steel", "J", gap=3.0))
    dt = 5e-4
    run = opensees_plan_run(model, pair, dt, duration=7.0)
    result = PlanRunResult.from_opensees(run, model, pair)
    twin = run["peaks"]
    # The velocities come from the displacements by Newmark's u₁ − u₀ = h(v₀ + v₁)/2; the
    # recorded accelerations are an independent channel, and the same step has
    # v₁ − v₀ = h(a₀ + a₁)/2. OpenSees updates v and a from the committed increment by these
    # formulas, so both hold to rounding: 2Δu/h carries ~eps·|u|/h = 2e-12 in/s per step, a
    # random walk over 14,000 steps; measured 3e-10 in/s against velocities up to 46 in/s.
    cols = model.pack().layout.floor_dofs[:, :2].reshape(-1)
    v, a = result.velocity[:, cols], result.acceleration[:, cols]
    dv = np.diff(v, axis=0) - 0.5 * dt * (a[:-1] + a[1:])
    assert np.abs(dv).max() <= 1e-10 * np.abs(v).max()
    # the same histories: the base mat's orbit, the drifts, the contact forces
    np.testing.assert_array_equal(result.base_displacement, run["base_displacement"])
    np.testing.assert_allclose(result.absolute_acceleration("y")[:, 1:],
                               run["acceleration"][:, 1:, 1], rtol=0, atol=1e-9)
    # impacts per wall: the twin counts closures of the indentation, the table its episodes
    for k, key in enumerate(("px", "mx", "py", "my")):
        assert result.peaks[f"impacts_{key}"] == twin["impacts"][k]
    assert min(twin["impacts"]) >= 2
    # Peaks: the samples' maxima are the twin's; ours add the crests between samples, never
    # below the samples and above them by at most the Hermite bound 4/27·h·(|v₀| + |v₁|)
    # (< 8/27·h·max|v| ≈ 1.5e-4·max|v|·s) and, for forces, the parabola through three samples.
    p = result.peaks
    vmax = np.hypot(*result.base_velocity.T).max()
    slack = 8.0 / 27.0 * dt * vmax
    assert twin["plan_base_displacement"] <= p["peak_plan_base_displacement"] \
        <= twin["plan_base_displacement"] + slack
    for k, axis in enumerate("xy"):
        assert twin["base_displacement"][k] <= p[f"peak_base_displacement_{axis}"] \
            <= twin["base_displacement"][k] + slack
        drift_v = np.abs(np.diff(result.velocity[:, result._cols(axis)], axis=1)).max(axis=0)
        assert np.all(twin["drift"][:, k] <= p[f"peak_drift_{axis}"])
        assert np.all(p[f"peak_drift_{axis}"] <= twin["drift"][:, k] + 8 / 27 * dt * drift_v)
        np.testing.assert_allclose(p[f"peak_floor_acceleration_{axis}"],
                                   twin["floor_acceleration"][:, k], rtol=1e-9)
    # (measured: 1.3e-3 above the largest sample at most)
    for k, key in enumerate(("px", "mx", "py", "my")):
        assert twin["impact_force"][k] <= p[f"peak_impact_force_{key}"] \
            <= 1.01 * twin["impact_force"][k]
    h = PlanHistory.from_result(result)
    ref = PlanHistory.from_opensees(run, model)
    np.testing.assert_array_equal(h.wall_force, ref.wall_force)
    np.testing.assert_array_equal(h.impacts(), ref.impacts())


def test_newmark_rates_of_a_constant_acceleration_are_exact():
    # Newmark's average-acceleration step is exact for a constant acceleration c: u = c·t²/2
    # gives u₁ − u₀ = c(t₁² − t₀²)/2 = h·(c·t₀ + c·t₁)/2, so the rates read back from the
    # displacements are v = c·t (and from those, a = c), however many steps (the twin's
    # velocities are read this way: test_the_opensees_twin_read_as_a_plan_result).
    from femoat.results.plan import _newmark_rate

    h, c = 0.01, np.array([3.0, -2.0])
    t = np.arange(1001) * h
    u = 0.5 * c[None, :] * t[:, None] ** 2
    v = _newmark_rate(u, np.zeros(2), h)
    np.testing.assert_allclose(v, c[None, :] * t[:, None], rtol=0, atol=1e-10)
    # The second rate differences the first again: rounding of ~eps·max|u|/h² = 3e-10 per step
    # (max|u| = 150 in), amplified by the alternating recursion over 1,000 steps (measured
    # 1.8e-6 in/s²): the tolerance 1e-5 is 3e-6 of c
    np.testing.assert_allclose(_newmark_rate(v, c, h), np.tile(c, (t.size, 1)), atol=1e-5)

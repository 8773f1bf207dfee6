"""The building solver on nonlinear problems: friction against an independent ODE solve, one
free mass into a wall against the precise single-impact solver, failures, HHT-α."""


import numpy as np
import pytest
from scipy.integrate import solve_ivp

from femoat.contact import make_law
from femoat.ground_motions import GroundMotion, erzincan_paper
from femoat.impact import simulate_impact
from femoat.integration import Integrator, SolverError
from femoat.run import run
from femoat.structure.building import Building
from femoat.structure.materials import Elastic, FrictionPendulum
from femoat.structure.pounding import MoatWall, PoundingModel
from femoat.units import G
from femoat.walls import wall_preset


def _first_seconds(gm, seconds):
    n = int(round(seconds / gm.dt)) + 1
    return GroundMotion(gm.accel_g[:n], gm.dt, name=gm.name)


def test_friction_isolated_building_against_solve_ivp():
    # FP isolator (constant μ, EPP friction spring) under elastic stories, no walls, Erzincan at
    # half the paper's scale for 4 s. Reference: the same equations with the EPP spring written
    # as a Bouc-Wen rate law ż = (v/u_y)·(1 − |z|^N) while loading (N = 25, a smoothed EPP),
    # integrated by scipy's LSODA with tight tolerances.
    iso = FrictionPendulum(W=33.0, R=30.0, u_y=0.01, mu=0.06)
    b = Building(isolator=iso, stories=(Elastic(42.799),) * 3)
    gm = _first_seconds(erzincan_paper(), 4.0).scaled(0.5)
    res = run(PoundingModel(b), gm, Integrator(rtol=1e-6), duration=4.0)

    m = np.array([b.base_weight, *b.floor_weights]) / G
    beta = b.story_damping_beta
    k, c = 42.799, beta * 42.799
    n_exp = 25

    def rhs(t, y):
        u, v, z = y[:4], y[4:8], y[8]
        ag = np.interp(t, gm.time, gm.accel)
        drift, drift_v = np.diff(u), np.diff(v)
        fs = k * drift + c * drift_v
        f = np.zeros(4)
        f[0] = iso.W / iso.R * u[0] + iso.mu * iso.W * z - fs[0]
        f[1:] += fs
        f[1:3] -= fs[1:]
        zdot = v[0] / iso.u_y * (1 - (abs(z) ** n_exp if z * v[0] > 0 else 0.0))
        return np.concatenate([v, (-f - m * ag) / m, [zdot]])

    sol = solve_ivp(rhs, (0, 4.0), np.zeros(9), method="LSODA", rtol=1e-8, atol=1e-10,
                    t_eval=res.time, max_step=gm.dt)
    ref = sol.y[0]
    peak = np.max(np.abs(ref))
    assert peak > 1.0  # the isolator slides well past its 0.01 in elastic range
    # Smoothing the EPP corner over ~u_y changes the slip history by a fraction of u_y per
    # reversal: the histories agree to about 1 % of the peak.
    assert np.max(np.abs(res.base_displacement - ref)) < 0.01 * peak
    # friction dissipates, the balance closes
    assert res.energy["friction"] > 0
    assert res.energy["residual"] < 1e-8


@pytest.mark.parametrize("law", list("EVJHM"))
@pytest.mark.parametrize("wall", ["concrete", "steel"])
def test_free_mass_into_wall_matches_single_impact(law, wall):
    # A building reduced to one free mass m_eff (no isolator, no stories, still ground) moving
    # at v0 toward one wall must reproduce the precise single-impact solver (DOP853 at 1e-11).
    preset = wall_preset(wall)
    contact = make_law(law, preset.contact)
    v0, gap = 10.0, 0.01
    b = Building(base_weight=preset.contact.m_eff * G, floor_weights=(), stories=(),
                 isolator=None)
    model = PoundingModel(b, (MoatWall(contact, preset.wall, gap, 1),))
    ref = simulate_impact(contact, v0, wall=preset.wall)
    duration = gap / v0 + 1.5 * ref.contact_duration
    still = GroundMotion(np.zeros(3), duration, name="still")
    res = run(model, still, Integrator(rtol=1e-9, contact_steps=400), duration=duration,
              v0=[v0, 0.0])
    imp = res.impacts[0]
    assert imp["approach_velocity"] == pytest.approx(v0, rel=1e-9)
    assert imp["peak_force"] == pytest.approx(ref.peak_force, rel=1e-4)
    assert imp["max_indentation"] == pytest.approx(ref.max_indentation, rel=1e-4)
    # rebound speed of the mass after the episode (free flight: constant)
    assert -res.velocity[-1, 0] / v0 == pytest.approx(ref.restitution, rel=1e-4, abs=1e-5)
    if law in "EJM":  # separation at δ = 0 is an event: the duration is located exactly
        assert imp["duration"] == pytest.approx(ref.contact_duration, rel=1e-4)


def test_unconvergeable_run_raises_with_time_and_advice():
    preset = wall_preset("steel")
    contact = make_law("H", preset.contact)
    b = Building(base_weight=preset.contact.m_eff * G, floor_weights=(), stories=(),
                 isolator=None)
    model = PoundingModel(b, (MoatWall(contact, preset.wall, 0.01, 1),))
    still = GroundMotion(np.zeros(3), 0.01, name="still")
    # two Newton iterations and a 1 ms smallest step cannot resolve a ~2 ms Hertz contact
    with pytest.raises(SolverError, match=r"could not converge at t = .* s \(pos wall in contact"):
        run(model, still, Integrator(max_newton=2, min_step=1e-3), duration=0.02, v0=[10.0, 0.0])


def test_hht_dissipates_high_frequencies_only():
    # HHT-α (α = −0.1) on an undamped linear chain: the energy decays (numerical damping), but
    # the slow isolation mode keeps its amplitude within a few tenths of a percent.
    b = Building(isolator=Elastic(2.0), stories=(Elastic(42.799),) * 3, story_damping_ratio=0.0)
    still = GroundMotion(np.zeros(3), 2.0, name="still")
    v_init = [1.0, 1.0, 1.0, 1.0]  # mostly the first mode
    newmark = run(PoundingModel(b), still, Integrator(method="newmark", rtol=0.099,
                                                      max_step=0.01), duration=4.0, v0=v_init)
    hht = run(PoundingModel(b), still, Integrator(method="newmark", alpha=-0.1, rtol=0.099,
                                                  max_step=0.01),
              duration=4.0, v0=v_init)
    assert newmark.energy["residual"] < 1e-10
    assert hht.energy["residual"] > 1e-6  # HHT's numerical dissipation shows in the balance
    assert np.max(np.abs(hht.base_displacement)) == pytest.approx(
        np.max(np.abs(newmark.base_displacement)), rel=5e-3)


def test_bad_inputs():
    preset = wall_preset("concrete")
    with pytest.raises(ValueError, match="alpha"):
        Integrator(alpha=0.2)
    with pytest.raises(ValueError, match=r"method = 'rk4'.*'newmark', 'dp5'"):
        Integrator(method="rk4")
    from femoat.scenario import solver_from_dict

    with pytest.raises(ValueError, match=r"\[solver\] method = 'rk4'"):
        solver_from_dict({"method": "rk4"})
    # a method given alone takes its own default rtol; numbers are still checked
    assert solver_from_dict({"method": "newmark"}) == Integrator(method="newmark")
    with pytest.raises(ValueError, match="rtol"):
        solver_from_dict({"method": "newmark", "rtol": "tight"})
    with pytest.raises(ValueError, match="gap"):
        MoatWall(make_law("E", preset.contact), preset.wall, gap=-1.0)
    with pytest.raises(ValueError, match="base_weight"):
        Building(base_weight=-1.0)
    with pytest.raises(ValueError, match="stories"):
        Building(floor_weights=(8.0,), stories=())
    with pytest.raises(ValueError, match="u0 puts the pos wall in contact"):
        model = PoundingModel(Building(), (MoatWall(make_law("E", preset.contact), preset.wall),))
        run(model, GroundMotion(np.zeros(3), 0.01), duration=0.01,
            u0=[5.0, 5.0, 5.0, 5.0, 0.0])


def test_lazy_wall_elimination_is_exact():
    # While no contact carries force the walls are uncoupled oscillators; eliminating them
    # separately must give the same run to round-off.
    from femoat.integration.solve import solve
    from femoat.paper import paper_model, paper_motion

    gm = paper_motion(quick=True)
    packed = paper_model("steel", "H").pack()
    lazy = solve(packed, gm.accel, gm.dt, 3.0, Integrator(), lazy=True)
    full = solve(packed, gm.accel, gm.dt, 3.0, Integrator(), lazy=False)
    lazy, full = lazy.arrays, full.arrays
    assert lazy["time"].size == full["time"].size
    np.testing.assert_allclose(lazy["displacement"], full["displacement"], rtol=0, atol=1e-10)
    np.testing.assert_allclose(lazy["contact_force"], full["contact_force"], rtol=1e-8,
                               atol=1e-8)


def test_deteriorating_stories_run_and_dissipate_more():
    # IMK stories with capping at 0.5 in of plastic drift and cyclic deterioration (Λ = 20 in)
    # lose strength: under the paper's motion they dissipate hysteretic energy and drift at least
    # as much as the non-deteriorating bilinear stories; the energy balance still closes.
    from femoat.paper import paper_model, paper_motion
    from femoat.structure.materials import IMKBilinear

    imk = IMKBilinear(theta_p=0.5, theta_pc=2.0, res=0.3, Lambda=20.0)
    b = Building(stories=(imk,) * 3)
    gm = paper_motion(quick=True)
    r_imk = run(paper_model("concrete", "H", building=b), gm)
    r_bil = run(paper_model("concrete", "H"), gm)
    assert r_imk.energy["residual"] < 1e-8
    assert r_imk.energy["hysteretic"] > 0
    assert max(r_imk.peaks["peak_drift"]) >= 0.99 * max(r_bil.peaks["peak_drift"])


def test_requested_channels_and_decimation_do_not_change_the_answer():
    # Recording fewer channels or every 10th open-phase step only changes what is stored; contact
    # steps are always kept, so the impact table and the peaks are identical.
    from femoat.paper import paper_model, paper_motion

    gm = paper_motion(quick=True)
    model = paper_model("concrete", "M")
    full = run(model, gm)
    lean = run(model, gm, Integrator(record_every=10), channels=("displacement", "contacts"))
    assert lean.time.size < full.time.size / 2
    assert lean.velocity.shape[1] == 0 and lean.acceleration.shape[1] == 0
    assert lean.impacts == full.impacts
    assert lean.peaks["peak_impact_force"] == full.peaks["peak_impact_force"]
    assert lean.peaks["peak_floor_acceleration"] is None
    with pytest.raises(ValueError, match="velocity channel was not recorded"):
        lean.story_shears()
    with pytest.raises(ValueError, match="channels"):
        run(model, gm, channels=("pressure",))


def test_closure_on_a_chunk_boundary_does_not_stall():
    # A 10 kip base mat at 0.05 in/s closes a 0.01 in gap at exactly t = 0.2 s, which is also a
    # boundary of the solver's progress chunks (1 s / 20 · 4); snapping the step onto that
    # boundary once undid the event shortening and repeated the step until the stall guard.
    preset = wall_preset("concrete")
    model = PoundingModel(Building(base_weight=10.0, floor_weights=(), stories=(),
                                   isolator=None),
                          (MoatWall(make_law("H", preset.contact), preset.wall, 0.01, 1),))
    res = run(model, GroundMotion(np.zeros(2), 1.0), duration=1.0, v0=[0.05, 0.0])
    assert res.impacts[0]["start"] == pytest.approx(0.2, abs=1e-12)
    assert res.energy["residual"] < 1e-10

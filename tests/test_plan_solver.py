"""femoat's own solver on plan models (femoat.plan): two ground components, the coupled friction
pendulum as a 2-DOF element, four walls, wall friction; against the 1D solver, symmetry, closed
forms and the OpenSees twin in 3D."""

import numpy as np
import pytest
from conftest import ahead, opensees_or_skip

from femoat.ground_motions import GroundMotion, RecordPair, fema_p695_pair
from femoat.integration import Integrator
from femoat.plan import PlanBuilding, PlanModel, rectangular_moat
from femoat.run import run
from femoat.structure.materials import Elastic
from femoat.units import G


def first_seconds(gm, seconds, factor=1.0):
    n = int(round(seconds / gm.dt)) + 1
    return GroundMotion(factor * gm.accel_g[:n], gm.dt, name=gm.name)


def zero_like(gm):
    return GroundMotion(np.zeros(gm.npts), gm.dt, name="zero")


def ff1(seconds, factor):
    """The first seconds of FEMA P695 far-field pair 1 (Northridge, Beverly Hills), scaled."""
    p = fema_p695_pair("farfield", 1)
    return first_seconds(p.x, seconds, factor), first_seconds(p.y, seconds, factor)


@pytest.mark.parametrize("method,isolator", [("newmark", "bearing"), ("dp5", "elastic"),
                                             ("tsit5", "elastic"), ("ark5", "bearing"),
                                             ("ark5", "tfp")])
def test_with_no_y_excitation_it_is_the_1d_run_bit_for_bit(method, isolator):
    # The plan model under (a_x, 0) is the 1D model along x (model.along("x")): nothing loads
    # y (the bearing's z stays on the x axis: its radial return is the 1D bearing's clamp),
    # the ±y walls stay open and unloaded, and the x equations are the 1D ones with the same
    # sums in the same order (the bearing enters before the stories, as the 1D isolator, the
    # first element). So the x history is the 1D history to the bit (the issue asks 1e-12),
    # the y DOFs stay exactly zero, and the step sequences are the same.
    # ark5, a plan run's default: a sliding bearing's friction rate (v − (z·v)·z)/u_y is
    # exactly 0 with z = (±1, 0) and v = (v_x, 0), so every step is the dp5 step with z held
    # (methods/ark5.py): the plan run is the 1D *default* run (dp5) to the bit.
    # The triple friction pendulum on ark5: its carried z_i = (±1, 0) have the rate
    # (ḋ_i − (z_i·ḋ_i)·z_i)/u_y,i = 0 with ḋ_i along x, and a carried z equal to the radial
    # return's is the free element's arithmetic (triple_friction_pendulum._element): the same
    # series solves as the 1D bearing's.
    x, _ = ff1(8.0, 3.0)
    if isolator == "tfp":
        from femoat.bearings.triple_friction_pendulum import TripleFrictionPendulum

        b = PlanBuilding(isolator=TripleFrictionPendulum())
    else:
        b = PlanBuilding() if isolator == "bearing" else PlanBuilding(isolator=Elastic(k=2.0))
    plan = PlanModel(b, rectangular_moat("concrete", "H", gap=2.0))
    integ = Integrator(method=method)
    p = run(plan, RecordPair(x, zero_like(x)), integ, duration=8.5)
    one = run(plan.along("x"), x, Integrator() if method == "ark5" else integ, duration=8.5)
    assert p.peaks["steps"] == one.peaks["steps"] and p.time.size == one.time.size
    assert p.peaks["impacts_px"] + p.peaks["impacts_mx"] >= 2  # it pounds
    lay = p.meta["floor_dofs"]
    xcols, ycols = [d[0] for d in lay], [d[1] for d in lay]
    np.testing.assert_array_equal(p.time, one.time)
    np.testing.assert_array_equal(p.displacement[:, xcols], one.displacement[:, :len(xcols)])
    assert np.all(p.displacement[:, ycols] == 0.0)
    # contacts: the plan's +x, -x walls are the 1D pos, neg walls
    np.testing.assert_array_equal(p.contact_force[:, :2], one.contact_force)
    assert np.all(p.contact_force[:, 2:] == 0.0)
    assert p.peaks["impacts_py"] == p.peaks["impacts_my"] == 0
    # One result over both layouts (femoat.results.base.Result): the accessors along x read
    # the same columns of bit-equal histories with the same arithmetic, so they are equal to
    # the bit; a 1D result takes axis "x" or none, a plan result needs one.
    for name in ("floor_displacement", "story_drifts", "absolute_acceleration"):
        np.testing.assert_array_equal(getattr(p, name)("x"), getattr(one, name)("x"))
        np.testing.assert_array_equal(getattr(one, name)(), getattr(one, name)("x"))
    for plan_side, side in (("+x", "pos"), ("-x", "neg")):
        np.testing.assert_array_equal(p.wall_displacement(plan_side), one.wall_displacement(side))
        np.testing.assert_array_equal(p.wall_force(plan_side), one.wall_force(side))
    np.testing.assert_array_equal(one.wall_force(1), one.wall_force("+x"))  # ±1 name sides
    with pytest.raises(ValueError, match="side = '\\+y': a 1D run's walls are 'pos'"):
        one.wall_force("+y")
    with pytest.raises(ValueError, match="axis = 'y': use 'x'"):
        one.story_drifts("y")
    with pytest.raises(ValueError, match="axis = None: use 'x' or 'y'"):
        p.story_drifts()


@pytest.fixture(scope="module")
def pair_and_model():
    x, y = ff1(6.0, 3.0)
    return RecordPair(x, y), PlanModel(walls=rectangular_moat("concrete", "H", gap=2.0))


def test_a_pair_turned_by_90_degrees_gives_the_mirrored_response(pair_and_model):
    # Turning the pair by +90° (counterclockwise) maps the ground motion (a_x, a_y) to
    # (−a_y, a_x); the model is square-symmetric (the same stories, bearing and wall on every
    # side), so the response turns with it: u_x' = −u_y, u_y' = u_x, and the wall hit at
    # +x is then hit at +y (+y → −x, −x → −y, −y → +x). Rounding differs (x and y are
    # different rows of one system), the adaptive steps then differ (13,369 against 13,057)
    # and the two runs differ by their discretisation: within the default accuracy, 1e-4 of
    # the response (measured 3e-5).
    pair, model = pair_and_model
    a = run(model, pair, duration=6.5)
    b = run(model, pair.rotated(90.0), duration=6.5)
    scale = a.peaks["peak_plan_base_displacement"]
    assert b.peaks["peak_plan_base_displacement"] == pytest.approx(scale, rel=1e-4)
    ua, ub = a.base_displacement, b.base_displacement
    t = np.linspace(0.0, 6.5, 1301)
    for got, want in ((ub[:, 0], -ua[:, 1]), (ub[:, 1], ua[:, 0])):
        assert np.abs(np.interp(t, b.time, got) - np.interp(t, a.time, want)).max() \
            <= 1e-4 * scale
    turned = {"px": "py", "py": "mx", "mx": "my", "my": "px"}
    for side, to in turned.items():
        assert b.peaks[f"impacts_{to}"] == a.peaks[f"impacts_{side}"] >= 1
        assert b.peaks[f"peak_impact_force_{to}"] == pytest.approx(
            a.peaks[f"peak_impact_force_{side}"], rel=1e-3)


@pytest.mark.slow
def test_a_quarter_turn_of_the_pair_turns_the_converged_response_to_1e_9(pair_and_model):
    # The same symmetry as above on ark5 at rtol 1e-9 (the coupled-friction step, issue 26:
    # "a quarter turn of the pair turns the response (1e-9)"): every peak of the turned run is
    # the original's on the turned wall or axis within 1e-9 (measured: equal, the two runs
    # taking the same 126,535 steps). Slow tier (5 s); the default tier keeps the test above.
    pair, model = pair_and_model
    integ = Integrator(method="ark5", rtol=1e-9)
    a = run(model, pair, integ, duration=6.5, history=False).peaks
    b = run(model, pair.rotated(90.0), integ, duration=6.5, history=False).peaks
    assert a["steps"] > 100_000
    assert b["peak_plan_base_displacement"] == pytest.approx(a["peak_plan_base_displacement"],
                                                             rel=1e-9)
    assert b["peak_drift_y"] == pytest.approx(a["peak_drift_x"], rel=1e-9)
    assert b["peak_drift_x"] == pytest.approx(a["peak_drift_y"], rel=1e-9)
    turned = {"px": "py", "py": "mx", "mx": "my", "my": "px"}
    for side, to in turned.items():
        assert b[f"impacts_{to}"] == a[f"impacts_{side}"] >= 1
        assert b[f"peak_impact_force_{to}"] == pytest.approx(a[f"peak_impact_force_{side}"],
                                                             rel=1e-9)


def test_diagonal_excitation_in_a_square_moat_hits_two_walls_at_once():
    # The same record on x and y: the ground moves along the diagonal x = y and the square
    # model is symmetric about it, so u_x = u_y throughout (to rounding) and the base mat
    # reaches the corner: the +x and +y walls (and −x, −y) are hit at the same instants with
    # the same forces.
    x, _ = ff1(6.0, 2.5)
    model = PlanModel(walls=rectangular_moat("concrete", "H", gap=2.0))
    r = run(model, RecordPair(x, x), duration=6.5)
    u = r.base_displacement
    assert np.abs(u[:, 0] - u[:, 1]).max() <= 1e-9 * np.abs(u).max()
    hits = {side: [i for i in r.impacts if i["side"] == side]
            for side in ("+x", "+y", "-x", "-y")}
    assert len(hits["+x"]) == len(hits["+y"]) >= 1 and len(hits["-x"]) == len(hits["-y"])
    for a, b in [("+x", "+y"), ("-x", "-y")]:
        for ia, ib in zip(hits[a], hits[b]):
            assert ia["start"] == pytest.approx(ib["start"], abs=1e-9)
            assert ia["peak_force"] == pytest.approx(ib["peak_force"], rel=1e-8)
    # the corner: both walls carry force on the same samples (a force that has fallen to
    # round-off at an episode's end may be 0 on one wall and 1e-13 kip on the other)
    f = r.contact_force
    tiny = 1e-9 * f.max()
    np.testing.assert_array_equal(f[:, 0] > tiny, f[:, 2] > tiny)
    assert np.any((f[:, 0] > 0) & (f[:, 2] > 0))


def test_wall_friction_stops_a_base_mat_sliding_along_the_wall():
    # A free base mat (no isolator, no floors) of mass m is pressed against the +x wall by a
    # constant ground acceleration a_x = −A (inertial load +m·A towards the wall) while it
    # slides along the wall (+y) at v0. Momentum along x: m·v_x(t) = m·A·t − ∫f_n dt; along y,
    # while the slip is fast (tanh(v/ε) = 1 to 1e-8 beyond 2 in/s): m·v_y(t) = m·v0 − μ∫f_n dt.
    # So v_y(t) = v0 − μ·(A·t − v_x(t)) exactly, whatever the impacts and the wall do: the
    # friction takes μ·(the normal impulse). Without friction v_y stays v0.
    A, v0, mu, gap = 0.5 * G, 60.0, 0.3, 1.0
    walls = rectangular_moat("concrete", "V", gap=gap, friction=mu, sides=("+x",))
    b = PlanBuilding(base_weight=33.0, floor_weights=(), stories_x=(), stories_y=(),
                     isolator=None)
    model = PlanModel(b, walls)
    n = 301
    pair = RecordPair(GroundMotion(np.full(n, -A / G), 0.01), GroundMotion(np.zeros(n), 0.01))
    u0 = np.zeros(model.layout().n)
    u0[0] = gap - 0.05  # 0.05 in from the wall
    v_init = np.zeros_like(u0)
    v_init[1] = v0
    r = run(model, pair, Integrator(method="newmark"), duration=2.0, u0=u0, v0=v_init)
    vx, vy, t = r.velocity[:, 0], r.velocity[:, 1], r.time
    fast = vy > 2.0
    assert fast.sum() > 100 and r.peaks["impacts_px"] >= 1
    np.testing.assert_allclose(vy[fast], v0 - mu * (A * t[fast] - vx[fast]), rtol=0,
                               atol=2e-6 * v0)
    # it stops near t* = v0/(μ·A) (= 1.036 s; the approach and the bounces add their time)
    stop = t[np.argmax(vy < 0.5)]
    assert v0 / (mu * A) < stop < v0 / (mu * A) + 0.1
    # the friction's work is in the balance (counted with the contacts')
    assert r.energy["residual"] < 1e-5


@pytest.mark.parametrize("method", ["dp5", "tsit5"])
def test_the_explicit_pairs_are_refused_on_a_plan_friction_pendulum(pair_and_model, method):
    # both explicit pairs read the friction direction from a path between stage values
    pair, model = pair_and_model
    with pytest.raises(ValueError, match=f"method = '{method}' on plan bearings.*'newmark'"):
        run(model, pair, Integrator(method=method), duration=1.0)


def _second_pair():
    """FEMA P695 far-field pair 6 (Imperial Valley, El Centro Array #11: another earthquake),
    its first 8 s x 3, turned by 30°, in a steel moat with the Hertz (E) law and 2 in gaps: a
    second record pair, wall and law; it hits all four walls (1, 1, 2, 2 impacts)."""
    p = fema_p695_pair("farfield", 6)
    x, y = first_seconds(p.x, 8.0, 3.0), first_seconds(p.y, 8.0, 3.0)
    return RecordPair(x, y, angle=30.0), PlanModel(walls=rectangular_moat("steel", "E", gap=2.0))


def _twin_case(which):
    """(pair, model, duration) of the OpenSees twin test on pair ``which``."""
    if which == "ff6":
        # the -y wall's second impact is a graze (8.7 kip against 59 kip on +y), the least
        # accurate peak of a Newmark plan run at its default (8.685 kip against OpenSees
        # extrapolated 8.741); the default step (ark5) holds it within 1e-3 as every other peak
        return (*_second_pair(), 8.5)
    # ff1: the pair_and_model fixture's, 6.5 s: 13 impacts (2, 4, 4, 3 on +x, -x, +y, -y);
    # ff1-5.3s: its first 5.3 s, 10 impacts (2, 3, 3, 2), every wall hit (measured: femoat's
    # default within 1e-4 of the extrapolated twin on every peak, as on the 6.5 s)
    x, y = ff1(6.0, 3.0)
    duration = {"ff1": 6.5, "ff1-5.3s": 5.3}[which]
    return (RecordPair(x, y), PlanModel(walls=rectangular_moat("concrete", "H", gap=2.0)),
            duration)


TWIN_STEPS = {"ff1-5.3s": (2e-4, 1e-4), "ff1": (1e-4, 5e-5), "ff6": (1e-4, 5e-5)}
"""The OpenSees twin's two fixed steps [s] per case: the first 5.3 s of pair 1 extrapolated from
2e-4 and 1e-4 s is within 3.7e-4 of the extrapolation from 1e-4 and 5e-5 s on every peak
(measured; impacts the same), inside the test's 1e-3 at half the OpenSees time; the whole pairs
need the finer pair (the second pair's graze)."""


def opensees_3d_twin(which):
    """The OpenSees twin's peaks (at the two steps of :data:`TWIN_STEPS`) on pair ``which``:
    OpenSees alone, so a parallel session computes it ahead (conftest.py, AHEAD)."""
    from femoat.opensees.plan import opensees_plan_run

    pair, model, duration = _twin_case(which)
    return tuple(opensees_plan_run(model, pair, dt, duration=duration)["peaks"]
                 for dt in TWIN_STEPS[which])


@pytest.mark.opensees
@pytest.mark.parametrize("which", ["ff1-5.3s", pytest.param("ff1", marks=pytest.mark.slow),
                                   pytest.param("ff6", marks=pytest.mark.slow)])
def test_against_the_opensees_twin_in_3d(which):
    opensees_or_skip()
    # The OpenSees twin (flatSliderBearing + W/R springs, four Masroor chains) at two fixed
    # steps (TWIN_STEPS), extrapolated to zero step (its error is first order in the step: the
    # slider's radial return is a backward-Euler step of the friction rule); femoat at its
    # default (method ark5, rtol 1e-5) on both pairs. Every peak the issue names (the plan base displacement, each wall's
    # peak impact force, the drifts of both directions) within 1e-3, the impact counts equal.
    # The slow tier runs both pairs whole at 1e-4 and 5e-5 s (19 and 20 s of OpenSees; the
    # second pair's graze needs these steps); the default tier the first 5.3 s of the first at
    # 2e-4 and 1e-4 s (the same assertions on 10 impacts on the four walls), and femoat's
    # default on a graze in plan against its exact solution (tests/test_grazing_impact.py:
    # peak force within 1e-3).
    pair, model, duration = _twin_case(which)
    ours = run(model, pair, duration=duration).peaks
    coarse, fine = ahead(opensees_3d_twin, which)
    assert all(ours[f"impacts_{s}"] > 0 for s in ("px", "mx", "py", "my"))  # every wall hit

    def extrapolated(key):
        return 2.0 * np.asarray(fine[key], dtype=float) - np.asarray(coarse[key], dtype=float)

    assert ours["peak_plan_base_displacement"] == pytest.approx(
        float(extrapolated("plan_base_displacement")), rel=1e-3)
    sides = ("px", "mx", "py", "my")
    assert [ours[f"impacts_{s}"] for s in sides] == [int(n) for n in fine["impacts"]]
    forces = extrapolated("impact_force")
    for s, f in zip(sides, forces):
        assert ours[f"peak_impact_force_{s}"] == pytest.approx(f, rel=1e-3), s
    drift = extrapolated("drift")
    for a, axis in enumerate("xy"):
        np.testing.assert_allclose(ours[f"peak_drift_{axis}"], drift[:, a], rtol=1e-3)

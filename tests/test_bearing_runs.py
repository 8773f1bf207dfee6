"""Every bearing kind through the whole loop: read from a scenario's ``[building.isolator] type``,
run in 1D and in plan (the plan run along one axis is the 1D run), its capacity a collapse
criterion, and against its OpenSees twins (1D and 3D) within 1e-3 on every peak.

The kernels' own closed forms and static twins are in each kind's test file
(``tests/test_bearing_lrb.py``, ...); here the kinds meet the building, the moat and the solver.
"""

import math
from dataclasses import replace

import numpy as np
import pytest

from conftest import ahead, opensees_or_skip
from femoat.bearings import registry
from femoat.bearings.lead_rubber import LeadRubberBearing
from femoat.bearings.triple_friction_pendulum import TripleFrictionPendulum
from femoat.collapse import CollapseCriteria, isolator_capacity
from femoat.ground_motions import GroundMotion, RecordPair
from femoat.integration import Integrator
from femoat.paper import paper_model, paper_motion
from femoat.plan import PlanBuilding, PlanModel, PlanWall
from femoat.run import run
from femoat.scenario.document import model_from_dict

BEARINGS = {"lrb": LeadRubberBearing(), "tfp": TripleFrictionPendulum()}
"""One bearing of each kind beyond the single friction pendulum (whose runs the paper's tests
hold), at its defaults: the paper building's isolation (each kind's docstring)."""

NEWMARK = Integrator(method="newmark")


def _first(motion, seconds):
    return GroundMotion(motion.accel_g[:int(round(seconds / motion.dt)) + 1], motion.dt,
                        name=motion.name)


def _model_on(bearing, law="E"):
    """The paper building in the paper's concrete moat on ``bearing``."""
    fp = paper_model("concrete", law)
    return replace(fp, building=replace(fp.building, isolator=bearing))


def _along_x(model):
    """The plan model whose restriction to x is the 1D ``model`` (its walls on ±x)."""
    walls = tuple(PlanWall(w.law, w.wall, w.gap, w.side)
                  for w in model.walls)
    plan_model = PlanModel(building=PlanBuilding.from_building(model.building), walls=walls)
    assert plan_model.along("x") == model
    return plan_model


def _peaks_1d(p):
    return np.array([p["peak_impact_force"], p["peak_base_displacement"],
                     p["peak_wall_displacement"], *p["peak_drift"]])


@pytest.mark.parametrize("key", sorted(BEARINGS))
def test_a_scenario_names_the_bearing_by_its_type(key):
    bearing = BEARINGS[key]
    mod = registry.by_key(key)
    assert type(bearing) is mod.AXIS_CLASS
    table = {"building": {"isolator": {"type": key}}}
    one_d = model_from_dict(table)
    assert one_d.building.isolator == bearing  # the kind's defaults, no weight to carry
    plan = model_from_dict({"building": {"plan": True, "isolator": {"type": key}}})
    assert plan.building.isolator == mod.PLAN_CLASS()
    with pytest.raises(ValueError, match=r"type = 'tfx'.*use .*'fp'"):
        model_from_dict({"building": {"isolator": {"type": "tfx"}}})


@pytest.mark.parametrize("key", sorted(BEARINGS))
def test_along_one_axis_the_plan_run_is_the_1d_run(key):
    # The plan model restricted to x is the 1D model (the same pack), and the plan kernels on
    # one axis are the 1D kernels (each kind's tests, bit for bit): the plan run under a pair
    # whose y component is zero, both on Newmark, is the 1D run. They part only where the two
    # loops land a kink or turning point differently (the plan one along the bearing's
    # turning direction, the 1D one on the material's tangent), by far less than rtol (1e-5):
    # 1e-6 on every peak, through the impacts.
    model = _model_on(BEARINGS[key])
    m = _first(paper_motion(), 10.0)
    one = run(model, m, integrator=NEWMARK)
    assert one.peaks["peak_impact_force"] > 10.0  # it pounds
    plan_model = _along_x(model)
    plan = run(plan_model, RecordPair(m, GroundMotion(0.0 * m.accel_g, m.dt, name="zero")),
               integrator=NEWMARK)
    p = plan.peaks
    assert p["peak_plan_base_displacement"] == pytest.approx(
        one.peaks["peak_base_displacement"], rel=1e-6)
    assert max(p["peak_impact_force_px"], p["peak_impact_force_mx"]) == pytest.approx(
        one.peaks["peak_impact_force"], rel=1e-6)
    assert p["peak_drift_x"] == pytest.approx(one.peaks["peak_drift"], rel=1e-6)
    assert max(p["peak_drift_y"]) == 0.0


def test_a_bearing_capacity_is_a_collapse_criterion():
    # the smaller of the building's isolator_capacity and the bearing's own (a lead-rubber
    # bearing's given limit): with 3 in the paper run (peak base displacement ≈ 4.6 in on this
    # bearing) collapses at the isolator, with the default (none) it does not
    m = _first(paper_motion(), 10.0)
    free = _model_on(LeadRubberBearing())
    capped = _model_on(LeadRubberBearing(capacity=3.0))
    assert isolator_capacity(free.building) == free.building.isolator_capacity == 7.0
    assert isolator_capacity(capped.building) == 3.0
    criteria = CollapseCriteria(drift_ratio=None, isolator=True)
    a = run(free, m, history=False, collapse=criteria)
    b = run(capped, m, history=False, collapse=criteria)
    assert a.peaks["peak_base_displacement"] > 3.0
    assert not a.collapse["collapsed"]
    assert b.collapse["collapsed"] and b.collapse["isolator"] is not None
    assert math.isinf(LeadRubberBearing().capacity)


# ---- against the OpenSees twins ---------------------------------------------------------------
# Each twin is OpenSees alone, a function of the bearing's key: a parallel session computes it
# ahead (conftest.py, AHEAD).


def opensees_1d_twin(key):
    """The peaks of the 1D test's twin: the lead-rubber twin is 1D; OpenSees'
    TripleFrictionPendulum is a 3D element only, so the triple pendulum's 1D twin is its 3D
    twin driven along x, y at rest (the plan model along x is this model: asserted), walls on
    ±x."""
    from femoat.opensees.building import opensees_run
    from femoat.opensees.plan import opensees_plan_run

    model = _model_on(BEARINGS[key])
    m = _first(paper_motion(), 10.0)
    if hasattr(registry.by_key(key), "opensees_axis_material"):
        return opensees_run(model, m, 2e-4)["peaks"]
    zero = GroundMotion(0.0 * m.accel_g, m.dt, name="zero")
    return opensees_plan_run(_along_x(model), RecordPair(m, zero), 2e-4, tol=1e-8)["peaks"]


def _plan_case(key):
    """(pair, model) of the plan test: the Erzincan record along x and its reversed copy at 0.6
    along y, turned by 30°, first 8 s; the paper building in plan on the bearing."""
    m = _first(paper_motion(), 8.0)
    pair = RecordPair(m, GroundMotion(-0.6 * m.accel_g[::-1], m.dt, name="y"), angle=30.0)
    return pair, PlanModel(building=PlanBuilding(isolator=registry.by_key(key).PLAN_CLASS()))


def opensees_plan_twin(key):
    """The peaks of the plan test's 3D twin at 2e-4 s."""
    from femoat.opensees.plan import opensees_plan_run

    pair, model = _plan_case(key)
    return opensees_plan_run(model, pair, 2e-4, tol=1e-8)["peaks"]


@pytest.mark.opensees
@pytest.mark.parametrize("key", sorted(BEARINGS))
def test_a_1d_run_matches_its_opensees_twin(key):
    # The paper building on the bearing in the concrete moat (law E, whose OpenSees twin is
    # exact), Erzincan N-S (first 10 s): femoat at its default against the twin at 2e-4 s
    # within 1e-3 on every peak. The lead-rubber twin is 1D (uniaxialMaterial BoucWen: its
    # backward-Euler step converges at first order, 1.5e-4 at this step on the worst peak of
    # the whole record, 3e-5 at 1e-4 s: measured); OpenSees' TripleFrictionPendulum is a 3D
    # element only, so the triple pendulum's 1D twin is its 3D twin driven along x, y at rest
    # (the plan model along x is this model: asserted), walls on ±x.
    opensees_or_skip()
    model = _model_on(BEARINGS[key])
    m = _first(paper_motion(), 10.0)
    ours = run(model, m)
    assert ours.peaks["impacts_pos"] + ours.peaks["impacts_neg"] > 0
    twin = ahead(opensees_1d_twin, key)
    if hasattr(registry.by_key(key), "opensees_axis_material"):
        assert (twin["impacts_pos"], twin["impacts_neg"]) == (ours.peaks["impacts_pos"],
                                                              ours.peaks["impacts_neg"])
        np.testing.assert_allclose(_peaks_1d(ours.peaks), _peaks_1d(twin), rtol=1e-3)
        return
    assert list(twin["impacts"]) == [ours.peaks["impacts_pos"], ours.peaks["impacts_neg"]]
    np.testing.assert_allclose(
        [ours.peaks["peak_base_displacement"], ours.peaks["peak_impact_force_pos"],
         ours.peaks["peak_impact_force_neg"], *ours.peaks["peak_drift"]],
        [twin["plan_base_displacement"], *twin["impact_force"],
         *np.asarray(twin["drift"])[:, 0]], rtol=1e-3)


@pytest.mark.opensees
@pytest.mark.parametrize("key", sorted(BEARINGS))
def test_the_3d_twin_reports_a_sliders_normal_force(key):
    # The triple pendulum is a slider: its twin takes N = W from a static gravity step (the
    # vertical material linear, so one load step is exact) and reports it, as the single
    # pendulum's does (test_opensees_plan); the lead-rubber bearing carries no normal force
    # in its twin (None).
    from femoat.opensees.plan import opensees_plan_run

    opensees_or_skip()
    pair, model = _plan_case(key)
    short = RecordPair(_first(pair.x, 0.05), _first(pair.y, 0.05), angle=30.0)
    normal = opensees_plan_run(model, short, 2e-4, tol=1e-8)["bearing_normal_force"]
    if key == "tfp":
        assert normal == pytest.approx(model.building.isolator.W, rel=1e-9)
    else:
        assert normal is None


@pytest.mark.opensees
@pytest.mark.parametrize("key", sorted(BEARINGS))
def test_a_plan_run_matches_its_opensees_twin(key):
    # The paper building in plan on the bearing in the square concrete moat (law H), the
    # Erzincan record along x and its reversed copy at 0.6 along y, turned by 30°, first 8 s:
    # femoat at its default against the 3D twin at 2e-4 s (4.5e-4 on the worst peak on the
    # whole record, 2e-4 at 1e-4 s: measured) within 1e-3 on every peak, the same impacts on
    # every wall.
    opensees_or_skip()
    pair, model = _plan_case(key)
    # (the triple pendulum's plan trial follows the step's path in 4 pieces, each a return:
    # 3.8e-4 off converged femoat at the default on this pair, 1.2e-3 with one chord return)
    ours = run(model, pair)
    twin = ahead(opensees_plan_twin, key)
    sides = [w.side for w in model.walls]
    tags = {"+x": "px", "-x": "mx", "+y": "py", "-y": "my"}
    assert list(twin["impacts"]) == [ours.peaks[f"impacts_{tags[s]}"] for s in sides]
    assert sum(twin["impacts"]) > 0
    ours_v = [ours.peaks["peak_plan_base_displacement"],
              *[ours.peaks[f"peak_impact_force_{tags[s]}"] for s in sides],
              *ours.peaks["peak_drift_x"], *ours.peaks["peak_drift_y"]]
    d = np.asarray(twin["drift"])
    twin_v = [twin["plan_base_displacement"], *twin["impact_force"],
              *d[:, 0], *d[:, 1]]
    np.testing.assert_allclose(ours_v, twin_v, rtol=1e-3)

"""The lead-rubber bearing and the triple friction pendulum against their OpenSees twins on two
FEMA P695 far-field pairs (issue 28: "a femoat run against its OpenSees twin within 1e-3 on every
peak, 1D and plan, laws E and H, a near-field pulse pair and two far-field pairs with impacts").

The near-field record is Erzincan (``tests/test_bearing_runs.py``); here the two far-field pairs,
the same models and the same peaks as there:

* **1D, law E**: the paper building on the bearing in the paper's concrete moat, under the pair's
  applied x component. The lead-rubber twin is 1D (``opensees_run``: uniaxialMaterial BoucWen);
  the triple pendulum's is its 3D twin driven along x, y at rest (``opensees_plan_run`` on the
  plan model whose restriction to x is the 1D model), walls on ±x.
* **plan, law H**: the paper building in plan on the bearing in the square concrete moat (the
  PlanModel's default walls), under the pair (a along x, b along y, angle 0).

femoat runs at its default (1D: dp5; plan: ark5, both bearings' rate forms) and must match the twin within rtol 1e-3 on every peak, with the same impacts on every
wall. Every number quoted here was measured (on the commit this file was written on): "twin h1
vs h2" is the twin's own change between two steps, "extrapolated" its first-order Richardson
extrapolation to zero step from 1e-4 and 5e-5 s (the Bouc-Wen twins converge at first order:
observed orders 0.6-1.4 on the lead-rubber drifts and displacements from 2e-4, 1e-4 and 5e-5 s;
the impact forces and the triple pendulum's peaks, which move by 2e-5 to 5e-4 between steps, in
no clean order), "converged femoat" femoat at Newmark rtol 1e-8 (ark5 rtol 1e-9 for the
lead-rubber bearing: the same to 1e-5).

**The records.** FEMA P695 far-field 9 (Kocaeli 1999, Duzce: DZC180 along x, DZC270 along y) and
2 (Northridge 1994, Canyon Country-WLC: LOS000 along x, LOS270 along y), normalized (NF) and
scaled by the bidirectional study's anchor SF (:func:`femoat.studies.bidirectional.full_anchor`:
the set at the MCE, S_MT at T = 3.5 s), time-scaled by 0.5 as in that study, cut to their first
5 s (the run then goes on 2 s at rest: every impact of these runs falls in 2.6-4.9 s). Both pairs
make each bearing's model pound in 1D and in plan, 2 to 5 impacts of 7 to 96 kip per run.

**Why these two.** The twin's Hertzdamp (plan, law H) does not cut tension (femoat's does:
``femoat.contact.hertzdamp``, a documented difference), which a low-velocity recontact reaches
when the building rebounds faster than its δ̇₀/ξ_h. Far-field 21 (cut at 5 s) on the lead-rubber
bearing pulls -1.2 kip on the -y wall at 3.17 s (a 0.43 in/s recontact), and converged
femoat and the converged twin part by 2.5e-2 on that wall's next impact; far-field 6 (cut at
6.5 s) on the triple pendulum pulls -0.34 kip on the +x wall at 5.65 s, and they part by 1.1e-3
(each of these two twins also stalls at 2e-4 s). On far-fields 9 and 2 no twin contact force is ever
below 0 (asserted; the smallest in contact is +1.7e-6 to +1.2e-3 kip at 1e-4 s). Far-field 1 on
the lead-rubber bearing in plan needs a finer twin: 9.1e-3 off its extrapolation at 2e-4 s,
4.3e-3 at 1e-4 s, converged femoat within 1.2e-4 of it.

**The steps.** The 1D twins run at 2e-4 s: there they are within 4.9e-4 (lead-rubber) and 7.7e-5
(triple pendulum) of their extrapolation. The plan twins at 2e-4 s are up to 7.4e-4 off theirs
(far-field 9, lead-rubber, the -x wall's force), which would leave femoat little of the 1e-3, so
they run at 1e-4 s (within 1.6e-4 of their extrapolation).

**Once a miss, on femoat's side**: the triple pendulum in plan under far-field 2 was 1.14e-3 off
the twin at 1e-4 s on the +y wall's peak force at femoat's default (ark5; Newmark's default
before it 1.33e-3), while converged femoat was within 7.3e-5 of the twin extrapolated to zero
step. The cause was femoat's: steps on which the outer element slid while the inner one stuck
went to the path form, first order in the step (benchmarks/README.md, issue 28, stops 39-40).
Carrying any sliding element, the default is 1.26e-4 off the twin (measured): an ordinary case
of the plan test now.
"""


import numpy as np
import pytest

from conftest import opensees_or_skip
from test_bearing_runs import _along_x, _model_on
from femoat.bearings import registry
from femoat.bearings.lead_rubber import LeadRubberBearing
from femoat.bearings.triple_friction_pendulum import TripleFrictionPendulum
from femoat.ground_motions import GroundMotion, RecordPair, fema_p695_pair
from femoat.plan import PlanBuilding, PlanModel
from femoat.run import run

BEARINGS = {"lrb": LeadRubberBearing(), "tfp": TripleFrictionPendulum()}
"""One bearing of each kind at its defaults (the paper building's isolation), as
``tests/test_bearing_runs.py``."""

ANCHOR = 4.234967569834693
"""[-] :func:`femoat.studies.bidirectional.full_anchor` (the FEMA P695 anchoring factor SF of the
bidirectional study: the median Sa(3.5 s) of the 44 normalized far-field components brought to
S_MT), pinned here because computing it takes 3-6 s (:func:`test_the_scale_is_the_study_anchor`
holds the pin)."""

CUT = 5.0  # [s] of the time-scaled pair: every impact of the eight runs falls in 2.6-4.9 s
TWIN_DT = {"1d": 2e-4, "plan": 1e-4}  # [s] the twins' steps (module docstring)
SIDE_TAGS = {"+x": "px", "-x": "mx", "+y": "py", "-y": "my"}
SLOW = pytest.mark.slow


def _first(motion, seconds):
    return GroundMotion(motion.accel_g[:int(round(seconds / motion.dt)) + 1], motion.dt,
                        name=motion.name)


def _pair(record_id):
    """Far-field pair ``record_id``: normalized, scaled by the study's anchor, time-scaled by 0.5
    and cut to its first :data:`CUT` seconds (a along x, b along y)."""
    pair = fema_p695_pair("farfield", record_id, scale=ANCHOR, normalized=True)
    x, y = (_first(m.time_scaled(0.5), CUT) for m in (pair.x, pair.y))
    return RecordPair(x, y, angle=pair.angle, scale=pair.scale, name=pair.name)


def _plan_model(key):
    """The paper building in plan on the bearing in the square concrete moat (law H)."""
    return PlanModel(building=PlanBuilding(isolator=registry.by_key(key).PLAN_CLASS()))


def _plan_peaks(model, peaks):
    """femoat's plan peaks in the twin's order: plan |u|, each wall's force, drifts x, y."""
    sides = [w.side for w in model.walls]
    return [peaks["peak_plan_base_displacement"],
            *[peaks[f"peak_impact_force_{SIDE_TAGS[s]}"] for s in sides],
            *peaks["peak_drift_x"], *peaks["peak_drift_y"]]


def _twin_plan_peaks(twin):
    d = np.asarray(twin["drift"])
    return [twin["plan_base_displacement"], *twin["impact_force"], *d[:, 0], *d[:, 1]]


def _impacts(model, peaks):
    return [peaks[f"impacts_{SIDE_TAGS[w.side]}"] for w in model.walls]


@SLOW
def test_the_scale_is_the_study_anchor():
    from femoat.studies.bidirectional import full_anchor

    assert full_anchor() == pytest.approx(ANCHOR, rel=1e-9)


# ---- 1D, law E ------------------------------------------------------------------------------
# femoat at its default (dp5) against the twin at 2e-4 s, worst peak [-] (twin 2e-4 vs 1e-4 s;
# femoat's default, converged femoat against the extrapolated twin), impacts (pos, neg):
#   lrb, 9: 4.5e-4 (2.8e-4; 1.1e-4, 1.8e-5), (1, 2); the worst the impact force
#   tfp, 9: 1.4e-4 (6.6e-5; 1.4e-4, 1.1e-5), (1, 1)
#   lrb, 2: 1.6e-4 (9.0e-5; 3.4e-5, 1.1e-5), (2, 2)
#   tfp, 2: 1.7e-5 (1.5e-5; 7.2e-5, 3.1e-5), (1, 1)
# Runtimes (pytest --durations, the numba cache warm, the machine idle): 0.5-2.2 s each (the
# first test of a process loads the kernels); far-field 9 is the default tier's case of each
# bearing, far-field 2 is marked slow only to keep one quick case per bearing.
@pytest.mark.opensees
@pytest.mark.parametrize("key, record_id", [
    ("lrb", 9), ("tfp", 9),
    pytest.param("lrb", 2, marks=SLOW), pytest.param("tfp", 2, marks=SLOW)])
def test_a_far_field_1d_run_matches_its_opensees_twin(key, record_id):
    opensees_or_skip()
    from femoat.opensees.building import opensees_run
    from femoat.opensees.plan import opensees_plan_run

    model = _model_on(BEARINGS[key])
    m = _pair(record_id).motion_x
    ours = run(model, m)
    p = ours.peaks
    assert p["impacts_pos"] + p["impacts_neg"] > 0  # it pounds
    dt = TWIN_DT["1d"]
    if hasattr(registry.by_key(key), "opensees_axis_material"):  # the lead-rubber bearing
        twin = opensees_run(model, m, dt)["peaks"]
        assert (twin["impacts_pos"], twin["impacts_neg"]) == (p["impacts_pos"], p["impacts_neg"])
        ours_v = [p["peak_impact_force"], p["peak_base_displacement"],
                  p["peak_wall_displacement"], *p["peak_drift"]]
        twin_v = [twin["peak_impact_force"], twin["peak_base_displacement"],
                  twin["peak_wall_displacement"], *twin["peak_drift"]]
        np.testing.assert_allclose(ours_v, twin_v, rtol=1e-3)
        return
    zero = GroundMotion(0.0 * m.accel_g, m.dt, name="zero")
    twin = opensees_plan_run(_along_x(model), RecordPair(m, zero), dt, tol=1e-8)["peaks"]
    assert list(twin["impacts"]) == [p["impacts_pos"], p["impacts_neg"]]
    np.testing.assert_allclose(
        [p["peak_base_displacement"], p["peak_impact_force_pos"], p["peak_impact_force_neg"],
         *p["peak_drift"]],
        [twin["plan_base_displacement"], *twin["impact_force"],
         *np.asarray(twin["drift"])[:, 0]], rtol=1e-3)


# ---- plan, law H ----------------------------------------------------------------------------
# femoat at its default (ark5) against the 3D twin at 1e-4 s, worst peak
# [-] (twin 2e-4 vs 1e-4 s; twin at 1e-4 s, femoat's default, converged femoat against the
# extrapolated twin), impacts (+x, -x, +y, -y):
#   lrb, 9: 1.2e-4 (6.4e-4; 1.5e-4, 9.2e-5, 8.3e-5), (1, 1, 2, 1)
#   tfp, 9: 2.2e-4 (2.6e-4; 1.6e-4, 2.6e-4, 7.9e-5), (1, 1, 2, 1); since stop 40 the default
#           1.33e-4 off the twin at 1e-4 s
#   lrb, 2: 1.4e-4 (2.6e-4; 1.3e-4, 1.1e-4, 6.1e-5), (1, 2, 1, 0)
#   tfp, 2: the default 1.26e-4 off the twin at 1e-4 s (1.14e-3 before stop 40), converged femoat
#           (Newmark rtol 1e-8) 6.9e-5, (1, 1, 1, 2)
# Runtimes: 4.7-5.1 s each (the twin at 1e-4 s nearly all of it; 7-10 s when the machine is
# shared); marked slow to keep one quick case per bearing in the default tier (the 1D ones).
@pytest.mark.opensees
@SLOW
@pytest.mark.parametrize("key, record_id", [("lrb", 9), ("tfp", 9), ("lrb", 2), ("tfp", 2)])
def test_a_far_field_plan_run_matches_its_opensees_twin(key, record_id):
    opensees_or_skip()
    from femoat.opensees.plan import opensees_plan_run

    pair = _pair(record_id)
    model = _plan_model(key)
    ours = run(model, pair)
    twin = opensees_plan_run(model, pair, TWIN_DT["plan"], tol=1e-8)
    assert twin["contact_force"].min() >= 0.0  # the twin's Hertzdamp never pulls (docstring)
    twin = twin["peaks"]
    assert list(twin["impacts"]) == _impacts(model, ours.peaks)
    assert sum(twin["impacts"]) > 0
    np.testing.assert_allclose(_plan_peaks(model, ours.peaks), _twin_plan_peaks(twin), rtol=1e-3)

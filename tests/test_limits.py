"""Limit states as data (femoat.integration.limits), element roles, the runaway bounds every run
has, and the record budget.

The criteria defined in this file are the proof that a criterion on a quantity the solver knows
is Python only: nothing in femoat names them.
"""

import math
from dataclasses import dataclass

import numpy as np
import pytest

from femoat.collapse import CRITERIA, CollapseCriteria
from femoat.ground_motions import GroundMotion
from femoat.integration import Integrator, Limit, RecordBudgetError, SolverError
from femoat.integration.limits import pack_limits
from femoat.integration.solve import error_scales
from femoat.paper import paper_model, paper_motion
from femoat.run import run
from femoat.structure.building import Building
from femoat.structure.materials import Bilinear, Elastic, FrictionPendulum, IMKBilinear
from femoat.structure.pounding import PoundingModel
from femoat.structure.roles import ISOLATOR, STORY, Role, role_of
from femoat.units import G

# ---- criteria defined here, on quantities the kernel already has ------------------------------

@dataclass(frozen=True)
class FloorAcceleration:
    """A floor's absolute acceleration above ``bound`` [in/s²] (floor 1 is DOF 1)."""

    bound: float
    floor: int = 3
    name = "floor_acceleration"

    def limits(self, model, packed):
        return [Limit("absolute_acceleration", self.floor, self.bound, criterion=self.name)]


@dataclass(frozen=True)
class BaseVelocity:
    """The base mat's speed relative to the ground above ``bound`` [in/s]."""

    bound: float
    name = "base_velocity"

    def limits(self, model, packed):
        return [Limit("velocity", 0, self.bound, criterion=self.name)]


def _floor3_acceleration(r):
    return np.abs(r.absolute_acceleration()[:, 3])


def _base_speed(r):
    return np.abs(r.velocity[:, 0])


@pytest.fixture(scope="module")
def plain():
    """The paper's concrete wall with law E under the quick motion, no criteria."""
    model, motion = paper_model("concrete", "E"), paper_motion(quick=True)
    return model, motion, run(model, motion)


@pytest.mark.parametrize("make, history", [(FloorAcceleration, _floor3_acceleration),
                                           (BaseVelocity, _base_speed)],
                         ids=["floor_acceleration", "base_velocity"])
def test_a_new_criterion_stops_the_run_at_the_first_sample_beyond_its_bound(plain, make, history):
    model, motion, free = plain
    x = history(free)
    # a bound the run crosses part-way: 60 % of the run's largest recorded value
    bound = 0.6 * float(x.max())
    # the kernel checks every accepted step, and every step is a sample (record_every = 1);
    # sample 0 is the initial state, which no step ends at
    k = 1 + int(np.argmax(x[1:] > bound))
    assert 0.0 < free.time[k] < free.time[-1]
    crit = CollapseCriteria(drift_ratio=None, isolator=False, extra=(make(bound),))
    stopped = run(model, motion, collapse=crit)
    name = make.name
    assert stopped.collapse == {**{c: None for c in CRITERIA}, name: free.time[k],
                                "collapsed": True, "stopped": True}
    # the same steps as the free run up to that sample, and not one more
    assert stopped.time.size == k + 1
    assert np.array_equal(stopped.time, free.time[: k + 1])
    assert np.array_equal(stopped.displacement, free.displacement[: k + 1])
    assert history(stopped)[-1] > bound >= history(stopped)[1:-1].max()
    # without the stop, the run is the free run bit for bit, with the time recorded
    kept = run(model, motion, collapse=CollapseCriteria(drift_ratio=None, isolator=False,
                                                        stop=False, extra=(make(bound),)))
    assert kept.collapse[name] == free.time[k] and not kept.collapse["stopped"]
    assert np.array_equal(kept.displacement, free.displacement)
    assert free.runaway is None and kept.runaway is None


def test_limit_rows_and_extra_criteria_are_validated():
    with pytest.raises(ValueError, match="quantity = 'speed'.*absolute_acceleration"):
        Limit("speed", 0, 1.0)
    with pytest.raises(ValueError, match="bound = -1.0"):
        Limit("velocity", 0, -1.0)
    with pytest.raises(ValueError, match="bound = inf"):
        Limit("velocity", 0, math.inf)
    with pytest.raises(ValueError, match="index = -1"):
        Limit("contact_force", -1, 1.0)
    packed = paper_model("concrete", "E").pack()  # 4 building DOFs, 2 walls, 4 elements
    with pytest.raises(ValueError, match="index 4, but the model has 4 building dofs"):
        pack_limits([Limit("absolute_acceleration", 4, 1.0)], packed)  # a wall DOF
    with pytest.raises(ValueError, match="index 2, but the model has 2 contacts"):
        pack_limits([Limit("contact_force", 2, 1.0)], packed)
    with pytest.raises(ValueError, match="not a criterion"):
        CollapseCriteria(extra=(object(),))
    with pytest.raises(ValueError, match="'drift' is already there"):
        CollapseCriteria(extra=(_Named("drift"),))
    for key in ("collapsed", "stopped"):  # the summary's own keys would overwrite its time
        with pytest.raises(ValueError, match=f"'{key}' is already there"):
            CollapseCriteria(extra=(_Named(key),))


def test_an_infinite_bound_switches_a_criterion_off(plain):
    # inf (as a scenario file may write it) means no criterion, as None does: the run is the
    # unbounded one, bit for bit, and the summary has no time for it (it was a run-time error
    # once limits became rows, which refuse an infinite bound)
    model, motion, free = plain
    off = CollapseCriteria(drift_ratio=math.inf, wall_displacement=math.inf,
                           wall_force=math.inf, isolator=False)
    assert off.criteria() == ()
    r = run(model, motion, collapse=off)
    assert np.array_equal(r.time, free.time) and np.array_equal(r.displacement, free.displacement)
    assert not r.collapse["collapsed"] and r.collapse["drift"] is None


@dataclass(frozen=True)
class _Named:
    name: str

    def limits(self, model, packed):
        return []


# ---- roles and the materials' own answers ------------------------------------------------------

def test_pack_emits_a_role_per_element_and_names_come_from_roles():
    packed = paper_model("concrete", "E").pack()
    assert packed.el_roles == (Role(ISOLATOR), Role(STORY, 1), Role(STORY, 2), Role(STORY, 3))
    assert packed.el_names == ["isolator", "story1", "story2", "story3"]
    assert [role_of(name) for name in packed.el_names] == list(packed.el_roles)
    with pytest.raises(ValueError, match="story = 0"):
        Role(STORY)
    with pytest.raises(ValueError, match="neither"):
        role_of("brace1")


def test_materials_answer_their_yield_deformation_and_the_error_scales_use_it():
    # u_y = Fy/k0 = 11.556/42.799 = 0.270 in (bilinear), My/K0 (IMK), the friction spring's
    # u_y (pendulum); an elastic spring never yields
    assert Bilinear().yield_deformation == 11.556 / 42.799
    assert IMKBilinear(1.0, 3.0, K0=40.0, My=10.0).yield_deformation == 10.0 / 40.0
    assert FrictionPendulum(u_y=0.02).yield_deformation == 0.02
    assert Elastic(k=1.0).yield_deformation is None
    # a story's error is scaled by min(gap, u_y): 0.270 in against the 4 in gap; an elastic
    # story by the gap
    packed = paper_model("concrete", "E").pack()
    scale_open, _, err_ref, _ = error_scales(packed, G)
    assert list(scale_open[1:4]) == [11.556 / 42.799] * 3 and list(err_ref[1:4]) == [0, 1, 2]
    elastic = PoundingModel(Building(stories=(Elastic(k=40.0),) * 3), ()).pack()
    assert list(error_scales(elastic, G)[0][1:4]) == [1.0] * 3  # no walls: a gap scale of 1 in


# ---- runaway: every run ends at the bounds, with its status and time named ---------------------

K_ISO, W_FLOOR, H_STORY = 1e5, 100.0, 20.0  # [kip/in], [kip], [in]


def test_a_buckling_story_without_criteria_ends_at_the_runaway_bound_at_the_closed_form_time():
    # A story of k = 2.5 kip/in under P/h = 100/20 = 5 kip/in (P-Delta) has the stiffness
    # −2.5 kip/in: from rest at a drift of 1e-3 in the floor moves as d(t) = d0·cosh(λt),
    # λ = √(2.5/m), m = 100/386.09 kip·s²/in (the base is held by K_ISO, 4e4 times stiffer).
    # It drifts by its height, 20 in, at t* = acosh(20/1e-3)/λ = 3.41 s: the runaway bound of
    # every run (femoat.collapse.RUNAWAY_DRIFT = 1 story height), criteria or not.
    b = Building(base_weight=1.0, floor_weights=(W_FLOOR,), isolator=Elastic(k=K_ISO),
                 stories=(Elastic(k=2.5),), story_damping_ratio=0.0, story_heights=(H_STORY,),
                 p_delta=True)
    lam = math.sqrt((W_FLOOR / H_STORY - 2.5) / (W_FLOOR / G))
    t_star = math.acosh(H_STORY / 1e-3) / lam
    quiet = GroundMotion(np.zeros(1001), 0.01, name="quiet")
    r = run(PoundingModel(b, ()), quiet, Integrator(rtol=1e-7, max_step=1e-3), duration=10.0,
            u0=np.array([0.0, 1e-3]))
    assert r.collapse is None
    assert r.runaway["element"] == "story1" and r.runaway["bound"] == H_STORY
    # the first step end beyond the bound: within one step (1e-3 s) of t*
    assert r.runaway["time"] == r.time[-1] == r.meta["stats"]["t_reached"]
    assert r.runaway["time"] == pytest.approx(t_star, abs=1e-3)
    # and the peaks are those of a story one height over, not of a run that went on
    drift = r.story_drifts()[:, 0]
    assert drift[-1] > H_STORY >= drift[-2]
    assert 1.0 < r.peaks["peak_drift_ratio"][0] < 1.001


def test_an_isolator_past_ten_times_its_capacity_ends_the_run():
    # a bare base mat on a spring of zero stiffness, sent off at 90 in/s: u = 90·t exactly (no
    # force). 10 × the 7 in capacity = 70 in is passed at t = 0.778 s, so the run ends at the
    # first step end after it: the record's sample at 0.78 s (steps never cross a sample)
    b = Building(floor_weights=(), stories=(), isolator=Elastic(k=0.0), isolator_capacity=7.0)
    quiet = GroundMotion(np.zeros(301), 0.01, name="quiet")
    r = run(PoundingModel(b, ()), quiet, duration=3.0, v0=np.array([90.0]))
    assert r.runaway == {"time": pytest.approx(0.78, abs=1e-12), "element": "isolator",
                         "bound": 70.0, "reason": "10 x the isolator capacity"}
    assert r.displacement[-1, 0] == pytest.approx(70.2, rel=1e-12)
    # with the isolator criterion too, the criterion's time is recorded and the run still
    # ends at the runaway bound (7 in at t = 0.0778 s: the sample at 0.08 s)
    kept = run(PoundingModel(b, ()), quiet, duration=3.0, v0=np.array([90.0]),
               collapse=CollapseCriteria(drift_ratio=None, stop=False))
    assert kept.collapse["isolator"] == pytest.approx(0.08, abs=1e-12)
    assert kept.collapse["stopped"] and kept.runaway["time"] == r.runaway["time"]


def test_the_record_budget_ends_a_long_run_with_a_named_error():
    # the paper model records 274 bytes a sample (t, a_g, u, v, a of 6 DOFs, 4 elements' force
    # and deformation, 2 contacts' force, indentation, rate [8 bytes each] and flags [1 byte]):
    # 1e6 bytes hold 3649 samples, and a quiet record steps once per 0.01 s sample
    model = paper_model("concrete", "E")
    quiet = GroundMotion(np.zeros(10001), 0.01, name="quiet")
    small = Integrator(record_budget=1e6)
    ok = run(model, quiet, small, duration=30.0)  # 3000 samples fit
    assert ok.time[-1] == pytest.approx(30.0, abs=1e-12) and ok.time.size == 3001
    with pytest.raises(RecordBudgetError, match=r"record_budget=1e\+06\) bytes \(3649 samples\) "
                                                r"at t = 36\.49"):
        run(model, quiet, small, duration=100.0)
    assert issubclass(RecordBudgetError, SolverError)  # a suite counts it as a solver failure
    with pytest.raises(ValueError, match="record_budget = 1000"):
        Integrator(record_budget=1000)


def test_femoat_run_prints_the_runaway(tmp_path, capsys):
    # the headline suite's building (IMK stories, P-Delta) under FEMA P695 far-field 5a at
    # 1.2 g, no [collapse] table: the run ends where story 1 has drifted by its height, 39 in
    # (t = 20.78 s, tests/test_stress.py), and the command says so; the time to 1e-4 s: converged
    # 20.77543 (dp5, rtol 1e-8) and 20.77547 s (Newmark, rtol 1e-8), the default 20.775445 s
    import json

    from femoat.cli import main

    scen = tmp_path / "s.toml"
    scen.write_text(
        '[building]\nstory_model = "imk"\np_delta = true\n'
        '[building.story]\ntheta_p = 1.0\ntheta_pc = 3.0\nres = 0.4\n'
        '[motion]\nsource = "fema"\nrecord_id = 5\ncomponent = "a"\npga = 1.2\n'
        f'[output]\nfolder = "{(tmp_path / "out").as_posix()}"\nfigures = false\n')
    assert main(["run", str(scen)]) == 0
    line = next(x for x in capsys.readouterr().out.splitlines() if x.startswith("runaway "))
    assert line.split(maxsplit=1)[1] == ("ended at t = 20.7754 s: story1 deformed beyond 39 in "
                                         "(a drift of 1 x the story height)")
    assert main(["run", str(scen), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["runaway"]["element"] == "story1" and "collapse" not in out
    assert out["runaway"]["time"] == pytest.approx(20.77545, abs=5e-5)
    assert out["units"]["runaway"] == "time in s, bound in in"


def test_femoat_run_reports_an_outgrown_record_budget_in_a_sentence(tmp_path, capsys):
    # the paper run records ~6000 samples; a budget of 1e6 bytes holds 3649 of them (274 bytes
    # each, test_the_record_budget_ends_a_long_run_with_a_named_error)
    from femoat.cli import main

    scen = tmp_path / "s.toml"
    scen.write_text('[motion]\nsource = "erzincan"\n[solver]\nrecord_budget = 1e6\n'
                    f'[output]\nfolder = "{(tmp_path / "out").as_posix()}"\nfigures = false\n')
    assert main(["run", str(scen)]) == 1
    err = capsys.readouterr().err
    assert err.startswith("femoat run: error: The recorded histories reached "
                          "Integrator(record_budget=1e+06) bytes (3649 samples)")
    assert "Traceback" not in err and not (tmp_path / "out" / "run.npz").exists()

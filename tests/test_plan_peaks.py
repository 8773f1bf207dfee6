"""A plan run without history (``run(plan_model, pair, ..., history=False)``, what a suite does):
its peaks come from the compiled loop's running peaks (femoat.integration.recording.peaks) and
equal those read from the full history (femoat.results.plan), with the same steps, impact table,
energy balance, collapse and runaway; its history accessors say why they have nothing; save and
load keep it; running peaks that do not fit the model are refused."""

import numpy as np
import pytest

from femoat.collapse import CollapseCriteria
from femoat.ground_motions import GroundMotion, RecordPair, fema_p695_pair
from femoat.integration import Integrator
from femoat.plan import PlanBuilding, PlanModel, rectangular_moat
from femoat.results.plan import ARRAY_UNITS, PlanRunResult
from femoat.plotting.plan_history import PlanHistory
from femoat.run import run
from femoat.structure.materials import Elastic
from femoat.units import G

SAME = 1e-12
"""Relative agreement of a peak that the loop and the history pass read from the same
interpolant by the same algorithm (the Hermite crests of the displacements, drifts and walls,
the quintic crest of a dp5 run's accelerations, the samples): only the order of a few roundings
may differ (tests/test_kernel_peaks.py holds the 1D peaks to the same bound)."""

PLAN_CREST = 1e-12
"""Relative agreement of the base mat's plan crest max |(u_x(θ), u_y(θ))|, found by two
algorithms on the same pair of cubic Hermite interpolants: ``hermite_norm_max`` takes the roots
of the degree-5 polynomial Σ u·u′ (numpy.roots), the loop refines the best of 16 points of the
interval by Newton on the same stationarity. At a crest d|u|/dθ = 0, so an error δθ in where it
is changes the value only by ½·|d²|u|/dθ²|·δθ²: with d²|u|/dθ² of the order of |u| (θ spans
one step) and δθ at most ~1e-8 (a simple root to √eps, the worst of either method), that is
~1e-16·|u|. What is left is the rounding of evaluating the cubics (power basis against Hermite
basis), a few ulp of max(|u₀|, |u₁|) + h·(|v₀| + |v₁|) ≈ |u|: ~1e-15 relative. 1e-12 leaves a
factor 1000 (measured: the same bits on the Newmark run, 2.1e-16 on the dp5 run)."""


def _pair(seconds=6.0, factor=3.0):
    """The first seconds of FEMA P695 far-field pair 1 (Northridge, Beverly Hills), both
    components scaled: in a 2 in moat it pounds all four walls (as tests/test_plan_solver.py)."""
    p = fema_p695_pair("farfield", 1)
    n = int(round(seconds / p.x.dt)) + 1
    return RecordPair(*(GroundMotion(factor * gm.accel_g[:n], gm.dt, name=gm.name)
                        for gm in (p.x, p.y)))


def _model(isolator="bearing", capacity=None):
    kw = {} if isolator == "bearing" else dict(isolator=Elastic(k=2.0))
    if capacity is not None:
        kw["isolator_capacity"] = capacity
    return PlanModel(PlanBuilding(**kw), rectangular_moat("concrete", "H", gap=2.0))


def _assert_same_peaks(bare, full):
    assert bare.peaks.keys() == full.peaks.keys()
    for key, want in full.peaks.items():
        got = bare.peaks[key]
        if key == "cpu_seconds":  # a measurement, never twice the same
            continue
        if key == "peak_plan_base_displacement":
            assert got == pytest.approx(want, rel=PLAN_CREST, abs=0), key
        elif isinstance(want, list):
            np.testing.assert_allclose(got, want, rtol=SAME, atol=0, err_msg=key)
        elif isinstance(want, float):
            assert got == pytest.approx(want, rel=SAME, abs=0), key
        else:  # impact counts, steps; None where there is no such quantity
            assert got == want, key


@pytest.fixture(scope="module")
def bearing_runs():
    """(no history, full history) of the paper building on its friction pendulum (Newmark,
    the plan default)."""
    model, pair = _model(), _pair()
    return run(model, pair, duration=6.5, history=False), run(model, pair, duration=6.5)


@pytest.mark.parametrize("method", ["newmark", "dp5"])
def test_a_plan_run_without_history_has_the_peaks_of_the_full_run(method, bearing_runs):
    # The step sequence does not depend on what is recorded (the ring of the last samples
    # holds what the running peaks and the episodes read), so the two runs take the same steps
    # and every peak is the crest of the same interpolants. dp5 runs on an Elastic isolator
    # (refused on the plan friction pendulum): its accelerations' quintic crests are compared.
    if method == "newmark":
        bare, full = bearing_runs
    else:
        model, pair, integ = _model("elastic"), _pair(), Integrator(method="dp5")
        bare = run(model, pair, integ, duration=6.5, history=False)
        full = run(model, pair, integ, duration=6.5)
    # the comparison means something: every wall is hit, and the plan crest lies between
    # samples (above every sampled |u|, by 1.9e-7 in measured), not at one
    assert all(full.peaks[f"impacts_{k}"] >= 1 for k in ("px", "mx", "py", "my"))
    assert full.peaks["peak_plan_base_displacement"] > full.plan_base_displacement.max()
    _assert_same_peaks(bare, full)
    assert bare.impacts == full.impacts
    assert bare.energy == full.energy
    for key in ("steps", "rejected_error", "rejected_newton", "newton_iterations", "events",
                "t_reached"):
        assert bare.meta["stats"][key] == full.meta["stats"][key], key
    assert bare.meta["stats"]["t_reached"] == full.time[-1] == 6.5
    assert bare.meta["stats"]["recorded"] == 0
    assert bare.time.shape == (0,)
    assert bare.displacement.shape == (0, full.displacement.shape[1])
    assert bare.collapse is None and bare.runaway is None and full.runaway is None


@pytest.mark.parametrize("stop", [True, False])
def test_collapse_and_runaway_of_a_run_without_history_are_the_full_runs(stop):
    # Criteria: a story drift ratio of 0.02 (story 1 reaches 0.099), a wall force of 100 kip
    # (146 kip reached) and the isolator's capacity of 0.4 in (in plan); the runaway bound,
    # 10 × the capacity = 4 in in plan, is passed too (the base mat reaches 4.23 in in a corner
    # when nothing stops it). With stop the run ends at the first criterion (the isolator's);
    # without, it runs on through the others to the runaway. Called as a suite calls it.
    model, pair, integ = _model(capacity=0.4), _pair(), Integrator(method="newmark")
    crit = CollapseCriteria(drift_ratio=0.02, wall_force=100.0, stop=stop)
    bare = run(model, pair, integ, extra_time=0.5, collapse=crit, history=False)
    full = run(model, pair, integ, extra_time=0.5, collapse=crit)
    assert bare.collapse == full.collapse and bare.runaway == full.runaway
    assert bare.meta["stats"]["steps"] == full.meta["stats"]["steps"]
    _assert_same_peaks(bare, full)
    assert bare.impacts == full.impacts
    # the full history says when each bound was first passed (None: not within the run): the
    # limits are checked at every accepted step, and each is recorded (record_every = 1)
    t = full.time
    ratio = np.abs(np.hstack([full.story_drifts(a) / full.meta["story_heights"]
                              for a in ("x", "y")])).max(axis=1)
    first = {"drift": _first(t, ratio > 0.02),
             "isolator": _first(t, full.plan_base_displacement > 0.4),
             "wall_force": _first(t, full.contact_force.max(axis=1) > 100.0)}
    assert full.collapse == {**first, "wall_displacement": None, "collapsed": True,
                             "stopped": True}
    if stop:  # the first criterion reached ends the run: only it is passed, at the last step
        assert [k for k in first if first[k] is not None] == ["isolator"]
        assert first["isolator"] == t[-1] and full.runaway is None
    else:  # every criterion is passed before the plan displacement reaches 4 in
        assert all(first[k] is not None for k in first)
        assert full.runaway["time"] == _first(t, full.plan_base_displacement > 4.0) == t[-1]
    assert bare.meta["stats"]["t_reached"] == t[-1] < 6.5


def _first(t, above):
    """The first time [s] at which ``above`` holds, or None."""
    return float(t[np.argmax(above)]) if above.any() else None


def test_history_accessors_of_a_run_without_history_raise(bearing_runs):
    bare, _ = bearing_runs
    for ask in (lambda r: r.base_displacement, lambda r: r.plan_base_displacement,
                lambda r: r.base_velocity, lambda r: r.floor_displacement("x"),
                lambda r: r.story_drifts("y"), lambda r: r.absolute_acceleration("x"),
                lambda r: r.wall_displacement(), lambda r: r.wall_velocity("+y"),
                lambda r: r.wall_force(), PlanHistory.from_result):
        with pytest.raises(ValueError, match="history=False"):
            ask(bare)
    with pytest.raises(ValueError, match="channels"):
        run(_model(), _pair(1.0), history=False, channels=("velocity",))


def test_save_and_load_keep_a_run_without_history(bearing_runs, tmp_path):
    bare, _ = bearing_runs
    path = tmp_path / "bare.npz"
    bare.save(path)
    back = PlanRunResult.load(path)
    assert back.peaks == bare.peaks and back.impacts == bare.impacts
    assert back.meta["stats"] == bare.meta["stats"] and back.energy == bare.energy
    assert back.time.shape == (0,) and back.displacement.shape == bare.displacement.shape
    with pytest.raises(ValueError, match="history=False"):
        back.story_drifts("x")


def test_running_peaks_are_read_in_their_layout_and_refused_when_they_do_not_fit(bearing_runs):
    # The layout of femoat.integration.recording.peaks for ns building DOFs and nc walls:
    # [0:ns] each building DOF against the floor below along its axis (the base mat against
    # the ground), [ns:ns+nc] the walls, [ns+nc:2ns+nc] absolute accelerations,
    # [2ns+nc] the base velocity, [2ns+nc+1] the indentation, [2ns+nc+2] the plan crest. The
    # paper building in plan: 4 floors (base mat + 3) × (x, y) node-major, ns = 8; one mode per
    # wall, nc = 4; 23 values. With value j + 1 at index j the result must read: base x, y at
    # 0, 1 (values 1, 2); drifts x at 2, 4, 6, y at 3, 5, 7; walls +x, -x, +y, -y at 8-11;
    # accelerations of the base mat and floors x at 12, 14, 16, 18, y at 13, 15, 17, 19 [in/s²];
    # the plan crest at 22.
    _, full = bearing_runs
    packed = _model().pack()
    assert (packed.n_struct, len(packed.c_names), packed.n) == (8, 4, 12)
    running = np.arange(1.0, 24.0)
    arrays = {k: getattr(full, k)[:0] for k in ARRAY_UNITS}
    meta = {k: full.meta[k] for k in ("impacts", "stats", "energy", "info")}
    pk = PlanRunResult.from_arrays(arrays, packed, meta, running_peaks=running).peaks
    assert pk["peak_plan_base_displacement"] == 23.0
    assert (pk["peak_base_displacement_x"], pk["peak_base_displacement_y"]) == (1.0, 2.0)
    assert pk["peak_drift_x"] == [3.0, 5.0, 7.0] and pk["peak_drift_y"] == [4.0, 6.0, 8.0]
    assert pk["peak_drift_ratio_y"] == [4.0 / 39.0, 6.0 / 39.0, 8.0 / 39.0]  # 39 in stories
    assert [pk[f"peak_wall_displacement_{k}"] for k in ("px", "mx", "py", "my")] == \
        [9.0, 10.0, 11.0, 12.0]
    assert pk["peak_base_acceleration_x"] == 13.0 / G
    assert pk["peak_floor_acceleration_y"] == [16.0 / G, 18.0 / G, 20.0 / G]
    # the impacts, energy and steps are the meta's (the full run's here)
    assert pk["impacts_px"] == full.peaks["impacts_px"] and pk["steps"] == full.peaks["steps"]
    with pytest.raises(ValueError, match="running_peaks has shape"):
        PlanRunResult.from_arrays(arrays, packed, meta, running_peaks=running[:-1])
    with pytest.raises(ValueError, match="running_peaks has shape"):
        PlanRunResult.from_arrays(arrays, packed, meta, running_peaks=running * np.nan)
    with pytest.raises(ValueError, match="no rows"):
        full_arrays = {k: getattr(full, k) for k in ARRAY_UNITS}
        PlanRunResult.from_arrays(full_arrays, packed, meta, running_peaks=running)
    with pytest.raises(ValueError, match="at least one sample"):
        PlanRunResult.from_arrays(arrays, packed, meta)

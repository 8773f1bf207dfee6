"""The impact table kept inside the compiled loop (femoat.integration.recording.episodes) equals the one
read afterwards from the recorded history (RunResult._impact_table), and a run that keeps no
history (run(history=False), every suite run) has the same peaks and impact table."""

import importlib

import numpy as np
import pytest

from femoat.ground_motions import fema_p695_record
from femoat.integration import Integrator
from femoat.paper import paper_model, paper_motion
from femoat.run import run

EXACT = ("side", "start", "duration")
CLOSE = ("approach_velocity", "peak_force", "max_indentation", "impulse")


def _assert_same_table(kernel, history):
    # the same samples, the same operations; only the impulse's sum runs in another order
    # (numpy's pairwise sum against the loop's running sum: a few ulps)
    assert len(kernel) == len(history)
    for k, h in zip(kernel, history):
        assert {f: k[f] for f in EXACT} == {f: h[f] for f in EXACT}
        for f in CLOSE:
            assert k[f] == pytest.approx(h[f], rel=1e-12, abs=0), f


def _fema():
    # far-field 1a at 1.0 g, time-scaled by 0.5 (15 s): stick-slip of the bearing and two
    # impacts on the steel wall
    return fema_p695_record("farfield", 1, "a").scaled_to_pga(1.0).time_scaled(0.5)


@pytest.mark.parametrize("method", ["dp5", "newmark"])
@pytest.mark.parametrize("wall, law", [("concrete", "V"), ("steel", "H")])
def test_kernel_impact_table_equals_the_history_table_on_paper_runs(method, wall, law):
    r = run(paper_model(wall, law), paper_motion(), Integrator(method=method))
    # the paper's Erzincan runs pound both walls (3 episodes at these gaps)
    assert len(r.impacts) >= 2 and {i["side"] for i in r.impacts} == {"pos", "neg"}
    _assert_same_table(r.impacts, r._impact_table())


@pytest.mark.parametrize("method", ["dp5", "newmark"])
def test_kernel_impact_table_equals_the_history_table_on_a_fema_record(method):
    r = run(paper_model("steel", "H"), _fema(), Integrator(method=method))
    assert len(r.impacts) >= 1
    _assert_same_table(r.impacts, r._impact_table())


def test_kernel_impact_table_follows_the_recorded_samples_when_decimated():
    # record_every = 7 thins the open phase only (contact steps are always recorded): both
    # tables read the same recorded samples
    r = run(paper_model("concrete", "E"), paper_motion(quick=True), Integrator(record_every=7))
    assert len(r.impacts) >= 1
    _assert_same_table(r.impacts, r._impact_table())


def test_the_impact_table_grows_when_it_is_short(monkeypatch):
    # no first room: the loop asks for room before every episode it may end (BUFFER_FULL),
    # the table is doubled and the run goes on to the same table
    solve = importlib.import_module("femoat.integration.solve")  # the module, not solve()
    model, motion = paper_model("concrete", "V"), paper_motion(quick=True)
    ref = run(model, motion).impacts
    monkeypatch.setattr(solve, "IMPACT_ROWS", 0)
    grown = run(model, motion).impacts
    assert grown == ref and len(ref) >= 1


@pytest.mark.parametrize("method", ["dp5", "newmark"])
@pytest.mark.parametrize("model, motion", [
    (lambda: paper_model("concrete", "J"), paper_motion),
    (lambda: paper_model("steel", "H"), _fema),
])
def test_a_run_without_history_has_the_peaks_and_impacts_of_a_full_run(method, model, motion):
    # the step sequence does not depend on what is recorded, and the peaks and the episodes
    # read the same last samples from the ring as from the full record
    integ = Integrator(method=method)
    full = run(model(), motion(), integ)
    bare = run(model(), motion(), integ, history=False)
    assert bare.impacts == full.impacts
    for key, value in full.peaks.items():
        if key == "cpu_seconds":
            continue
        if isinstance(value, list):
            np.testing.assert_allclose(bare.peaks[key], value, rtol=1e-12, atol=0)
        elif isinstance(value, float):
            assert bare.peaks[key] == pytest.approx(value, rel=1e-12, abs=0), key
        else:
            assert bare.peaks[key] == value, key
    assert bare.energy == full.energy
    assert bare.meta["stats"]["t_reached"] == full.time[-1]
    assert bare.time.shape == (0,) and bare.displacement.shape == (0, full.displacement.shape[1])


def test_a_run_without_history_says_so_when_asked_for_one():
    r = run(paper_model("concrete", "E"), paper_motion(quick=True), history=False)
    with pytest.raises(ValueError, match="history=False"):
        r.absolute_acceleration()
    with pytest.raises(ValueError, match="channels"):
        run(paper_model("concrete", "E"), paper_motion(quick=True), history=False,
            channels=("displacement",))

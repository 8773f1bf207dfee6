"""integrate() beside solve(): the same run without raising, its status saying how it ended."""

import numpy as np
import pytest

from femoat.contact.laws import make_law
from femoat.integration import Integrator, RecordBudgetError, SolverError, integrate, solve
from femoat.paper import paper_model, paper_motion
from femoat.structure.building import Building
from femoat.structure.pounding import MoatWall, PoundingModel
from femoat.units import G
from femoat.walls.presets import wall_preset


def test_a_finished_run_is_done_and_is_solves_history():
    packed, motion = paper_model("concrete", "H").pack(), paper_motion(quick=True)
    args = (packed, motion.accel, motion.dt, motion.duration + 0.5)
    hist, status = integrate(*args)
    assert status.code == "done" and status.error is None and status.message == ""
    # the run reaches its duration (the last step lands on it)
    assert status.t == pytest.approx(motion.duration + 0.5, abs=1e-12) == hist.arrays["time"][-1]
    ref = solve(*args)
    for name in ("time", "displacement", "contact_force", "contact_closed"):
        assert np.array_equal(hist.arrays[name], ref.arrays[name]), name
    for name in ("peaks", "impacts"):
        assert np.array_equal(getattr(hist, name), getattr(ref, name)), name


def test_a_run_that_cannot_converge_returns_its_status_and_what_it_reached():
    # the mass of the steel wall's contact against the wall 0.01 in away at 10 in/s: two Newton
    # iterations and a 1 ms smallest step cannot resolve the ~2 ms Hertz contact (the model of
    # test_solver_nonlinear's unconvergeable run)
    preset = wall_preset("steel")
    b = Building(base_weight=preset.contact.m_eff * G, floor_weights=(), stories=(),
                 isolator=None)
    packed = PoundingModel(b, (MoatWall(make_law("H", preset.contact), preset.wall, 0.01, 1),)
                           ).pack()
    args = (packed, np.zeros(3), 0.01, 0.02, Integrator(max_newton=2, min_step=1e-3))
    hist, status = integrate(*args, v0=[10.0, 0.0])
    assert status.code == "failed" and status.error is SolverError
    assert "could not converge at t = " in status.message and "pos wall in contact" in status.message
    # it stopped inside the run, in contact, with the samples before recorded
    assert 0.0 < status.t < 0.02 and hist.arrays["time"][-1] <= status.t
    assert hist.arrays["contact_closed"][-1, 0] == 1
    assert hist.stats["t_reached"] == status.t
    with pytest.raises(SolverError) as raised:
        solve(*args, v0=[10.0, 0.0])
    assert str(raised.value) == status.message


def test_an_outgrown_record_budget_is_a_status_too():
    # 274 bytes a sample of the paper model: 1e6 bytes hold 3649 samples, one per 0.01 s of a
    # quiet record (test_limits), so the record is full at t = 36.49 s
    packed = paper_model("concrete", "E").pack()
    hist, status = integrate(packed, np.zeros(10001), 0.01, 100.0,
                             Integrator(record_budget=1e6))
    assert status.code == "budget" and status.error is RecordBudgetError
    assert status.t == pytest.approx(36.49, abs=1e-9) and "record_budget=1e+06" in status.message
    t = hist.arrays["time"]
    assert t.size == 3649 + 1 and t[-1] == pytest.approx(36.49, abs=1e-9)


@pytest.mark.parametrize("method", ["dp5", "newmark"])
def test_a_run_does_not_depend_on_where_the_loop_was_re_entered(method):
    # The loop returns to Python at each chunk (a progress display) and when a buffer grows;
    # its controller (next step, cruising step, a pending landing, samples since the last
    # record) is carried in the state, and a chunk's end does not cut a step, so the run is
    # the same bit for bit however often it was re-entered (it was not: 6,001 against 5,995
    # dp5 steps with 20 chunks on this run, peak forces 1e-8 apart).
    packed, motion = paper_model("concrete", "H").pack(), paper_motion(quick=True)
    args = (packed, motion.accel, motion.dt, motion.duration + 0.5, Integrator(method=method))
    one = solve(*args)
    many = solve(*args, chunks=37)
    assert one.stats["steps"] == many.stats["steps"]
    for name in one.arrays:
        assert np.array_equal(one.arrays[name], many.arrays[name]), name
    for name in ("peaks", "impacts"):
        assert np.array_equal(getattr(one, name), getattr(many, name)), name
    assert one.energy == many.energy

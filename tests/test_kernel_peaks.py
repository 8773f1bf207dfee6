"""The solver's running peaks (femoat.integration.recording.peaks, kept sample by sample inside the
compiled loop) equal the peaks read afterwards from the recorded history (femoat.dense_peaks)."""

import numpy as np
import pytest

from femoat.ground_motions import fema_p695_record
from femoat.integration import Integrator
from femoat.paper import paper_model, paper_motion
from femoat.run import run

KEYS = ("peak_base_displacement", "peak_base_velocity", "peak_wall_displacement_pos",
        "peak_wall_displacement_neg", "peak_indentation", "peak_drift", "peak_floor_acceleration",
        "peak_base_acceleration")


def _flat(p):
    out = []
    for k in KEYS:
        v = p[k]
        out += list(v) if isinstance(v, list) else [v]
    return np.array(out, dtype=float)


def _both(result):
    """(the run's peaks, the same peaks read from its recorded history)."""
    return _flat(result.peaks), _flat(result._peaks())


@pytest.mark.parametrize("method", ["dp5", "newmark"])
@pytest.mark.parametrize("wall, law", [("concrete", "V"), ("steel", "H")])
def test_running_peaks_equal_the_history_peaks_on_paper_runs(method, wall, law):
    # impacts on both walls: events, restarts and samples recorded twice at an instant
    kernel, history = _both(run(paper_model(wall, law), paper_motion(),
                                Integrator(method=method)))
    assert np.all(kernel > 0)
    np.testing.assert_allclose(kernel, history, rtol=1e-12, atol=0)


@pytest.mark.parametrize("method", ["dp5", "newmark"])
def test_running_peaks_equal_the_history_peaks_on_a_fema_record(method):
    # far-field 12a at 0.9 g on the steel wall: stick-slip, turning points, pounding
    gm = fema_p695_record("farfield", 12, "a").scaled_to_pga(0.9).time_scaled(0.5)
    r = run(paper_model("steel", "H"), gm, Integrator(method=method))
    kernel, history = _both(r)
    np.testing.assert_allclose(kernel, history, rtol=1e-12, atol=0)


def test_running_peaks_follow_the_recorded_samples_when_decimated():
    # record_every = 7: both read the interpolants between the recorded samples (an
    # approximation then, the same one)
    r = run(paper_model("concrete", "E"), paper_motion(quick=True),
            Integrator(record_every=7))
    kernel, history = _both(r)
    np.testing.assert_allclose(kernel, history, rtol=1e-12, atol=0)

"""Peaks read inside the steps (femoat.dense_peaks), not at the step ends."""

import math

import numpy as np
import pytest

from femoat.dense_peaks import hermite_abs_max, linear_accel_velocity_abs_max
from femoat.ground_motions import GroundMotion
from femoat.integration.settings import Integrator
from femoat.run import run
from femoat.structure.building import Building
from femoat.structure.materials import Elastic
from femoat.structure.pounding import PoundingModel
from femoat.units import G

W, K = 10.0, 4.0   # [kip], [kip/in]: a bare base mat on an elastic isolator


def test_undamped_sdof_reports_its_exact_amplitude_with_large_steps():
    # m = W/g, ω = √(K/m), T = 2π/ω = 0.5 s. From u = A·sin φ, v = ωA·cos φ the exact
    # amplitude is A. Newmark's average acceleration conserves ½k·u² + ½m·v² at every step end,
    # so the step ends lie on the exact energy ellipse; with 64 steps per period and φ chosen so
    # that the first crest falls in the middle of the fourth step, the nearest step end is
    # ωh/2 = 0.049 rad from it and misses it by 1 − cos(0.049) = 1.2e-3·A, while the cubic
    # Hermite interpolant's error is below ω⁴h⁴/384·A = 2.4e-7·A.
    m = W / G
    omega = math.sqrt(K / m)
    period = 2 * math.pi / omega
    amp = 1.7
    model = PoundingModel(Building(base_weight=W, floor_weights=(), isolator=Elastic(k=K),
                                   stories=()), ())
    quiet = GroundMotion(np.zeros(240), period / 64, name="quiet")  # steps end on samples
    integ = Integrator(method="newmark", rtol=0.05)
    phi = math.pi / 2 - 3.5 * 2 * math.pi / 64
    r = run(model, quiet, integ, duration=0.25 * period, u0=[amp * math.sin(phi)],
            v0=[omega * amp * math.cos(phi)])
    assert r.meta["stats"]["steps"] == 16  # large steps indeed: 64 per period
    at_ends = np.abs(r.base_displacement).max()
    assert abs(at_ends - amp) > 1e-3 * amp            # the step ends miss the crest
    assert r.peaks["peak_base_displacement"] == pytest.approx(amp, rel=1e-6)



def test_hermite_peak_of_a_sampled_sine_converges_at_fourth_order():
    # x = sin t sampled every h with the crest (t = π/2) in the middle of an interval: the
    # interpolant's crest error falls as h⁴ (slope 4 in log-log)
    errors, steps = [], [0.4, 0.2, 0.1, 0.05]
    for h in steps:
        t = np.pi / 2 - 0.5 * h + h * np.arange(-5, 6)
        errors.append(abs(hermite_abs_max(t, np.sin(t), np.cos(t)) - 1.0))
    slope = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert slope == pytest.approx(4.0, abs=0.3)


def test_velocity_peak_between_samples_is_exact_for_a_linear_acceleration():
    # a(t) = 1 − t on [0, 2]: v(t) = t − t²/2 peaks at t = 1 with v = 1/2; samples at 0 and 2
    t = np.array([0.0, 2.0])
    a = 1.0 - t
    v = t - t * t / 2
    assert linear_accel_velocity_abs_max(t, v, a) == pytest.approx(0.5, abs=1e-15)
    # the same between samples that are repeated (an event recorded twice at one instant)
    t2 = np.array([0.0, 0.0, 2.0])
    assert linear_accel_velocity_abs_max(t2, np.r_[0.0, v], np.r_[1.0, a]) == pytest.approx(0.5)


def test_quintic_acceleration_crest_converges_at_fourth_order():
    # u = sin t with u̇, ü exact at samples h apart, the crest of |ü| = 1 (t = π/2) in the middle
    # of an interval, no ground motion: the quintic Hermite interpolant's second derivative
    # misses the crest by O(h⁴) (the interpolant is exact to degree 5: u − p = O(h⁶), two
    # derivatives cost h²), so the log-log slope is about 4; the samples alone miss it by
    # 1 − cos(h/2) ≈ h²/8.
    from femoat.dense_peaks import quintic_accel_abs_max

    errors, steps = [], [0.4, 0.2, 0.1, 0.05]
    for h in steps:
        t = np.pi / 2 - 0.5 * h + h * np.arange(-5, 6)
        u, v, a = np.sin(t)[:, None], np.cos(t)[:, None], -np.sin(t)[:, None]
        peak = quintic_accel_abs_max(t, u, v, a, np.zeros(t.size), np.ones(t.size - 1, bool))
        errors.append(abs(peak[0] - 1.0))
        assert abs(np.abs(a).max() - 1.0) == pytest.approx(1 - np.cos(h / 2), rel=1e-9)
    slope = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert 3.7 < slope < 4.5, (slope, errors)
    # an interval not marked smooth keeps its samples (the crest is missed there)
    h = 0.4
    t = np.pi / 2 - 0.5 * h + h * np.arange(-5, 6)
    peak = quintic_accel_abs_max(t, np.sin(t)[:, None], np.cos(t)[:, None],
                                 -np.sin(t)[:, None], np.zeros(t.size),
                                 np.zeros(t.size - 1, bool))
    assert peak[0] == pytest.approx(np.sin(t).max(), rel=1e-15)

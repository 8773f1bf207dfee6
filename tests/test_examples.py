"""The example files the README shows: they are the README's text, and they run."""

import json
import re
from pathlib import Path

import pandas as pd

from femoat.cli import main

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"


def _readme_block(name):
    """The first ```toml block of the README after it names ``examples/<name>``."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    match = re.search(rf"`examples/{re.escape(name)}`.*?```toml\n(.*?)```", text, re.S)
    assert match, f"README.md shows no ```toml block after `examples/{name}`"
    return match.group(1)


def test_the_readme_shows_the_example_files_as_they_are():
    for name in ("my_building.toml", "my_suite.toml"):
        assert _readme_block(name) == (EXAMPLES / name).read_text(encoding="utf-8")


def test_the_example_building_runs_and_pounds(tmp_path, capsys):
    # Rinaldi at 0.8 g against a 3 in gap: the isolator (R = 30 in) slides past the gap, so
    # the base mat strikes a wall at least once; no story reaches 10 % drift
    assert main(["run", str(EXAMPLES / "my_building.toml"), "--out", str(tmp_path),
                 "--no-figures", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["peak_base_displacement"] > 3.0 and out["impacts_pos"] + out["impacts_neg"] >= 1
    assert not out["collapse"]["collapsed"] and (tmp_path / "run.npz").is_file()


def test_the_example_suite_runs_and_prints_its_verdict(tmp_path, capsys):
    # 4 records x 2 laws x 2 walls x 5 levels = 80 runs; the stiffer steel wall, struck
    # harder, collapses the building at lower intensities, never at higher ones
    out = tmp_path / "suite"
    assert main(["suite", str(EXAMPLES / "my_suite.toml"), "--serial", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "80 runs stored" in text and "mu_T = 3 (suite file [p695] mu_t)" in text
    s = pd.read_csv(out / "report" / "collapse_summary.csv").set_index("variation")
    assert list(s.index) == ["E / concrete", "H / concrete", "E / steel", "H / steel"]
    assert (s["n_records"] == 4).all()
    for law in ("E", "H"):
        assert s.loc[f"{law} / steel", "S_CT empirical [g]"] <= \
            s.loc[f"{law} / concrete", "S_CT empirical [g]"]


def test_the_tfp_example_is_the_readme_s_and_pounds_in_plan(tmp_path, capsys):
    # the README shows its [building.isolator] table as it is in the file
    shown = _readme_block("tfp_building.toml")
    assert shown.startswith("[building.isolator]") and shown in (
        EXAMPLES / "tfp_building.toml").read_text(encoding="utf-8")
    # the paper building on the isolators study's TFP under far-field pair 1 at the MCE: the
    # base mat reaches the 4 in moat in plan (the pendulum's run, examples/plan_building.toml,
    # pounds too), within the TFP's 9 in ultimate displacement
    assert main(["run", str(EXAMPLES / "tfp_building.toml"), "--out", str(tmp_path),
                 "--no-figures", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert 4.0 < out["peak_plan_base_displacement"] < 9.0
    assert sum(out[f"impacts_{w}"] for w in ("px", "mx", "py", "my")) >= 1
    assert not out["collapse"]["collapsed"]

"""Compile only the bearing kinds a command needs (femoat.startup.bearing_kinds and
femoat.bearings.registry.select): the generated dispatcher of a part of the kinds, the choice a
command makes from its models, the rules of choosing once per process, and (slow) that a process
compiled for the paper's pendulum makes no kernel of the other kinds and gives the same bits.

The test session itself runs with FEMOAT_BEARINGS=all (tests/conftest.py): the choices that
would narrow a process are made in subprocesses, or recorded without being applied."""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from femoat.bearings import registry
from femoat.startup import bearing_kinds as selection

ROOT = Path(__file__).resolve().parents[1]
EVERY = tuple(range(len(registry.KINDS)))
FP, LRB, TFP = (registry.keys().index(k) for k in ("fp", "lrb", "tfp"))


def _branches(source):
    """{dispatcher function: the kinds it has an ``if kind == k`` branch for}."""
    out, current = {}, None
    for line in source.splitlines():
        m = re.match(r"def (bearing_\w+)\(", line)
        if m:
            current = m.group(1)
            out[current] = set()
        m = re.match(r"    if kind == (\d+):", line)
        if m and current:
            out[current].add(int(m.group(1)))
    return out


def test_a_dispatcher_for_part_of_the_kinds_has_their_branches_only():
    # every kernel of the contract (and every rate kernel of a kind with a rate form) has a
    # branch per kind in the committed dispatcher; generated for the pendulum alone, each has
    # the pendulum's branch and no other, so numba compiles no kernel of the others (a kind
    # left out keeps its code: the loop's bearing rows and material codes do not change)
    full = _branches(registry.generate(registry.KINDS))
    part = _branches(registry.generate(registry.KINDS, compiled=(FP,)))
    assert set(full) == set(part) == set(registry.KERNELS) | set(registry.RATE_KERNELS)
    for fn in registry.KERNELS:
        assert full[fn] == set(EVERY)
    for fn in full:
        assert part[fn] == full[fn] & {FP}
    tfp_lrb = _branches(registry.generate(registry.KINDS, compiled=(LRB, TFP)))
    assert all(tfp_lrb[fn] == full[fn] - {FP} for fn in full)


def _model(isolator_key=None, plan=False):
    from femoat.plan import PlanBuilding, PlanModel
    from femoat.structure.building import Building
    from femoat.structure.materials import Elastic
    from femoat.structure.pounding import PoundingModel

    if isolator_key is None:
        building = Building()
    elif isolator_key == "elastic":
        building = Building(isolator=Elastic(k=2.0))
    else:
        building = Building(isolator=registry.by_key(isolator_key).AXIS_CLASS())
    if plan:
        return PlanModel(PlanBuilding.from_building(building))
    return PoundingModel(building)


def test_a_command_compiles_the_pendulum_alone_or_every_kind():
    # the paper's pendulum (1D or plan), an elastic isolator and no model at all need the
    # pendulum's loop; any other kind among the models takes every kind (two loops at most)
    none = {}
    assert selection.kinds_for([_model()], env=none) == (FP,)
    assert selection.kinds_for([_model(plan=True), _model("elastic")], env=none) == (FP,)
    assert selection.kinds_for([], env=none) == (FP,)
    assert selection.kinds_for([_model(), _model("tfp", plan=True)], env=none) == EVERY
    assert selection.kinds_for([_model("lrb")], env=none) == EVERY
    # FEMOAT_BEARINGS overrides (what the test session sets), by scenario keys or "all"
    assert selection.kinds_for([_model()], env={"FEMOAT_BEARINGS": "all"}) == EVERY
    assert selection.kinds_for([_model()], env={"FEMOAT_BEARINGS": "tfp, fp"}) == (FP, TFP)
    with pytest.raises(ValueError, match="use 'all' or some of fp, lrb, tfp"):
        selection.kinds_for([_model()], env={"FEMOAT_BEARINGS": "fp,triple"})


def test_the_commands_choose_from_their_models(monkeypatch, tmp_path):
    # femoat paper asks for the pendulum's loop, femoat run for its scenario's kind (the TFP
    # example: every kind); the choice is recorded here, not applied (this session's loop
    # carries every kind), and each command then runs as usual
    from femoat import cli

    asked = []

    def record(chosen, cache_dir=None):
        asked.append(registry.indices(chosen))
        return EVERY

    monkeypatch.delenv("FEMOAT_BEARINGS")
    monkeypatch.setattr(registry, "select", record)
    assert cli.main(["paper", "--quick", "--no-figures", "--out", str(tmp_path / "p")]) == 0
    assert asked == [(FP,)]
    scenario = ROOT / "examples" / "tfp_building.toml"
    assert cli.main(["run", str(scenario), "--no-figures", "--out", str(tmp_path / "r")]) == 0
    assert asked[-1] == EVERY
    # femoat compile: every kind unless told (--bearings, or FEMOAT_BEARINGS)
    assert cli.main(["compile"]) == 0 and asked[-1] == EVERY
    assert cli.main(["compile", "--bearings", "fp"]) == 0 and asked[-1] == (FP,)
    monkeypatch.setenv("FEMOAT_BEARINGS", "tfp")
    assert cli.main(["compile"]) == 0 and asked[-1] == (TFP,)
    assert cli.main(["compile", "--bearings", "pendulum"]) == 2  # a clear error, not a trace


def _env(tmp_path):
    """A new process's environment: femoat importable, its own numba cache, no choice made."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba"),
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    env.pop("FEMOAT_BEARINGS")
    return env


_RULES = r"""
import json, os
from femoat.bearings import registry, dispatch
from femoat.compilation import jit
from femoat.bearings.triple_friction_pendulum import TripleFrictionPendulum
from femoat.structure.materials import FrictionPendulum
out = {}
original = dispatch.bearing_axis_trial.py_func
out["fp"] = registry.select(("fp",))
out["cache"] = os.environ["NUMBA_CACHE_DIR"]
out["module"] = dispatch.bearing_axis_trial.py_func.__module__
registry.check_compiled(FrictionPendulum())
try:
    registry.check_compiled(TripleFrictionPendulum())
except RuntimeError as exc:
    out["refused"] = str(exc)
out["widened"] = registry.select("tfp")            # before any compile: both choices
out["all"] = registry.select("all")
out["restored"] = dispatch.bearing_axis_trial.py_func is original
out["cache_back"] = os.environ.get("NUMBA_CACHE_DIR")
out["kept"] = registry.select("fp")                # an earlier choice that covers it stays
jit._started.append("a kernel")                    # as if numba had compiled one
out["after"] = registry.select("lrb")              # covered: kept
print(json.dumps(out))
"""


def test_choosing_the_kinds_follows_its_rules(tmp_path):
    # in a new process (this session's loop must keep every kind); nothing is compiled
    env = _env(tmp_path)
    done = subprocess.run([sys.executable, "-c", _RULES], capture_output=True, text=True,
                          env=env, cwd=tmp_path, timeout=300)
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["fp"] == [FP]
    # the pendulum's loop is cached apart, in a folder keyed by its dispatcher
    assert Path(out["cache"]).parent.parent == tmp_path / "numba"
    assert Path(out["cache"]).parent.name.startswith("bearings-")
    assert out["module"].startswith("femoat_bearings_dispatch_")
    assert "TripleFrictionPendulum" in out["refused"] and "FEMOAT_BEARINGS=all" in out["refused"]
    assert out["widened"] == [FP, TFP]
    assert out["all"] == list(EVERY) and out["restored"]
    assert out["cache_back"] == str(tmp_path / "numba")
    assert out["kept"] == list(EVERY) and out["after"] == list(EVERY)


_PAPER_LOOP = r"""
import json, os
from femoat.compilation import jit
from femoat.startup.bearing_kinds import select_for
from femoat.structure.building import Building
assert select_for([Building()]) == ("fp",)
from femoat.paper import paper_model, paper_motion
from femoat.plan import PlanModel
from femoat.ground_motions import GroundMotion, RecordPair
from femoat.run import run
gm = paper_motion(quick=True)
one = run(paper_model("concrete", "H"), gm).peaks
pair = RecordPair(gm, GroundMotion(0.5 * gm.accel_g, gm.dt, name="y"))
plan = run(PlanModel(), pair, duration=3.0).peaks
made = sorted({k.py_func.__module__ for k in jit._started})
from femoat.bearings import registry
from femoat.structure.pounding import PoundingModel
lrb = registry.by_key("lrb").AXIS_CLASS()
try:
    run(PoundingModel(Building(isolator=lrb)), gm)
    refused = ""
except RuntimeError as exc:
    refused = str(exc)
# a suite of the pendulum on a local Dask cluster: the client's choice reaches its worker,
# which loads the client's loop from the pendulum's cache and compiles nothing
import io, sys
from femoat.suite import load_suite, run_suite
record = os.path.join(sys.argv[1], "Rinaldi228.AT2")
open("suite.toml", "w").write(
    f'[records]\nfiles = ["{record}"]\nduration = 1.0\nextra_time = 0.5\n'
    '[scaling]\nmethod = "pga"\ntargets = [0.3]\n')
summary = run_suite(load_suite("suite.toml"), "suite_out", workers=1, stream=io.StringIO())
suite = {k: summary[k] for k in ("runs", "failed_tasks", "bearings", "worker_compiles")}
print(json.dumps({"one": one, "plan": plan, "made": made, "refused": refused,
                  "suite": suite}))
"""


@pytest.mark.slow
def test_the_paper_loop_compiles_no_other_kind_and_gives_the_same_bits(tmp_path):
    # a process that chose the paper's pendulum (what femoat paper does) compiles its loop in a
    # private cache: numba makes no kernel of the lead-rubber bearing or the triple pendulum
    # (their modules absent from the kernels it made), a 1D paper run and a plan run give the
    # bits of this session's loop of every kind (the same kernels, fewer branches), and a
    # model on another kind is refused with the way out; a suite of the pendulum on a local
    # Dask cluster hands the choice to its worker
    env = _env(tmp_path)
    peer = Path(__file__).resolve().parent / "data" / "peer"
    done = subprocess.run([sys.executable, "-c", _PAPER_LOOP, str(peer)], capture_output=True,
                          text=True, env=env, cwd=tmp_path, timeout=1800)
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert "femoat.bearings.friction_pendulum" in out["made"]
    assert not [m for m in out["made"] if "lead_rubber" in m or "triple_friction" in m]
    assert registry.by_key("lrb").AXIS_CLASS.__name__ in out["refused"]
    # its suite: one run on one local worker, which chose the client's kinds and loaded the
    # client's loop (no signature compiled in the worker)
    assert out["suite"] == {"runs": 1, "failed_tasks": 0, "bearings": ["fp"],
                            "worker_compiles": [0]}

    from femoat.ground_motions import GroundMotion, RecordPair
    from femoat.paper import paper_model, paper_motion
    from femoat.plan import PlanModel
    from femoat.run import run

    gm = paper_motion(quick=True)
    pair = RecordPair(gm, GroundMotion(0.5 * gm.accel_g, gm.dt, name="y"))
    expected = {"one": run(paper_model("concrete", "H"), gm).peaks,
                "plan": run(PlanModel(), pair, duration=3.0).peaks}
    for key in ("one", "plan"):
        mine = json.loads(json.dumps(expected[key]))  # the same JSON round trip
        for name, value in mine.items():
            if name != "cpu_seconds":
                assert out[key][name] == value, (key, name)

"""The bearing registry (femoat.bearings.registry): the committed dispatcher is the one its list
generates, every kind provides the contract, and a kind written in a test file, registered for one
process, runs in 1D and in plan through the compiled loop (tests/bearing_kinds/capped_spring.py).
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from femoat.bearings import registry

TESTS = Path(__file__).resolve().parent


def test_the_committed_dispatcher_is_what_the_registry_generates():
    # numba cannot add a branch at run time: the loop calls the kinds through a generated,
    # committed module; after a new line in KINDS it must be written anew (this test says so)
    committed = (Path(registry.__file__).with_name("dispatch.py")).read_text()
    assert committed == registry.generate(registry.KINDS), (
        "femoat/bearings/dispatch.py is stale: run `python -m femoat.bearings.registry`.")


def test_every_kind_provides_the_contract_and_its_own_axis_code():
    for kind, name in enumerate(registry.KINDS):
        mod = registry.check_kind(name)
        assert registry.kind_of(mod.AXIS_CLASS()) == kind == registry.kind_of(mod.PLAN_CLASS())
        assert mod.AXIS_CLASS().code == registry.AXIS_CODE_START + kind
        assert registry.by_key(mod.KEY) is mod
        assert len(mod.AXIS_CLASS().params()) == mod.N_PARAMS
        assert len(mod.PLAN_CLASS().initial_state_plan()) == mod.N_STATE_PLAN
    assert len(set(registry.keys())) == len(registry.KINDS)


def test_a_dispatcher_for_other_kinds_is_refused_at_import():
    with pytest.raises(RuntimeError, match="python -m femoat.bearings.registry"):
        registry.check_dispatcher(("femoat.bearings.friction_pendulum", "some.other.kind"))


def test_a_kind_that_misses_part_of_the_contract_is_refused_by_name():
    # this test module is not a bearing kind: it lacks every name of the contract
    sys.path.insert(0, str(TESTS))
    try:
        with pytest.raises(ValueError, match="missing KEY, N_PARAMS"):
            registry.check_kind("test_bearing_registry")
    finally:
        sys.path.remove(str(TESTS))


def test_a_kind_written_in_a_test_file_meets_the_contract_and_gets_its_branch():
    # the capped spring provides every name of the contract, and the dispatcher generated
    # with it appended gives it the next code: one more `if kind == n` branch per kernel, the
    # committed kinds' branches unchanged (what register() loads in a fresh process: the
    # slow tests below run it through the dispatcher and the whole loop)
    sys.path.insert(0, str(TESTS))
    try:
        mod = registry.check_kind("bearing_kinds.capped_spring")
    finally:
        sys.path.remove(str(TESTS))
    n = len(registry.KINDS)
    names = (*registry.KINDS, "bearing_kinds.capped_spring")
    source = registry.generate(names)
    for fn, (own, args, _) in registry.KERNELS.items():
        body = source.split(f"def {fn}(kind, ")[1].split("\n\n\n")[0]
        assert f"    if kind == {n}:\n" in body, fn
        assert f"_{own}_{n}({args})" in body.split(f"if kind == {n}:")[1].splitlines()[1], fn
    committed = registry.generate()
    assert all(line in source for line in committed.splitlines() if "if kind ==" in line)
    assert mod.KEY not in registry.keys()  # not registered in this process


def _in_process_with_kind(code, tmp_path):
    """Run ``code`` in a new process that registered the capped spring first; its JSON output."""
    prelude = (
        "import json, sys\n"
        "from femoat.bearings import registry\n"
        f"kind = registry.register('bearing_kinds.capped_spring', cache_dir={str(tmp_path)!r})\n"
    )
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(TESTS), *filter(None, [os.environ.get("PYTHONPATH")])])}
    done = subprocess.run([sys.executable, "-c", prelude + code], capture_output=True,
                          text=True, env=env, timeout=1800)
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.mark.slow
def test_a_kind_registered_from_a_test_file_runs_through_the_dispatcher(tmp_path):
    # The dispatcher alone (its kernels compile for every kind, ~35 s): the capped spring's kernels,
    # reached through femoat.bearings.dispatch with the new kind's code, on one cycle of
    # amplitude u0 = 0.5 in at k = 1.1, F = 1.98, k_f = 198 kip/in (u_y = 0.01 in):
    # the loop's area is the cap's alone, 4·F·(u0 − u_y) = 4·1.98·0.49 = 3.8808 kip·in; the
    # trapezoid rule over a cycle cut at the kinks (u_y after each reversal) is exact on its
    # piecewise-linear force. In plan, along the diagonal the two uncoupled caps resist with
    # F per axis (a square yield surface): √2·F along it.
    out = _in_process_with_kind(
        "import numpy as np\n"
        "from femoat.bearings import dispatch\n"
        "from bearing_kinds.capped_spring import CappedSpring\n"
        "b = CappedSpring(); p = b.params(); s = b.initial_state_axis()\n"
        "u0, uy = 0.5, b.yield_deformation\n"
        "path = np.concatenate([np.linspace(0, u0, 51), [u0 - 2 * uy], np.linspace(u0 - 2 * uy,"
        " -u0, 50), [-u0 + 2 * uy], np.linspace(-u0 + 2 * uy, u0, 50)])\n"
        "f = []\n"
        "for u in path:\n"
        "    f.append(dispatch.bearing_axis_trial(kind, p, s, u, 0.0)[0])\n"
        "    dispatch.bearing_axis_commit(kind, p, s, u, 0.0)\n"
        "f = np.array(f); i = 50\n"
        "area = float(np.trapezoid(f[i:], path[i:]))\n"
        "ps = b.initial_state_plan(); fp = np.zeros(2); k = np.zeros((2, 2)); c = np.zeros((2, 2))\n"
        "for r in np.linspace(0.0, 1.0, 21):\n"
        "    dispatch.bearing_plan_trial(kind, p, ps, 0, 0, 0, 0, r, r, 0, 0, 0.0, fp, k, c)\n"
        "    dispatch.bearing_plan_commit(kind, p, ps, 0, 0, 0, 0, r, r, 0, 0, 0.0)\n"
        "print(json.dumps({'kind': kind, 'area': area, 'fp': fp.tolist(),"
        " 'energy': dispatch.bearing_plan_energy(kind, p, ps),"
        " 'fp_kind': dispatch.bearing_axis_trial(0, np.array([33.0, 30, 0.01, 0.06, 0.06, 0,"
        " 1e-3]), np.zeros(3), 0.005, 0.0)[0]}))\n", tmp_path)
    assert out["kind"] == len(registry.KINDS)  # appended after the committed kinds
    assert out["area"] == pytest.approx(4 * 1.98 * (0.5 - 0.01), rel=1e-12)
    # at r = 1 in on both axes each cap holds F = 1.98 and the spring 1.1·1 kip
    assert out["fp"] == pytest.approx([1.1 + 1.98, 1.1 + 1.98], rel=1e-14)
    # stored: k·|u|²/2 + Σ q²/(2 k_f) = 1.1·2/2 + 2·1.98²/(2·198)
    assert out["energy"] == pytest.approx(1.1 + 1.98 ** 2 / 198, rel=1e-14)
    # the committed kind 0 (the friction pendulum) still answers on its own branch:
    # W/R·u + μW·u/u_y at u = u_y/2 = 1.1·0.005 + 1.98·0.5
    assert out["fp_kind"] == pytest.approx(1.1 * 0.005 + 0.99, rel=1e-14)


@pytest.mark.slow
def test_a_kind_registered_from_a_test_file_runs_in_1d_and_in_plan(tmp_path):
    # The whole loop compiled for the committed kinds plus the capped spring (~2 min of numba):
    # * 1D: the capped spring with k = W/R, F = μW, k_f = μW/u_y is the paper's friction
    #   pendulum written in force instead of z, so the paper building on it in the paper's moat
    #   under the Erzincan record gives the friction pendulum's run (round-off apart: the same
    #   rule, the cap's force kept instead of z, so 1e-9 on every peak through the impacts);
    # * plan, one axis: a pair whose y component is zero leaves y at rest, and the x response
    #   is the 1D run's (1e-9);
    # * plan, both axes: without walls and with stories that do not couple x and y, the two
    #   uncoupled caps make the plan run two 1D runs, one per component (1e-9).
    out = _in_process_with_kind(
        "import numpy as np\n"
        "from bearing_kinds.capped_spring import CappedSpring\n"
        "from femoat.ground_motions import GroundMotion, RecordPair\n"
        "from femoat.paper import paper_model, paper_motion\n"
        "from femoat.plan import PlanBuilding, PlanModel\n"
        "from femoat.structure.pounding import PoundingModel\n"
        "from femoat.run import run\n"
        "from dataclasses import replace\n"
        "fp_model = paper_model('concrete', 'H')\n"
        "iso = fp_model.building.isolator\n"
        "cap = CappedSpring(k=iso.W / iso.R, k_f=iso.mu * iso.W / iso.u_y, F=iso.mu * iso.W)\n"
        "cap_model = replace(fp_model, building=replace(fp_model.building, isolator=cap))\n"
        "m = paper_motion()\n"
        "m = GroundMotion(m.accel_g[:int(12 / m.dt)], m.dt, name=m.name)\n"
        "a, b = run(fp_model, m), run(cap_model, m)\n"
        "zero = GroundMotion(0.0 * m.accel_g, m.dt, name='zero')\n"
        "plan_x = run(PlanModel(building=PlanBuilding.from_building(cap_model.building),"
        " walls=()), RecordPair(m, zero))\n"
        "free = PoundingModel(building=cap_model.building, walls=())\n"
        "from femoat.integration import Integrator\n"
        "x1 = run(free, m, integrator=Integrator(method='newmark'))\n"
        "tight = Integrator(method='newmark', rtol=1e-8)\n"
        "ym = GroundMotion(-0.7 * m.accel_g[::-1], m.dt, name='y')\n"
        "x2, y2 = run(free, m, integrator=tight), run(free, ym, integrator=tight)\n"
        "both = run(PlanModel(building=PlanBuilding.from_building(cap_model.building), walls=()),"
        " RecordPair(m, ym), integrator=tight)\n"
        "print(json.dumps({'fp': a.peaks, 'cap': b.peaks, 'free_x': x1.peaks, 'free_x2': x2.peaks,"
        " 'free_y2': y2.peaks, 'plan_x': plan_x.peaks, 'both': both.peaks,"
        " 'impacts': len(a.impacts)}, default=float))\n",
        tmp_path)
    assert out["impacts"] > 0  # the comparison goes through impacts
    # The same rule, round-off apart (the cap keeps its force q where the pendulum keeps z, and
    # μW·(z + Δu/u_y) and q + k_f·Δu round differently): where a kink's bisection meets such a
    # rounding, the step lands 2^-12 of a step elsewhere and the runs part by far less than the
    # solver's local tolerance (rtol 1e-5): 1e-7 on every peak.
    for key, value in out["fp"].items():
        if key.startswith("peak") and isinstance(value, (int, float)):
            assert out["cap"][key] == pytest.approx(value, rel=1e-7, abs=1e-9), key
    free_x, plan_x, both = out["free_x"], out["plan_x"], out["both"]
    # y at rest: the plan run (Newmark, the plan default) is the 1D Newmark run along x (the
    # plan pack restricted to x is the 1D pack) through the capped spring's plan kernels
    assert plan_x["peak_drift_x"] == pytest.approx(free_x["peak_drift"], rel=1e-9)
    assert max(plan_x["peak_drift_y"]) == 0.0
    # both axes: the same physics as two 1D runs, but one step size for both axes (the step
    # controller sees the pair), so the runs agree to the solver's tolerance: at rtol 1e-8,
    # 1e-6 (at the default 1e-5 they part by 1e-4)
    assert both["peak_drift_x"] == pytest.approx(out["free_x2"]["peak_drift"], rel=1e-6)
    assert both["peak_drift_y"] == pytest.approx(out["free_y2"]["peak_drift"], rel=1e-6)


def test_the_rate_forms_optional_kernels_default_to_one_sliding_direction():
    # the pendulum and the lead-rubber bearing leave plan_rate_turn and plan_rate_branch out of
    # their modules: the generated dispatcher gives them the one-direction measure r = z·v,
    # ṙ = g·v + z·a (g = ż from their plan_rate) and plan_branch; the triple pendulum keeps its
    # own. A rate form without one of its required kernels is refused (check_kind).
    import numpy as np

    from femoat.bearings.dispatch import bearing_plan_rate_turn
    from femoat.bearings.friction_pendulum import FrictionPendulum

    source = registry.generate()
    turn = source.split("def bearing_plan_rate_turn(kind, ")[1].split("\n\n\n")[0]
    assert "_turn_along(z, g, vx, vy, ax, ay)" in turn.split("if kind == 0:")[1].split("if")[0]
    assert "_plan_rate_turn_2(" in turn
    branch = source.split("def bearing_plan_rate_branch(kind, ")[1].split("\n\n\n")[0]
    assert "_plan_branch_0(p, s, ux, uy)" in branch and "_plan_rate_branch_2(" in branch
    fp = FrictionPendulum()
    p, s = fp.params(), fp.initial_state_plan()
    u_y = fp.u_y
    # z = (0.6, 0.8) on the rim, v = (1, 2) [in/s], a = (3, -1) [in/s²]: z·v = 2.2,
    # g = (v − (z·v)·z)/u_y = (−0.32, 0.24)/u_y, ṙ = g·v + z·a = 0.16/u_y + 1.0
    z, g, J = np.array([0.6, 0.8]), np.zeros(2), np.zeros((2, 2))
    r, dr = bearing_plan_rate_turn(0, p, s, 0.0, 0.0, 1.0, 2.0, 3.0, -1.0, z, g, J)
    assert r == pytest.approx(2.2, rel=1e-15)
    assert dr == pytest.approx(0.16 / u_y + 1.0, rel=1e-13)

"""numba's SSA reconstruction walking only the blocks that name each variable
(femoat.compilation.ssa).

What must hold: the IR it gives is numba's own, statement for statement: the same blocks in the
same order, the same statements with the same (fresh) variable names, the same phi nodes in the
same places, the same variables in the scope. Checked here on the IR of femoat's largest
functions (the time-stepping loop, the coupled-friction step, the triple pendulum's series solve,
the explicit step's wall propagators, the event search, the commit) as numba's front end builds
it, and on every function compiled for a tree of nested inline helpers (the IR after inlining,
as the loop's); the solver's stored fingerprints (tests/test_fingerprints.py) are computed with
it installed.
"""

import copy
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _functions():
    from femoat.bearings import triple_friction_pendulum as tfp
    from femoat.integration import commit, driver, events
    from femoat.integration.methods import ark5, dp5

    return {"run_chunk": driver.run_chunk, "coupled_step": ark5.coupled_step,
            "_series": tfp._series, "_newton_update": ark5._newton_update,
            "find_events": events.find_events, "_expm": dp5._expm, "accept": commit.accept}


def _statements(blocks):
    return [(label, [str(stmt) for stmt in block.body]) for label, block in blocks.items()]


@pytest.mark.parametrize("name", sorted(_functions()))
def test_the_ir_is_numbas_statement_for_statement(name):
    from numba.core import ir, ssa
    from numba.core.analysis import compute_cfg_from_blocks
    from numba.core.compiler import run_frontend

    from femoat.compilation import jit
    from femoat.compilation.ssa import run_ssa

    jit._register()  # installs femoat's version: numba's own is then its __wrapped__
    numbas = getattr(ssa._run_ssa, "__wrapped__", ssa._run_ssa)
    assert numbas is not run_ssa
    func_ir = run_frontend(_functions()[name].py_func)
    blocks = func_ir.blocks
    violators = ssa._find_defs_violators(blocks, compute_cfg_from_blocks(blocks))
    assert len(violators) >= 3  # variables assigned more than once: there is work to compare
    theirs, ours = copy.deepcopy(blocks), copy.deepcopy(blocks)  # (each with its own scope)
    theirs, ours = numbas(theirs), run_ssa(ours)
    assert _statements(ours) == _statements(theirs)
    scope = next(iter(theirs.values())).scope
    assert sorted(next(iter(ours.values())).scope.localvars._con) == sorted(scope.localvars._con)
    # the input is not changed, the output is SSA: a phi where definitions meet, one
    # assignment per name
    assert _statements(blocks) == _statements(func_ir.blocks)
    phis = [s for b in ours.values() for s in b.body
            if isinstance(s, ir.Assign) and isinstance(s.value, ir.Expr) and s.value.op == "phi"]
    assert phis
    targets = [s.target.name for b in ours.values() for s in b.body if isinstance(s, ir.Assign)]
    assert len(targets) == len(set(targets))


def test_a_function_without_violators_is_returned_as_it_is():
    from numba.core.compiler import run_frontend

    from femoat.compilation.ssa import run_ssa

    def straight(x, y):
        z = x * y
        return z + 1.0

    blocks = run_frontend(straight).blocks
    assert run_ssa(blocks) is blocks  # as numba's: nothing to rename, the same blocks


CHECKED = """
import copy, json, os, sys, tempfile, types
import numpy as np
from femoat.compilation import jit, ssa as fast
jit._register()
import numba.core.ssa as ssa
numbas = fast.run_ssa.__wrapped__
seen = {"functions": 0, "differ": 0, "phis": 0}

def statements(blocks):
    return [(label, [str(s) for s in b.body]) for label, b in blocks.items()]

def checked(blocks):
    theirs, ours = copy.deepcopy(blocks), copy.deepcopy(blocks)
    theirs, ours = numbas(theirs), fast.run_ssa(ours)
    seen["functions"] += 1
    seen["differ"] += statements(theirs) != statements(ours)
    seen["phis"] += sum(str(s).count("phi(") for b in ours.values() for s in b.body)
    return fast.run_ssa(blocks)

ssa._run_ssa = checked
from test_inlining import LOAD_TREE, TREE
TREE_MODULE = "femoat._ssa_tree"
exec(LOAD_TREE)
xs = np.linspace(-3.0, 3.0, 41)
mod.tree(xs, np.array([0.3, -0.2, 0.7, 0.1]), np.zeros_like(xs))
print(json.dumps(seen))
"""


def test_after_inlining_too(tmp_path):
    # A tree of inline helpers (tests/test_inlining.py: four levels, each inlined at two sites,
    # with loops and branches) compiled in a fresh process with numba's SSA run beside femoat's
    # on a copy of every IR handed to it: the same statements each time.
    import json

    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path),
           "PYTHONPATH": os.pathsep.join([str(ROOT), str(ROOT / "tests"),
                                          os.environ.get("PYTHONPATH", "")])}
    out = subprocess.run([sys.executable, "-c", CHECKED], env=env, capture_output=True,
                         text=True, timeout=300, check=False)
    assert out.returncode == 0, out.stderr[-2000:]
    seen = json.loads(out.stdout.strip().splitlines()[-1])
    assert seen["functions"] >= 1 and seen["phis"] > 0
    assert seen["differ"] == 0

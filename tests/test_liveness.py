"""numba's variable liveness with the reaching definitions found once per loop
(femoat.compilation.liveness), and numba's compile flags read as one dict
(femoat.compilation.flags).

What must hold: the live sets are numba's own, block for block, and the flags' values, hash and
equality are numba's. Checked on the IR of femoat's largest functions (the time-stepping loop,
the coupled-friction step, the triple pendulum's series solve, ...) as numba's front end builds
it and after numba's SSA reconstruction, on a graph with a loop, a nested loop and a dead block
worked by hand, and on flags with and without options set; the solver's stored fingerprints
(tests/test_fingerprints.py) are computed with both installed.
"""

import copy

import pytest


def _functions():
    from femoat.bearings import triple_friction_pendulum as tfp
    from femoat.integration import commit, driver, events
    from femoat.integration.methods import ark5, dp5

    return {"run_chunk": driver.run_chunk, "coupled_step": ark5.coupled_step,
            "_series": tfp._series, "_newton_update": ark5._newton_update,
            "find_events": events.find_events, "_expm": dp5._expm, "accept": commit.accept}


def _numbas():
    from femoat.compilation import jit
    from femoat.compilation.liveness import compute_live_map

    jit._register()  # installs femoat's version: numba's own is then its __wrapped__
    return getattr(compute_live_map, "__wrapped__", None)


def _both(blocks):
    from numba.core import analysis

    from femoat.compilation.liveness import compute_live_map

    cfg = analysis.compute_cfg_from_blocks(blocks)
    usedefs = analysis.compute_use_defs(blocks)
    theirs = _numbas()(cfg, blocks, usedefs.usemap, usedefs.defmap)
    ours = compute_live_map(cfg, blocks, usedefs.usemap, usedefs.defmap)
    return theirs, ours


@pytest.mark.parametrize("ssa", [False, True], ids=["front-end", "ssa"])
@pytest.mark.parametrize("name", sorted(_functions()))
def test_the_live_sets_are_numbas_block_for_block(name, ssa):
    from numba.core import ssa as numba_ssa
    from numba.core.compiler import run_frontend

    blocks = run_frontend(_functions()[name].py_func).blocks
    if ssa:
        blocks = numba_ssa._run_ssa(copy.deepcopy(blocks))
    theirs, ours = _both(blocks)
    assert list(ours) == list(theirs)  # every block, in numba's order
    assert ours == theirs
    assert sum(map(len, ours.values())) > 0  # there is something alive to compare


def _graph(edges, uses, defs):
    """A control-flow graph from ``edges`` (label -> successors), entry 0, with the blocks'
    used and defined names; (cfg, labels)."""
    from numba.core.controlflow import CFGraph

    g = CFGraph()
    labels = sorted(set(edges) | {s for t in edges.values() for s in t})
    for label in labels:
        g.add_node(label)
    for label, targets in edges.items():
        for t in targets:
            g.add_edge(label, t)
    g.set_entry_point(0)
    g.process()
    return g, {k: set(uses.get(k, ())) for k in labels}, {k: set(defs.get(k, ())) for k in labels}


def test_a_loop_a_nested_loop_and_a_dead_block_worked_by_hand():
    from femoat.compilation.liveness import compute_live_map, reaching_names

    # 0 -> 1 (outer loop head) -> 2 (inner head) <-> 3 (inner body); 2 -> 4 -> 1 (outer
    # back edge); 1 -> 5 (exit). 9 is dead (no path from 0) and jumps into 3.
    # 0 defines i, n; 1 uses i, n; 2 uses j; 3 uses x, defines j, x; 4 defines i, j;
    # 5 uses x; 9 defines x.
    edges = {0: [1], 1: [2, 5], 2: [3, 4], 3: [2], 4: [1], 5: [], 9: [3]}
    uses = {1: "in", 2: "j", 3: "x", 5: "x"}
    defs = {0: "in", 3: "jx", 4: "ij", 9: "x"}
    cfg, use, dfn = _graph(edges, uses, defs)
    reach = reaching_names(cfg, use, dfn)
    # Reaching: 0 sees its own {i, n}; the loop blocks 1-4 reach one another, so each sees
    # everything named in 0-4: {i, n, j, x}; 5 too (reached from 1). 9 is outside the
    # topological order: nothing reaches it and its own names are not pushed.
    assert reach[0] == set("in")
    assert all(reach[k] == set("injx") for k in (1, 2, 3, 4, 5))
    assert reach[9] == set()
    live = compute_live_map(cfg, {k: None for k in sorted(use)}, use, dfn)
    # Alive at entry: a block's own uses, and what is alive in a successor, reaches the block
    # and is not defined in it. From the uses 1: {i, n}, 2: {j}, 3: {x}, 5: {x}: 5 gives 1
    # x; 3 gives 2 x; 2 gives 1 j and x; 1 gives 4 n and x (i, j defined in 4) and 0 nothing
    # (i, n defined there; j, x do not reach 0); 4 gives 2 n; 2 gives 3 n (j, x defined
    # there); 9 gets nothing from 3 (nothing reaches 9).
    assert live == {0: set(), 1: set("injx"), 2: set("jxn"), 3: set("xn"), 4: set("nx"),
                    5: set("x"), 9: set()}
    assert live == _numbas()(cfg, {k: None for k in sorted(use)}, use, dfn)


def test_flags_values_hash_and_equality_are_numbas():
    from numba.core.compiler import Flags

    from femoat.compilation import flags

    _numbas()
    numbas = getattr(Flags.values, "__wrapped__", None)
    assert numbas is not None and Flags.values is flags.values
    plain, set_ = Flags(), Flags()
    set_.nrt = False
    set_.no_cpython_wrapper = True
    set_.fastmath = True
    same = Flags()
    same.nrt = False
    same.no_cpython_wrapper = True
    same.fastmath = True
    for f in (plain, set_, same, set_.copy()):
        assert list(f.values().items()) == list(numbas(f).items())  # keys, order and values
    assert set_ == same and set_ != plain and hash(set_) == hash(same)
    assert plain.values()["nrt"] is numbas(plain)["nrt"]  # an unset option: its default

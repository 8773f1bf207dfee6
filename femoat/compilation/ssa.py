"""numba's SSA reconstruction, walking for each variable only the blocks that mention it.

numba rebuilds static single assignment form once per compiled function
(``numba.core.ssa._run_ssa``, Choi et al.'s algorithm): for each variable assigned more than
once (a *violator*) it renames the assignments (``_fresh_vars``), then points every use at its
reaching definition, inserting phi nodes where definitions meet (``_fix_ssa_vars``). Each of
the two steps walks every statement of the function, although only the statements that name
the variable can change: the cost is the number of violators times the size of the function.
femoat's loop, with its helpers inlined, has hundreds of violators and thousands of blocks.

:func:`run_ssa` does the same, variable by variable and in the same order, with numba's own
handlers, but hands each step only the blocks that mention the variable (a statement that does
not mention it is returned unchanged by both handlers, so the other blocks need not be walked);
phi nodes go to the same blocks. Fresh names come from the same calls in the same order, so the
resulting IR is the same statement for statement (``tests/test_ssa.py`` compares the two on the
IR of femoat's kernels, and the solver's stored fingerprints hold).

Installed by :func:`install` when femoat first imports numba (:mod:`femoat.compilation.jit`),
on the numba versions whose ``ssa`` module was read and tested (:data:`NUMBA_VERSIONS`);
``FEMOAT_FAST_SSA=0`` leaves numba's own.
"""

from collections import defaultdict

from femoat.compilation import numba_version

NUMBA_VERSIONS = ((0, 68), (0, 68))
"""The first and last numba minor versions whose ``numba.core.ssa`` this module was read and
tested against (both ends included)."""

_installed = []


def supported():
    """Whether this numba's SSA module is one :func:`run_ssa` knows."""
    return numba_version.supported(NUMBA_VERSIONS)


def install():
    """Make numba's SSA reconstruction use :func:`run_ssa` (once a process). Returns whether it
    is installed (False on an unknown numba, or with ``FEMOAT_FAST_SSA=0``)."""
    if _installed:
        return True
    if not numba_version.wanted("FEMOAT_FAST_SSA", NUMBA_VERSIONS):
        return False
    from numba.core import ssa

    if not all(hasattr(ssa, name) for name in (
            "_run_ssa", "_iterated_domfronts", "_find_defs_violators", "_CacheListVars",
            "_make_states", "_compute_phi_locations", "_run_ssa_block_pass",
            "_FreshVarHandler", "_FixSSAVars")):
        return False
    run_ssa.__wrapped__ = ssa._run_ssa
    ssa._run_ssa = run_ssa
    _installed.append(True)
    return True


def run_ssa(blocks):
    """numba's ``_run_ssa(blocks)``: the blocks of a function in SSA form (new blocks; the
    statements that change are new, the others shared, as numba's)."""
    from numba.core import errors, ir, ssa
    from numba.core.analysis import compute_cfg_from_blocks

    if not blocks:
        return {}
    cfg = compute_cfg_from_blocks(blocks)
    df_plus = ssa._iterated_domfronts(cfg)
    violators = ssa._find_defs_violators(blocks, cfg)
    if not violators:
        return blocks  # (numba's returns its argument too)
    cache_list_vars = ssa._CacheListVars()
    out = {}
    for label, blk in blocks.items():
        new = ir.Block(scope=blk.scope, loc=blk.loc)
        new.body = list(blk.body)
        out[label] = new
    position = {label: k for k, label in enumerate(out)}
    mentions = defaultdict(set)  # variable name -> labels of the blocks naming it
    for label, blk in out.items():
        for stmt in blk.body:
            for var in stmt.list_vars():
                mentions[var.name].add(label)
    for varname in violators:
        labels = sorted(mentions[varname], key=position.__getitem__)
        defmap = _fresh_vars(out, labels, varname)
        _fix_ssa_vars(out, labels, varname, defmap, cfg, df_plus, cache_list_vars)
    if compute_cfg_from_blocks(out) != cfg:
        raise errors.CompilerError("CFG mutated in SSA pass")
    return out


def _rewrite(blocks, labels, states, handler):
    """numba's ``_run_block_rewrite`` on the blocks ``labels`` only, in place."""
    from numba.core import ssa

    for label in labels:
        blk = blocks[label]
        states["label"] = label
        states["block"] = blk
        body = list(ssa._run_ssa_block_pass(states, blk, handler))
        assert all(stmt is not None for stmt in body)
        blk.body = body


def _fresh_vars(blocks, labels, varname):
    """numba's ``_fresh_vars``: the assignments to ``varname`` renamed; returns the map of
    each block's definitions."""
    from numba.core import ssa

    states = ssa._make_states(blocks)
    states["varname"] = varname
    states["defmap"] = defmap = defaultdict(list)
    _rewrite(blocks, labels, states, ssa._FreshVarHandler())
    return defmap


def _fix_ssa_vars(blocks, labels, varname, defmap, cfg, df_plus, cache_list_vars):
    """numba's ``_fix_ssa_vars``: every use of ``varname`` pointed at its reaching definition,
    phi nodes prepended where definitions meet."""
    from numba.core import ssa

    states = ssa._make_states(blocks)
    states["varname"] = varname
    states["defmap"] = defmap
    states["phimap"] = phimap = defaultdict(list)
    states["cfg"] = cfg
    states["phi_locations"] = ssa._compute_phi_locations(df_plus, defmap)
    _rewrite(blocks, labels, states, ssa._FixSSAVars(cache_list_vars))
    for label, philist in phimap.items():
        blk = blocks[label]
        blk.body = philist + blk.body

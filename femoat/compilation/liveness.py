"""numba's variable liveness, with the definitions reaching each block found once per loop.

numba asks which variables are alive at the entry of each block every time it post-processes
a function's IR (``numba.core.analysis.compute_live_map``, about 2,200 times in a cold compile
of femoat's loop, each time on the whole function). It first finds, for each block, the
variables defined or used in any block that can reach it, by sweeping the blocks in
topological order and pushing each block's set into its successors until no set grows; in a
function whose blocks mostly sit inside one large loop (the solver's step loop, with its helpers
inlined) every sweep unites sets of thousands of names along every edge, twice or more.

:func:`compute_live_map` gives the same sets: the blocks that reach one another (a strongly
connected component of the control-flow graph) share one set, built once, and the components
are visited once in topological order. The backward liveness pass that follows is numba's
(a worklist instead of repeated sweeps). Both are least fixed points of the same equations,
so the result is the same set for every block (``tests/test_liveness.py`` compares the two on
the IR of femoat's largest kernels, and the solver's stored fingerprints hold).

Installed by :func:`install` when femoat first imports numba (:mod:`femoat.compilation.jit`),
on the numba versions whose ``analysis`` module was read and tested (:data:`NUMBA_VERSIONS`);
``FEMOAT_FAST_LIVENESS=0`` leaves numba's own.
"""

from collections import defaultdict

from femoat.compilation import numba_version

NUMBA_VERSIONS = ((0, 68), (0, 68))
"""The first and last numba minor versions whose ``compute_live_map`` this module was read and
tested against (both ends included)."""

_installed = []


def install():
    """Make numba's liveness analysis use :func:`compute_live_map` (once a process). Returns
    whether it is installed (False on an unknown numba, or with ``FEMOAT_FAST_LIVENESS=0``)."""
    if _installed:
        return True
    if not numba_version.wanted("FEMOAT_FAST_LIVENESS", NUMBA_VERSIONS):
        return False
    from numba.core import analysis, ir_utils

    compute_live_map.__wrapped__ = analysis.compute_live_map
    analysis.compute_live_map = compute_live_map
    ir_utils.compute_live_map = compute_live_map
    _installed.append(True)
    return True


def compute_live_map(cfg, blocks, var_use_map, var_def_map):
    """The variables alive at the entry of each block of ``blocks`` (a dict: block label to a
    set of names), as numba's ``analysis.compute_live_map`` computes them, from the control-flow
    graph ``cfg`` and each block's used and defined names."""
    reach = reaching_names(cfg, var_use_map, var_def_map)
    live = {label: set(var_use_map[label]) for label in blocks}
    order = cfg.topo_order()
    pushes = set(order)  # numba pushes names back from the blocks of the order only
    pending = list(order)
    queued = set(pending)
    while pending:
        label = pending.pop()
        queued.discard(label)
        alive = live[label]
        for pred, _ in cfg.predecessors(label):
            grown = (alive & reach[pred]) - var_def_map[pred]
            if not grown <= live[pred]:
                live[pred] |= grown
                if pred in pushes and pred not in queued:
                    queued.add(pred)
                    pending.append(pred)
    return live


def reaching_names(cfg, var_use_map, var_def_map):
    """For each block, the names used or defined in any block of the topological order that
    reaches it (itself included), following the graph's edges: numba's ``def_reach`` fixed
    point, one set per strongly connected component. A ``defaultdict(set)``, as numba's."""
    order = list(cfg.topo_order())
    succ = {label: [s for s, _ in cfg.successors(label)] for label in order}
    for targets in list(succ.values()):
        for s in targets:
            succ.setdefault(s, [])
    component = _components(succ)  # label -> component index, components in reverse topo order
    count = max(component.values(), default=-1) + 1
    names = [set() for _ in range(count)]
    for label in order:
        names[component[label]] |= var_def_map[label] | var_use_map[label]
    into = [set() for _ in range(count)]
    for label, targets in succ.items():
        c = component[label]
        for s in targets:
            if component[s] != c:
                into[component[s]].add(c)
    # Tarjan numbers components so that every edge between two goes to a lower index: visit
    # the highest first, and each component's sources are complete before it is reached.
    for c in range(count - 1, -1, -1):
        for source in into[c]:
            names[c] |= names[source]
    reach = defaultdict(set)
    for label in succ:
        reach[label] = names[component[label]]
    return reach


def _components(succ):
    """Tarjan's strongly connected components of the graph ``succ`` (label -> successor
    labels), iteratively: label -> component index, every edge from one component to another
    going to a lower index."""
    index, low, component = {}, {}, {}
    stack, on_stack = [], set()
    counter = 0
    found = 0
    for root in succ:
        if root in index:
            continue
        work = [(root, iter(succ[root]))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, targets = work[-1]
            for target in targets:
                if target not in index:
                    index[target] = low[target] = counter
                    counter += 1
                    stack.append(target)
                    on_stack.add(target)
                    work.append((target, iter(succ[target])))
                    break
                if target in on_stack:
                    low[node] = min(low[node], index[target])
            else:
                work.pop()
                if work:
                    parent = work[-1][0]
                    low[parent] = min(low[parent], low[node])
                if low[node] == index[node]:
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component[member] = found
                        if member == node:
                            break
                    found += 1
    return component

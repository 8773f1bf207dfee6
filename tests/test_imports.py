"""The package's import graph: no circle, and no import of a higher layer.

Every ``import femoat...`` in every module counts, at module level or inside a function (a
function-level import is still a dependency: it only moves the cost to the call). The layers
below are the house plan, lowest first; a module may import its own layer and the ones below.
A module belongs to the layer of the longest prefix listed.
"""

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "femoat"

LAYERS = [
    # 0 foundations: units, files, compiled-code plumbing, records
    ("femoat", "femoat.units", "femoat.checks", "femoat.atomic", "femoat.compilation",
     "femoat.dense_peaks", "femoat.ground_motions"),
    # 1 constitutive laws: contact laws, structural materials, isolation bearings
    ("femoat.contact", "femoat.structure.materials", "femoat.bearings"),
    # 2 moat walls (FE models, reduction, presets)
    ("femoat.walls",),
    # 3 the building and its pounding model (in plan: femoat.plan)
    ("femoat.structure", "femoat.plan"),
    # 4 time integration: the building solver, the single-impact solver
    ("femoat.integration", "femoat.impact"),
    # 5 runs and what they produce; the warm-up; the OpenSees twin
    ("femoat.results", "femoat.collapse", "femoat.run",
     "femoat.startup",
     "femoat.opensees"),
    # 6 figures and renderings (never imported by layers 0-5)
    ("femoat.plotting", "femoat.render"),
    # 7 studies and scenarios
    ("femoat.paper", "femoat.scenario", "femoat.suite", "femoat.report", "femoat.studies"),
    # 8 the command line
    ("femoat.commands", "femoat.cli"),
]


def _module_name(path):
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _modules():
    return {_module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def _imports(name, path, modules):
    """The femoat modules ``name`` imports (``from a import b`` counts as ``a.b`` when b is a
    module, else as ``a``)."""
    is_package = path.name == "__init__.py"
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names if a.name.split(".")[0] == "femoat")
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                pkg = name.split(".") if is_package else name.split(".")[:-1]
                pkg = pkg[: len(pkg) - (node.level - 1)]
                base = ".".join(pkg + ([base] if base else []))
            if base.split(".")[0] != "femoat":
                continue
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                out.add(sub if sub in modules else base)
    out.discard(name)
    return out


def _graph():
    modules = _modules()
    return {name: _imports(name, path, modules) for name, path in modules.items()}


def _layer(name):
    best, level = -1, None
    for i, prefixes in enumerate(LAYERS):
        for p in prefixes:
            if (name == p or name.startswith(p + ".")) and len(p) > best:
                best, level = len(p), i
    return level


def test_every_module_has_a_layer():
    assert [m for m in _modules() if _layer(m) is None] == []


def test_no_module_imports_a_higher_layer():
    graph = _graph()
    upward = sorted(f"{m} (layer {_layer(m)}) imports {d} (layer {_layer(d)})"
                    for m, deps in graph.items() for d in deps if _layer(d) > _layer(m))
    assert upward == []


def test_no_import_circle():
    graph = _graph()
    # a package's __init__ re-exporting its submodules is not a circle when the submodules
    # import their siblings directly; an edge submodule -> own package is one
    cycles, state = [], {}

    def visit(m, stack):
        state[m] = 1
        stack.append(m)
        for d in sorted(graph.get(m, ())):
            if state.get(d) == 1:
                cycles.append(" -> ".join(stack[stack.index(d):] + [d]))
            elif d not in state:
                visit(d, stack)
        stack.pop()
        state[m] = 2

    for m in sorted(graph):
        if m not in state:
            visit(m, [])
    assert cycles == []

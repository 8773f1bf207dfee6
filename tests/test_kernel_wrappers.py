"""Kernels that only compiled kernels call are built without numba's Python-argument wrapper
(``njit(python=False)``, femoat.compilation.jit): the kernels taking the loop's bundles, whose
wrappers unboxed about a thousand values each. A call from Python still works, through a copy
of the kernel with the wrapper; every kernel is built without numba's C wrapper.
"""

import importlib
import inspect

import numpy as np
import pytest

from femoat.compilation.exports import EXPORTS
from femoat.compilation.jit import Kernel, njit


@njit(python=False)
def _scaled_sum(a, k):
    s = 0.0
    for i in range(a.size):
        s += k * a[i]
    return s


@njit
def _caller(a):
    return _scaled_sum(a, 2.0) + 1.0


def test_an_internal_kernel_gives_the_same_numbers_from_python_and_from_a_kernel():
    a = np.array([0.5, -1.25, 3.0])
    # 2·(0.5 − 1.25 + 3) + 1 = 5.5, exact in binary
    assert _caller(a) == 5.5
    assert _scaled_sum(a, 2.0) == 4.5
    inner = _scaled_sum.dispatcher
    outer = _scaled_sum.python_dispatcher
    assert inner.targetoptions.get("no_cpython_wrapper") is True
    assert outer is not inner and not outer.targetoptions.get("no_cpython_wrapper")
    # the Python copy is its own function for numba's cache (its index is named after it)
    assert outer.py_func.__qualname__ == "_scaled_sum__python"
    assert outer.py_func.__code__ is _scaled_sum.py_func.__code__
    # numba compiled the compiled-code version for the kernel, the copy for Python
    assert len(inner.signatures) == 1 and len(outer.signatures) == 1
    # every kernel is built without the C wrapper
    assert _caller.dispatcher.targetoptions.get("no_cfunc_wrapper") is True
    assert _caller.python_dispatcher is _caller.dispatcher


def test_python_must_be_true_or_false():
    with pytest.raises(TypeError, match=r"python = 'no'.*True .*False"):
        njit(python="no")(lambda x: x)


BUNDLES = {"model", "state", "settings", "work", "rec"}
"""The parameter names of the loop's bundles (femoat.integration.bundles), in every kernel."""


def _kernels():
    """Every femoat kernel, from the kernel sources (folders without an ``__init__`` too)."""
    from femoat.compilation.sources import PACKAGE, sources

    for path in sources("kernels"):
        name = ".".join(("femoat",) + path.relative_to(PACKAGE).with_suffix("").parts)
        module = importlib.import_module(name.removesuffix(".__init__"))
        for value in vars(module).values():
            if isinstance(value, Kernel) and value.py_func.__module__ == module.__name__:
                yield value


def test_every_kernel_taking_the_loops_bundles_is_internal_unless_python_calls_it():
    # The rule that keeps the compile's saving: a compiled (not inlined) kernel that takes a
    # bundle is called from the loop; only the solver's entry points are called from Python.
    checked = 0
    for kernel in _kernels():
        if kernel.options.get("inline", "never") != "never":
            continue
        takes = set(inspect.signature(kernel.py_func).parameters) & BUNDLES
        exported = EXPORTS.get(kernel.py_func.__name__) == kernel.py_func.__module__
        if exported:
            assert kernel.python, kernel
        elif takes:
            assert not kernel.python, kernel
            checked += 1
    assert checked >= 9  # record_sample, coupled_step, restart, check_limits, ... (9 today)

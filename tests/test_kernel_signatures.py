"""A kernel called from compiled code is compiled once per argument types, not once per constant
(femoat.compilation.jit: numba would type ``f(p, 0)`` as ``f(p, Literal[int](0))`` and compile
``f`` anew for each constant it is called with)."""

import numpy as np

from femoat.compilation.jit import njit


@njit
def _callee(a, o, flag):
    # branches on both arguments: what a literal would specialise away
    s = 0.0
    for k in range(o, a.size):
        s += a[k]
    return -s if flag else s


@njit
def _caller(a, n, out):
    out[0] = _callee(a, 0, True)      # constants: Literal[int](0), Literal[bool](True)
    out[1] = _callee(a, 2, False)     # two other constants
    out[2] = _callee(a, n, n > 1)     # variables: int64, bool


def test_constants_and_variables_share_one_compiled_callee():
    a = np.array([1.0, 2.0, 4.0, 8.0])
    out = np.zeros(3)
    _caller(a, 1, out)
    # the sums by hand: all four entries 15, from index 2 on 12, from index 1 on 14 (n = 1:
    # flag False)
    np.testing.assert_array_equal(out, [-15.0, 12.0, 14.0])
    from numba.core import types

    sigs = _callee.dispatcher.signatures
    assert len(sigs) == 1, sigs
    assert not any(isinstance(t, types.Literal) for t in sigs[0]), sigs

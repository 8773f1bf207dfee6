"""llvmlite's IR builder positioned before a block's terminator in constant time.

numba's lowering allocates every local variable in the function's entry block
(``cgutils.alloca_once``: ``builder.goto_block(entry)``), and llvmlite's ``goto_block``
positions the builder before the block's terminator by searching the block's instruction list
for it from the start (``IRBuilder.position_before``: ``instructions.index``). femoat's loop
has thousands of locals, so each new one searched an entry block thousands of instructions
long: quadratic, about 2 s of a cold compile.

:func:`position_before` finds the instruction at the end of the list first (a terminator is
always there) and otherwise searches as llvmlite does: the same block and position. Installed
by :func:`install` when femoat first imports numba (:mod:`femoat.compilation.jit`), on the
llvmlite versions whose ``ir.builder`` was read and tested (:data:`LLVMLITE_VERSIONS`);
``FEMOAT_FAST_IR_BUILDER=0`` leaves llvmlite's own.
"""

import os

LLVMLITE_VERSIONS = ((0, 50), (0, 50))
"""The first and last llvmlite minor versions whose ``IRBuilder`` this module was read and
tested against (both ends included)."""

_installed = []


def install():
    """Make llvmlite's ``IRBuilder.position_before`` :func:`position_before` (once a process).
    Returns whether it is installed (False on an unknown llvmlite, or with
    ``FEMOAT_FAST_IR_BUILDER=0``)."""
    if _installed:
        return True
    import llvmlite
    from llvmlite.ir.builder import IRBuilder

    low, high = LLVMLITE_VERSIONS
    version = tuple(int(p) for p in llvmlite.__version__.split(".")[:2])
    if os.environ.get("FEMOAT_FAST_IR_BUILDER", "1") == "0" or not low <= version <= high:
        return False
    position_before.__wrapped__ = IRBuilder.position_before
    IRBuilder.position_before = position_before
    _installed.append(True)
    return True


def position_before(self, instr):
    """Position the builder immediately before ``instr``, in ``instr``'s block: llvmlite's
    ``IRBuilder.position_before``."""
    block = instr.parent
    instructions = block.instructions
    if instructions and instructions[-1] is instr:
        self._block = block
        self._anchor = len(instructions) - 1
    else:
        position_before.__wrapped__(self, instr)

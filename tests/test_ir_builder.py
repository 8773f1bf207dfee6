"""llvmlite's builder positioned before a terminator in constant time
(femoat.compilation.ir_builder).

What must hold: the builder's block and position are llvmlite's for every instruction of a
block (the terminator, the first, one in the middle), and numba's way of using it (an
allocation at the end of a long entry block, through ``goto_block``) puts the instruction just
before the terminator.
"""

import pytest


def _block(n):
    from llvmlite import ir

    module = ir.Module()
    fn = ir.Function(module, ir.FunctionType(ir.VoidType(), []), name="f")
    entry = fn.append_basic_block("entry")
    builder = ir.IRBuilder(entry)
    slots = [builder.alloca(ir.DoubleType(), name=f"x{i}") for i in range(n)]
    builder.ret_void()
    return builder, entry, slots


def test_every_position_is_llvmlites_and_an_allocation_lands_before_the_terminator():
    from femoat.compilation import ir_builder, jit

    jit._register()
    if not ir_builder._installed:
        pytest.skip("femoat.compilation.ir_builder is not installed here (llvmlite version "
                    "or FEMOAT_FAST_IR_BUILDER=0)")
    from llvmlite import ir

    builder, entry, slots = _block(500)
    theirs, _, _ = _block(500)
    llvmlites = ir_builder.position_before.__wrapped__
    for instr in (entry.terminator, slots[0], slots[250], slots[-1]):
        builder.position_before(instr)
        llvmlites(theirs, theirs.block.instructions[entry.instructions.index(instr)])
        assert builder.block is entry and builder._anchor == theirs._anchor
        assert entry.instructions[builder._anchor] is instr
    # numba's alloca_once: at the end of the entry block, before its terminator
    with builder.goto_block(entry):
        new = builder.alloca(ir.DoubleType(), name="late")
    assert entry.instructions[-2] is new and entry.instructions[-1] is entry.terminator
    assert len(entry.instructions) == 502

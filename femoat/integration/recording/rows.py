"""The recorder's row of a sample: sample k lives in row k of a recorder that keeps every
sample, and in row k modulo its length in the ring of a run without history."""

from femoat.compilation.jit import njit


@njit(cache=True, inline="always")
def row(k, rows):
    """The row of sample ``k`` in a recorder of ``rows`` rows (no division while k < rows: the
    step loop records every sample)."""
    return k if k < rows else k % rows

"""Structured-mesh coordinates that put element edges on the impact patch edges."""

import math

import numpy as np


def axis_coordinates(length, divisions, breaks=(), name="divisions"):
    """Node coordinates on [0, length] [in] with element size <= length/divisions.

    Every value in ``breaks`` inside (0, length) becomes a node, so the impact point or the
    edges of the impact patch fall on element boundaries; each interval between consecutive
    breaks is split uniformly.
    """
    if int(divisions) != divisions or divisions < 1:
        raise ValueError(f"{name} (elements along that side) must be a positive integer, got "
                         f"{divisions!r}")
    size = length / divisions
    tol = 1e-9 * length
    cuts = sorted({0.0, float(length), *(float(b) for b in breaks if tol < b < length - tol)})
    pieces = []
    for a, b in zip(cuts[:-1], cuts[1:]):
        n = max(1, math.ceil((b - a) / size - 1e-9))
        pieces.append(np.linspace(a, b, n + 1)[:-1])
    pieces.append([float(length)])
    return np.concatenate(pieces)

"""Integer codes of the structural materials, shared by the kernels and the Python side.

The compiled loop selects a material by one of these integers (numba reads module-level integers
as compile-time constants).
"""

ELASTIC = 0
BILINEAR = 1
IMK = 2
from femoat.bearings.registry import AXIS_CODE_START as BEARING  # noqa: E402

# BEARING: the first bearing kind's code; kind k of femoat.bearings.registry has code BEARING + k
FRICTION_PENDULUM = BEARING + 0
"""The single friction pendulum (:mod:`femoat.bearings.friction_pendulum`), kind 0."""

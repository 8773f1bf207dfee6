"""Integer codes of the structural materials, shared by the kernels and the Python side.

The compiled loop selects a material by one of these integers (numba reads module-level integers
as compile-time constants).
"""

ELASTIC = 0
BILINEAR = 1
IMK = 2
FRICTION_PENDULUM = 3

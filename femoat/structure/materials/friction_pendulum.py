"""The single friction pendulum on one axis, the isolator of a 1D building.

It lives with the other bearing kinds in :mod:`femoat.bearings.friction_pendulum` (one module for
one axis and plan); these are its names as the materials package has always given them.
"""

from femoat.bearings.friction_pendulum import (
    N_PARAMS,
    N_STATE,
    FrictionPendulum,
    friction_coefficient,
)
from femoat.bearings.friction_pendulum import axis_commit as friction_pendulum_commit
from femoat.bearings.friction_pendulum import axis_energy as friction_pendulum_energy
from femoat.bearings.friction_pendulum import axis_trial as friction_pendulum_trial

__all__ = [
    "N_PARAMS",
    "N_STATE",
    "FrictionPendulum",
    "friction_coefficient",
    "friction_pendulum_commit",
    "friction_pendulum_energy",
    "friction_pendulum_trial",
]

"""The bidirectional friction pendulum: the single friction pendulum's plan face.

It lives with the other bearing kinds in :mod:`femoat.bearings.friction_pendulum` (one module for
one axis and plan); these are its names as the plan package has always given them.
"""

from femoat.bearings.friction_pendulum import (
    MAX_SUBSTEPS,
    N_PARAMS,
    N_STATE_PLAN,
    BidirectionalFrictionPendulum,
    plan_friction_coefficient,
)
from femoat.bearings.friction_pendulum import plan_commit as plan_friction_pendulum_path_commit
from femoat.bearings.friction_pendulum import plan_energy as plan_friction_pendulum_energy
from femoat.bearings.friction_pendulum import plan_return_commit as plan_friction_pendulum_commit
from femoat.bearings.friction_pendulum import plan_return_trial as plan_friction_pendulum_trial
from femoat.bearings.friction_pendulum import plan_trial as plan_friction_pendulum_path_trial
from femoat.bearings.friction_pendulum import plan_z as plan_friction_pendulum_z
from femoat.bearings.friction_pendulum import plan_z_trial as plan_friction_pendulum_z_trial

N_STATE = N_STATE_PLAN

__all__ = [
    "MAX_SUBSTEPS",
    "N_PARAMS",
    "N_STATE",
    "BidirectionalFrictionPendulum",
    "plan_friction_coefficient",
    "plan_friction_pendulum_commit",
    "plan_friction_pendulum_energy",
    "plan_friction_pendulum_path_commit",
    "plan_friction_pendulum_path_trial",
    "plan_friction_pendulum_trial",
    "plan_friction_pendulum_z",
    "plan_friction_pendulum_z_trial",
]

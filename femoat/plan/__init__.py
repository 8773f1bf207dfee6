"""The building in plan (issue 18): two horizontal directions, x and y.

What exists so far: the bidirectional friction pendulum bearing
(:mod:`femoat.plan.bearing`); the record pairs that drive a plan model live with the ground
motions (:mod:`femoat.ground_motions.pair`). ``docs/plan.md`` says what comes next.

Conventions (as in :mod:`femoat.ground_motions.pair`): plan axes x, y of the building, z up;
angles positive from +x toward +y [deg]; kip, in, s. Vectors in plan are (x, y) pairs.
"""

from femoat.plan.bearing import (
    BidirectionalFrictionPendulum,
    plan_friction_coefficient,
    plan_friction_pendulum_commit,
    plan_friction_pendulum_energy,
    plan_friction_pendulum_trial,
)

__all__ = [
    "BidirectionalFrictionPendulum",
    "plan_friction_coefficient",
    "plan_friction_pendulum_commit",
    "plan_friction_pendulum_energy",
    "plan_friction_pendulum_trial",
]

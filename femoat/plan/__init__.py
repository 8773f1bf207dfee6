"""The building in plan (issue 18): two horizontal directions, x and y, no torsion.

The model a plan solver integrates: :class:`PlanModel` (:mod:`femoat.plan.model`), a
:class:`PlanBuilding` (:mod:`femoat.plan.building`: floors translating in x and y, story springs
per direction, P-Delta in both) on the bidirectional friction pendulum
(:mod:`femoat.plan.bearing`, friction coupled in plan) in a rectangular moat of up to four
:class:`PlanWall` entries (:mod:`femoat.plan.moat`). The record pairs that drive it live with the
ground motions (:mod:`femoat.ground_motions.pair`); its OpenSees twin in 3D is
:mod:`femoat.opensees.plan`. ``docs/plan.md`` says what exists and what comes next.

Conventions (as in :mod:`femoat.ground_motions.pair`): plan axes x, y of the building, z up;
angles positive from +x toward +y [deg]; kip, in, s. Vectors in plan are (x, y) pairs; walls
in the order +x, −x, +y, −y.
"""

from femoat.plan.bearing import (
    BidirectionalFrictionPendulum,
    plan_friction_coefficient,
    plan_friction_pendulum_commit,
    plan_friction_pendulum_energy,
    plan_friction_pendulum_trial,
)
from femoat.plan.building import PlanBuilding
from femoat.plan.moat import SIDES, PlanWall, rectangular_moat, wall_side
from femoat.plan.model import PackedPlanModel, PlanLayout, PlanModel

__all__ = [
    "SIDES",
    "BidirectionalFrictionPendulum",
    "PackedPlanModel",
    "PlanBuilding",
    "PlanLayout",
    "PlanModel",
    "PlanWall",
    "plan_friction_coefficient",
    "plan_friction_pendulum_commit",
    "plan_friction_pendulum_energy",
    "plan_friction_pendulum_trial",
    "rectangular_moat",
    "wall_side",
]

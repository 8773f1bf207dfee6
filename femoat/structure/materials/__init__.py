"""Nonlinear springs of the base-isolated building: story springs and isolators.

Each material is a frozen dataclass (parameters with units, validated) that packs a float64
params array ``p`` and a virgin committed state ``s`` for the compiled kernels in
:mod:`femoat.structure.materials.kernels`, selected by an integer code, and answers its own
questions: ``yield_deformation`` [in] (None if it never yields; the solver scales a story's
error by it). The codes and params:

* ``ELASTIC`` (0), :class:`Elastic`: p = [k]
* ``BILINEAR`` (1), :class:`Bilinear`: p = [k0, Fy, b]
* ``IMK`` (2), :class:`IMKBilinear`: p = [K0, as, My, Λ, c, θp, θpc, Res, θu, D]
* ``FRICTION_PENDULUM`` (3), :class:`FrictionPendulum`: p = [W, R, u_y, μ_slow, μ_fast, a, v_reg]

Units: kip, in, s (:mod:`femoat.units`).
"""

from femoat.structure.materials.bilinear import Bilinear
from femoat.structure.materials.codes import BILINEAR, ELASTIC, FRICTION_PENDULUM, IMK
from femoat.structure.materials.elastic import Elastic
from femoat.structure.materials.friction_pendulum import FrictionPendulum
from femoat.structure.materials.imk import IMKBilinear
from femoat.structure.materials.kernels import (
    material_commit,
    material_recoverable_energy,
    material_trial,
    param_size,
    state_size,
)

__all__ = [
    "BILINEAR",
    "ELASTIC",
    "FRICTION_PENDULUM",
    "IMK",
    "Bilinear",
    "Elastic",
    "FrictionPendulum",
    "IMKBilinear",
    "material_commit",
    "material_recoverable_energy",
    "material_trial",
    "param_size",
    "state_size",
]

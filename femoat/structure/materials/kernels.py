"""Compiled entry points the time-stepping loop calls, dispatching on the material code.

Conventions: deformation u [in] and its rate v [in/s] are positive in the element's positive
direction; the force f [kip] is the force the element resists with (positive for positive u in
the elastic range). Every material has a params array ``p`` and a committed state array ``s``
(float64, length :func:`state_size`).

* :func:`material_trial` returns ``(f, df/du, df/dv)`` for a trial (u, v) from the *committed*
  state, which it never modifies, so a Newton iteration may call it any number of times; df/du is
  the consistent tangent of that trial force.
* :func:`material_commit` advances ``s`` in place to the converged (u, v), once per step.
* :func:`material_recoverable_energy` is the elastic energy [kip·in] stored at the committed
  state: hysteretic dissipation = ∫f du − recoverable.

Nothing here allocates.
"""

import numpy as np

from femoat.compilation.jit import njit
from femoat.structure.materials import bilinear, elastic, friction_pendulum, imk
from femoat.structure.materials.codes import BILINEAR, ELASTIC, FRICTION_PENDULUM, IMK
from femoat.structure.materials.bilinear import bilinear_commit, bilinear_energy, bilinear_trial
from femoat.structure.materials.elastic import elastic_commit, elastic_energy, elastic_trial
from femoat.structure.materials.friction_pendulum import (
    friction_pendulum_commit,
    friction_pendulum_energy,
    friction_pendulum_trial,
)
from femoat.structure.materials.imk import imk_commit, imk_energy, imk_trial

_STATE_SIZES = {
    ELASTIC: elastic.N_STATE,
    BILINEAR: bilinear.N_STATE,
    IMK: imk.N_STATE,
    FRICTION_PENDULUM: friction_pendulum.N_STATE,
}
_PARAM_SIZES = {
    ELASTIC: elastic.N_PARAMS,
    BILINEAR: bilinear.N_PARAMS,
    IMK: imk.N_PARAMS,
    FRICTION_PENDULUM: friction_pendulum.N_PARAMS,
}


def state_size(code: int) -> int:
    """Length of the committed-state array of material ``code``."""
    try:
        return _STATE_SIZES[code]
    except KeyError:
        raise ValueError(
            f"code = {code!r}: unknown material code; use one of {sorted(_STATE_SIZES)}."
        ) from None


def param_size(code: int) -> int:
    """Length of the params array of material ``code``."""
    state_size(code)
    return _PARAM_SIZES[code]


@njit(cache=True)
def material_trial(code, p, s, u, v):
    """Force [kip], df/du [kip/in] and df/dv [kip·s/in] at trial (u [in], v [in/s])."""
    if code == ELASTIC:
        return elastic_trial(p, s, u)
    if code == BILINEAR:
        return bilinear_trial(p, s, u)
    if code == IMK:
        return imk_trial(p, s, u)
    if code == FRICTION_PENDULUM:
        return friction_pendulum_trial(p, s, u, v)
    return np.nan, np.nan, np.nan


@njit(cache=True)
def material_commit(code, p, s, u, v):
    """Advance the committed state ``s`` in place to the converged (u, v)."""
    if code == ELASTIC:
        elastic_commit(p, s, u)
    elif code == BILINEAR:
        bilinear_commit(p, s, u)
    elif code == IMK:
        imk_commit(p, s, u)
    elif code == FRICTION_PENDULUM:
        friction_pendulum_commit(p, s, u, v)


@njit(cache=True)
def material_recoverable_energy(code, p, s):
    """Elastic energy [kip·in] stored at the committed state."""
    if code == ELASTIC:
        return elastic_energy(p, s)
    if code == BILINEAR:
        return bilinear_energy(p, s)
    if code == IMK:
        return imk_energy(p, s)
    if code == FRICTION_PENDULUM:
        return friction_pendulum_energy(p, s)
    return np.nan

"""Compiled entry points the time-stepping loop calls, dispatching on the material code.

Conventions: deformation u [in] and its rate v [in/s] are positive in the element's positive
direction; the force f [kip] is the force the element resists with (positive for positive u in
the elastic range). Every material has a params array ``p`` and a committed state array ``s``
(float64, length :func:`state_size`; in a packed model a row one entry longer, below).

* :func:`material_trial` returns ``(f, df/du, df/dv)`` for a trial (u, v) from the *committed*
  state, which it never modifies, so a Newton iteration may call it any number of times; df/du is
  the consistent tangent of that trial force.
* :func:`material_commit` advances ``s`` in place to the converged (u, v), once per step.
* :func:`material_recoverable_energy` is the elastic energy [kip·in] stored at the committed
  state: hysteretic dissipation = ∫f du − recoverable.

The state rows of a packed model's elements (``el_S``) have one column more than the widest
material's state, :data:`DURATION`: for a material whose return over the step depends on its
duration (the triple pendulum's velocity-dependent friction, whose one-axis state ends with that
entry too), the duration [s] of the step the loop is solving from the committed state to the
trial, written by Newmark's solve (:func:`stamp_duration`; 0 before the first step); −1 for every
other material, which never reads it. The one-axis kink search skips an element whose column is
not −1 (its tangent along a step depends on the step's duration, not only on a branch).

The isolation bearings' codes start at ``BEARING`` (one code per bearing kind of
:mod:`femoat.bearings.registry`, its one-axis kernels through the registry's dispatcher).

Nothing here allocates.
"""

import numpy as np

from femoat.bearings import registry
from femoat.bearings.dispatch import bearing_axis_commit, bearing_axis_energy, bearing_axis_trial
from femoat.bearings.friction_pendulum import axis_commit as fp_axis_commit
from femoat.bearings.friction_pendulum import axis_trial as fp_axis_trial
from femoat.compilation.jit import njit
from femoat.structure.materials import bilinear, elastic, imk
from femoat.structure.materials.bilinear import bilinear_commit, bilinear_energy, bilinear_trial
from femoat.structure.materials.codes import BEARING, BILINEAR, ELASTIC, IMK
from femoat.structure.materials.elastic import elastic_commit, elastic_energy, elastic_trial
from femoat.structure.materials.imk import imk_commit, imk_energy, imk_trial

DURATION = -1
"""Column of an element's state row that holds the duration [s] of the step being solved."""

DURATION_COLUMNS = 1
"""Columns a packed model's element states carry after the widest material's (:data:`DURATION`)."""

_SIZES = {  # code: (params, state)
    ELASTIC: (elastic.N_PARAMS, elastic.N_STATE),
    BILINEAR: (bilinear.N_PARAMS, bilinear.N_STATE),
    IMK: (imk.N_PARAMS, imk.N_STATE),
}


def _sizes(code):
    if code in _SIZES:
        return _SIZES[code]
    kinds = registry.kinds()
    if isinstance(code, int) and BEARING <= code < BEARING + len(kinds):
        mod = registry.module(code - BEARING)
        return mod.N_PARAMS, mod.N_STATE_AXIS
    known = sorted(_SIZES) + list(range(BEARING, BEARING + len(kinds)))
    raise ValueError(f"code = {code!r}: unknown material code; use one of {known}.")


def state_size(code: int) -> int:
    """Length of the committed-state array of material ``code``."""
    return _sizes(code)[1]


def param_size(code: int) -> int:
    """Length of the params array of material ``code``."""
    return _sizes(code)[0]


@njit(cache=True)
def stamp_duration(el_S, tau):
    """Write the duration ``tau`` [s] of the step about to be solved into the state row of every
    element that reads it (its last entry, :data:`DURATION`, not −1)."""
    last = el_S.shape[1] - 1
    for e in range(el_S.shape[0]):
        if el_S[e, last] != -1.0:
            el_S[e, last] = tau


@njit(cache=True)
def _other_bearing_trial(code, p, s, u, v):
    """The bearing kinds after the friction pendulum, through the dispatcher."""
    return bearing_axis_trial(code - BEARING, p, s, u, v)


@njit(cache=True)
def _other_bearing_commit(code, p, s, u, v):
    """The bearing kinds after the friction pendulum, through the dispatcher."""
    bearing_axis_commit(code - BEARING, p, s, u, v)


@njit(cache=True)
def material_trial(code, p, s, u, v):
    """Force [kip], df/du [kip/in] and df/dv [kip·s/in] at trial (u [in], v [in/s])."""
    if code == ELASTIC:
        return elastic_trial(p, s, u)
    if code == BILINEAR:
        return bilinear_trial(p, s, u)
    if code == IMK:
        return imk_trial(p, s, u)
    if code == BEARING:  # the single friction pendulum, kind 0: called directly
        return fp_axis_trial(p, s, u, v)
    if code > BEARING:
        return _other_bearing_trial(code, p, s, u, v)
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
    elif code == BEARING:  # the single friction pendulum, kind 0: called directly
        fp_axis_commit(p, s, u, v)
    elif code > BEARING:
        _other_bearing_commit(code, p, s, u, v)


@njit(cache=True)
def material_recoverable_energy(code, p, s):
    """Elastic energy [kip·in] stored at the committed state."""
    if code == ELASTIC:
        return elastic_energy(p, s)
    if code == BILINEAR:
        return bilinear_energy(p, s)
    if code == IMK:
        return imk_energy(p, s)
    if code >= BEARING:
        return bearing_axis_energy(code - BEARING, p, s)
    return np.nan

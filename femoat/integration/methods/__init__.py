"""The integration methods of the open phase, one module each, and the registry the loop
dispatches on.

A method's module defines ``NAME``, ``DEFAULT_RTOL``, ``EXPLICIT`` (every stage evaluated from
the committed state: the driver then lands on turning points, looks inside a step for a gap
that closes and reopens in it, and keeps a cruising step), ``QUINTIC_DENSE`` (fifth-order dense
output for the acceleration peaks), the controller's constants ``SAFETY``, ``SHRINK_MIN``,
``GROW_MAX``, ``ERROR_EXPONENT``, and three kernels with the same arguments in every module:

* ``step(hh, ag1, any_closed, model, state, settings, work) -> (solved, err)``: the trial step
  of length ``hh`` into ``work`` and its scaled error (1 = at the tolerance);
* ``retry(t, hh, h, model, state, settings, work, rec) -> (h, failed)``: the step to try after
  one that could not be solved (``failed``: none is left);
* ``next_step(hh, err, h_min) -> h``: the step after an accepted one.

:data:`MODULES` is the registry: a method's code is its position. A new method is its module,
its line in :data:`MODULES` and its branch in each of the three dispatchers below (numba
cannot call a module chosen at run time; the branches are the whole of that cost). Every
contact phase is integrated by :data:`CONTACT` (Newmark/HHT-α), whatever the open phase's
method.
"""

from femoat.compilation.jit import njit
from femoat.integration.methods import ark5, dp5, newmark, tsit5

MODULES = (newmark, dp5, ark5, tsit5)
"""The methods, by code."""
NAMES = tuple(m.NAME for m in MODULES)
"""The methods' names, by code (``Integrator(method=...)``)."""
CODES = {m.NAME: code for code, m in enumerate(MODULES)}
"""{name: code}."""
CONTACT = CODES["newmark"]
"""The method of every contact phase."""
EXPLICIT = tuple(m.EXPLICIT for m in MODULES)
"""Per code: every stage evaluated from the committed state (the module docstring)."""
_SAFETY = tuple(float(m.SAFETY) for m in MODULES)
_SHRINK_MIN = tuple(float(m.SHRINK_MIN) for m in MODULES)
_ERROR_EXPONENT = tuple(float(m.ERROR_EXPONENT) for m in MODULES)
FINE_LANDING = tuple(bool(getattr(m, "FINE_LANDING", False)) for m in MODULES)
"""Per code: plan bearings' kinks and turns off a line landed to ``kinks.FINE_RESOLUTION``."""
QUINTIC_METHODS = tuple(m.NAME for m in MODULES if m.QUINTIC_DENSE)
"""The methods whose open phase has fifth-order dense output (the acceleration crests)."""
EXPLICIT_PAIRS = tuple(m.NAME for m in MODULES if hasattr(m, "PAIR"))
"""The methods that are an explicit pair on dp5's step (``PAIR``): every stage, a plan
bearing's friction state too, read from the committed state and the step's path (refused on
plan bearings with coupled friction)."""
N_STAGES = max(getattr(m, "N_STAGES", 0) for m in MODULES)
"""Stage rows of the work bundle's ``kv``, ``ka``, ``kz``: the most any method takes."""


def module(name):
    """The module of the method ``name``."""
    return MODULES[CODES[name]]


@njit(cache=True, inline="always")
def step(code, hh, ag1, any_closed, model, state, settings, work):
    """The method ``code``'s trial step: (solved, scaled error). ark5 takes dp5's step where no
    friction state moves (``ark5.plan``), through the one inlined copy of the explicit pairs'
    step here, which tsit5 takes with its own tableau."""
    if code == 0:
        return newmark.step(hh, ag1, any_closed, model, state, settings, work)
    how = ark5.plan(model, state, work) if code == 2 else ark5.DP5_STEP
    if how != ark5.COUPLED:
        pair = tsit5.PAIR if code == 3 else dp5.PAIR
        solved, err = dp5.pair_step(pair, hh, ag1, model, state, settings, work)
        if code != 2 or how == ark5.DP5_STEP or (solved and ark5.rates_vanish(model, state, work)):
            return solved, err
    return ark5.step(hh, ag1, any_closed, model, state, settings, work)


@njit(cache=True, inline="always")
def retry(code, t, hh, h, model, state, settings, work, rec):
    """The method ``code``'s step after one it could not solve: (h, failed)."""
    if code == 2:
        return ark5.retry(t, hh, h, model, state, settings, work, rec)
    if code == 1 or code == 3:
        return dp5.retry(t, hh, h, model, state, settings, work, rec)
    return newmark.retry(t, hh, h, model, state, settings, work, rec)


@njit(cache=True, inline="always")
def next_step(code, hh, err, h_min):
    """The method ``code``'s step after an accepted one."""
    if code == 2:
        return ark5.next_step(hh, err, h_min)
    if code == 1 or code == 3:
        return dp5.next_step(hh, err, h_min)
    return newmark.next_step(hh, err, h_min)


@njit(cache=True, inline="always")
def shrink_factor(code, err):
    """Factor of a step rejected with scaled error ``err`` > 1: the method's
    SAFETY·err^ERROR_EXPONENT, at least its SHRINK_MIN."""
    return max(_SHRINK_MIN[code], _SAFETY[code] * err ** _ERROR_EXPONENT[code])

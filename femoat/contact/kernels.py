"""Compiled contact-law entry points the time-stepping loops call, dispatching on the law code.

Conventions (docs/paper.md §2): indentation ``d`` = δ [in] > 0 in contact; ``v`` = δ̇ [in/s] > 0 while
approaching. Forces are compressive-positive [kip]. Every force kernel returns
``(f, df/dδ, df/dδ̇)`` evaluated from the *committed* history ``h`` (never modified here), so a
Newton iteration may call it any number of times; :func:`contact_commit` advances the history once
a step has converged.

Each law lives in its own module with its params layout (``p``, from
:meth:`femoat.contact.laws.ContactLaw.packed`) and kernels: :mod:`~femoat.contact.linear` (E),
:mod:`~femoat.contact.kelvin_voigt` (V), :mod:`~femoat.contact.jankowski` (J),
:mod:`~femoat.contact.hertzdamp` (H), :mod:`~femoat.contact.muthukumar` (M). The history layout
``h`` is in :mod:`femoat.contact.codes`. Adding a law touches its own module, this dispatcher
and the registry in :mod:`femoat.contact.laws`.
"""

from pathlib import Path

import numpy as np

from femoat.jit import njit
from femoat.numba_cache import drop_stale_cache

# the dispatchers below inline the kernels of the sibling modules (numba's cache does not see it)
drop_stale_cache(__file__, sorted(Path(__file__).resolve().parent.glob("*.py")))

from femoat.contact import (  # noqa: E402
    hertzdamp,
    jankowski,
    kelvin_voigt,
    linear,
    muthukumar,
)
from femoat.contact.codes import (  # noqa: E402
    H_D_LAST,
    H_DMAX,
    H_F_LAST,
    H_V0,
    HERTZDAMP,
    JANKOWSKI,
    KELVIN_VOIGT,
    LINEAR,
    MUTHUKUMAR,
    N_HISTORY,
)
from femoat.contact.hertz import K_H, hertz_gradient  # noqa: E402
from femoat.contact.hertzdamp import hertzdamp_energy, hertzdamp_force  # noqa: E402
from femoat.contact.jankowski import jankowski_energy, jankowski_force  # noqa: E402
from femoat.contact.kelvin_voigt import kelvin_voigt_energy, kelvin_voigt_force  # noqa: E402
from femoat.contact.linear import linear_energy, linear_force  # noqa: E402
from femoat.contact.muthukumar import (  # noqa: E402
    muthukumar_commit,
    muthukumar_energy,
    muthukumar_force,
)

__all__ = ["HERTZDAMP", "JANKOWSKI", "KELVIN_VOIGT", "LINEAR", "MUTHUKUMAR", "N_HISTORY",
           "N_PARAMS", "contact_closure", "contact_commit", "contact_force",
           "contact_stored_energy", "recorded_force", "step_commit", "step_force"]

N_PARAMS = max(m.N_PARAMS for m in (linear, kelvin_voigt, jankowski, hertzdamp, muthukumar))
"""Width of a contact's params row (the longest law's; shorter laws leave the rest zero)."""


@njit(cache=True)
def contact_force(code, p, h, d, v):
    """Force [kip] and tangents (df/dδ [kip/in], df/dδ̇ [kip·s/in]) of law ``code``."""
    if d <= 0.0:
        return 0.0, 0.0, 0.0
    if code == LINEAR:
        return linear_force(p, d)
    if code == KELVIN_VOIGT:
        return kelvin_voigt_force(p, d, v)
    if code == JANKOWSKI:
        return jankowski_force(p, d, v)
    if code == HERTZDAMP:
        return hertzdamp_force(p, h, d, v)
    if code == MUTHUKUMAR:
        return muthukumar_force(p, h, d)
    return np.nan, np.nan, np.nan


@njit(cache=True)
def contact_stored_energy(code, p, h, d):
    """Elastic energy [kip·in] the contact would return if unloaded now from indentation ``d``.

    Used by energy balances while a contact is open. Zero at separation for every law.
    """
    if d <= 0.0:
        return 0.0
    if code == LINEAR:
        return linear_energy(p, d)
    if code == KELVIN_VOIGT:
        return kelvin_voigt_energy(p, d)
    if code == JANKOWSKI:
        return jankowski_energy(p, d)
    if code == HERTZDAMP:
        return hertzdamp_energy(p, d)
    if code == MUTHUKUMAR:
        return muthukumar_energy(p, h, d)
    return np.nan


@njit(cache=True)
def contact_closure(h, v):
    """Open a contact episode at gap closure with approach velocity δ̇₀ = ``v`` [in/s].

    Each impact is a new loading of the contact surface: the bilinear law's largest indentation
    starts again from zero, the Hertz spring unloaded (h[H_D_LAST] keeps the committed δ ≤ 0).
    """
    h[H_V0] = v
    h[H_DMAX] = 0.0
    h[H_F_LAST] = 0.0


@njit(cache=True)
def contact_commit(code, h, d):
    """Advance the history of law ``code`` after a converged step ending at indentation ``d``."""
    if code == MUTHUKUMAR:
        muthukumar_commit(h, d)


# ---- implicit time stepping -------------------------------------------------------------------


@njit(cache=True)
def _hertzian(code):
    """Does law ``code`` carry the Hertz spring (its elastic part takes the discrete gradient)?"""
    return code == JANKOWSKI or code == HERTZDAMP


@njit(cache=True)
def step_force(code, p, h, d, v):
    """contact_force for an implicit trapezoidal step from the committed state
    (h[H_D_LAST], h[H_F_LAST]) of an open episode.

    Identical to :func:`contact_force` except: the elastic part k_h·δ^1.5 of the Hertz laws is
    replaced by its discrete gradient (:mod:`femoat.contact.hertz`), and the step that ends a
    contact (δ₁ ≤ 0, from δ₀ > 0) returns the energy stored at δ₀ too; a Kelvin-Voigt episode
    still open at δ ≤ 0 acts as at δ = 0⁺ (its dashpot).
    """
    if d <= 0.0 and code == KELVIN_VOIGT:
        d = 1e-300
    f, kf, cf = contact_force(code, p, h, d, v)
    if not _hertzian(code):
        return f, kf, cf
    if d <= 0.0 and h[H_D_LAST] <= 0.0:
        return f, kf, cf
    fe, kfe = 0.0, 0.0
    if d > 0.0:
        sd = np.sqrt(d)
        fe = p[K_H] * d * sd
        kfe = 1.5 * p[K_H] * sd
    g, kg = hertz_gradient(p[K_H], h[H_D_LAST], h[H_F_LAST], d)
    if d == h[H_D_LAST]:
        g = h[H_F_LAST]  # at the committed state itself (a restart): the force the step ended with
    return f - fe + g, kf - kfe + kg, cf


@njit(cache=True)
def step_commit(code, p, h, d):
    """contact_commit, plus the state (δ_n, f̃_n) the next step's discrete gradient starts from."""
    contact_commit(code, h, d)
    g = 0.0
    if _hertzian(code) and (d > 0.0 or h[H_D_LAST] > 0.0):
        g = hertz_gradient(p[K_H], h[H_D_LAST], h[H_F_LAST], d)[0]
    h[H_D_LAST] = d
    h[H_F_LAST] = g if d > 0.0 else 0.0


@njit(cache=True)
def recorded_force(code, p, h, d, v, f_step):
    """The force [kip] to record for an open episode after a step that used ``f_step``: the law's
    own force at the recorded state for the Hertz laws (their step force differs from it by the
    discrete gradient's O(Δδ²) trapezoidal defect), ``f_step`` for the others."""
    if _hertzian(code):
        return contact_force(code, p, h, d, v)[0]
    return f_step

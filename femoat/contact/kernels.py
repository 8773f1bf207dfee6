"""Compiled contact-law entry points the time-stepping loops call, dispatching on the law code.

Conventions (docs/paper.md §2): indentation ``d`` = δ [in] > 0 in contact; ``v`` = δ̇ [in/s] > 0 while
approaching. Forces are compressive-positive [kip]. Every force kernel returns
``(f, df/dδ, df/dδ̇)`` evaluated from the *committed* history ``h`` (never modified here), so a
Newton iteration may call it any number of times; :func:`contact_commit` advances the history once
a step has converged.

A law's ``code`` (:attr:`femoat.contact.laws.ContactLaw.code`) numbers its kernel family; the
family's kernels and params layout (``p``, from :meth:`~femoat.contact.laws.ContactLaw.packed`)
live in the law's module, and :mod:`femoat.contact._dispatch`, generated from the registry,
selects them by that number. The history layout ``h`` is in :mod:`femoat.contact.history`.
What the family declares (:class:`~femoat.contact.spec.KernelFamily`: a Hertz spring, a force
that need not vanish at δ = 0⁺) is all the time-stepping variants below ask of it.
"""

import numpy as np

from femoat.compilation.jit import njit
from femoat.contact import _dispatch
from femoat.contact._dispatch import (
    N_PARAMS,
    acts_at_zero,
    family_commit,
    family_energy,
    family_force,
    hertz_spring,
)
from femoat.contact.hertz import K_H, hertz_gradient
from femoat.contact.history import H_D_LAST, H_DMAX, H_F_LAST, H_V0, N_HISTORY
from femoat.contact.laws import FAMILIES

if (_dispatch.FAMILIES, N_PARAMS) != (tuple(f.name for f in FAMILIES),
                                      max(f.n_params for f in FAMILIES)):
    raise ImportError(
        f"femoat/contact/_dispatch.py dispatches the kernel families {_dispatch.FAMILIES}, the "
        f"registry has {tuple(f.name for f in FAMILIES)} (or other params widths): run "
        "`python -m femoat.contact.generate`."
    )

__all__ = ["N_HISTORY", "N_PARAMS", "contact_closure", "contact_commit", "contact_force",
           "contact_stored_energy", "recorded_force", "step_commit", "step_force"]


@njit(cache=True)
def contact_force(code, p, h, d, v):
    """Force [kip] and tangents (df/dδ [kip/in], df/dδ̇ [kip·s/in]) of law ``code``."""
    if d <= 0.0:
        return 0.0, 0.0, 0.0
    return family_force(code, p, h, d, v)


@njit(cache=True)
def contact_stored_energy(code, p, h, d):
    """Elastic energy [kip·in] the contact would return if unloaded now from indentation ``d``.

    Used by energy balances while a contact is open. Zero at separation for every law.
    """
    if d <= 0.0:
        return 0.0
    return family_energy(code, p, h, d)


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
    family_commit(code, h, d)


# ---- implicit time stepping -------------------------------------------------------------------


@njit(cache=True)
def step_force(code, p, h, d, v):
    """contact_force for an implicit trapezoidal step from the committed state
    (h[H_D_LAST], h[H_F_LAST]) of an open episode.

    Identical to :func:`contact_force` except: the elastic part k_h·δ^1.5 of the Hertz laws is
    replaced by its discrete gradient (:mod:`femoat.contact.hertz`), and the step that ends a
    contact (δ₁ ≤ 0, from δ₀ > 0) returns the energy stored at δ₀ too; an episode still open at
    δ ≤ 0 of a law whose force need not vanish at δ = 0⁺ (Kelvin-Voigt's dashpot) acts as at
    δ = 0⁺.
    """
    if d <= 0.0 and acts_at_zero(code):
        d = 1e-300
    f, kf, cf = contact_force(code, p, h, d, v)
    if not hertz_spring(code):
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
    if hertz_spring(code) and (d > 0.0 or h[H_D_LAST] > 0.0):
        g = hertz_gradient(p[K_H], h[H_D_LAST], h[H_F_LAST], d)[0]
    h[H_D_LAST] = d
    h[H_F_LAST] = g if d > 0.0 else 0.0


@njit(cache=True)
def recorded_force(code, p, h, d, v, f_step):
    """The force [kip] to record for an open episode after a step that used ``f_step``: the law's
    own force at the recorded state for the Hertz laws (their step force differs from it by the
    discrete gradient's O(Δδ²) trapezoidal defect), ``f_step`` for the others."""
    if hertz_spring(code):
        return contact_force(code, p, h, d, v)[0]
    return f_step

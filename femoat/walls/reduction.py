"""A finite-element wall reduced to a modal wall: which modes to keep, the residual-flexibility
vector, the modal damping (the reasons are in :mod:`femoat.walls.modal`).

:func:`reduce_fe_wall` does the work of :meth:`femoat.walls.ModalWall.from_fe` and returns the
ModalWall's fields; the wall is solved for its modes once (the contact time may be computed
from that same solution, ``contact_duration`` given as a callable).
"""

import math

import numpy as np

CUTOFF_FACTOR = 4.0
"""Modes up to CUTOFF_FACTOR / contact_duration [Hz] are kept when a contact duration is given."""


def _check_duration(t_c):
    if t_c is not None and not (math.isfinite(t_c) and t_c > 0):
        raise ValueError(f"contact_duration = {t_c!r} must be a positive time [s] or None")
    return t_c


def reduce_fe_wall(source, n_modes=None, flexibility_target=0.99, contact_duration=None,
                   damping_ratio=0.0, rayleigh=None, computed_modes=None, residual=True):
    """The fields of the :class:`~femoat.walls.ModalWall` of ``source`` (a WallModel or a
    ModalResult); the parameters are those of :meth:`~femoat.walls.ModalWall.from_fe`."""
    from femoat.walls.fe.modal import (ModalResult, impact_modes, modal_analysis,
                                       residual_mode)
    from femoat.walls.fe.model import WallModel

    if n_modes is not None and (int(n_modes) != n_modes or n_modes < 1):
        raise ValueError(f"n_modes = {n_modes!r} must be a positive integer or None (choose "
                         "from flexibility_target)")
    if not (isinstance(flexibility_target, (int, float)) and 0 < flexibility_target < 1):
        raise ValueError(f"flexibility_target = {flexibility_target!r} must be in (0, 1), "
                         "e.g. 0.99")
    if not callable(contact_duration):
        _check_duration(contact_duration)
    if rayleigh is not None:
        if damping_ratio:
            raise ValueError("give damping_ratio or rayleigh, not both")
        try:
            alpha, beta = (float(x) for x in rayleigh)
        except (TypeError, ValueError):
            raise ValueError("rayleigh must be a pair (alpha [1/s], beta [s])") from None
        if not (math.isfinite(alpha) and math.isfinite(beta) and alpha >= 0 and beta >= 0):
            raise ValueError(f"rayleigh = {rayleigh!r}: alpha [1/s] and beta [s] must be "
                             ">= 0")
    if not (isinstance(damping_ratio, (int, float)) and math.isfinite(damping_ratio)
            and damping_ratio >= 0):
        raise ValueError(f"damping_ratio = {damping_ratio!r} must be a ratio >= 0 [-] "
                         "(e.g. an SdofWall's damping_ratio)")

    if isinstance(source, WallModel):
        kind = source.kind
        n_dofs = len(source.free)
        count = computed_modes or max(12, 2 * (n_modes or 0))
        while True:
            count = min(count, n_dofs)
            result = modal_analysis(source, count)
            if callable(contact_duration):  # t_c from this wall's own first mode
                contact_duration = _check_duration(contact_duration(result))
            if computed_modes or count >= n_dofs or _enough(result, n_modes,
                                                            flexibility_target,
                                                            contact_duration):
                break
            count *= 2
    elif isinstance(source, ModalResult):
        result, kind = source, source.kind
        if callable(contact_duration):
            contact_duration = _check_duration(contact_duration(result))
    else:
        raise ValueError("source must be a WallModel (femoat.walls.fe.beam_model, ...) or the "
                         "ModalResult of modal_analysis")

    modes = impact_modes(result)
    available = len(modes.mode_numbers)
    flex = np.cumsum(1.0 / modes.modal_stiffnesses) * result.static_flexibility ** -1
    if n_modes is None:
        reached = np.nonzero(flex >= flexibility_target)[0]
        if reached.size == 0:
            raise ValueError(f"the {available} computed impact modes capture only "
                             f"{flex[-1]:.4f} of the impact flexibility (< flexibility_target "
                             f"{flexibility_target}): pass a WallModel or a ModalResult with "
                             "more modes")
        n = int(reached[0]) + 1
        how = f"N from flexibility >= {flexibility_target}"
        if contact_duration is not None:
            f_cut = CUTOFF_FACTOR / contact_duration
            below = int(np.sum(modes.frequencies <= f_cut))
            n_free = np.count_nonzero(np.any(result.shapes != 0, axis=1))
            if result.frequencies[-1] <= f_cut and len(result.frequencies) < n_free:
                raise ValueError(f"all {len(result.frequencies)} computed modes lie below "
                                 f"the cut-off {f_cut:.4g} Hz: pass a WallModel or a "
                                 "ModalResult with more modes")
            if below > n:
                n, how = below, f"N from f <= {CUTOFF_FACTOR:g}/t_c = {f_cut:.4g} Hz"
    else:
        n = int(n_modes)
        if n > available:
            raise ValueError(f"n_modes = {n} but only {available} computed modes move the "
                             "impact point: compute more modes (modal_analysis n_modes)")
        how = "N given"
    m = modes.modal_masses[:n]
    k = modes.modal_stiffnesses[:n]
    numbers = modes.mode_numbers[:n]
    ground = modes.ground_factors[:n]
    freqs = modes.frequencies[:n]
    shapes = modes.shapes[:, :n]
    fraction = float(flex[n - 1])
    extra = None
    if residual and result.static_shape is None:
        import warnings

        warnings.warn("this ModalResult carries no static deflection (built by hand?), so "
                      "the residual-flexibility vector is left out; run "
                      "femoat.walls.fe.modal_analysis on the WallModel to include it",
                      stacklevel=3)
    elif residual:
        extra = residual_mode(result, numbers)
    if extra is not None:
        m, k = np.append(m, extra.modal_mass), np.append(k, extra.modal_stiffness)
        ground, freqs = np.append(ground, extra.ground_factor), np.append(freqs, extra.frequency)
        shapes = np.column_stack([shapes, extra.shape])
        fraction = 1.0
        how += (f"; + residual-flexibility vector, {extra.frequency:.4g} Hz, "
                f"r_N = {extra.flexibility:.4g} in/kip")
    if rayleigh is not None:
        c = alpha * m + beta * k
        damping_source = f"rayleigh alpha={alpha:g} 1/s, beta={beta:g} s"
    else:
        c = 2.0 * damping_ratio * np.sqrt(k * m)
        damping_source = f"uniform xi={damping_ratio:g}"
    return dict(
        modal_masses=m, modal_stiffnesses=k, modal_dampings=c, impact_shape=np.ones(m.size),
        ground_participation=ground, frequencies=freqs,
        source=f"{kind} model, modes {(numbers + 1).tolist()} ({how})",
        damping_source=damping_source,
        mode_numbers=numbers if extra is None else np.append(numbers, -1), shapes=shapes,
        flexibility_fraction=fraction, residual=extra is not None,
    )


def _enough(result, n_modes, target, contact_duration):
    """Do the computed modes cover what from_fe needs?"""
    from femoat.walls.fe.modal import impact_modes

    modes = impact_modes(result)
    if n_modes is not None:
        return len(modes.mode_numbers) >= n_modes
    flex = np.sum(1.0 / modes.modal_stiffnesses) / result.static_flexibility
    if flex < target:
        return False
    if contact_duration is not None:
        return result.frequencies[-1] > CUTOFF_FACTOR / contact_duration
    return True

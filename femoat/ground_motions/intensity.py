"""A record's intensity for scaling to a target: Sa(T) [g], 5 %-damped pseudo-spectral
acceleration (:func:`~femoat.ground_motions.spectrum.response_spectrum`), and the intensity of
a pair, the **geometric mean** of its two components' (FEMA P695 practice, docs/plan.md §2).

One place for the suites' ``[scaling]`` (:mod:`femoat.suite.scaling`) and the scenario files'
``[motion] sa`` (:mod:`femoat.scenario.intensity`), so that a scenario scaled to Sa(T) and a
suite's record at the same Sa(T) get the same factor.
"""

import numpy as np

from .spectrum import response_spectrum

DAMPING = 0.05
"""Damping ratio [-] of the spectra that scale records (5 %, as FEMA P695 and ASCE 7)."""


def spectral_acceleration(motion, period):
    """Sa(T) [g] of ``motion`` (a GroundMotion) at ``period`` T [s] > 0, :data:`DAMPING`."""
    return float(response_spectrum(motion, period, DAMPING).psa)


def geometric_mean(values):
    """The geometric mean of positive intensities (one value: itself) [their unit]."""
    return float(np.prod(values)) ** (1.0 / len(values))

"""V, the Kelvin-Voigt contact: f = k_eff·δ + c_eff·δ̇ (docs/paper.md §2), cut at zero unless it may
pull (then the episode ends at δ = 0 only).

Params ``p = [k_eff, c_eff, tension]``: stiffness [kip/in], dashpot [kip·s/in], 1.0 if the law
may pull else 0.0. History: none.
"""

import math
from dataclasses import dataclass

import numpy as np

from femoat import checks as _checks
from femoat.compilation.jit import njit
from femoat.contact.spec import Bracket, KernelFamily, LawSpec

K_EFF, C_EFF, TENSION = 0, 1, 2
N_PARAMS = 3


@njit(cache=True)
def kelvin_voigt_force(p, h, d, v):
    f = p[K_EFF] * d + p[C_EFF] * v
    if f < 0.0 and p[TENSION] == 0.0:
        return 0.0, 0.0, 0.0
    return f, p[K_EFF], p[C_EFF]


@njit(cache=True)
def kelvin_voigt_energy(p, h, d):
    return 0.5 * p[K_EFF] * d * d


def xi_kelvin_voigt(e):
    """Kelvin-Voigt damping ratio ξ_KV solving ln(1/e) = 2ξ/√(1−ξ²)·arctan(√(1−ξ²)/ξ).

    The relation assumes that contact ends when the force returns to zero (no tension). The
    right-hand side grows monotonically from 0 (ξ→0) to 2 (ξ→1), so a root exists for
    e > exp(−2) ≈ 0.135; below that a tension-free Kelvin-Voigt contact cannot dissipate enough.
    """
    from scipy.optimize import brentq

    _checks.restitution(e)
    if e == 1.0:
        return 0.0
    target = math.log(1.0 / e)
    if target >= 2.0:
        raise ValueError(
            f"e = {e} is too small for the Kelvin-Voigt law: a tension-free Kelvin-Voigt contact "
            f"reaches at least e = exp(-2) = {math.exp(-2):.4f}; use another law or a larger e."
        )

    def g(xi):
        s = math.sqrt(1.0 - xi * xi)
        return 2.0 * xi / s * math.atan(s / xi) - target

    return brentq(g, 1e-12, 1.0 - 1e-15, xtol=1e-15, rtol=1e-14)


@dataclass(frozen=True)
class KelvinVoigt:
    """The Kelvin-Voigt law.

    Parameters
    ----------
    k_eff : float         [kip/in]    spring stiffness (k_h·√δ_me), > 0
    c_eff : float         [kip·s/in]  dashpot 2·ξ_KV·√(m_eff·k_eff), >= 0
    allow_tension : bool              keep contact (and pull) until δ = 0
    """

    k_eff: float
    c_eff: float
    allow_tension: bool = False

    def __post_init__(self):
        _checks.positive("k_eff", self.k_eff, "[kip/in]")
        _checks.non_negative("c_eff", self.c_eff, "[kip·s/in]")
        _checks.flag("allow_tension", self.allow_tension)

    @classmethod
    def from_law(cls, law):
        pr = law.params
        c_eff = 2.0 * law.damping_parameter() * math.sqrt(pr.m_eff * pr.k_eff)
        return cls(pr.k_eff, c_eff, law.allow_tension)

    def params(self):
        return np.array([self.k_eff, self.c_eff, 1.0 if self.allow_tension else 0.0])

    def separation_indicator(self, d, v, v0):
        """The unclipped force [kip]: its zero crossing ends a tension-free contact."""
        if self.allow_tension:
            return 1.0
        return self.k_eff * d + self.c_eff * v

    def opensees_material(self, gap):
        """``ViscoelasticGap k_eff c_eff −g0``. Pulls (tension) until δ = 0, so it equals the
        ``allow_tension=True`` variant, not the default (e = 0.679 instead of 0.700)."""
        return ("ViscoelasticGap", self.k_eff, self.c_eff, -gap)


KERNELS = KernelFamily("kelvin_voigt", kelvin_voigt_force, kelvin_voigt_energy, N_PARAMS,
                       acts_at_zero=True)

LAW = LawSpec("V", "Kelvin-Voigt", KERNELS, KelvinVoigt, paper=True,
              style=dict(color="#ff7f0e", linestyle="--"),
              damping="xi_KV", damping_from_e=xi_kelvin_voigt, calibration=Bracket(0.0, 0.999),
              options=("allow_tension",))

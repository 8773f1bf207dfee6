"""V, the Kelvin-Voigt contact: f = k_eff·δ + c_eff·δ̇ (docs/paper.md §2), cut at zero unless it may
pull (then the episode ends at δ = 0 only).

Params ``p = [k_eff, c_eff, tension]``: stiffness [kip/in], dashpot [kip·s/in], 1.0 if the law
may pull else 0.0. History: none.
"""

from dataclasses import dataclass

import numpy as np

from femoat.contact.codes import KELVIN_VOIGT
from femoat.jit import njit

K_EFF, C_EFF, TENSION = 0, 1, 2
N_PARAMS = 3


@njit(cache=True)
def kelvin_voigt_force(p, d, v):
    f = p[K_EFF] * d + p[C_EFF] * v
    if f < 0.0 and p[TENSION] == 0.0:
        return 0.0, 0.0, 0.0
    return f, p[K_EFF], p[C_EFF]


@njit(cache=True)
def kelvin_voigt_energy(p, d):
    return 0.5 * p[K_EFF] * d * d


@dataclass(frozen=True)
class KelvinVoigt:
    """The Kelvin-Voigt law.

    Parameters
    ----------
    k_eff : float         [kip/in]    spring stiffness (k_h·√δ_me)
    c_eff : float         [kip·s/in]  dashpot 2·ξ_KV·√(m_eff·k_eff)
    allow_tension : bool              keep contact (and pull) until δ = 0
    """

    k_eff: float
    c_eff: float
    allow_tension: bool = False
    code = KELVIN_VOIGT

    @classmethod
    def from_law(cls, law):
        return cls(law.params.k_eff, law.c_eff, law.allow_tension)

    def params(self):
        return np.array([self.k_eff, self.c_eff, 1.0 if self.allow_tension else 0.0])

    def separation_indicator(self, d, v, v0):
        """The unclipped force [kip]: its zero crossing ends a tension-free contact."""
        if self.allow_tension:
            return 1.0
        return self.k_eff * d + self.c_eff * v

"""J, Jankowski's nonlinear viscoelastic contact (docs/paper.md §2): f = k_h·δ^1.5 + c_J·δ̇ while
approaching (δ̇ > 0), k_h·δ^1.5 while separating, with c_J = 2·ξ_J·√(m_eff·k_h·√δ).

Params ``p = [k_h, xi_J, m_eff]`` (k_h at :data:`femoat.contact.hertz.K_H`). History: none.
"""

from dataclasses import dataclass

import numpy as np

from femoat.contact.codes import JANKOWSKI
from femoat.contact.hertz import K_H, hertz_energy
from femoat.jit import njit

XI_J, M_EFF = 1, 2
N_PARAMS = 3


@njit(cache=True)
def jankowski_force(p, d, v):
    sd = np.sqrt(d)
    f = p[K_H] * d * sd
    dfd = 1.5 * p[K_H] * sd
    if v > 0.0:
        # c_J = 2 ξ_J √(m k_h √δ); ∂c_J/∂δ = c_J / (4δ)
        cj = 2.0 * p[XI_J] * np.sqrt(p[M_EFF] * p[K_H] * sd)
        return f + cj * v, dfd + 0.25 * cj * v / d, cj
    return f, dfd, 0.0


@njit(cache=True)
def jankowski_energy(p, d):
    return hertz_energy(p, d)


@dataclass(frozen=True)
class Jankowski:
    """Jankowski's law.

    Parameters
    ----------
    k_h : float    [kip/in^1.5]  Hertz stiffness
    xi_J : float   [-]           damping ratio
    m_eff : float  [kip·s²/in]   effective mass of the impact
    """

    k_h: float
    xi_J: float
    m_eff: float
    code = JANKOWSKI

    @classmethod
    def from_law(cls, law):
        return cls(law.params.k_h, law.damping_parameter(), law.params.m_eff)

    def params(self):
        return np.array([self.k_h, self.xi_J, self.m_eff], dtype=np.float64)

    def separation_indicator(self, d, v, v0):
        """The force never vanishes before δ = 0 (no dashpot while separating)."""
        return 1.0

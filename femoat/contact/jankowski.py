"""J, Jankowski's nonlinear viscoelastic contact (docs/paper.md §2): f = k_h·δ^1.5 + c_J·δ̇ while
approaching (δ̇ > 0), k_h·δ^1.5 while separating, with c_J = 2·ξ_J·√(m_eff·k_h·√δ).

Params ``p = [k_h, xi_J, m_eff]`` (k_h at :data:`femoat.contact.hertz.K_H`). History: none.
"""

import math
from dataclasses import dataclass

import numpy as np

from femoat import checks as _checks
from femoat.compilation.jit import njit
from femoat.contact.hertz import K_H, hertz_energy
from femoat.contact.spec import Bracket, KernelFamily, LawSpec

XI_J, M_EFF = 1, 2
N_PARAMS = 3


@njit(cache=True)
def jankowski_force(p, h, d, v):
    sd = np.sqrt(d)
    f = p[K_H] * d * sd
    dfd = 1.5 * p[K_H] * sd
    if v > 0.0:
        # c_J = 2 ξ_J √(m k_h √δ); ∂c_J/∂δ = c_J / (4δ)
        cj = 2.0 * p[XI_J] * np.sqrt(p[M_EFF] * p[K_H] * sd)
        return f + cj * v, dfd + 0.25 * cj * v / d, cj
    return f, dfd, 0.0


def xi_jankowski(e):
    """Jankowski damping ratio ξ_J = (9√5/2)·(1−e²)/(e·(e(9π−16)+16))."""
    _checks.restitution(e)
    return 9.0 * math.sqrt(5.0) / 2.0 * (1.0 - e * e) / (e * (e * (9.0 * math.pi - 16.0) + 16.0))


@dataclass(frozen=True)
class Jankowski:
    """Jankowski's law.

    Parameters
    ----------
    k_h : float    [kip/in^1.5]  Hertz stiffness, > 0
    xi_J : float   [-]           damping ratio, >= 0
    m_eff : float  [kip·s²/in]   effective mass of the impact, > 0
    """

    k_h: float
    xi_J: float
    m_eff: float

    def __post_init__(self):
        _checks.positive("k_h", self.k_h, "[kip/in^1.5]")
        _checks.non_negative("xi_J", self.xi_J, "[-]")
        _checks.positive("m_eff", self.m_eff, "[kip·s²/in]")

    @classmethod
    def from_law(cls, law):
        return cls(law.params.k_h, law.damping_parameter(), law.params.m_eff)

    def params(self):
        return np.array([self.k_h, self.xi_J, self.m_eff], dtype=np.float64)

    def separation_indicator(self, d, v, v0):
        """The force never vanishes before δ = 0 (no dashpot while separating)."""
        return 1.0

    def opensees_material(self, gap):
        """``JankowskiImpact k_h ξ_J m_eff −g0 1.5``: the same law."""
        return ("JankowskiImpact", self.k_h, self.xi_J, self.m_eff, -gap, 1.5)


KERNELS = KernelFamily("jankowski", jankowski_force, hertz_energy, N_PARAMS, hertz_spring=True)

LAW = LawSpec("J", "Jankowski", KERNELS, Jankowski, paper=True,
              style=dict(color="#2ca02c", linestyle="-."),
              damping="xi_J", damping_from_e=xi_jankowski, calibration=Bracket(0.0, 20.0))

"""E, the linear elastic contact spring: f = k_eff·δ (docs/paper.md §2). No damping: e = 1.

Params ``p = [k_eff]``. History: none.
"""

from dataclasses import dataclass

import numpy as np

from femoat import checks as _checks
from femoat.compilation.jit import njit
from femoat.contact.spec import KernelFamily, LawSpec

K_EFF = 0
N_PARAMS = 1

_FY_NEVER = 1e12
"""A yield force [kip] OpenSees' ElasticPPGap never reaches: a purely elastic gap."""


@njit(cache=True)
def linear_force(p, h, d, v):
    return p[K_EFF] * d, p[K_EFF], 0.0


@njit(cache=True)
def linear_energy(p, h, d):
    return 0.5 * p[K_EFF] * d * d


@dataclass(frozen=True)
class Linear:
    """The linear elastic law.

    Parameters
    ----------
    k_eff : float  [kip/in]  spring stiffness (k_h·√δ_me), > 0
    """

    k_eff: float

    def __post_init__(self):
        _checks.positive("k_eff", self.k_eff, "[kip/in]")

    @classmethod
    def from_law(cls, law):
        return cls(law.params.k_eff)

    def params(self):
        return np.array([self.k_eff], dtype=np.float64)

    def separation_indicator(self, d, v, v0):
        """Sign of the unclipped force when it can end a contact before δ = 0 (never here)."""
        return 1.0

    def opensees_material(self, gap):
        """``ElasticPPGap k_eff −Fy_huge −g0``: the same law."""
        return ("ElasticPPGap", self.k_eff, -_FY_NEVER, -gap)


KERNELS = KernelFamily("linear", linear_force, linear_energy, N_PARAMS)

LAW = LawSpec("E", "linear elastic", KERNELS, Linear, paper=True,
              style=dict(color="#1f77b4", linestyle="-"))

"""E, the linear elastic contact spring: f = k_eff·δ (docs/paper.md §2). No damping: e = 1.

Params ``p = [k_eff]``. History: none.
"""

from dataclasses import dataclass

import numpy as np

from femoat.contact.codes import LINEAR
from femoat.jit import njit

K_EFF = 0
N_PARAMS = 1


@njit(cache=True)
def linear_force(p, d):
    return p[K_EFF] * d, p[K_EFF], 0.0


@njit(cache=True)
def linear_energy(p, d):
    return 0.5 * p[K_EFF] * d * d


@dataclass(frozen=True)
class Linear:
    """The linear elastic law.

    Parameters
    ----------
    k_eff : float  [kip/in]  spring stiffness (k_h·√δ_me)
    """

    k_eff: float
    code = LINEAR

    @classmethod
    def from_law(cls, law):
        return cls(law.params.k_eff)

    def params(self):
        return np.array([self.k_eff], dtype=np.float64)

    def separation_indicator(self, d, v, v0):
        """Sign of the unclipped force when it can end a contact before δ = 0 (never here)."""
        return 1.0

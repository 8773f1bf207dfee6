"""H, Hertzdamp (docs/paper.md §2): f = k_h·δ^1.5·(1 + ξ_h·δ̇/δ̇₀), cut at zero, with δ̇₀ the approach
velocity at gap closure (at least v0_min).

Params ``p = [k_h, xi_h, v0_min]`` (k_h at :data:`femoat.contact.hertz.K_H`). History:
``h[H_V0]`` = δ̇₀ [in/s].
"""

from dataclasses import dataclass

import numpy as np

from femoat.contact.codes import H_V0, HERTZDAMP
from femoat.contact.hertz import K_H, hertz_energy
from femoat.jit import njit

XI_H, V0_MIN = 1, 2
N_PARAMS = 3


@njit(cache=True)
def hertzdamp_force(p, h, d, v):
    v0 = max(h[H_V0], p[V0_MIN])
    sd = np.sqrt(d)
    fh = p[K_H] * d * sd
    r = 1.0 + p[XI_H] * v / v0
    if r <= 0.0:
        return 0.0, 0.0, 0.0
    return fh * r, 1.5 * p[K_H] * sd * r, fh * p[XI_H] / v0


@njit(cache=True)
def hertzdamp_energy(p, d):
    return hertz_energy(p, d)


@dataclass(frozen=True)
class Hertzdamp:
    """The Hertzdamp law.

    Parameters
    ----------
    k_h : float     [kip/in^1.5]  Hertz stiffness
    xi_h : float    [-]           damping factor
    v0_min : float  [in/s]        smallest approach velocity divided by
    """

    k_h: float
    xi_h: float
    v0_min: float
    code = HERTZDAMP

    @classmethod
    def from_law(cls, law):
        return cls(law.params.k_h, law.damping_parameter(), law.v0_min)

    def params(self):
        return np.array([self.k_h, self.xi_h, self.v0_min], dtype=np.float64)

    def separation_indicator(self, d, v, v0):
        """1 + ξ_h·δ̇/δ̇₀ [-]: its zero crossing ends the contact before δ = 0."""
        return 1.0 + self.xi_h * v / max(v0, self.v0_min)

"""H, Hertzdamp (docs/paper.md §2): f = k_h·δ^1.5·(1 + ξ_h·δ̇/δ̇₀), cut at zero, with δ̇₀ the approach
velocity at gap closure (at least v0_min).

Params ``p = [k_h, xi_h, v0_min]`` (k_h at :data:`femoat.contact.hertz.K_H`). History:
``h[H_V0]`` = δ̇₀ [in/s].
"""

from dataclasses import dataclass

import numpy as np

from femoat import checks as _checks
from femoat.compilation.jit import njit
from femoat.contact.hertz import K_H, hertz_energy
from femoat.contact.history import H_V0
from femoat.contact.spec import Bracket, KernelFamily, LawSpec

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


def xi_hertzdamp(e):
    """Hertzdamp damping factor ξ_h = (8/5)·(1−e)/e."""
    _checks.restitution(e)
    return 1.6 * (1.0 - e) / e


@dataclass(frozen=True)
class Hertzdamp:
    """The Hertzdamp law.

    Parameters
    ----------
    k_h : float     [kip/in^1.5]  Hertz stiffness, > 0
    xi_h : float    [-]           damping factor, >= 0
    v0_min : float  [in/s]        smallest approach velocity divided by, > 0
    """

    k_h: float
    xi_h: float
    v0_min: float

    def __post_init__(self):
        _checks.positive("k_h", self.k_h, "[kip/in^1.5]")
        _checks.non_negative("xi_h", self.xi_h, "[-]")
        _checks.positive("v0_min", self.v0_min, "[in/s]")

    @classmethod
    def from_law(cls, law):
        return cls(law.params.k_h, law.damping_parameter(), law.v0_min)

    def params(self):
        return np.array([self.k_h, self.xi_h, self.v0_min], dtype=np.float64)

    def separation_indicator(self, d, v, v0):
        """1 + ξ_h·δ̇/δ̇₀ [-]: its zero crossing ends the contact before δ = 0."""
        return 1.0 + self.xi_h * v / max(v0, self.v0_min)

    def opensees_material(self, gap):
        """``Hertzdamp k_h ξ_h −g0 1.5``. δ̇₀ is the rate at the end of the first contact step
        (not at closure); tension is not cut (reached only if the rebound rate exceeds
        δ̇₀/ξ_h)."""
        return ("Hertzdamp", self.k_h, self.xi_h, -gap, 1.5)


KERNELS = KernelFamily("hertzdamp", hertzdamp_force, hertz_energy, N_PARAMS, hertz_spring=True)

LAW = LawSpec("H", "Hertzdamp", KERNELS, Hertzdamp, paper=True,
              style=dict(color="#d62728", linestyle=":"),
              damping="xi_h", damping_from_e=xi_hertzdamp, calibration=Bracket(0.0, 200.0))

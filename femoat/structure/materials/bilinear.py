"""Bilinear spring with kinematic hardening (OpenSees ``Steel01`` with a1..a4 = 0, 1, 0, 1).

The force is the elastic predictor f_c + k0·(u − u_c) clipped between the two fixed bounding
lines f = b·k0·u ± (1 − b)·Fy (kinematic hardening: the elastic range always spans 2·Fy).

Params ``p = [k0, Fy, b]``: initial stiffness [kip/in], yield force [kip], hardening ratio [-].
State ``s = [u_c, f_c]``: committed deformation [in] and force [kip].
Recoverable energy: f_c²/(2·k0), the energy released by elastic unloading to zero force.
"""

from dataclasses import dataclass

import numpy as np

from femoat import checks as _checks
from femoat.compilation.jit import njit
from femoat.structure.materials.codes import BILINEAR

N_PARAMS = 3
N_STATE = 2


@njit(cache=True)
def bilinear_trial(p, s, u):
    k0, fy, b = p[0], p[1], p[2]
    f = s[1] + k0 * (u - s[0])
    upper = b * k0 * u + (1.0 - b) * fy
    lower = b * k0 * u - (1.0 - b) * fy
    if f > upper:
        return upper, b * k0, 0.0
    if f < lower:
        return lower, b * k0, 0.0
    return f, k0, 0.0


@njit(cache=True)
def bilinear_commit(p, s, u):
    f, _, _ = bilinear_trial(p, s, u)
    s[0] = u
    s[1] = f


@njit(cache=True)
def bilinear_energy(p, s):
    return 0.5 * s[1] * s[1] / p[0]


@dataclass(frozen=True)
class Bilinear:
    """Kinematic-hardening bilinear spring (one story of the paper's quarter-scale frame by default).

    Parameters
    ----------
    k0 : float
        Initial (elastic and unloading) stiffness [kip/in], > 0.
    Fy : float
        Yield force [kip], > 0.
    b : float
        Hardening ratio: post-yield stiffness / k0 [-], in [0, 1).
    """

    k0: float = 42.799
    Fy: float = 11.556
    b: float = 0.03

    def __post_init__(self):
        _checks.positive("k0", self.k0, "[kip/in]")
        _checks.positive("Fy", self.Fy, "[kip]")
        _checks.in_range("b", self.b, "[-]", 0.0, 1.0, hi_open=True)

    code = BILINEAR

    @property
    def uy(self) -> float:
        """Yield deformation Fy/k0 [in]."""
        return self.Fy / self.k0

    @property
    def initial_stiffness(self) -> float:
        """Initial (elastic) stiffness [kip/in]: k0; a story's dashpot is β times it."""
        return self.k0

    @property
    def yield_deformation(self) -> float:
        """Deformation at first yield [in]: u_y = Fy/k0."""
        return self.uy

    def params(self) -> np.ndarray:
        return np.array([self.k0, self.Fy, self.b], dtype=np.float64)

    def initial_state(self) -> np.ndarray:
        return np.zeros(N_STATE)

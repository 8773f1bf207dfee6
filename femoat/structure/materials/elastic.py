"""Linear elastic spring: f = k·u.

Params ``p = [k]`` (k [kip/in]). State ``s = [u]``: the committed deformation [in], kept only so the
stored energy k·u²/2 can be reported from the state alone.
"""

from dataclasses import dataclass

import numpy as np

from femoat import checks as _checks
from femoat.compilation.jit import njit
from femoat.structure.materials.codes import ELASTIC

N_PARAMS = 1
N_STATE = 1


@njit(cache=True)
def elastic_trial(p, s, u):
    return p[0] * u, p[0], 0.0


@njit(cache=True)
def elastic_commit(p, s, u):
    s[0] = u


@njit(cache=True)
def elastic_energy(p, s):
    return 0.5 * p[0] * s[0] * s[0]


@dataclass(frozen=True)
class Elastic:
    """Linear elastic spring.

    Parameters
    ----------
    k : float
        Stiffness [kip/in], finite and ≥ 0.
    """

    k: float

    def __post_init__(self):
        _checks.in_range("k", self.k, "[kip/in]", 0.0, float("inf"), hi_open=True)

    code = ELASTIC

    @property
    def initial_stiffness(self) -> float:
        """Initial (elastic) stiffness [kip/in]: the spring's k; a story's dashpot is β times it."""
        return self.k

    @property
    def yield_deformation(self) -> None:
        """None: an elastic spring never yields."""
        return None

    def params(self) -> np.ndarray:
        return np.array([self.k], dtype=np.float64)

    def initial_state(self) -> np.ndarray:
        return np.zeros(N_STATE)

"""M, Muthukumar's bilinear contact (docs/paper.md §2, §5.2): loading on k1 up to δ_y, then on k2;
below the episode's largest indentation δ_m, the unloading path from (δ_m, f_m) (slope k1 over
δ_y, then the line f = k2·δ through the origin). Reloading after a partial unloading retraces
that path (no dissipation in inner cycles) until it meets the backbone again at δ_m.

Params ``p = [k1, k2, delta_y]``: stiffnesses [kip/in], yield indentation [in]. History:
``h[H_DMAX]`` = δ_m [in], advanced by :func:`muthukumar_commit`.
"""

from dataclasses import dataclass

import numpy as np

from femoat.contact.codes import H_DMAX, MUTHUKUMAR
from femoat.jit import njit

K1, K2, DELTA_Y = 0, 1, 2
N_PARAMS = 3


@njit(cache=True)
def bilinear_backbone(p, d):
    """Loading branch: k1 up to δ_y, then k2. Returns (f, df/dδ)."""
    k1, k2, dy = p[K1], p[K2], p[DELTA_Y]
    if d <= dy:
        return k1 * d, k1
    return k1 * dy + k2 * (d - dy), k2


@njit(cache=True)
def _unloading(p, dm, d):
    if d >= dm:
        return bilinear_backbone(p, d)
    k1, k2, dy = p[K1], p[K2], p[DELTA_Y]
    if dm <= dy:  # never yielded: elastic on k1
        return k1 * d, k1
    fm = k1 * dy + k2 * (dm - dy)
    upper = fm - k1 * (dm - d)
    lower = k2 * d
    if upper >= lower:
        return upper, k1
    return lower, k2


@njit(cache=True)
def muthukumar_force(p, h, d):
    f, k = _unloading(p, h[H_DMAX], d)
    return f, k, 0.0


@njit(cache=True)
def muthukumar_energy(p, h, d):
    """Area under the unloading path from d down to 0 (unloading from max(d, δ_m))."""
    dm = max(h[H_DMAX], d)
    k1, k2, dy = p[K1], p[K2], p[DELTA_Y]
    if dm <= dy:
        return 0.5 * k1 * d * d
    dk = dm - dy  # the unloading path has its corner at δ = δ_m − δ_y
    if d <= dk:
        return 0.5 * k2 * d * d
    f_corner = k2 * dk
    f_d, _ = _unloading(p, dm, d)
    return 0.5 * k2 * dk * dk + 0.5 * (f_corner + f_d) * (d - dk)


@njit(cache=True)
def muthukumar_commit(h, d):
    if d > h[H_DMAX]:
        h[H_DMAX] = d


@dataclass(frozen=True)
class Muthukumar:
    """Muthukumar's bilinear law.

    Parameters
    ----------
    k1 : float       [kip/in]  first loading stiffness
    k2 : float       [kip/in]  second loading stiffness
    delta_y : float  [in]      yield indentation a·δ_me
    """

    k1: float
    k2: float
    delta_y: float
    code = MUTHUKUMAR

    @classmethod
    def from_law(cls, law):
        k1, k2 = law.stiffnesses()
        return cls(k1, k2, law.params.delta_y)

    def params(self):
        return np.array([self.k1, self.k2, self.delta_y], dtype=np.float64)

    def separation_indicator(self, d, v, v0):
        """The force never vanishes before δ = 0 (the unloading path ends at the origin)."""
        return 1.0

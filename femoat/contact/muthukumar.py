"""M, Muthukumar's bilinear contact (docs/paper.md §2, §5.2): loading on k1 up to δ_y, then on k2;
below the episode's largest indentation δ_m, the unloading path from (δ_m, f_m) (slope k1 over
δ_y, then the line f = k2·δ through the origin). Reloading after a partial unloading retraces
that path (no dissipation in inner cycles) until it meets the backbone again at δ_m.

Params ``p = [k1, k2, delta_y]``: stiffnesses [kip/in], yield indentation [in]. History:
``h[H_DMAX]`` = δ_m [in], advanced by :func:`muthukumar_commit`.
"""

from dataclasses import dataclass, replace

import numpy as np

from femoat import checks as _checks
from femoat.compilation.jit import njit
from femoat.contact.history import H_DMAX
from femoat.contact.spec import KernelFamily, LawSpec

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
def muthukumar_force(p, h, d, v):
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


def muthukumar_loss_factor(e):
    """Loss factor λ = 0.4·(1−e²) of the Muthukumar bilinear law [-]."""
    _checks.restitution(e)
    return 0.4 * (1.0 - e * e)


def muthukumar_stiffnesses(k_eff, e, a, loss=None):
    """Loading stiffnesses (k1, k2) [kip/in] of the Muthukumar bilinear law.

    k1 = (1 + λ/a)·k_eff and k2 = (1 − λ/(1−a))·k_eff with λ = 0.4(1−e²) unless ``loss`` gives λ.
    With these, the loop dissipates λ·k_eff·δ_me² when the indentation reaches δ_me, while the
    backbone stores ½(1+λ)·k_eff·δ_me² (so that, at δ_max = δ_me, e² = (1−λ)/(1+λ) exactly).
    """
    lam = muthukumar_loss_factor(e) if loss is None else loss
    k1 = (1.0 + lam / a) * k_eff
    k2 = (1.0 - lam / (1.0 - a)) * k_eff
    if k2 <= 0.0 and loss is None:
        raise ValueError(
            f"The Muthukumar law with loss factor {lam:.4g} (e = {e}) and a = {a} has a "
            f"non-positive second stiffness k2 = {k2:.4g} kip/in: choose a smaller a "
            "(a < 1 - loss factor) or a larger e."
        )
    if k2 <= 0.0:
        raise ValueError(
            f"damping (loss_factor) = {lam!r} must be in [0, 1 - a) = [0, {1.0 - a:.6g}): a "
            f"larger loss factor gives a non-positive second stiffness k2 = {k2:.4g} kip/in."
        )
    return k1, k2


@dataclass(frozen=True)
class Muthukumar:
    """Muthukumar's bilinear law.

    Parameters
    ----------
    k1 : float       [kip/in]  first loading stiffness, > 0
    k2 : float       [kip/in]  second loading stiffness, > 0
    delta_y : float  [in]      yield indentation a·δ_me, > 0
    """

    k1: float
    k2: float
    delta_y: float

    def __post_init__(self):
        _checks.positive("k1", self.k1, "[kip/in]")
        _checks.positive("k2", self.k2, "[kip/in]")
        _checks.positive("delta_y", self.delta_y, "[in]")

    @classmethod
    def from_law(cls, law):
        pr = law.params
        k1, k2 = muthukumar_stiffnesses(pr.k_eff, pr.e, pr.a, loss=law.damping_parameter())
        return cls(k1, k2, pr.delta_y)

    def params(self):
        return np.array([self.k1, self.k2, self.delta_y], dtype=np.float64)

    def separation_indicator(self, d, v, v0):
        """The force never vanishes before δ = 0 (the unloading path ends at the origin)."""
        return 1.0

    def opensees_material(self, gap):
        """``ImpactMaterial k1 k2 −δ_y −g0``. Incremental (σ = σ_c + k1·Δε): the first contact
        step's Δε includes the free travel before closure, an offset k1·θ·v0·dt (θ: fraction of
        the step before closure) that lasts until the loading branch meets the k2 backbone."""
        return ("ImpactMaterial", self.k1, self.k2, -self.delta_y, -gap)


def calibrate_bilinear(law, search):
    """The bilinear law made self-consistent at the search's impact speed and target e.

    Its loop is sized for an indentation that reaches δ_me, and a slow impact that never passes
    δ_y = a·δ_me dissipates nothing whatever the loss factor (at 1 in/s with the concrete preset
    the peak indentation is 0.0005 in < δ_y = 0.0025 in). So δ_me is set to the indentation the
    impact actually reaches and λ to the value that gives e. Against a rigid stop both follow in
    closed form: the backbone stores ½(1+λ)·k_eff·δ_me² and the loop dissipates λ·k_eff·δ_me², so

        e² = (1−λ)/(1+λ)  →  λ = (1−e²)/(1+e²),    ½·m·v0² = ½(1+λ)·k_h·δ_me^2.5.

    Against a wall a fixed-point iteration on δ_me wraps the search for λ.
    """
    pr, target, v0 = law.params, search.target, search.v0
    lam = (1.0 - target**2) / (1.0 + target**2)
    if lam >= 1.0 - pr.a:
        raise ValueError(
            f"target = {target}: the bilinear law needs a loss factor {lam:.3f} >= 1 - a = "
            f"{1 - pr.a:.3f}, which makes k2 <= 0; lower a or raise the target."
        )
    delta_me = (pr.m_eff * v0**2 / ((1.0 + lam) * pr.k_h)) ** 0.4
    calibrated = replace(law, params=replace(pr, delta_me=delta_me), damping=lam)
    if search.wall is None:
        return search.check(calibrated)
    for _ in range(50):
        calibrated = search.solve(calibrated, 0.0, 1.0 - pr.a - 1e-9)
        d_max = search.max_indentation(calibrated)
        if abs(d_max - calibrated.params.delta_me) <= 1e-8 * d_max:
            return search.check(calibrated)
        calibrated = replace(calibrated, params=replace(calibrated.params, delta_me=d_max))
    raise RuntimeError("Calibration of the bilinear law against the wall did not converge.")


KERNELS = KernelFamily("muthukumar", muthukumar_force, muthukumar_energy, N_PARAMS,
                       commit=muthukumar_commit)

LAW = LawSpec("M", "Muthukumar bilinear", KERNELS, Muthukumar, paper=True,
              style=dict(color="#9467bd", linestyle=(0, (5, 1, 1, 1))),
              damping="loss_factor", damping_from_e=muthukumar_loss_factor,
              calibration=calibrate_bilinear)

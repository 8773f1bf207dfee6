"""Single friction-pendulum bearing lumped into one horizontal element.

    f = (W/R)·u + μ(v)·W·z

u [in] is the bearing displacement, v [in/s] its velocity. The restoring term (W/R)·u comes from the
spherical surface of radius R; the friction term is μ(v)·W times a hysteretic variable z in
[−1, 1] that follows an elastic-perfectly-plastic rule with yield displacement u_y:
z = clip(z_c + (u − u_c)/u_y, −1, 1). While z is inside (−1, 1) the bearing sticks with initial
friction stiffness μ·W/u_y; at |z| = 1 it slides and the friction force is ±μ·W.

Friction coefficient (Constantinou et al., 1990, as in OpenSees ``VelDependent``):

    μ(v) = μ_fast − (μ_fast − μ_slow)·exp(−a·|v|)

With μ_fast = μ_slow it is constant Coulomb friction. The kink of |v| at v = 0 is smoothed as
|v|_ε = sqrt(v² + ε²) − ε with ε = ``v_reg`` [in/s]: |v|_ε is within ε of |v|, zero at v = 0, and
has the continuous derivative v/sqrt(v² + ε²), so ∂f/∂v is continuous and zero at v = 0 (Newton
sees no jump when the bearing reverses).

Params ``p = [W, R, u_y, mu_slow, mu_fast, a, v_reg]``
(kip, in, in, -, -, s/in, in/s). State ``s = [u_c, z_c, v_c]``: committed displacement [in],
hysteretic variable [-], velocity [in/s].

Recoverable energy: (W/R)·u²/2 + (μWz)²/(2·μW/u_y) = (W/R)·u²/2 + μ·W·u_y·z²/2, with μ at the
committed velocity.
"""

from dataclasses import dataclass

import numpy as np

from femoat import checks as _checks
from femoat.compilation.jit import njit
from femoat.structure.materials.codes import FRICTION_PENDULUM

N_PARAMS = 7
N_STATE = 3
_W, _R, _UY, _MU_SLOW, _MU_FAST, _A, _VREG = range(N_PARAMS)


@njit(cache=True)
def friction_coefficient(p, v):
    """μ(v) [-] and dμ/dv [s/in] with the smoothed |v| (see the module docstring)."""
    if p[_MU_FAST] == p[_MU_SLOW]:  # constant friction: the same numbers without exp and sqrt
        return p[_MU_FAST], 0.0
    eps = p[_VREG]
    root = np.sqrt(v * v + eps * eps)
    speed = root - eps
    e = np.exp(-p[_A] * speed)
    dmu = p[_MU_FAST] - p[_MU_SLOW]
    return p[_MU_FAST] - dmu * e, dmu * p[_A] * e * (v / root)


@njit(cache=True)
def _z(p, s, u):
    """Hysteretic variable and dz/du [1/in] for a trial displacement u."""
    z = s[1] + (u - s[0]) / p[_UY]
    if z > 1.0:
        return 1.0, 0.0
    if z < -1.0:
        return -1.0, 0.0
    return z, 1.0 / p[_UY]


@njit(cache=True)
def friction_pendulum_trial(p, s, u, v):
    w = p[_W]
    z, dz = _z(p, s, u)
    mu, dmu = friction_coefficient(p, v)
    k_r = w / p[_R]
    return k_r * u + mu * w * z, k_r + mu * w * dz, dmu * w * z


@njit(cache=True)
def friction_pendulum_commit(p, s, u, v):
    z, _ = _z(p, s, u)
    s[0] = u
    s[1] = z
    s[2] = v


@njit(cache=True)
def friction_pendulum_energy(p, s):
    w = p[_W]
    mu, _ = friction_coefficient(p, s[2])
    return 0.5 * w / p[_R] * s[0] * s[0] + 0.5 * mu * w * p[_UY] * s[1] * s[1]


@dataclass(frozen=True)
class FrictionPendulum:
    """Single friction-pendulum bearing (defaults: the paper's test bearings, R = 30 in).

    Parameters
    ----------
    W : float
        Weight carried by the bearing [kip], > 0.
    R : float
        Effective radius of the sliding surface [in], > 0 (the restoring stiffness is W/R).
    u_y : float
        Yield displacement of the friction spring [in], > 0 (sticking stiffness μ·W/u_y).
    mu : float
        Friction coefficient [-] in (0, 1): the constant Coulomb value, or μ_slow (at v = 0) when
        ``mu_fast`` is given.
    mu_fast : float or None
        Friction coefficient at high sliding speed [-] in (0, 1); ``None`` for constant friction.
    a : float
        Rate parameter of the velocity dependence [s/in], > 0 when ``mu_fast`` is given.
    v_reg : float
        Smoothing speed ε of |v| at v = 0 [in/s], > 0; only used with ``mu_fast``.
    """

    W: float = 33.0
    R: float = 30.0
    u_y: float = 0.01
    mu: float = 0.06
    mu_fast: float | None = None
    a: float = 0.0
    v_reg: float = 1e-3

    def __post_init__(self):
        _checks.positive("W", self.W, "[kip]")
        _checks.positive("R", self.R, "[in]")
        _checks.positive("u_y", self.u_y, "[in]")
        _checks.in_range("mu", self.mu, "[-]", 0.0, 1.0, lo_open=True, hi_open=True)
        _checks.positive("v_reg", self.v_reg, "[in/s]")
        if self.mu_fast is None:
            _checks.in_range("a", self.a, "[s/in]", 0.0, float("inf"), hi_open=True)
        else:
            _checks.in_range("mu_fast", self.mu_fast, "[-]", 0.0, 1.0, lo_open=True, hi_open=True)
            _checks.positive("a", self.a, "[s/in] (needed with mu_fast)")

    code = FRICTION_PENDULUM

    @property
    def yield_deformation(self) -> float:
        """Deformation at which the bearing starts to slide [in]: the friction spring's u_y."""
        return self.u_y

    @property
    def mu_slow(self) -> float:
        """Friction coefficient at zero velocity [-]."""
        return self.mu

    def params(self) -> np.ndarray:
        mu_fast = self.mu if self.mu_fast is None else self.mu_fast
        a = 0.0 if self.mu_fast is None else self.a
        return np.array(
            [self.W, self.R, self.u_y, self.mu, mu_fast, a, self.v_reg], dtype=np.float64
        )

    def initial_state(self) -> np.ndarray:
        return np.zeros(N_STATE)

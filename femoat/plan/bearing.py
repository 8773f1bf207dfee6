"""Bidirectional friction pendulum bearing: friction coupled in plan.

    F = (W/R)·u + μ(|v|)·W·z          (F, u, v, z vectors in the plan x, y)

u [in] is the bearing displacement, v [in/s] its velocity. The restoring force (W/R)·u is the
spherical surface's, the same stiffness in every direction. The friction force is μ·W times a
vector z in the unit disk that follows a circular elastic-perfectly-plastic rule with yield
displacement u_y, integrated by radial return (the closest point on the disk):

    z_trial = z_c + (u − u_c)/u_y
    z = z_trial                  if |z_trial| <= 1   (sticking: stiffness μW/u_y in every direction)
    z = z_trial/|z_trial|        otherwise           (sliding: friction force μW along z)

so the friction force never exceeds μW in magnitude, whatever the direction of sliding (two
uncoupled 1D bearings would resist with μW per axis, √2·μW at 45°). Along one axis (u, v and the
committed z on x) this is :mod:`femoat.structure.materials.friction_pendulum` exactly, and under
a straight motion along any line it is that bearing along the line.

Consistent tangent (for a Newton solver), with n = z when sliding:

    ∂F/∂u = (W/R)·I + μW·∂z/∂u,   ∂z/∂u = I/u_y (sticking),  (I − n nᵀ)/(u_y·|z_trial|) (sliding)
    ∂F/∂v = W·z ⊗ ∂μ/∂v

Friction coefficient as in the 1D bearing, of the speed |v| smoothed the same way:
μ = μ_fast − (μ_fast − μ_slow)·exp(−a·s), s = sqrt(|v|² + ε²) − ε, ε = ``v_reg``; so
∂μ/∂v = (μ_fast − μ_slow)·a·exp(−a·s)·v/sqrt(|v|² + ε²), continuous and zero at v = 0.

OpenSees twin: ``flatSliderBearing`` in 3D (FlatSliderSimple3d) with a ``Coulomb`` friction
model and kInit = μW/u_y uses the same circular yield surface, radial return and tangent; its
normal force N comes from its axial material (the basic axial force, with no-tension uplift),
so N = W needs an axial load on the slider node; in parallel with a linear W/R spring in x and y
it is this bearing (cross-checked in ``tests/test_plan_bearing.py``). ``singleFPBearing`` adds
the second-order growth of N with V·u/R, not modelled here.

Params ``p`` are the 1D bearing's, ``[W, R, u_y, mu_slow, mu_fast, a, v_reg]`` (kip, in, in, -,
-, s/in, in/s). State ``s = [u_cx, u_cy, z_cx, z_cy, v_cx, v_cy]``: committed displacement [in],
hysteretic vector [-], velocity [in/s].

Recoverable energy: (W/R)·|u|²/2 + μ·W·u_y·|z|²/2, with μ at the committed velocity.
"""

from dataclasses import dataclass

import numpy as np

from femoat.compilation.jit import njit
from femoat.structure.materials.friction_pendulum import N_PARAMS, FrictionPendulum

N_STATE = 6
_W, _R, _UY, _MU_SLOW, _MU_FAST, _A, _VREG = range(N_PARAMS)
_UCX, _UCY, _ZCX, _ZCY, _VCX, _VCY = range(N_STATE)


@njit(cache=True)
def plan_friction_coefficient(p, vx, vy):
    """μ [-] and ∂μ/∂v_x, ∂μ/∂v_y [s/in] at the plan velocity (vx, vy) [in/s]."""
    if p[_MU_FAST] == p[_MU_SLOW]:  # constant friction, as in 1D
        return p[_MU_FAST], 0.0, 0.0
    eps = p[_VREG]
    root = np.sqrt(vx * vx + vy * vy + eps * eps)
    e = np.exp(-p[_A] * (root - eps))
    dmu = p[_MU_FAST] - p[_MU_SLOW]
    slope = dmu * p[_A] * e
    return p[_MU_FAST] - dmu * e, slope * (vx / root), slope * (vy / root)


@njit(cache=True)
def _z(p, s, ux, uy):
    """Hysteretic vector (z_x, z_y) after radial return, and |z_trial|."""
    zx = s[_ZCX] + (ux - s[_UCX]) / p[_UY]
    zy = s[_ZCY] + (uy - s[_UCY]) / p[_UY]
    norm = np.sqrt(zx * zx + zy * zy)
    if norm > 1.0:
        return zx / norm, zy / norm, norm
    return zx, zy, norm


@njit(cache=True)
def plan_friction_pendulum_z_trial(p, s, ux, uy):
    """|z_trial| [-] at the trial (ux, uy) [in] from the committed state ``s``: above 1 the
    bearing slides, at or below it sticks (the branch the solver's kink search follows)."""
    zx = s[_ZCX] + (ux - s[_UCX]) / p[_UY]
    zy = s[_ZCY] + (uy - s[_UCY]) / p[_UY]
    return np.sqrt(zx * zx + zy * zy)


@njit(cache=True)
def plan_friction_pendulum_z(s):
    """The committed hysteretic vector (z_x, z_y) [-] (on the unit circle while sliding)."""
    return s[_ZCX], s[_ZCY]


@njit(cache=True)
def plan_friction_pendulum_trial(p, s, ux, uy, vx, vy, f, k, c):
    """Force ``f`` [kip] (2,), ∂f/∂u ``k`` [kip/in] (2, 2) and ∂f/∂v ``c`` [kip·s/in] (2, 2),
    written in place, at the trial (ux, uy) [in], (vx, vy) [in/s] from the committed state
    ``s``, which is not modified."""
    w = p[_W]
    k_r = w / p[_R]
    zx, zy, norm = _z(p, s, ux, uy)
    mu, dmu_x, dmu_y = plan_friction_coefficient(p, vx, vy)
    f[0] = k_r * ux + mu * w * zx
    f[1] = k_r * uy + mu * w * zy
    if norm > 1.0:  # sliding: μW·(I − z zᵀ)/(u_y·|z_trial|)
        g = mu * w / (p[_UY] * norm)
        k[0, 0] = k_r + g * (1.0 - zx * zx)
        k[0, 1] = -g * zx * zy
        k[1, 0] = k[0, 1]
        k[1, 1] = k_r + g * (1.0 - zy * zy)
    else:  # sticking: μW/u_y in every direction (as the 1D bearing rounds it: μW·(1/u_y))
        k[0, 0] = k_r + mu * w * (1.0 / p[_UY])
        k[0, 1] = 0.0
        k[1, 0] = 0.0
        k[1, 1] = k[0, 0]
    c[0, 0] = w * zx * dmu_x
    c[0, 1] = w * zx * dmu_y
    c[1, 0] = w * zy * dmu_x
    c[1, 1] = w * zy * dmu_y


@njit(cache=True)
def plan_friction_pendulum_commit(p, s, ux, uy, vx, vy):
    """Advance the committed state ``s`` in place to the converged (ux, uy), (vx, vy)."""
    zx, zy, _ = _z(p, s, ux, uy)
    s[_UCX] = ux
    s[_UCY] = uy
    s[_ZCX] = zx
    s[_ZCY] = zy
    s[_VCX] = vx
    s[_VCY] = vy


@njit(cache=True)
def plan_friction_pendulum_energy(p, s):
    """Recoverable energy [kip·in] at the committed state (module docstring)."""
    w = p[_W]
    mu, _, _ = plan_friction_coefficient(p, s[_VCX], s[_VCY])
    u2 = s[_UCX] * s[_UCX] + s[_UCY] * s[_UCY]
    z2 = s[_ZCX] * s[_ZCX] + s[_ZCY] * s[_ZCY]
    return 0.5 * w / p[_R] * u2 + 0.5 * mu * w * p[_UY] * z2


@dataclass(frozen=True)
class BidirectionalFrictionPendulum:
    """Single friction-pendulum bearing in plan, friction coupled (defaults: the paper's bearing).

    Parameters (validated as the 1D :class:`~femoat.structure.materials.FrictionPendulum`)
    ----------
    W : float
        Weight carried by the bearing [kip], > 0.
    R : float
        Effective radius of the sliding surface [in], > 0 (restoring stiffness W/R).
    u_y : float
        Yield displacement of the friction spring [in], > 0 (sticking stiffness μ·W/u_y).
    mu : float
        Friction coefficient [-] in (0, 1): constant, or μ_slow (at v = 0) with ``mu_fast``.
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
        self.uniaxial()  # the same parameters, the same checks and messages

    def uniaxial(self) -> FrictionPendulum:
        """This bearing along one axis: the 1D friction pendulum with the same parameters."""
        return FrictionPendulum(W=self.W, R=self.R, u_y=self.u_y, mu=self.mu,
                                mu_fast=self.mu_fast, a=self.a, v_reg=self.v_reg)

    def params(self) -> np.ndarray:
        """``p`` for the kernels: the 1D bearing's params."""
        return self.uniaxial().params()

    def initial_state(self) -> np.ndarray:
        """Virgin committed state ``s``: at rest at the centre, z = 0."""
        return np.zeros(N_STATE)

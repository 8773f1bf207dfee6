"""The single friction-pendulum bearing: the first bearing kind (:mod:`femoat.bearings`), on one
axis and in plan.

    f = (W/R)·u + μ(v)·W·z          (on one axis: u, v, z scalars; in plan: vectors in x, y)

u [in] is the bearing displacement, v [in/s] its velocity. The restoring term (W/R)·u comes from
the spherical surface of radius R, the same stiffness in every direction; the friction term is
μ(v)·W times a hysteretic variable z that follows an elastic-perfectly-plastic rule with yield
displacement u_y: on one axis z = clip(z_c + (u − u_c)/u_y, −1, 1); in plan z is a vector in the
unit disk, integrated by radial return (the closest point on the disk):

    z_trial = z_c + (u − u_c)/u_y
    z = z_trial                  if |z_trial| <= 1   (sticking: stiffness μW/u_y in every direction)
    z = z_trial/|z_trial|        otherwise           (sliding: friction force μW along z)

so the friction force never exceeds μW in magnitude, whatever the direction of sliding (two
uncoupled one-axis bearings would resist with μW per axis, √2·μW at 45°). Along one axis (u, v
and the committed z on x) the plan form is the one-axis form to the bit, and under a straight
motion along any line it is that bearing along the line.

Friction coefficient (Constantinou et al., 1990, as in OpenSees ``VelDependent``):

    μ = μ_fast − (μ_fast − μ_slow)·exp(−a·s),  s = sqrt(|v|² + ε²) − ε,  ε = ``v_reg`` [in/s]

With μ_fast = μ_slow it is constant Coulomb friction. s is within ε of |v|, zero at v = 0, with
the continuous derivative v/sqrt(|v|² + ε²), so ∂f/∂v is continuous and zero at v = 0 (Newton sees
no jump when the bearing reverses).

Consistent tangent (for a Newton solver), in plan with n = z when sliding:

    ∂f/∂u = (W/R)·I + μW·∂z/∂u,   ∂z/∂u = I/u_y (sticking),  (I − n nᵀ)/(u_y·|z_trial|) (sliding)
    ∂f/∂v = W·z ⊗ ∂μ/∂v

OpenSees twins: on one axis ``singleFPBearing``'s friction model in the 1D building
(:mod:`femoat.opensees.building`); in plan ``flatSliderBearing`` in 3D (FlatSliderSimple3d) with a
``Coulomb`` friction model and kInit = μW/u_y uses the same circular yield surface, radial return
and tangent, its normal force N from its axial material (N = W needs an axial load on the slider
node), in parallel with a linear W/R spring in x and y (:mod:`femoat.opensees.plan`;
``tests/test_plan_bearing.py``). ``singleFPBearing``'s second-order growth of N with V·u/R is not
modelled here.

Params ``p = [W, R, u_y, mu_slow, mu_fast, a, v_reg]`` (kip, in, in, -, -, s/in, in/s), the same on
one axis and in plan. State on one axis ``s = [u_c, z_c, v_c]``: committed displacement [in],
hysteretic variable [-], velocity [in/s]; in plan ``s = [u_cx, u_cy, z_cx, z_cy, v_cx, v_cy]``.

Recoverable energy: (W/R)·|u|²/2 + (μW|z|)²/(2·μW/u_y) = (W/R)·|u|²/2 + μ·W·u_y·|z|²/2, with μ at
the committed velocity.
"""

from dataclasses import dataclass

import numpy as np

from femoat import checks as _checks
from femoat.bearings import registry
from femoat.bearings.rate_form import write_rate
from femoat.compilation.jit import njit

KEY = "fp"
"""The bearing's key in scenario and suite files (``[building.isolator] type = "fp"``)."""

N_PARAMS = 7
N_STATE_AXIS = 3
N_STATE_PLAN = 6
N_STATE = N_STATE_AXIS  # the one-axis form's (the material convention)
_W, _R, _UY, _MU_SLOW, _MU_FAST, _A, _VREG = range(N_PARAMS)
_UCX, _UCY, _ZCX, _ZCY, _VCX, _VCY = range(N_STATE_PLAN)


# ---- on one axis -------------------------------------------------------------------------------

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
def _z_axis(p, s, u):
    """Hysteretic variable and dz/du [1/in] for a trial displacement u."""
    z = s[1] + (u - s[0]) / p[_UY]
    if z > 1.0:
        return 1.0, 0.0
    if z < -1.0:
        return -1.0, 0.0
    return z, 1.0 / p[_UY]


@njit(cache=True)
def axis_trial(p, s, u, v):
    """Force [kip], df/du [kip/in] and df/dv [kip·s/in] at the trial (u [in], v [in/s]) from
    the committed state ``s`` (not modified)."""
    w = p[_W]
    z, dz = _z_axis(p, s, u)
    mu, dmu = friction_coefficient(p, v)
    k_r = w / p[_R]
    return k_r * u + mu * w * z, k_r + mu * w * dz, dmu * w * z


@njit(cache=True)
def axis_commit(p, s, u, v):
    """Advance the committed state ``s`` in place to the converged (u, v)."""
    z, _ = _z_axis(p, s, u)
    s[0] = u
    s[1] = z
    s[2] = v


@njit(cache=True)
def axis_energy(p, s):
    """Recoverable energy [kip·in] at the committed state (module docstring)."""
    w = p[_W]
    mu, _ = friction_coefficient(p, s[2])
    return 0.5 * w / p[_R] * s[0] * s[0] + 0.5 * mu * w * p[_UY] * s[1] * s[1]


# ---- in plan ------------------------------------------------------------------------------------


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


MAX_SUBSTEPS = 256
"""The most pieces a step's path is cut into by :func:`_path_z` (each at most u_y long)."""


@njit(cache=True, inline="always")
def _hermite(th, h, x0, v0, x1, v1):
    """The cubic Hermite interpolant of a path of duration ``h`` at fraction ``th``."""
    t2 = th * th
    t3 = t2 * th
    return ((2 * t3 - 3 * t2 + 1) * x0 + (t3 - 2 * t2 + th) * h * v0
            + (-2 * t3 + 3 * t2) * x1 + (t3 - t2) * h * v1)


@njit(cache=True, inline="always")
def _straight(zx, zy, dx, dy, u_y):
    """(z_x, z_y, |z_trial|): the exact hysteresis along a straight piece (dx, dy) [in] from z.

    The rule's continuous form: ż = u̇/u_y inside the disk (sticking); on its rim, moving
    outwards (z·u̇ > 0), ż = (u̇ − (z·u̇)·z)/u_y (sliding). Along a straight piece of direction
    d the sticking part is a straight line in z up to the rim (|z + σ·d| = 1, σ ≥ 0 the root
    of σ² + 2(z·d)σ + |z|² − 1 = 0); then the angle φ from d to z obeys dφ/ds = −sin φ/u_y, so
    tan(φ/2) decays as exp(−s/u_y). |z_trial| is the single return's, |z + piece/u_y|, for the
    tangent."""
    length = np.sqrt(dx * dx + dy * dy)
    tx, ty = zx + dx / u_y, zy + dy / u_y
    trial = np.sqrt(tx * tx + ty * ty)
    if length == 0.0:
        return zx, zy, trial
    ex, ey = dx / length, dy / length
    b = zx * ex + zy * ey
    c = zx * zx + zy * zy - 1.0
    sigma = -b + np.sqrt(max(b * b - c, 0.0))  # [-] z-travel to the rim
    if sigma * u_y >= length:
        return tx, ty, trial  # sticking all along
    zx, zy = zx + sigma * ex, zy + sigma * ey
    rest = length - sigma * u_y
    cos0 = zx * ex + zy * ey
    sin0 = ex * zy - ey * zx
    t = sin0 / (1.0 + cos0) * np.exp(-rest / u_y) if cos0 > -1.0 else 0.0
    cos1 = (1.0 - t * t) / (1.0 + t * t)
    sin1 = 2.0 * t / (1.0 + t * t)
    return cos1 * ex - sin1 * ey, cos1 * ey + sin1 * ex, max(trial, 1.0 + 1e-15)


@njit(cache=True)
def _path_z(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau):
    """(z_x, z_y, |z_trial|) at the end (ux, uy) of a step of duration ``tau`` [s] that starts
    at the committed state with velocity (v0x, v0y) and ends with (vx, vy) [in/s].

    A single radial return from the committed state follows the chord of the step: on a curved
    path its friction direction lags the sliding direction by half the step's turn, an error of
    first order in the step, and is a backward-Euler step of the rule's continuous form. Here
    the step's cubic Hermite path is cut into straight pieces at most u_y long (at most
    MAX_SUBSTEPS), each integrated exactly (:func:`_straight`): z then follows the path as the
    continuous rule does. Motion along a line through z (the path straight and parallel to
    z, e.g. along one axis) is one radial return, which is exact there: :func:`_z`, the one-axis
    bearing's bits."""
    dx, dy = ux - s[_UCX], uy - s[_UCY]
    cross = abs(dx * v0y - dy * v0x) + abs(dx * vy - dy * vx) + abs(dx * s[_ZCY] - dy * s[_ZCX])
    length = np.sqrt(dx * dx + dy * dy)
    if tau <= 0.0 or cross == 0.0 or length == 0.0:
        return _z(p, s, ux, uy)
    pieces = min(MAX_SUBSTEPS, max(1, int(np.ceil(length / p[_UY]))))
    zx, zy = s[_ZCX], s[_ZCY]
    px, py = s[_UCX], s[_UCY]
    norm = 0.0
    for k in range(1, pieces + 1):
        if k == pieces:
            qx, qy = ux, uy
        else:
            th = k / pieces
            qx = _hermite(th, tau, u0x, v0x, ux, vx)
            qy = _hermite(th, tau, u0y, v0y, uy, vy)
        zx, zy, norm = _straight(zx, zy, qx - px, qy - py, p[_UY])
        px, py = qx, qy
    return zx, zy, norm


@njit(cache=True)
def plan_trial(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau, f, k, c):
    """:func:`plan_return_trial` at the end of a step of duration ``tau`` [s] from
    the committed state (start velocity (v0x, v0y) [in/s]), the friction direction followed
    along the step's path (:func:`_path_z`). The tangent is the last return's (Newton's and
    the error estimate's; the force is exact to the path)."""
    w = p[_W]
    k_r = w / p[_R]
    zx, zy, norm = _path_z(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau)
    mu, dmu_x, dmu_y = plan_friction_coefficient(p, vx, vy)
    f[0] = k_r * ux + mu * w * zx
    f[1] = k_r * uy + mu * w * zy
    if norm > 1.0:  # sliding: the softer of the last piece's and the chord's tangent
        norm = max(norm, _z(p, s, ux, uy)[2])
    _tangents(p, w, k_r, mu, dmu_x, dmu_y, zx, zy, norm, k, c)


@njit(cache=True)
def plan_commit(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau):
    """:func:`plan_return_commit` along the step's path (:func:`_path_z`)."""
    zx, zy, _ = _path_z(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau)
    s[_UCX] = ux
    s[_UCY] = uy
    s[_ZCX] = zx
    s[_ZCY] = zy
    s[_VCX] = vx
    s[_VCY] = vy


@njit(cache=True)
def plan_z_trial(p, s, ux, uy):
    """|z_trial| [-] at the trial (ux, uy) [in] from the committed state ``s``: above 1 the
    bearing slides, at or below it sticks (the branch the solver's kink search follows)."""
    zx = s[_ZCX] + (ux - s[_UCX]) / p[_UY]
    zy = s[_ZCY] + (uy - s[_UCY]) / p[_UY]
    return np.sqrt(zx * zx + zy * zy)


@njit(cache=True)
def plan_z(s):
    """The committed hysteretic vector (z_x, z_y) [-] (on the unit circle while sliding)."""
    return s[_ZCX], s[_ZCY]


@njit(cache=True)
def plan_branch(p, s, ux, uy):
    """The branch of the trial (ux, uy) [in] from the committed state: 1 sliding (|z_trial| > 1),
    0 sticking (the kink search lands a step where it changes)."""
    return 1 if plan_z_trial(p, s, ux, uy) > 1.0 else 0


@njit(cache=True)
def plan_turn_direction(s):
    """The committed friction direction z while sliding (on the unit circle), (0, 0) while
    sticking: a velocity along it that turns negative unloads the bearing into sticking."""
    zx, zy = plan_z(s)
    if zx * zx + zy * zy < 1.0 - 1e-9:
        return 0.0, 0.0
    return zx, zy


@njit(cache=True)
def plan_return_trial(p, s, ux, uy, vx, vy, f, k, c):
    """Force ``f`` [kip] (2,), ∂f/∂u ``k`` [kip/in] (2, 2) and ∂f/∂v ``c`` [kip·s/in] (2, 2),
    written in place, at the trial (ux, uy) [in], (vx, vy) [in/s] from the committed state
    ``s``, which is not modified: one radial return (a path of no duration)."""
    plan_trial(p, s, s[_UCX], s[_UCY], 0.0, 0.0, ux, uy, vx, vy, 0.0, f, k, c)


@njit(cache=True, inline="always")
def _tangents(p, w, k_r, mu, dmu_x, dmu_y, zx, zy, norm, k, c):
    """∂f/∂u into ``k``, ∂f/∂v into ``c`` (module docstring) at z after a return whose trial
    had length ``norm``."""
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
def plan_return_commit(p, s, ux, uy, vx, vy):
    """Advance the committed state ``s`` in place to the converged (ux, uy), (vx, vy): one
    radial return (a path of no duration)."""
    plan_commit(p, s, s[_UCX], s[_UCY], 0.0, 0.0, ux, uy, vx, vy, 0.0)


# ---- in plan, the rate form (the coupled-friction step, femoat.integration.methods.ark5) -------


@njit(cache=True)
def plan_rate_active(p, s, vx, vy):
    """True when the committed state slides (z on the rim) and the velocity (vx, vy) [in/s] keeps
    loading it (z·v > 0): over a step from here z is a state with the rate :func:`plan_rate`."""
    zx, zy = s[_ZCX], s[_ZCY]
    return zx * zx + zy * zy >= 1.0 - 1e-9 and zx * vx + zy * vy > 0.0


N_RATE_PLAN = 2
"""The rate form's state: z (z_x, z_y) [-]."""


@njit(cache=True)
def plan_rate_state(p, s, z):
    """The committed rate-form variable z (z_x, z_y) [-] into ``z``; returns its width, 2."""
    z[0] = s[_ZCX]
    z[1] = s[_ZCY]
    return N_RATE_PLAN


@njit(cache=True)
def rim_rate(p, zx, zy, vx, vy):
    """(g_x, g_y, ∂g_x/∂z_x, ∂g_x/∂z_y, ∂g_y/∂z_x, ∂g_y/∂z_y): the sliding rule's rate
    ż = g(z, v) = (v − (z·v)·z)/u_y [1/s] at z and the velocity (vx, vy) [in/s], and its
    Jacobian ∂g/∂z = −((z·v)·I + z·vᵀ)/u_y. On the rim the rule of :func:`_straight`; off it
    |z| is drawn back to 1 at the rate 2(z·v)/u_y. Along a line through z (v ∥ z, |z| = 1) the
    rate is exactly zero."""
    u_y = p[_UY]
    zv = zx * vx + zy * vy
    return ((vx - zv * zx) / u_y, (vy - zv * zy) / u_y,
            -(zv + zx * vx) / u_y, -(zx * vy) / u_y, -(zy * vx) / u_y, -(zv + zy * vy) / u_y)


@njit(cache=True)
def plan_rate(p, s, ux, uy, vx, vy, z, g, J):
    """The rate ż = g(z, v) of :func:`rim_rate` into ``g`` (2,) and its Jacobian into ``J``
    (at least 2 × 2) at the velocity (vx, vy) [in/s] (the displacement does not enter)."""
    write_rate(rim_rate(p, z[0], z[1], vx, vy), g, J)


@njit(cache=True)
def _moved_back(p, s, ux, uy):
    """Whether the trial (ux, uy) [in] from the committed state is inside the disk: the bearing
    has moved back and unloads (sticks) there, whatever a carried z says."""
    tx = s[_ZCX] + (ux - s[_UCX]) / p[_UY]
    ty = s[_ZCY] + (uy - s[_UCY]) / p[_UY]
    return tx * tx + ty * ty <= 1.0


@njit(cache=True)
def plan_rate_force(p, s, ux, uy, vx, vy, z, f, k, c):
    """Force ``f`` [kip] (2,), ∂f/∂u ``k`` [kip/in] and ∂f/∂v ``c`` [kip·s/in] (2, 2) in place at
    (ux, uy) [in], (vx, vy) [in/s] with the friction state z = (zx, zy) [-] given (a stage's):
    f = (W/R)·u + μ(v)·W·z (z a state: no friction stiffness). A trial that is back inside the
    disk from the committed state ``s`` (the stage moved back) reads the radial return instead,
    as the one-axis clip does (along a line: the one-axis force to the bit, whatever the signs
    of a tableau's coefficients)."""
    if _moved_back(p, s, ux, uy):
        plan_return_trial(p, s, ux, uy, vx, vy, f, k, c)
        return
    zx, zy = z[0], z[1]
    w = p[_W]
    k_r = w / p[_R]
    mu, dmu_x, dmu_y = plan_friction_coefficient(p, vx, vy)
    f[0] = k_r * ux + mu * w * zx
    f[1] = k_r * uy + mu * w * zy
    k[0, 0] = k_r
    k[0, 1] = 0.0
    k[1, 0] = 0.0
    k[1, 1] = k_r
    c[0, 0] = w * zx * dmu_x
    c[0, 1] = w * zx * dmu_y
    c[1, 0] = w * zy * dmu_x
    c[1, 1] = w * zy * dmu_y


@njit(cache=True)
def plan_rate_commit(p, s, ux, uy, vx, vy, z):
    """Commit the end (ux, uy), (vx, vy) of a step that carried z as a state, z = (zx, zy) its
    end value: put on the rim (the rate form leaves |z| − 1 at the step's truncation error; on
    the rim the branch and turn searches see a sliding bearing); a trial back inside the disk
    commits the radial return (as :func:`plan_rate_force` reads it)."""
    if _moved_back(p, s, ux, uy):
        plan_return_commit(p, s, ux, uy, vx, vy)
        return
    zx, zy = z[0], z[1]
    norm = np.sqrt(zx * zx + zy * zy)
    s[_UCX] = ux
    s[_UCY] = uy
    s[_ZCX] = zx / norm
    s[_ZCY] = zy / norm
    s[_VCX] = vx
    s[_VCY] = vy


@njit(cache=True)
def plan_energy(p, s):
    """Recoverable energy [kip·in] at the committed state (module docstring)."""
    w = p[_W]
    mu, _, _ = plan_friction_coefficient(p, s[_VCX], s[_VCY])
    u2 = s[_UCX] * s[_UCX] + s[_UCY] * s[_UCY]
    z2 = s[_ZCX] * s[_ZCX] + s[_ZCY] * s[_ZCY]
    return 0.5 * w / p[_R] * u2 + 0.5 * mu * w * p[_UY] * z2


@dataclass(frozen=True)
class _FrictionPendulumParameters:
    """The parameters, checks and params array of the single friction pendulum, on one axis and in
    plan (the two faces below)."""

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

    def initial_state_axis(self) -> np.ndarray:
        """Virgin committed state ``s`` on one axis: at rest at the centre, z = 0."""
        return np.zeros(N_STATE_AXIS)

    def initial_state_plan(self) -> np.ndarray:
        """Virgin committed state ``s`` in plan: at rest at the centre, z = 0."""
        return np.zeros(N_STATE_PLAN)

    @property
    def capacity(self) -> float:
        """No displacement capacity of its own [in]: the building's ``isolator_capacity`` holds."""
        return float("inf")



@dataclass(frozen=True)
class FrictionPendulum(_FrictionPendulumParameters):
    """Single friction-pendulum bearing on one axis (defaults: the paper's test bearings, R = 30 in).

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

    def initial_state(self) -> np.ndarray:
        """Virgin committed state ``s`` on one axis: at rest at the centre, z = 0."""
        return np.zeros(N_STATE_AXIS)

    @property
    def code(self):
        """The material code of this bearing on one axis (:mod:`femoat.bearings.registry`)."""
        return registry.axis_code(self)


@dataclass(frozen=True)
class BidirectionalFrictionPendulum(_FrictionPendulumParameters):
    """Single friction-pendulum bearing in plan, friction coupled (defaults: the paper's bearing).

    The same parameters, checks and kernels as :class:`FrictionPendulum`, its plan face: a plan
    building takes this class, a 1D building that one, so that a model says which form its
    isolator has (equality compares the class too).

    Parameters
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

    def uniaxial(self) -> FrictionPendulum:
        """This bearing along one axis: the 1D friction pendulum with the same parameters."""
        return FrictionPendulum(W=self.W, R=self.R, u_y=self.u_y, mu=self.mu,
                                mu_fast=self.mu_fast, a=self.a, v_reg=self.v_reg)

    def initial_state(self) -> np.ndarray:
        """Virgin committed state ``s`` in plan: at rest at the centre, z = 0."""
        return np.zeros(N_STATE_PLAN)


AXIS_CLASS = FrictionPendulum
"""The bearing on one axis (the isolator of a 1D building)."""

PLAN_CLASS = BidirectionalFrictionPendulum
"""The bearing in plan (the isolator of a plan building)."""


# ---- OpenSees twins ------------------------------------------------------------------------------

OPENSEES_AXIAL_LOAD = True
"""The plan twin's slider takes its normal force from its axial material: the base mat's vertical
DOF is free and a gravity step puts N = W on it before the transient (femoat.opensees.plan)."""

OPENSEES_AXIAL_STIFFNESS = 1.0e6
"""Axial (and rotational) stiffness of the flat slider [kip/in]: it only carries N = W."""


def opensees_axis_material(bearing, mat_tag):
    """The openseespy calls of the 1D twin of ``bearing``: ``Elastic`` W/R in ``Parallel`` with
    ``ElasticPP`` (μW/u_y, u_y), the same elastic-perfectly-plastic rule as the one-axis kernels;
    the last material is the bearing. Returns (commands, the next free material tag).

    Raises ValueError for a velocity-dependent μ (``mu_fast``): ElasticPP's friction is
    constant (the 3D twin's ``VelDependent`` friction model is close, not exact)."""
    b = bearing
    if b.mu_fast is not None:
        raise ValueError(
            "isolator: a velocity-dependent friction coefficient (mu_fast) has no exact OpenSees "
            "twin in 1D (ElasticPP friction is constant-μ; the 3D twin femoat.opensees.plan "
            "has a close VelDependent one); set mu_fast=None to cross-check.")
    return [("uniaxialMaterial", "Elastic", mat_tag, b.W / b.R),
            ("uniaxialMaterial", "ElasticPP", mat_tag + 1, b.mu * b.W / b.u_y, b.u_y),
            ("uniaxialMaterial", "Parallel", mat_tag + 2, mat_tag, mat_tag + 1)], mat_tag + 3


def opensees_plan_element(bearing, ele_tag, i_node, j_node, mat_tag):
    """The openseespy calls of the 3D twin of ``bearing`` between ``i_node`` (ground) and
    ``j_node`` of a ``-ndm 3 -ndf 6`` model, shear in global x, y: ``flatSliderBearing``
    ``ele_tag`` (friction model ``mat_tag``: ``Coulomb`` μ, or ``VelDependent`` (μ_slow, μ_fast,
    a); kInit = μ_slow·W/u_y; a stiff axial material; rotations and torsion elastic) in parallel
    with a ``zeroLength`` W/R spring ``ele_tag + 1`` in x and y. Its normal force comes from the
    axial load W (:data:`OPENSEES_AXIAL_LOAD`). Returns (commands, the next free material
    tag)."""
    b = bearing
    friction = (("frictionModel", "Coulomb", mat_tag, b.mu) if b.mu_fast is None else
                ("frictionModel", "VelDependent", mat_tag, b.mu, b.mu_fast, b.a))
    return [friction,
            ("uniaxialMaterial", "Elastic", mat_tag, OPENSEES_AXIAL_STIFFNESS),
            ("uniaxialMaterial", "Elastic", mat_tag + 1, b.W / b.R),
            # local x along global z (the bearing's axis), local y along global x: the shear
            # directions y, z are the global x, y
            ("element", "flatSliderBearing", ele_tag, i_node, j_node, mat_tag,
             b.mu * b.W / b.u_y, "-P", mat_tag, "-T", mat_tag, "-My", mat_tag, "-Mz", mat_tag,
             "-orient", 0.0, 0.0, 1.0, 1.0, 0.0, 0.0),
            ("element", "zeroLength", ele_tag + 1, i_node, j_node,
             "-mat", mat_tag + 1, mat_tag + 1, "-dir", 1, 2)], mat_tag + 2

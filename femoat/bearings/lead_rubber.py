"""The lead-rubber bearing: a biaxial Bouc-Wen hysteretic bearing, the second bearing kind
(:mod:`femoat.bearings`), on one axis and in plan.

    f = K_d·u + Q_d·z                      (on one axis: u, z scalars; in plan: vectors in x, y)

    u_y·dz = A·du − (β·sgn(z·du) + γ)·|z|^(η−2)·(z·du)·z

u [in] is the bearing displacement, f [kip] its shear force. The rubber gives the linear term
K_d·u; the lead core the hysteretic term Q_d·z, z [-] following the coupled Bouc-Wen rule of
Park, Wen & Ang (1986) in the isotropic form of OpenSees' ``elastomericBearingBoucWen`` (3D:
ElastomericBearingBoucWen3d), whose sign term is sgn(z·du), so that the bearing responds alike in
every direction. On one axis the rule is the classical Bouc-Wen law

    u_y·dz/du = A − (β·sgn(z·du) + γ)·|z|^η

with β on the sign term (Wen's and OpenSees' convention; LeadRubberX and Nagarajaiah et al. 1991
swap the names). Parameters: Q_d [kip] the characteristic strength, K_d [kip/in] the post-yield
stiffness, K_u [kip/in] the elastic stiffness, the yield displacement u_y = Q_d/(K_u − K_d)
[in] derived, A = 1 (fixed, as in OpenSees' element: the elastic stiffness is then
K_d + Q_d·A/u_y = K_u), β > 0, γ > −β and the exponent η >= 1 (default 1, the value of
OpenSees' documentation and its example). Loading (z·du > 0) drives |z| towards its cap
(A/(β + γ))^(1/η), 1 for β + γ = 1 (the characteristic strength is Q_d times the cap); unloading
has dz/du = (A − (γ − β)·|z|^η)/u_y, elastic (K_u) for β = γ. As η grows the loop tends to the
bilinear loop of strength Q_d and yield displacement u_y.

In plan the nonlinear term is along z, so it changes |z| only: z's direction turns towards the
motion's at the elastic rate A/u_y, and at most the cap is reached (never crossed).

Integration. The rule is rate-independent: z depends on the path of u, not on time. A trial
integrates z along the step's path from the committed state: the chord from the committed
displacement when the path is straight (on one axis, at tau = 0, or when both end velocities lie
along the chord), else the step's cubic Hermite path (its end displacements and velocities, tau
only scaling the velocities into a path) cut into straight pieces at most :data:`PIECE`·u_y long.
(On a curved path the chord alone errs by O(step²) in the force over a few u_y of travel:
measured 2e-3 of the force at 0.3 in steps on a 3 in circle, 1e-5 with the pieces.) Along a
straight segment Δu the component a = z·Δu/|Δu| increases monotonically (for β > 0, γ > −β), so
it has at most two phases: unloading (a < 0, β·sgn + γ = γ − β) up to the point where a = 0,
then loading (β + γ). Each phase is a flow with a constant coefficient c, integrated exactly
where a closed form exists:

* c = 0 (unloading with β = γ, the default): z + A·Δu/u_y, any η;
* η = 2: along the chord's direction d, a = z·d obeys a Riccati equation and the part b across
  it a linear one: a = (C·a_0 + (A/u_y)·S)/(C + (c/u_y)·S·a_0), b = b_0/(C + (c/u_y)·S·a_0),
  C = cosh(ω s), S = sinh(ω s)/ω, ω² = A·c/u_y² (cos, sin for c < 0) after a length s; the end
  of unloading is at tanh(ω s)/ω = −a_0·u_y/A;
* η = 1 with z along the chord (one axis, or from z = 0): u_y·da/ds = A − κ·a with κ = ±c,
  an exponential, and the end of unloading in closed form;

otherwise by classical Runge-Kutta (order 4) in the chord's fraction, each substep at most
:data:`STEP`·u_y/max(1, η/cap) long (the law's stiffness near the cap grows as η/u_y) and at most
:data:`GRADE`·|z|·u_y (near z = 0 the law for η < 2 is not smooth: z turns into the motion over
a length |z|·u_y, e.g. when loading starts after an unloading that nearly reversed z); the end of
unloading is then found by Newton's method on the same integrator. Against converged references
(``benchmarks/lrb_bearing.py``) the error in z is a few 1e-8 at worst for η = 1 and smaller for
η >= 2, three orders below the solver's default rtol; the result is a smooth function of the
trial but for jumps of that size where the substeps change. STEP = 0.05 is where the worst error
stops being set by the rule near z = 0 and falls at the method's order (the benchmark's table).

Tangent ∂f/∂u = K_d·I + Q_d·∂z/∂u, consistent: the derivative of the update itself with respect
to the end displacement (the closed forms differentiated, the Runge-Kutta stages carried with
their derivative, the pieces of a path by the Hermite weight of the end point), the substep and
piece fractions held fixed (the end of unloading moves with the trial, but the flow is continuous
across it, so its derivative does not enter). At a zero increment the derivative depends on the
direction of the next increment (the reversal kink); the trial velocity chooses it (loading if
z·v > 0, else unloading). ∂f/∂v = 0: the path's shape depends on the end velocity, by a weight
of order tau, which the tangent leaves out.

Branches: the force is continuously differentiable along any path except where the path reverses
(z·du changes sign with z != 0, the loading and unloading coefficients differ by 2β|z|^η) and,
in plan, where unloading ends (a = 0 with z across the motion: the nonlinear term is zero on
both sides, its derivative across the motion is not). :func:`plan_branch` gives the phase at the
end of the chord (1 loading, 0 unloading; on one axis always 1, unloading ending at z = 0 with a
continuous tangent), so the kink search lands on the end of unloading; the reversals are found
by the solver's turning-point search along :func:`plan_turn_direction`: the committed z
direction when a reversal there changes the tangent by more than :data:`TURN_RATIO` (the 1D
solver's criterion for materials, femoat.integration.kinks.KINK_RATIO), else (0, 0). Since the
kernel has no parameters, :func:`plan_commit` stores that direction in the state.

Rate form (the coupled-friction step, femoat.integration.methods.ark5): while loading
(z·v > 0, |z| >= :data:`Z_CARRY`) z is a state of the step with the loading rule as its rate,
ż = (A·v − (β + γ)·|z|^(η−2)·(z·v)·z)/u_y, and f = K_d·u + Q_d·z; unloading follows the
step's path from the committed state as above (for β = γ exactly: z + A·Δu/u_y). A carried
step's commit sets the turning direction to z's whatever the tangents: every reversal of a
carried z is landed on (searched on z·v with z moving in the step), so the loading rate never
runs past one.

Recoverable energy: K_d·|u|²/2 + Q_d·u_y·|z|²/(2A), the hysteretic spring's as if unloaded at
its elastic stiffness Q_d·A/u_y (exact for β = γ).

OpenSees twins (:func:`opensees_plan_element`, :func:`opensees_axis_material`): in 3D
``elastomericBearingBoucWen`` with kInit = K_u, qd = Q_d, alpha1 = K_d/K_u, alpha2 = 0 and the
same η, β, γ (its u_y = qd/((1 − alpha1)·kInit) is this one). Older OpenSees sources (the 2012
revision) read the ``qd`` slot as a yield force F_y and used (1 − alpha1)·F_y as the strength;
openseespy 3.7 reads it as Q_d, as documented (the twin test checks the strength). On one axis
``uniaxialMaterial BoucWen`` (z in displacement units, A0 = 1, gamma = γ/u_y^η, beta = β/u_y^η,
no degradation). Both take one backward-Euler step per
increment (Newton on z): first-order accurate in the increment, converging to this bearing.
``LeadRubberX`` is not a twin: its biaxial rule is Park-Wen-Ang's with a sign per component,
sgn(z_x·du_x) and sgn(z_y·du_y) (not isotropic), with η = 2, β = 0.1, γ = 0.9 hard-coded.

Lead heating (Kalpakidis & Constantinou 2009, LeadRubberX's option: Q_d·exp(−E_2·ΔT_L) with the
lead temperature driven by the power Q_d·|v|·|z|) is not modelled: it is rate-dependent (it
integrates the dissipated power over time, where this rule depends on the path only) and
LeadRubberX integrates it from its node velocities, which are zero in a static analysis, so it
has no static twin to check it against; its constants are in SI units and it needs the bearing's
geometry (lead core diameter, layers, shims), none of which this bearing carries.

Params ``p = [Q_d, K_d, K_u, u_y, beta, gamma, eta]`` (kip, kip/in, kip/in, in, -, -, -), the same
on one axis and in plan. State on one axis ``s = [u_c, z_c]``: committed displacement [in] and
hysteretic variable [-]; in plan ``s = [u_cx, u_cy, z_cx, z_cy, t_x, t_y]``, (t_x, t_y) the
committed turning direction (:func:`plan_turn_direction`).
"""

import math
from dataclasses import dataclass

import numpy as np

from femoat import checks as _checks
from femoat.bearings.faces import BearingFaces
from femoat.bearings.rate_form import write_rate
from femoat.compilation.jit import njit

KEY = "lrb"
"""The bearing's key in scenario and suite files (``[building.isolator] type = "lrb"``)."""

N_PARAMS = 7
N_STATE_AXIS = 2
N_STATE_PLAN = 6
N_STATE = N_STATE_AXIS  # the one-axis form's (the material convention)
_QD, _KD, _KU, _UY, _BETA, _GAMMA, _ETA = range(N_PARAMS)
_UCX, _UCY, _ZCX, _ZCY, _TX, _TY = range(N_STATE_PLAN)

A = 1.0
"""Bouc-Wen's A [-], fixed: the elastic stiffness is K_u by definition (as in OpenSees' element)."""

STEP = 0.05
"""Runge-Kutta substeps are at most STEP·u_y/max(1, η/cap) long (module docstring)."""

GRADE = 0.1
"""Runge-Kutta substeps are also at most GRADE·|z|·u_y long (at the start of each substep): near
z = 0, where z turns into the motion over a length |z|·u_y."""

GRADE_LEVELS = 20
"""A substep is at least 2^-GRADE_LEVELS of STEP·u_y/rate long."""

PIECE = 0.05
"""A curved step's path is cut into straight pieces at most PIECE·u_y long (module docstring)."""

MAX_PIECES = 256
"""The most pieces a step's path is cut into."""

MAX_SUBSTEPS = 2 ** 20
"""A guard against a runaway loop: the most Runge-Kutta substeps per phase of a chord (a chord
of 5e4·u_y/max(1, η/cap), far beyond any step)."""

TURN_RATIO = 0.5
"""A reversal whose tangent differs by more than this fraction is a turning point for the solver
(femoat.integration.kinks.KINK_RATIO, the criterion of the 1D solver's materials)."""


# ---- scalar functions of the closed forms -------------------------------------------------------


@njit(cache=True)
def _hyper(q):
    """With C = cosh(√q), S = sinh(√q)/√q, G = (C − 1)/q (cos, sin for q < 0: analytic through
    0): 1/C, S/C, G/C, (dS/dq)/C, (dG/dq)/C (dC/dq = S/2), bounded for any q >= 0."""
    if abs(q) < 1e-2:  # Taylor series: truncation below 1e-15
        big_c = 1.0 + q * (0.5 + q * (1.0 / 24.0 + q * (1.0 / 720.0 + q / 40320.0)))
        s = 1.0 + q * (1.0 / 6.0 + q * (1.0 / 120.0 + q * (1.0 / 5040.0 + q / 362880.0)))
        g = 0.5 + q * (1.0 / 24.0 + q * (1.0 / 720.0 + q * (1.0 / 40320.0 + q / 3628800.0)))
        ds = 1.0 / 6.0 + q * (1.0 / 60.0 + q * (1.0 / 1680.0 + q / 90720.0))
        dg = 1.0 / 24.0 + q * (1.0 / 360.0 + q * (1.0 / 13440.0 + q / 907200.0))
        return 1.0 / big_c, s / big_c, g / big_c, ds / big_c, dg / big_c
    if q > 0.0:
        x = np.sqrt(q)
        ic, sc = 1.0 / np.cosh(x), np.tanh(x) / x
    else:  # only while unloading with β > γ, before the end of unloading: √−q < π/2
        x = np.sqrt(-q)
        ic, sc = 1.0 / np.cos(x), np.tan(x) / x
    gc = (1.0 - ic) / q
    return ic, sc, gc, (1.0 - sc) / (2.0 * q), (0.5 * sc - gc) / q


@njit(cache=True)
def _atanc(y):
    """artanh(√y)/√y (arctan(√−y)/√−y for y < 0), 1 at y = 0."""
    if abs(y) < 1e-4:
        return 1.0 + y * (1.0 / 3.0 + y * (0.2 + y / 7.0))
    if y > 0.0:
        x = np.sqrt(y)
        return np.arctanh(x) / x
    x = np.sqrt(-y)
    return np.arctan(x) / x


@njit(cache=True)
def _log1pc(x):
    """log(1 + x)/x, 1 at x = 0."""
    return 1.0 if x == 0.0 else np.log1p(x) / x


@njit(cache=True)
def _expc(x):
    """(1 − exp(−x))/x, 1 at x = 0."""
    return 1.0 if x == 0.0 else -np.expm1(-x) / x


@njit(cache=True)
def _phi(c, eta, rho):
    """c·|z|^(η−2) (|z| = rho > 0)."""
    if eta == 2.0:
        return c
    if eta == 1.0:
        return c / rho
    return c * rho ** (eta - 2.0)


# ---- one phase of a straight segment: z and M = ∂z/∂u (row i, column j: ∂z_i/∂u_j) ------------


@njit(cache=True)
def _linear_piece(yd, zx, zy, mxx, mxy, myx, myy, dx, dy, frac, w):
    """The fraction ``frac`` of the segment (dx, dy) with c = 0: z + A·frac·Δu/u_y, exactly.
    M = ∂z/∂u (the trial's end displacement), the segment being w·I of it (every piece below)."""
    g = frac * A / yd
    return zx + g * dx, zy + g * dy, mxx + w * g, mxy, myx, myy + w * g


@njit(cache=True)
def _mobius_piece(c, yd, zx, zy, mxx, mxy, myx, myy, dx, dy, frac, w):
    """The fraction ``frac`` of the segment (dx, dy) for η = 2, exactly (module docstring), with its
    derivatives: z_1 = N/D, N = z_0 + (k·G·p_0 + (A/u_y)·S)·Δp, D = C + (c/u_y)·S·p_0,
    p_0 = z_0·Δp, q = k·|Δp|², k = A·c/u_y² (:func:`_hyper`), N and D divided by C."""
    px, py = frac * dx, frac * dy
    kq = A * c / (yd * yd)
    ic, sc, gc, dsc, dgc = _hyper(kq * (px * px + py * py))
    p0 = zx * px + zy * py
    e = A / yd
    w = w * frac  # this piece's share of ∂Δu/∂u
    h = (c / yd) * sc
    lam = kq * gc * p0 + e * sc
    den = 1.0 + h * p0
    z1x = (ic * zx + lam * px) / den
    z1y = (ic * zy + lam * py) / den
    # ∂z1/∂z0 = (I/C + k·(G/C)·Δp Δpᵀ − z1·h·Δpᵀ)/D'
    r = kq * gc
    jxx = (ic + r * px * px - z1x * h * px) / den
    jxy = (r * px * py - z1x * h * py) / den
    jyx = (r * py * px - z1y * h * px) / den
    jyy = (ic + r * py * py - z1y * h * py) / den
    # (∂N/∂Δp)/C = λ'·I + Δp·(k·(G/C)·z0 + 2k·(k·G'/C·p0 + e·S'/C)·Δp)ᵀ
    # (∂D/∂Δp)/C = (k·S/C + 2k·(c/u_y)·(S'/C)·p0)·Δpᵀ + h·z0ᵀ
    t = 2.0 * kq * (kq * dgc * p0 + e * dsc)
    nx, ny = r * zx + t * px, r * zy + t * py
    m = kq * sc + 2.0 * kq * (c / yd) * dsc * p0
    qx, qy = m * px + h * zx, m * py + h * zy
    kxx = (lam + px * nx - z1x * qx) / den
    kxy = (px * ny - z1x * qy) / den
    kyx = (py * nx - z1y * qx) / den
    kyy = (lam + py * ny - z1y * qy) / den
    return (z1x, z1y,
            jxx * mxx + jxy * myx + w * kxx, jxx * mxy + jxy * myy + w * kxy,
            jyx * mxx + jyy * myx + w * kyx, jyx * mxy + jyy * myy + w * kyy)


@njit(cache=True)
def _line_piece(kappa, yd, zx, zy, mxx, mxy, myx, myy, dx, dy, frac, w):
    """The fraction ``frac`` of the segment (dx, dy) for η = 1 with z along the chord, exactly:
    u_y·da/ds = A − κ·a, κ = c·sgn(a) on this phase. Derivatives: e^(−x)·I for z0; for the
    chord (A − κ·a_1)/u_y along it, (A/u_y)·E(x) across it (z's perpendicular part obeys
    u_y·db/ds = A·dΔu_⊥/ds − κ·b there)."""
    px, py = frac * dx, frac * dy
    w = w * frac
    lp = np.sqrt(px * px + py * py)
    ex, ey = px / lp, py / lp
    a0 = zx * ex + zy * ey
    x = kappa * lp / yd
    big_e = _expc(x)
    a1 = a0 + (A - kappa * a0) * (lp / yd) * big_e
    decay = np.exp(-x)
    along = (A - kappa * a1) / yd
    across = (A / yd) * big_e
    kxx = across + (along - across) * ex * ex
    kxy = (along - across) * ex * ey
    kyy = across + (along - across) * ey * ey
    return (a1 * ex, a1 * ey, decay * mxx + w * kxx, decay * mxy + w * kxy,
            decay * myx + w * kxy, decay * myy + w * kyy)


@njit(cache=True)
def _rates(c, eta, yd, zx, zy, dx, dy, mxx, mxy, myx, myy, w):
    """dz/dσ along the whole segment (dx, dy) (σ its fraction) and its derivative
    ∂g/∂z·M + w·∂g/∂Δu: g = (A·Δu − φ·(z·Δu)·z)/u_y, φ = c·|z|^(η−2)."""
    rho2 = zx * zx + zy * zy
    e = A / yd
    if rho2 == 0.0:
        return e * dx, e * dy, mxx + w * e, mxy, myx, myy + w * e
    phi = _phi(c, eta, np.sqrt(rho2)) / yd
    p = zx * dx + zy * dy
    gx = e * dx - phi * p * zx
    gy = e * dy - phi * p * zy
    t = (eta - 2.0) * p / rho2  # ∂g/∂z = −φ(p·I + z Δuᵀ + t·z zᵀ)
    gxx = -phi * (p + zx * dx + t * zx * zx)
    gxy = -phi * (zx * dy + t * zx * zy)
    gyx = -phi * (zy * dx + t * zy * zx)
    gyy = -phi * (p + zy * dy + t * zy * zy)
    qxx, qxy, qyy = w * (e - phi * zx * zx), -w * phi * zx * zy, w * (e - phi * zy * zy)
    return (gx, gy, gxx * mxx + gxy * myx + qxx, gxx * mxy + gxy * myy + qxy,
            gyx * mxx + gyy * myx + qxy, gyx * mxy + gyy * myy + qyy)


@njit(cache=True)
def _rk4(c, eta, yd, zx, zy, mxx, mxy, myx, myy, dx, dy, h, w):
    """One classical Runge-Kutta substep of fraction ``h`` of the segment, z with M."""
    k1 = _rates(c, eta, yd, zx, zy, dx, dy, mxx, mxy, myx, myy, w)
    b = 0.5 * h
    k2 = _rates(c, eta, yd, zx + b * k1[0], zy + b * k1[1], dx, dy, mxx + b * k1[2],
                mxy + b * k1[3], myx + b * k1[4], myy + b * k1[5], w)
    k3 = _rates(c, eta, yd, zx + b * k2[0], zy + b * k2[1], dx, dy, mxx + b * k2[2],
                mxy + b * k2[3], myx + b * k2[4], myy + b * k2[5], w)
    k4 = _rates(c, eta, yd, zx + h * k3[0], zy + h * k3[1], dx, dy, mxx + h * k3[2],
                mxy + h * k3[3], myx + h * k3[4], myy + h * k3[5], w)
    s = h / 6.0
    return (zx + s * (k1[0] + 2.0 * (k2[0] + k3[0]) + k4[0]),
            zy + s * (k1[1] + 2.0 * (k2[1] + k3[1]) + k4[1]),
            mxx + s * (k1[2] + 2.0 * (k2[2] + k3[2]) + k4[2]),
            mxy + s * (k1[3] + 2.0 * (k2[3] + k3[3]) + k4[3]),
            myx + s * (k1[4] + 2.0 * (k2[4] + k3[4]) + k4[4]),
            myy + s * (k1[5] + 2.0 * (k2[5] + k3[5]) + k4[5]))


@njit(cache=True)
def _rk_piece(c, eta, yd, rate, zx, zy, mxx, mxy, myx, myy, dx, dy, f0, f1, w):
    """The segment (dx, dy) from fraction f0 to f1 by Runge-Kutta, each substep at most
    STEP·u_y/rate and GRADE·|z|·u_y long (module docstring)."""
    length = np.sqrt(dx * dx + dy * dy)
    hmax = STEP * yd / (rate * length)
    hmin = hmax * 2.0 ** -GRADE_LEVELS
    near = GRADE * yd / length
    z = (zx, zy, mxx, mxy, myx, myy)
    sigma = f0
    for _ in range(MAX_SUBSTEPS - 1):
        h = min(hmax, max(hmin, near * np.sqrt(z[0] * z[0] + z[1] * z[1])))
        rest = f1 - sigma
        if rest <= 1.5 * h:  # the last substep, or the last two halves of the rest
            h = rest if rest <= h else 0.5 * rest
        z = _rk4(c, eta, yd, z[0], z[1], z[2], z[3], z[4], z[5], dx, dy, h, w)
        if h == rest:
            return z
        sigma += h
    return _rk4(c, eta, yd, z[0], z[1], z[2], z[3], z[4], z[5], dx, dy, f1 - sigma, w)


@njit(cache=True)
def _rate(p):
    """The stiffness scale of the law near its cap, in units of 1/u_y: max(1, η/cap)."""
    eta = p[_ETA]
    return max(1.0, eta * (p[_BETA] + p[_GAMMA]) ** (1.0 / eta) / A ** (1.0 / eta))


@njit(cache=True)
def _piece(p, c, sign, one_d, zx, zy, mxx, mxy, myx, myy, dx, dy, f0, f1, w):
    """The segment (dx, dy) from fraction f0 to f1 with the coefficient c (sgn(a) = ``sign`` on
    it), by the exact form that applies, else Runge-Kutta; M carried (the segment is w·I of
    ∂Δu/∂u)."""
    eta, yd = p[_ETA], p[_UY]
    if c == 0.0:
        return _linear_piece(yd, zx, zy, mxx, mxy, myx, myy, dx, dy, f1 - f0, w)
    if eta == 2.0:
        return _mobius_piece(c, yd, zx, zy, mxx, mxy, myx, myy, dx, dy, f1 - f0, w)
    if eta == 1.0 and one_d:
        return _line_piece(c * sign, yd, zx, zy, mxx, mxy, myx, myy, dx, dy, f1 - f0, w)
    return _rk_piece(c, eta, yd, _rate(p), zx, zy, mxx, mxy, myx, myy, dx, dy, f0, f1, w)


@njit(cache=True)
def _unloading_end(p, c, one_d, zx, zy, dx, dy):
    """The fraction of the segment (dx, dy) at which z·Δu reaches 0 from z·Δu < 0 (the end of
    unloading, c = γ − β on the way), 2 if it does not within the segment."""
    eta, yd = p[_ETA], p[_UY]
    length = np.sqrt(dx * dx + dy * dy)
    a0 = (zx * dx + zy * dy) / length
    if c == 0.0:  # u_y·da/ds = A
        return -a0 * yd / (A * length)
    if eta == 2.0:  # tanh(ω s)/ω = −a0·u_y/A
        return -a0 * (yd / A) * _atanc(c * a0 * a0 / A) / length
    if eta == 1.0 and one_d:  # u_y·da/ds = A + c·a
        return -a0 * (yd / A) * _log1pc(c * a0 / A) / length
    end = _piece(p, c, -1.0, one_d, zx, zy, 0.0, 0.0, 0.0, 0.0, dx, dy, 0.0, 1.0, 0.0)
    if end[0] * dx + end[1] * dy <= 0.0:
        return 2.0
    lo, hi = 0.0, 1.0  # Newton's method on a(f), kept inside the bracket
    f = min(0.5, -a0 * yd / (A * length))
    for _ in range(60):
        z = _piece(p, c, -1.0, one_d, zx, zy, 0.0, 0.0, 0.0, 0.0, dx, dy, 0.0, f, 0.0)
        val = z[0] * dx + z[1] * dy
        if val < 0.0:
            lo = f
        else:
            hi = f
        g = _rates(c, eta, yd, z[0], z[1], dx, dy, 0.0, 0.0, 0.0, 0.0, 0.0)
        slope = g[0] * dx + g[1] * dy
        new = f - val / slope if slope > 0.0 else 0.5 * (lo + hi)
        if not lo < new < hi:
            new = 0.5 * (lo + hi)
        if abs(new - f) <= 1e-15 or hi - lo <= 1e-15:
            return new
        f = new
    return f


@njit(cache=True)
def _segment(p, zx, zy, mxx, mxy, myx, myy, dx, dy, w):
    """(z, M) at the end of the straight segment (dx, dy) [in] from z, M: its unloading phase
    (if z·Δu < 0) up to its end, then its loading phase (module docstring)."""
    c_load = p[_BETA] + p[_GAMMA]
    c_unload = p[_GAMMA] - p[_BETA]
    one_d = zx * dy - zy * dx == 0.0
    if zx * dx + zy * dy < 0.0:
        end = _unloading_end(p, c_unload, one_d, zx, zy, dx, dy)
        if end >= 1.0:
            return _piece(p, c_unload, -1.0, one_d, zx, zy, mxx, mxy, myx, myy, dx, dy, 0.0, 1.0,
                          w)
        z = _piece(p, c_unload, -1.0, one_d, zx, zy, mxx, mxy, myx, myy, dx, dy, 0.0, end, w)
        return _piece(p, c_load, 1.0, one_d, z[0], z[1], z[2], z[3], z[4], z[5], dx, dy, end,
                      1.0, w)
    return _piece(p, c_load, 1.0, one_d, zx, zy, mxx, mxy, myx, myy, dx, dy, 0.0, 1.0, w)


@njit(cache=True)
def _z_path(p, ucx, ucy, zcx, zcy, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau):
    """(z_x, z_y, ∂z_x/∂u_x, ∂z_x/∂u_y, ∂z_y/∂u_x, ∂z_y/∂u_y) at the end (ux, uy) [in] of a step
    of duration ``tau`` [s] from the committed (ucx, ucy), z_c with start velocity (v0x, v0y) and
    end velocity (vx, vy) [in/s]: along the chord if the path is straight (tau = 0, or both
    velocities along the chord), else along the step's cubic Hermite path cut into pieces at
    most PIECE·u_y long (module docstring). At a zero increment the velocity chooses the
    tangent."""
    yd = p[_UY]
    dx, dy = ux - ucx, uy - ucy
    if dx == 0.0 and dy == 0.0:
        rho2 = zcx * zcx + zcy * zcy
        e = A / yd
        if rho2 == 0.0:
            return zcx, zcy, e, 0.0, 0.0, e
        c = p[_BETA] + p[_GAMMA] if zcx * vx + zcy * vy > 0.0 else p[_GAMMA] - p[_BETA]
        phi = _phi(c, p[_ETA], np.sqrt(rho2)) / yd
        return (zcx, zcy, e - phi * zcx * zcx, -phi * zcx * zcy, -phi * zcy * zcx,
                e - phi * zcy * zcy)
    if tau <= 0.0 or (dx * v0y - dy * v0x == 0.0 and dx * vy - dy * vx == 0.0):
        return _segment(p, zcx, zcy, 0.0, 0.0, 0.0, 0.0, dx, dy, 1.0)
    length = max(np.sqrt(dx * dx + dy * dy),
                 0.5 * tau * (np.sqrt(v0x * v0x + v0y * v0y) + np.sqrt(vx * vx + vy * vy)))
    pieces = min(MAX_PIECES, max(1, int(np.ceil(length / (PIECE * yd)))))
    z = (zcx, zcy, 0.0, 0.0, 0.0, 0.0)
    px, py, h_prev = ucx, ucy, 0.0
    for k in range(1, pieces + 1):
        th = k / pieces
        t2 = th * th
        t3 = t2 * th
        h01 = 3.0 * t2 - 2.0 * t3  # ∂q/∂u of the Hermite point q(θ)
        if k == pieces:
            qx, qy = ux, uy
        else:
            h00, h10, h11 = 2.0 * t3 - 3.0 * t2 + 1.0, t3 - 2.0 * t2 + th, t3 - t2
            qx = h00 * u0x + h10 * tau * v0x + h01 * ux + h11 * tau * vx
            qy = h00 * u0y + h10 * tau * v0y + h01 * uy + h11 * tau * vy
        if qx != px or qy != py:
            z = _segment(p, z[0], z[1], z[2], z[3], z[4], z[5], qx - px, qy - py, h01 - h_prev)
        px, py, h_prev = qx, qy, h01
    return z


@njit(cache=True)
def _bearing(p, ucx, ucy, zcx, zcy, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau):
    """The bearing, written once: (f_x, f_y [kip], ∂f/∂u (xx, xy, yx, yy) [kip/in], z_x, z_y)
    at the end (ux, uy) [in], (vx, vy) [in/s] of a step (:func:`_z_path`) from the committed
    displacement and z. The one-axis kernels call it with the y components and tau zero (the
    chord)."""
    zx, zy, mxx, mxy, myx, myy = _z_path(p, ucx, ucy, zcx, zcy, u0x, u0y, v0x, v0y, ux, uy,
                                         vx, vy, tau)
    qd, kd = p[_QD], p[_KD]
    return (kd * ux + qd * zx, kd * uy + qd * zy, kd + qd * mxx, qd * mxy, qd * myx,
            kd + qd * myy, zx, zy)


# ---- on one axis --------------------------------------------------------------------------------


@njit(cache=True)
def axis_trial(p, s, u, v):
    """Force [kip], df/du [kip/in] and df/dv (0) at the trial (u [in], v [in/s]) from the
    committed state ``s`` (not modified): :func:`_bearing` on the x axis."""
    r = _bearing(p, s[0], 0.0, s[1], 0.0, s[0], 0.0, 0.0, 0.0, u, 0.0, v, 0.0, 0.0)
    return r[0], r[2], 0.0


@njit(cache=True)
def axis_commit(p, s, u, v):
    """Advance the committed state ``s`` in place to the converged (u, v)."""
    r = _bearing(p, s[0], 0.0, s[1], 0.0, s[0], 0.0, 0.0, 0.0, u, 0.0, v, 0.0, 0.0)
    s[0] = u
    s[1] = r[6]


@njit(cache=True)
def axis_energy(p, s):
    """Recoverable energy [kip·in] at the committed state (module docstring)."""
    return 0.5 * p[_KD] * s[0] * s[0] + 0.5 * p[_QD] * p[_UY] * s[1] * s[1] / A


# ---- in plan ------------------------------------------------------------------------------------


@njit(cache=True)
def plan_trial(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau, f, k, c):
    """Force ``f`` [kip] (2,), ∂f/∂u ``k`` [kip/in] and ∂f/∂v ``c`` (zero) (2, 2), written in
    place, at the end (ux, uy) [in], (vx, vy) [in/s] of a step of duration ``tau`` [s] from the
    committed state ``s`` (not modified), start velocity (v0x, v0y): z along the step's path
    (:func:`_z_path`; the chord for tau = 0)."""
    r = _bearing(p, s[_UCX], s[_UCY], s[_ZCX], s[_ZCY], u0x, u0y, v0x, v0y, ux, uy, vx, vy,
                 tau)
    f[0] = r[0]
    f[1] = r[1]
    k[0, 0] = r[2]
    k[0, 1] = r[3]
    k[1, 0] = r[4]
    k[1, 1] = r[5]
    c[0, 0] = 0.0
    c[0, 1] = 0.0
    c[1, 0] = 0.0
    c[1, 1] = 0.0


@njit(cache=True)
def plan_commit(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau):
    """Advance the committed state ``s`` in place to the converged end (ux, uy) of the step: z
    along its path (as :func:`plan_trial`), and the turning direction for the solver
    (:func:`plan_turn_direction`)."""
    r = _bearing(p, s[_UCX], s[_UCY], s[_ZCX], s[_ZCY], u0x, u0y, v0x, v0y, ux, uy, vx, vy,
                 tau)
    zx, zy = r[6], r[7]
    s[_UCX] = ux
    s[_UCY] = uy
    s[_ZCX] = zx
    s[_ZCY] = zy
    tx, ty = _turning(p, zx, zy)
    s[_TX] = tx
    s[_TY] = ty


@njit(cache=True)
def _turning(p, zx, zy):
    """z's direction if a reversal at z changes the tangent by more than TURN_RATIO, else (0, 0):
    the loading and unloading tangents K_d + Q_d·(A − c·|z|^η)/u_y, c = β + γ or γ − β."""
    rho = np.sqrt(zx * zx + zy * zy)
    if rho == 0.0:
        return 0.0, 0.0
    r_eta = rho ** p[_ETA]
    g = p[_QD] / p[_UY]
    k_on = p[_KD] + g * (A - (p[_BETA] + p[_GAMMA]) * r_eta)
    k_back = p[_KD] + g * (A - (p[_GAMMA] - p[_BETA]) * r_eta)
    if abs(k_back - k_on) <= TURN_RATIO * max(abs(k_on), abs(k_back)):
        return 0.0, 0.0
    return zx / rho, zy / rho


@njit(cache=True)
def plan_energy(p, s):
    """Recoverable energy [kip·in] at the committed state (module docstring)."""
    u2 = s[_UCX] * s[_UCX] + s[_UCY] * s[_UCY]
    z2 = s[_ZCX] * s[_ZCX] + s[_ZCY] * s[_ZCY]
    return 0.5 * p[_KD] * u2 + 0.5 * p[_QD] * p[_UY] * z2 / A


@njit(cache=True)
def plan_branch(p, s, ux, uy):
    """The phase at the trial (ux, uy) [in] reached along the chord from the committed state:
    1 loading (z·Δu >= 0 at its end), 0 still unloading. The end of unloading is where the
    path's coefficient changes (γ − β to β + γ): in plan, where z is across the motion, the
    tangent across it changes there, and beyond it z depends on the path again; the kink search
    lands a step on it. Along z (one axis) unloading ends at z = 0 with a continuous tangent:
    no kink, 1 throughout, as the one-axis bearing. (The other kinks are the reversals, which
    :func:`plan_turn_direction` locates.)"""
    dx, dy = ux - s[_UCX], uy - s[_UCY]
    zx, zy = s[_ZCX], s[_ZCY]
    if zx * dx + zy * dy >= 0.0 or dx * dx + dy * dy == 0.0:
        return 1
    if zx * dy - zy * dx == 0.0:
        return 1  # along z (one axis): unloading ends at z = 0, where the tangent is continuous
    return 0 if _unloading_end(p, p[_GAMMA] - p[_BETA], False, zx, zy, dx, dy) >= 1.0 else 1


# ---- in plan, the rate form (the coupled-friction step, femoat.integration.methods.ark5) -------


Z_CARRY = 1e-6
"""[-] |z| from which the rate form carries z. At z = 0 the rule for η < 2 has no direction to
carry (its rate is continuous there, its Jacobian bounded, its higher derivatives not), so a
virgin bearing's first step follows the step's path; from this |z| on z is carried (at 0.05
the path's share of a circular orbit set a second-order floor, benchmarks/README.md)."""


@njit(cache=True)
def plan_rate_active(p, s, vx, vy):
    """True when the committed z is at least Z_CARRY long and the velocity (vx, vy) [in/s]
    loads it (z·v > 0): over a step from here z is a state with the loading rate
    :func:`plan_rate`. Unloading (z·v < 0) follows the step's path from the committed state
    (for β = γ exactly: z + A·Δu/u_y does not depend on the path)."""
    zx, zy = s[_ZCX], s[_ZCY]
    return zx * zx + zy * zy >= Z_CARRY * Z_CARRY and zx * vx + zy * vy > 0.0


N_RATE_PLAN = 2
"""The rate form's state: z (z_x, z_y) [-]."""


@njit(cache=True)
def plan_rate_state(p, s, z):
    """The committed rate-form variable z (z_x, z_y) [-] into ``z``; returns its width, 2."""
    z[0] = s[_ZCX]
    z[1] = s[_ZCY]
    return N_RATE_PLAN


@njit(cache=True)
def loading_rate(p, zx, zy, vx, vy):
    """(g_x, g_y, ∂g_x/∂z_x, ∂g_x/∂z_y, ∂g_y/∂z_x, ∂g_y/∂z_y): the loading rule's rate
    ż = g(z, v) = (A·v − (β + γ)·|z|^(η−2)·(z·v)·z)/u_y [1/s] at z and the velocity (vx, vy)
    [in/s], and its Jacobian (the path integration's :func:`_rates` with the velocity as the
    segment). The coefficient is the loading one throughout: a step carries z only while
    loading, and the reversals are landed on (:func:`plan_rate_commit`)."""
    return _rates(p[_BETA] + p[_GAMMA], p[_ETA], p[_UY], zx, zy, vx, vy, 1.0, 0.0, 0.0, 1.0,
                  0.0)


@njit(cache=True)
def plan_rate(p, s, ux, uy, vx, vy, z, g, J):
    """The rate of :func:`loading_rate` into ``g`` (2,) and its Jacobian into ``J`` (at least
    2 × 2) at the velocity (vx, vy) [in/s] (the displacement does not enter)."""
    write_rate(loading_rate(p, z[0], z[1], vx, vy), g, J)


@njit(cache=True)
def plan_rate_force(p, s, ux, uy, vx, vy, z, f, k, c):
    """Force ``f`` [kip] (2,), ∂f/∂u ``k`` [kip/in] and ∂f/∂v ``c`` (zero) (2, 2) in place at
    (ux, uy) [in] with the state z = (zx, zy) [-] given (a stage's): f = K_d·u + Q_d·z (z a
    state: the hysteretic term adds no stiffness)."""
    qd, kd = p[_QD], p[_KD]
    zx, zy = z[0], z[1]
    f[0] = kd * ux + qd * zx
    f[1] = kd * uy + qd * zy
    k[0, 0] = kd
    k[0, 1] = 0.0
    k[1, 0] = 0.0
    k[1, 1] = kd
    c[0, 0] = 0.0
    c[0, 1] = 0.0
    c[1, 0] = 0.0
    c[1, 1] = 0.0


@njit(cache=True)
def plan_rate_commit(p, s, ux, uy, vx, vy, z):
    """Commit the end (ux, uy) of a step that carried z, z = (zx, zy) its end value, and z's
    direction as the turning direction whatever the tangents (every reversal of a carried z is
    then landed on: the loading rate must not run past one)."""
    zx, zy = z[0], z[1]
    s[_UCX] = ux
    s[_UCY] = uy
    s[_ZCX] = zx
    s[_ZCY] = zy
    rho = np.sqrt(zx * zx + zy * zy)
    s[_TX] = zx / rho
    s[_TY] = zy / rho


@njit(cache=True)
def plan_turn_direction(s):
    """The committed direction of z when a reversal there is a kink for the solver (the
    tangent changes by more than TURN_RATIO), else (0, 0): a velocity along it that turns
    negative unloads the bearing."""
    return s[_TX], s[_TY]


# ---- the parameters -----------------------------------------------------------------------------


@dataclass(frozen=True)
class LeadRubberBearing(BearingFaces):
    """Lead-rubber bearing (biaxial Bouc-Wen), on one axis and in plan: one class for both faces.

    Defaults: the isolation of the paper building (W = 33 kip, its four masses on one bearing):
    Q_d = 2.0 kip ≈ 0.06·W, the friction pendulum's μ·W; K_d = 0.45 kip/in, a post-yield period
    T_d = 2π·sqrt(W/(g·K_d)) = 2.74 s; K_u = 4.5 kip/in = 10·K_d, hence u_y = Q_d/(K_u − K_d)
    = 0.49 in, a usual lead-rubber yield displacement; η = 1, β = γ = 0.5 (OpenSees'
    documented defaults and example).

    Parameters
    ----------
    Q_d : float
        Characteristic strength [kip], > 0: the force at zero displacement on the loop (times
        the cap (1/(β + γ))^(1/η), 1 for β + γ = 1).
    K_d : float
        Post-yield stiffness [kip/in], >= 0 (the rubber's).
    K_u : float
        Elastic (unloading) stiffness [kip/in], > K_d.
    beta : float
        Bouc-Wen β [-] (on the sign term), > 0: loading and unloading differ by 2β.
    gamma : float
        Bouc-Wen γ [-], > −beta.
    eta : float
        Bouc-Wen exponent η [-] in [1, 100]: the larger, the sharper the yield (bilinear as
        η → ∞).
    capacity : float
        Displacement capacity [in], > 0 (math.inf: none; e.g. a shear-strain limit times the
        rubber height).
    """

    Q_d: float = 2.0
    K_d: float = 0.45
    K_u: float = 4.5
    beta: float = 0.5
    gamma: float = 0.5
    eta: float = 1.0
    capacity: float = math.inf

    def __post_init__(self):
        _checks.positive("Q_d", self.Q_d, "[kip]")
        _checks.non_negative("K_d", self.K_d, "[kip/in]")
        _checks.positive("K_u", self.K_u, "[kip/in]")
        if self.K_u <= self.K_d:
            raise ValueError(f"K_u = {self.K_u!r} [kip/in]: must be > K_d = {self.K_d!r} (the "
                             "elastic stiffness exceeds the post-yield one; K_u ≈ 10·K_d is "
                             "usual).")
        _checks.positive("beta", self.beta, "[-]")
        _checks.finite("gamma", self.gamma, "[-]")
        if self.gamma <= -self.beta:
            raise ValueError(f"gamma = {self.gamma!r} [-]: must be > -beta = {-self.beta!r} "
                             "(β + γ > 0 bounds z; β = γ = 0.5 is usual).")
        _checks.in_range("eta", self.eta, "[-]", 1.0, 100.0)
        _checks.positive_or_inf("capacity", self.capacity, "[in]")

    @property
    def u_y(self) -> float:
        """Yield displacement [in]: Q_d/(K_u − K_d)."""
        return self.Q_d / (self.K_u - self.K_d)

    @property
    def yield_deformation(self) -> float:
        """Deformation at which the lead yields [in]: u_y."""
        return self.u_y

    @property
    def z_cap(self) -> float:
        """The largest |z| [-]: (A/(β + γ))^(1/η)."""
        return (A / (self.beta + self.gamma)) ** (1.0 / self.eta)

    def params(self) -> np.ndarray:
        return np.array([self.Q_d, self.K_d, self.K_u, self.u_y, self.beta, self.gamma,
                         self.eta], dtype=np.float64)


AXIS_CLASS = LeadRubberBearing
"""The bearing on one axis (the isolator of a 1D building)."""

PLAN_CLASS = LeadRubberBearing
"""The bearing in plan (the isolator of a plan building): the same class."""


# ---- OpenSees twins -----------------------------------------------------------------------------

OPENSEES_AXIAL_LOAD = False
"""The plan twin needs no normal force (the hysteresis does not depend on it): the base mat's
vertical DOF stays fixed, no gravity step."""

AXIAL_STIFFNESS = 1.0e6
"""Stiffness [kip/in, kip·in/rad] of the twin element's axial, torsional and rocking springs."""


def opensees_plan_element(bearing, ele_tag, i_node, j_node, mat_tag):
    """The openseespy calls, ``(function name, *args)`` tuples, of the 3D twin of ``bearing``
    between nodes ``i_node`` (ground) and ``j_node`` of a ``-ndm 3 -ndf 6`` model, shear in
    global x and y (the bearing's axis along global z): ``elastomericBearingBoucWen`` with
    kInit = K_u, qd = Q_d, alpha1 = K_d/K_u, no nonlinear hardening (alpha2 = 0, mu unused), the
    same η, β, γ, and stiff elastic springs on the other four components (the j node's vertical
    displacement is held by the axial one). Returns (commands, the next free material tag)."""
    b = bearing
    cmds = [("uniaxialMaterial", "Elastic", mat_tag, AXIAL_STIFFNESS),
            # local x along global z, local y along global x: shear y, z = global x, y
            ("element", "elastomericBearingBoucWen", ele_tag, i_node, j_node, b.K_u, b.Q_d,
             b.K_d / b.K_u, 0.0, 2.0, b.eta, b.beta, b.gamma,
             "-P", mat_tag, "-T", mat_tag, "-My", mat_tag, "-Mz", mat_tag,
             "-orient", 0.0, 0.0, 1.0, 1.0, 0.0, 0.0)]
    return cmds, mat_tag + 1


def opensees_axis_material(bearing, mat_tag):
    """The openseespy calls of the 1D twin of ``bearing``: ``uniaxialMaterial BoucWen`` (z in
    displacement units: Z = u_y·z) with alpha = K_d/K_u, ko = K_u, n = η, gamma = γ/u_y^η,
    beta = β/u_y^η, A0 = 1, no degradation, Newton tolerance 1e-12. Returns (commands, the next
    free material tag)."""
    b = bearing
    scale = b.u_y ** b.eta
    cmds = [("uniaxialMaterial", "BoucWen", mat_tag, b.K_d / b.K_u, b.K_u, b.eta,
             b.gamma / scale, b.beta / scale, A, 0.0, 0.0, 0.0, 1e-12, 50)]
    return cmds, mat_tag + 1

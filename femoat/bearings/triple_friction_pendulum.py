"""The triple friction-pendulum bearing: a bearing kind (:mod:`femoat.bearings`), one plan element
that is also its own one-axis form.

Notation of OpenSees' ``TripleFrictionPendulum`` (Dao et al., 2013): L1 the effective radius
(R − h) of the two inner surfaces (the inner slider, friction μ1, displacement capacity d1 on
each), L2 and L3 those of the two outer surfaces (friction μ2 and μ3, capacities d2 and d3).
In Fenz & Constantinou's (2008) notation 1, 2/3, 4: L2 = R_eff1, L1 = R_eff2 = R_eff3,
L3 = R_eff4, μ2 = μ_1, μ1 = μ_2 = μ_3, μ3 = μ_4, d2 = d_1, d1 = d_2 = d_3, d3 = d_4.

Effective and manufacturer's notation (:meth:`TripleFrictionPendulum.from_geometry`). A
manufacturer (and Fenz & Constantinou, 2008) gives each surface's actual radius of curvature R,
the height h of the slider's pivot above it and its nominal displacement capacity d* (the
slider's travel along the surface to the restrainer). The pivot moves on a circle of radius
R − h concentric with the surface: a rotation θ moves the slider R·θ along the surface and the
pivot, hence the bearing, (R − h)·θ. So the pendulum's length is the effective radius
L = R − h, and the actual capacity, the bearing's displacement on that surface when the slider
meets the restrainer, is d = d*·(R − h)/R, a little less than d*. This class's L1..L3 and
d1..d3, like OpenSees' (whose documentation defines L_i = R_i − h_i, and whose
TripleFrictionPendulumX, the same series model, takes d_i as the actual capacities, L_i/R_i
times the nominal ones), are the effective radii and the actual capacities. ``from_geometry``
takes R1..R3, h1..h3 and d1_nominal..d3_nominal [in] with OpenSees' indices (1 the two inner
surfaces, 2 and 3 the outer ones; in Fenz & Constantinou's: R1 = R_2 = R_3, R2 = R_1, R3 = R_4,
h and d* alike) and returns L_i = R_i − h_i, d_i = d_i,nominal·L_i/R_i. (Fenz & Constantinou
star the nominal capacity, d_i*; TripleFrictionPendulumX's documentation stars the actual one:
hence the spelled-out ``_nominal``.)

Series model (Fenz & Constantinou, 2008): three plan friction pendulums in series carry the same
force F [kip] and add up to the bearing's displacement u = d_1 + d_2 + d_3 [in]:

    element 1 (inner slider, surfaces 2 and 3):  radius 2·L1,     friction μ1, gap 2·(d1 + L1·m)
    element 2 (outer surface of L2):              radius L2 − L1,  friction μ2, gap d2·(1 − L1/L2)
    element 3 (outer surface of L3):              radius L3 − L1,  friction μ3, gap d3·(1 − L1/L3)

with m = min(d2/L2, d3/L3). Each element i is a single friction pendulum (as in
:mod:`femoat.bearings.friction_pendulum`) plus a restrainer, in parallel:

    f_i = (W/L̄_i)·d_i + μ_i·W·z_i + k_0·(|d_i| − g_i)₊·d_i/|d_i|

z_i the element's hysteretic vector in the unit disk, integrated by radial return with the
element's yield displacement u_y,i = μ_i·W/(k_0 − W/L̄_i), so that every element is elastic with
the one stiffness k_0 = 3·μ1·W/u_y while it sticks: three in series start at μ1·W/u_y, and the
bearing first slides at a displacement 3·u_y,1 ≈ u_y (``yield_deformation``). The restrainer of
element i (the slider reaching the rim of its surfaces) acts past its gap g_i with the same
stiffness k_0 (as OpenSees' element). The bearing stiffens for good once element 1 reaches its
gap, at ``capacity`` = g_1 + g_2 + g_3 = 2·d1 + d2 + d3 − L1·|d2/L2 − d3/L3| [in].

Regimes on one axis, rigid-plastic (u_y → 0), with μ1 < μ2 ≤ μ3 and the outer surface of L2
reaching its restrainer first (F_dr1 ≤ F_dr4), F&C's closed forms, F [kip] against u [in]:

    I    0    ≤ u ≤ u*:     F = μ1·W + W·u/(2·L1)                   (element 1 slides)
    II   u*   ≤ u ≤ u**:    F = μ2·W + W·(u − u*)/(L1 + L2)         (1 and 2)
    III  u**  ≤ u ≤ u_dr1:  F = μ3·W + W·(u − u**)/(L2 + L3)        (1, 2 and 3)
    IV   u_dr1 ≤ u ≤ u_dr4: F = F_dr1 + W·(u − u_dr1)/(L1 + L3)     (2 at its restrainer)
    V    u_dr4 ≤ u ≤ u_ult: F = F_dr4 + W·(u − u_dr4)/(2·L1)        (3 too)

    u* = 2·L1·(μ2 − μ1),  u** = u* + (L1 + L2)·(μ3 − μ2),
    F_dr1 = W·(μ2 + d2/L2),  u_dr1 = u** + (L2 + L3)·(F_dr1/W − μ3),
    F_dr4 = W·(μ3 + d3/L3),  u_dr4 = u_dr1 + (L1 + L3)·(F_dr4 − F_dr1)/W,
    u_ult = ``capacity``     (F = W·(μ1 + d1/L1 + m))

With u_y > 0 each element i sticking carries d_i = F/k_0, sliding d_i = (F − μ_i·W)·L̄_i/W, the
larger of the two (it starts sliding at F = μ_i·W·k_0/(k_0 − W/L̄_i)), and past its gap
d_i = g_i + (F − μ_i·W − W·g_i/L̄_i)/(W/L̄_i + k_0): the backbone is u(F) = Σ d_i(F), which the
tests check to round-off, and which tends to F&C's as u_y → 0 (at first order in u_y).

Ultimate displacement. OpenSees' documentation gives 2·d1 + d2 + d3 + L1·d3/L3 − L1·d2/L2 (its
element 1's gap is 2·(d1 + L1·d3/L3)). With both outer sliders at their restrainers (F&C's
regime V) the inner slider's displacements on the surfaces next to those of L2 and L3 are
L1·(F/W − μ1 − d2/L2) and L1·(F/W − μ1 − d3/L3): the first to reach d1 is the one next to the
outer surface of smaller d/L, at u = 2·d1 + d2 + d3 − L1·|d2/L2 − d3/L3|. That is OpenSees'
formula when d3/L3 ≤ d2/L2 (a symmetric bearing: 2·d1 + 2·d2); otherwise OpenSees stiffens
2·L1·(d3/L3 − d2/L2) too late. This module uses m = min(d2/L2, d3/L3); its OpenSees twin
(:func:`opensees_plan_element`) lists the outer surfaces so that OpenSees' gap is the same.

Series solve (one per trial or per piece of a curved step's path, from the committed internal
state or the previous piece's): the internal displacements minimise the elements' incremental
energy Φ = Σ φ_i(d_i) subject to Σ d_i = u, with

    φ_i(d) = (W/L̄_i)·|d|²/2 + μ_i·W·u_y,i·H(z_c,i + (d − d_c,i)/u_y,i) + k_0·(|d| − g_i)₊²/2,
    H(t) = |t|²/2 (|t| ≤ 1), |t| − 1/2 (|t| > 1),

whose gradient is f_i(d): strictly convex (W/L̄_i > 0), so the series state exists and is unique;
the common force F is the constraint's multiplier. Newton's step from a feasible point keeps
Σ d_i = u: with K_i = ∂f_i/∂d_i (symmetric, positive definite) and C_i = K_i⁻¹,

    F = (Σ C_i)⁻¹·Σ C_i·f_i,   Δd_i = C_i·(F − f_i)      (2×2 matrices only),

halved until Φ decreases enough (Armijo), which makes it converge from any start. It starts
from the committed state with the increment split by each element's compliance as it was
(sliding on along its z, or sticking): exact on one axis when no element changes branch. On
one axis Φ is piecewise quadratic and Newton ends on the exact solution (1.1 iterations a
trial on a random history, the last one the check); in plan it converges quadratically (3.5 to
4.6; at most 15 seen, 12 for one step from rest to past the capacity: measured by
``benchmarks/tfp_bearing.py``). It stops when the largest internal step is below
TOLERANCE·(|u| + capacity). The force returned is the last F (second-order accurate in that
step), the consistent tangent ∂F/∂u = (Σ C_i)⁻¹ at the solution (the condensed series). The
force and tangent are NaN only for a NaN or infinite trial, or if the iteration had not come
within ACCEPT·(|u| + capacity) after MAX_ITERATIONS (never seen); the solver turns NaN into an
error. ∂F/∂v = 0: constant friction does not read the velocity, and velocity-dependent friction
reads the slip over the step's duration, a function of the displacement (its rate effect is in
∂F/∂u); a curved step's force depends on its end velocity through the shape of its path, which
the tangent ignores.

Path of a step: a single series solve from the committed state follows the chord of the step:
each element's return is a backward-Euler step of the friction rule, so on a curved path its
friction direction lags the sliding direction by about half the step's turn, an error of first
order in the step (the paper building in plan under a bidirectional record: 1.2e-3 on a story
drift at the solver's default rtol, halving per decade of rtol). The plan kernels therefore
follow the step's path (the contract's start u0, velocities v0 and v, duration tau): its cubic
Hermite path is cut into :data:`PIECES` pieces at equal steps of its parameter, each a series
solve from the previous piece's end state (held in the state's scratch slots). When the path is
straight (tau <= 0, a zero increment, or both velocities and every committed internal vector
along the chord, e.g. on one axis) it is the chord: one solve. Along one axis the
plan element is thus the one-axis element to the bit: the axis kernels call the plan core with
u_y = v_y = 0.

The error stays of first order, in the piece (each piece's return is a backward-Euler step):
1/PIECES of the chord's on circles and figure eights with steps of 0.05 to 0.5 in (the tests).
A fixed count rather than a length (the single pendulum's u_y, the lead-rubber bearing's
0.05·u_y): replaying the paper building's base trajectory through the kernels against pieces
of 2e-5 in, the chord's error per step hardly depends on the step's length (median 0.0035 in,
about the inner element's u_y,1), so pieces of a given length (0.001 in, 6.7 a step on average)
or of a given turn (0.001 rad, 7.8 a step) do worse than 4 a step (largest force error 1.8e-3
and 2.7e-3 of the peak force against 1.3e-3; the chord 5e-3). In the whole solver (the paper
building in plan on this bearing's defaults, Erzincan along x and its reversal at 0.6 along y,
turned by 30°, 8 s, Newmark at its default rtol = 1e-5; the worst peak against a converged
reference, the CPU against the chord's):

    pieces        1        2        4        8        16
    error      1.2e-3   6.6e-4   3.4e-4   1.7e-4   1.2e-4
    CPU        1        1.3      1.8      2.7      ~4

(the single friction pendulum's default: 2.6e-4). Four pieces put the bearing at the other kinds'
accuracy. The tangent is the last piece's (Newton only needs it approximately: 20 % more
iterations than with the chord).

Rate form (the coupled-friction step, :mod:`femoat.integration.methods.ark5`; a plan run's
default): each element that slides and loads carries its z as a state of the step (in plan the
outer element can slide while the inner one sticks; an element a hair inside its rim that would
reach it within :data:`SNAP` counts as sliding, one moving within :data:`LOADING` of
perpendicular to its z as unloading; ``N_RATE_PLAN`` = 6: z_1, z_2, z_3; the carried mask in
the scratch slot ``_CARRY``, set by :func:`plan_rate_active`). The series carries one force F, so with each
element's compliance C_i (its spring and restrainer, and for a carried element the sliding rule's
μ_i·W/u_y,i·(I − z_i z_iᵀ), for the others their sticking stiffness) Ḟ = (Σ C_i)⁻¹·v, ḋ_i = C_i·Ḟ,
and a carried z moves by the single pendulum's rule on its own displacement rate,
ż_i = (ḋ_i − (z_i·ḋ_i)·z_i)/u_y,i (:func:`plan_rate`, with its 6 × 6 Jacobian). At a stage the
force is the series solve with the carried elements sliding at their given z and the others
from the committed state (:func:`_carried_solve`): exact while they stick. The switches are
landed on: an element that starts to slide (the kink search follows the carried z along the step,
:func:`plan_rate_branch`), a carried element that unloads (z_i·Ḟ crossing zero,
:func:`plan_rate_turn`). Along one axis the rates vanish and the plan run is the 1D default run
to the bit. Measured orders on the bearing alone and the cost on real records:
``benchmarks/README.md`` (issue 28).

OpenSees twin: ``TripleFrictionPendulum`` (Dao et al., 2013) is this series model, each element
a kinematic-hardening plasticity (elastic modulus E = 3·μ1_OS/u_y_OS·W for all three, the
quirk) in parallel with a circular gap spring of stiffness E. Linear kinematic hardening with a
circular yield surface and radial return is exactly a spring of the post-yield stiffness in
parallel with an elastic-perfectly-plastic disk of stiffness E − W/L̄_i and strength
μ_OS·(1 − W/(L̄_i·E)): OpenSees' friction force while sliding is μ_OS·W·(1 − W/(L̄_i·E)), not
μ_OS·W. :func:`opensees_plan_element` therefore gives OpenSees μ_i·k_0/(k_0 − W/L̄_i) and
u_y_OS = u_y·μ1_OS/μ1, so that its elements are these to round-off.

Params ``p = [W, u_y, k_0, kr_1, q_1, uy_1, g_1, kr_2, q_2, uy_2, g_2, kr_3, q_3, uy_3, g_3,
scale]``: weight [kip], u_y [in], k_0 [kip/in], then per element its restoring stiffness W/L̄_i
[kip/in], friction force μ_i·W [kip], yield displacement [in] and gap [in], and the length
[in] that scales the solver's tolerances (the capacity). State (``N_STATE_PLAN`` = 24 in plan;
on one axis the same then the step's duration, ``N_STATE_AXIS`` = 25): ``s[:12] = [d_1x, d_1y, d_2x, d_2y, d_3x, d_3y, z_1x,
z_1y, z_2x, z_2y, z_3x, z_3y]``, the committed internal displacements [in] and hysteretic
vectors [-] (on one axis the y entries stay 0), which only ``plan_commit`` and ``axis_commit``
modify; ``s[12:]`` scratch slots, the internal state at the end of a piece while a plan trial
walks a curved path (written by ``plan_trial`` and ``plan_commit``, never read before they write
them: not part of the state's value); on one axis ``s[-1]`` the duration [s] of the step being
solved, written by the loop (:data:`femoat.structure.materials.kernels.DURATION`).

Recoverable energy: Σ_i (W/L̄_i)·|d_i|²/2 + μ_i·W·u_y,i·|z_i|²/2 + k_0·(|d_i| − g_i)₊²/2.

Velocity-dependent friction (``mu1_fast``, ``mu2_fast``, ``mu3_fast``, ``a``). Each surface's
friction follows Constantinou's law at its own sliding speed, μ_i(v) = μ_fast,i −
(μ_fast,i − μ_i)·e^(−a·v) (μ_i then the value at rest), the surface's speed being fact_i times
its element's slip rate (fact = 1/2 for the inner slider, whose element spans its two surfaces,
L2/(L2 − L1) and L3/(L3 − L1) for the outer ones: OpenSees' v1Fact, v3Fact, v5Fact). Unlike the
single pendulum, whose μ(v) reads the bearing's own velocity, the surfaces' rates are not a
function of the bearing's state and velocity: with the sliders massless, two elements sliding
share one force, W·d_1/L̄_1 + μ_1(ḋ_1)·W = W·d_2/L̄_2 + μ_2(ḋ_2)·W with ḋ_1 + ḋ_2 = v, and the
split of v follows from the friction laws' slopes (relaxation rate ~(1/L̄_1 + 1/L̄_2)/μ′, large
and unbounded as μ′ → 0 at speed, where it tends to the rate-independent split). Each element
is therefore an elastic-viscoplastic friction disk: its friction force Q (|Q| ≤ μ_i·W: sticking,
the elastic stiffness k_e = k_0 − W/L̄_i; beyond it the slip rate w with |Q| = μ_i(fact_i·w)·W,
along Q), integrated by the backward-Euler step over the step's duration τ (each piece's, on a
curved path) (:func:`_rate_return`): the elastic trial Q_tr = Q_n + k_e·Δd, and where
|Q_tr| > μ_i·W the rate w solving |Q_tr| − μ_i(fact_i·w)·W = k_e·τ·w (one root: the left side
falls, the right rises), Q = μ_i(fact_i·w)·W along Q_tr. Its incremental potential
|Q|²/(2·k_e) + τ·D(w), D(w) = ∫₀ʷ μ(fact·s)·W ds, has Q as gradient and is convex, so the
series solve (Newton with its line search) holds unchanged, with the consistent tangent
k_e·(γ·n nᵀ + |Q|/|Q_tr|·(I − n nᵀ)), γ = q′/(q′ + k_e·τ). Constant friction is its μ_fast = μ
case (the same return to round-off: tested); ``z`` stores Q/(μ_i·W), so |z| > 1 while an element
slides faster than at rest. The step is first order in τ (a steady orbit's force converges at
first order to its closed form: tested); OpenSees' element does the same step but reads each
friction law at its element's whole deformation rate |Δd_i|/Δt from its previous Newton
iteration. It needs the step's duration: the plan kernels are given it, the one-axis kernels
read it from the last entry of their state row, where the loop writes the duration of the step it
is solving (:data:`femoat.structure.materials.kernels.DURATION`; the one-axis kernels are the
plan element at (u, 0) with that duration, to the bit: tested). On one axis a velocity-dependent
bearing runs on Newmark's step (the explicit pairs refuse it: their stages would take the return
over their offsets).

In plan it runs on the coupled-friction step (ark5, the plan default) by the same model's rate
form (:func:`_viscous_rate`): each element within :data:`CARRY_INSIDE` of its rim or beyond
carries z_i = Q_i/(μ_i·W) as a state, sliding or not, with ż_i = (ḋ_i − w_i(|z_i|)·n_i)/u_y,i,
the slip rate w_i the friction law's inverse (0 inside the disk, where the rate is the sticking
one; so an element that unloads has a continuous rate and no turn is landed on), and ḋ_i from
the series' one force. The continuous model is the backward-Euler return's: Newmark's path form
and ark5 converge to the same runs (tested). Where the law flattens the rate is stiff (the
eigenvalue −w′(|z|)/u_y grows as e^(a·fact·w)), which the implicit part of the step absorbs;
beyond a·fact·w = :data:`RATE_CAP` the inverse goes on along its tangent (the friction within
1e-13 of μ_fast). It needs μ_fast > μ_slow on all three surfaces (:func:`rate_form_covers`:
a bearing with some equal pairs takes Newmark).
"""

from dataclasses import dataclass

import numpy as np

from femoat import checks as _checks
from femoat.bearings.faces import BearingFaces
from femoat.bearings.friction_pendulum import _hermite
from femoat.bearings.rate_form import turn_along
from femoat.compilation.jit import njit

KEY = "tfp"
"""The bearing's key in scenario and suite files (``[building.isolator] type = "tfp"``)."""

GEOMETRY_KEYS = ("R1", "R2", "R3", "h1", "h2", "h3", "d1_nominal", "d2_nominal", "d3_nominal")
"""The manufacturer's geometry [in] (:meth:`TripleFrictionPendulum.from_geometry`): keys a
``[building.isolator]`` table of this kind may give instead of :data:`GEOMETRY_REPLACES`."""

GEOMETRY_REPLACES = ("L1", "L2", "L3", "d1", "d2", "d3")
"""The fields the geometry determines (a table gives these or :data:`GEOMETRY_KEYS`, not both)."""

N_PARAMS = 22
N_STATE_PLAN = 24  # the committed internal state, then the scratch slots of a path's pieces
N_STATE_AXIS = N_STATE_PLAN + 1  # the plan element's (y entries at 0), then the step's duration
N_STATE = N_STATE_AXIS  # the one-axis form's (the material convention)
_W, _UY, _K0 = range(3)
_E0 = 3  # element i's [kr, q, uy, gap] start at _E0 + 4·i
_SCALE = 15
_RATE = 16  # element i's [μ_fast,i·W, a·fact_i] at _RATE + 2·i (a = 0: constant friction)
_PIECE = 12  # the scratch slots: the internal state at the end of a path's previous piece

MAX_ITERATIONS = 60
"""Newton iterations of a series solve before it gives up (the force is then NaN)."""

TOLERANCE = 1e-14
"""Newton stops when its largest internal step is below this fraction of |u| + the capacity."""

ACCEPT = 1e-9
"""After MAX_ITERATIONS, a solve whose last step is below this fraction still counts."""

PIECES = 4
"""A curved step's Hermite path is cut into this many pieces, at equal steps of its parameter
(module docstring: the error is of first order in the piece; its cost and accuracy measured)."""


# ---- one series element ------------------------------------------------------------------------


@njit(cache=True, inline="always")
def _element(p, i, s, o, dx, dy, carried, Z, tau):
    """Series element ``i`` (0, 1, 2) at the trial (dx, dy) [in] from the internal state held in
    ``s`` from slot ``o`` on (0: the committed state; _PIECE: a path's piece, module docstring),
    reached in ``tau`` [s] (read by velocity-dependent friction only, :func:`_rate_return`):
    force (fx, fy) [kip], symmetric tangent (kxx, kxy, kyy) [kip/in], incremental energy φ
    [kip·in], hysteretic vector (zx, zy), sliding (0/1) and restrainer contact (0/1).
    ``carried``: the element slides with its hysteretic vector given, (Z[2i], Z[2i + 1]) (a
    stage of the coupled-friction step, :func:`plan_rate`): a spring of stiffness W/L̄_i beside
    the constant friction force μ_i·W·z, its energy φ = (W/L̄_i)·|d|²/2 + μ_i·W·z·d."""
    b = _E0 + 4 * i
    kr, q, uyi, gap, ks = p[b], p[b + 1], p[b + 2], p[b + 3], p[_K0]
    tx = s[o + 6 + 2 * i] + (dx - s[o + 2 * i]) / uyi
    ty = s[o + 7 + 2 * i] + (dy - s[o + 2 * i + 1]) / uyi
    t = np.sqrt(tx * tx + ty * ty)
    if carried and not (t > 1.0 and p[_RATE + 2 * i + 1] == 0.0 and tx / t == Z[2 * i]
                        and ty / t == Z[2 * i + 1]):
        # (a carried z equal to the radial return's, as on a straight step along z, is the
        # free element's arithmetic: a plan run along one axis is the one-axis run to the bit;
        # constant friction only: a velocity-dependent carried z has its own magnitude)
        zx, zy = Z[2 * i], Z[2 * i + 1]
        kxx = kr
        kxy = 0.0
        kyy = kr
        energy = q * (zx * dx + zy * dy)
        sliding = 1
    elif t > 1.0 and p[_RATE + 2 * i + 1] > 0.0:  # sliding, velocity-dependent friction
        zn = np.sqrt(s[o + 6 + 2 * i] ** 2 + s[o + 7 + 2 * i] ** 2)
        zx, zy, kxx, kxy, kyy, energy = _rate_return(
            q, p[_RATE + 2 * i], p[_RATE + 2 * i + 1], uyi, tx, ty, t, tau, zn)
        kxx += kr
        kyy += kr
        sliding = 1
    elif t > 1.0:  # sliding: z = t/|t|, ∂z/∂d = (I − z zᵀ)/(u_y,i·|t|)
        zx, zy = tx / t, ty / t
        g = q / (uyi * t)
        kxx = kr + g * (1.0 - zx * zx)
        kxy = -g * zx * zy
        kyy = kr + g * (1.0 - zy * zy)
        energy = q * uyi * (t - 0.5)
        sliding = 1
    else:  # sticking: ∂z/∂d = I/u_y,i
        zx, zy = tx, ty
        kxx = kr + q / uyi
        kxy = 0.0
        kyy = kxx
        energy = 0.5 * q * uyi * t * t
        sliding = 0
    fx = kr * dx + q * zx
    fy = kr * dy + q * zy
    energy += 0.5 * kr * (dx * dx + dy * dy)
    r = np.sqrt(dx * dx + dy * dy)
    contact = 0
    if r > gap:  # restrainer: k_0·(r − g) radially, tangent k_0·((1 − g/r)·I + (g/r)·e eᵀ)
        ex, ey = dx / r, dy / r
        over = r - gap
        fx += ks * over * ex
        fy += ks * over * ey
        a = ks * gap / r
        kxx += ks - a + a * ex * ex
        kxy += a * ex * ey
        kyy += ks - a + a * ey * ey
        energy += 0.5 * ks * over * over
        contact = 1
    return fx, fy, kxx, kxy, kyy, energy, zx, zy, sliding, contact


RATE_ITERATIONS = 60
"""Newton iterations of a velocity-dependent element's slip rate (:func:`_rate_return`; it
converges monotonically from below, quadratically)."""


@njit(cache=True)
def _rate_return(q, qf, b, uyi, tx, ty, t, tau, zn):
    """The friction of a sliding element with velocity-dependent friction (module docstring,
    "Velocity-dependent friction"): the backward-Euler return over ``tau`` [s] from the elastic
    trial q·(tx, ty) (|t| = ``t`` > 1), q = μ_slow·W [kip], ``qf`` = μ_fast·W [kip], ``b`` =
    a·fact [s/in] (the friction law read at the surface's rate, fact times the element's slip
    rate w), ``uyi`` = q/k_e [in]. The slip rate w [in/s] solves q·t − q(w) = k_e·τ·w with
    q(w) = qf − (qf − q)·e^(−b·w), and the friction force is q(w) along t. Returns (zx, zy)
    (the friction force over q, |z| = q(w)/q ≥ 1), its tangent ∂(q·z)/∂d (kxx, kxy, kyy)
    [kip/in] and its incremental potential |Q|²/(2·k_e) + τ·D(w), D(w) = ∫₀ʷ q(s) ds [kip·in],
    whose gradient in d is the force (so the series solve's line search holds). ``tau`` ≤ 0
    (the committed state itself): elastic up to qf, then qf. ``zn`` = |z| committed: Newton
    starts from the committed slip rate (q(w_n) = q·zn) when the root lies beyond it, else from
    0 (from the left of the root either way: it converges monotonically)."""
    ke = q / uyi
    nx, ny = tx / t, ty / t
    qt = q * t
    if tau <= 0.0:
        if qt <= qf:  # elastic: the trial force itself
            return tx, ty, ke, 0.0, ke, 0.5 * qt * uyi * t
        g = qf / (uyi * t)  # capped at qf: no stiffness along n, qf/|e_trial| across
        energy = 0.5 * qf * qf / ke + qf * (uyi * t - qf / ke)
        return qf / q * nx, qf / q * ny, g * (1.0 - nx * nx), -g * nx * ny, g * (1.0 - ny * ny), \
            energy
    drop = qf - q
    ktau = ke * tau
    w = 0.0
    qw = q
    slope = b * drop
    if zn > 1.0 and q * zn < qf:  # the committed slip rate, if the root lies beyond it
        wn = -np.log((qf - q * zn) / drop) / b
        decay = np.exp(-b * wn)
        qn = qf - drop * decay
        if qt - qn - ktau * wn > 0.0:
            w, qw, slope = wn, qn, b * drop * decay
    for _ in range(RATE_ITERATIONS):
        # g(w) = q·t − q(w) − k_e·τ·w is convex and decreasing: Newton from w = 0 stays below
        # the root and rises to it
        step = (qt - qw - ktau * w) / (slope + ktau)
        w += step
        decay = np.exp(-b * w)
        qw = qf - drop * decay
        slope = b * drop * decay
        if not step > 1e-15 * w:
            break
    gamma = slope / (slope + ktau)  # ∂|Q|/∂|q·t|: 1 at τ = 0 (elastic), 0 for constant friction
    g = qw / (uyi * t)
    kxx = ke * gamma * nx * nx + g * (1.0 - nx * nx)
    kxy = ke * gamma * nx * ny - g * nx * ny
    kyy = ke * gamma * ny * ny + g * (1.0 - ny * ny)
    dissipated = qf * w + drop * np.expm1(-b * w) / b  # (expm1: no cancellation at small b·w)
    energy = 0.5 * qw * qw / ke + tau * dissipated
    return qw / q * nx, qw / q * ny, kxx, kxy, kyy, energy


@njit(cache=True, inline="always")
def _committed(p, i, s, o, dux, duy):
    """Series element ``i``'s compliance (cxx, cxy, cyy) [in/kip] for going on from the state
    at slot ``o`` of ``s`` as it was (sliding on along its z if it slides and the bearing moves
    on along z, sticking otherwise): the solve's predictor (a carried element's too)."""
    b = _E0 + 4 * i
    kr, q, uyi, gap, ks = p[b], p[b + 1], p[b + 2], p[b + 3], p[_K0]
    dx, dy, zx, zy = s[o + 2 * i], s[o + 2 * i + 1], s[o + 6 + 2 * i], s[o + 7 + 2 * i]
    g = q / uyi
    kxx, kxy, kyy = kr + g, 0.0, kr + g
    zz = zx * zx + zy * zy
    if zz > 1.0 + 1e-9:  # velocity-dependent friction above μ_slow: its direction
        zz = np.sqrt(zz)
        zx, zy = zx / zz, zy / zz
    if zx * zx + zy * zy >= 1.0 - 1e-12 and zx * dux + zy * duy > 0.0:
        kxx -= g * zx * zx
        kxy -= g * zx * zy
        kyy -= g * zy * zy
    kxx, kxy, kyy = _restrained(ks, gap, dx, dy, kxx, kxy, kyy)
    return _inverse(kxx, kxy, kyy)


@njit(cache=True, inline="always")
def _restrained(ks, gap, dx, dy, kxx, kxy, kyy):
    """The tangent (kxx, kxy, kyy) [kip/in] plus the restrainer's, k_0·((1 − g/r)·I +
    (g/r)·e eᵀ), where the element's displacement (dx, dy) [in] is past its gap g (r = |d|)."""
    r = np.sqrt(dx * dx + dy * dy)
    if r > gap:
        ex, ey = dx / r, dy / r
        a = ks * gap / r
        kxx += ks - a + a * ex * ex
        kxy += a * ex * ey
        kyy += ks - a + a * ey * ey
    return kxx, kxy, kyy


@njit(cache=True, inline="always")
def _inverse(kxx, kxy, kyy):
    """The inverse of the symmetric 2×2 matrix [[kxx, kxy], [kxy, kyy]]."""
    det = kxx * kyy - kxy * kxy
    return kyy / det, -kxy / det, kxx / det


# ---- the series solve (the plan element; one axis is its y = 0 case) -----------------------------


@njit(cache=True)
def series_solve(p, s, ux, uy):
    """The series state at the trial (ux, uy) [in] from the committed state ``s`` (not modified).

    Returns (Fx, Fy, Kxx, Kxy, Kyy, d_1x, d_1y, d_2x, d_2y, d_3x, d_3y, z_1x, z_1y, z_2x, z_2y,
    z_3x, z_3y, iterations, branch): the force [kip], the consistent tangent [kip/in], the
    internal displacements [in] and hysteretic vectors, the Newton iterations, and the branch
    code Σ_i (sliding_i·2^i + contact_i·2^(3+i)). NaN force and tangent if Newton failed."""
    return _series(p, s, 0, ux, uy, 0, s, 0.0)


@njit(cache=True, inline="always")
def _affine_part(p, i, s, carry, Z):
    """Element ``i``'s scalar stiffness k_i [kip/in] and offset (c_x, c_y) [kip] in a carried
    solve that is affine (:func:`_carried_affine`): f_i = k_i·d_i + c_i."""
    b = _E0 + 4 * i
    kr, q, uyi = p[b], p[b + 1], p[b + 2]
    if (carry >> i) & 1:
        return kr, q * Z[2 * i], q * Z[2 * i + 1]
    return (kr + q / uyi, q * (s[6 + 2 * i] - s[2 * i] / uyi),
            q * (s[7 + 2 * i] - s[2 * i + 1] / uyi))


@njit(cache=True, inline="always")
def _affine_element(p, i, s, carry, Z, fx, fy, k, cx, cy):
    """Element ``i``'s displacement (dx, dy) [in] and hysteretic vector at the series force
    (fx, fy) [kip] of an affine carried solve, and whether the affine form holds for it (an
    element not carried sticks, no restrainer is reached, a carried z is not its radial
    return's direction to the bit: :func:`_carried_affine`)."""
    b = _E0 + 4 * i
    uyi, gap = p[b + 2], p[b + 3]
    dx, dy = (fx - cx) / k, (fy - cy) / k
    tx = s[6 + 2 * i] + (dx - s[2 * i]) / uyi
    ty = s[7 + 2 * i] + (dy - s[2 * i + 1]) / uyi
    t = np.sqrt(tx * tx + ty * ty)
    ok = dx * dx + dy * dy <= gap * gap
    if (carry >> i) & 1:
        if t > 1.0 and p[_RATE + 2 * i + 1] == 0.0 and tx / t == Z[2 * i] and \
                ty / t == Z[2 * i + 1]:
            ok = False
        return dx, dy, Z[2 * i], Z[2 * i + 1], ok
    return dx, dy, tx, ty, ok and t <= 1.0


@njit(cache=True, inline="always")
def _carried_affine(p, s, ux, uy, carry, Z):
    """(True, the series result) when a carried solve at (ux, uy) [in] (the elements of
    ``carry`` sliding at their z given in ``Z``, from the committed state) is affine: each other
    element sticks and no restrainer is reached. Then every element's force is k_i·d_i + c_i
    with a scalar k_i (a carried element: W/L̄_i, c_i = μ_i·W·z_i; a sticking one: W/L̄_i +
    μ_i·W/u_y,i, c_i = μ_i·W·(z_i − d_i/u_y,i) committed), so the one force is
    F = (u + Σ c_i/k_i)/Σ 1/k_i and d_i = (F − c_i)/k_i: in closed form, the minimum that
    Newton approaches (the energy is convex). (False, ...) when an element would slide
    uncarried or touch its restrainer, or when a carried z equals its radial return's direction
    to the bit (a step along a line: :func:`_element` then takes the free element's arithmetic,
    so that a plan run on a line stays the one-axis run to the bit): the Newton solve decides."""
    k1, c1x, c1y = _affine_part(p, 0, s, carry, Z)
    k2, c2x, c2y = _affine_part(p, 1, s, carry, Z)
    k3, c3x, c3y = _affine_part(p, 2, s, carry, Z)
    kk = 1.0 / (1.0 / k1 + 1.0 / k2 + 1.0 / k3)
    fx = kk * (ux + c1x / k1 + c2x / k2 + c3x / k3)
    fy = kk * (uy + c1y / k1 + c2y / k2 + c3y / k3)
    d1x, d1y, z1x, z1y, ok1 = _affine_element(p, 0, s, carry, Z, fx, fy, k1, c1x, c1y)
    d2x, d2y, z2x, z2y, ok2 = _affine_element(p, 1, s, carry, Z, fx, fy, k2, c2x, c2y)
    d3x, d3y, z3x, z3y, ok3 = _affine_element(p, 2, s, carry, Z, fx, fy, k3, c3x, c3y)
    return ok1 and ok2 and ok3, (fx, fy, kk, 0.0, kk, d1x, d1y, d2x, d2y, d3x, d3y, z1x, z1y,
                                 z2x, z2y, z3x, z3y, 1.0, float(carry))


@njit(cache=True)
def _series(p, s, o, ux, uy, carry, Z, tau):
    """:func:`series_solve` from the internal state held in ``s`` from slot ``o`` on (0: the
    committed state, _PIECE: the end of a path's previous piece); the elements whose bit is set
    in ``carry`` (bit i: element i) slide with their hysteretic vectors given in ``Z`` (6,)
    (:func:`_element`; ``Z`` is not read when ``carry`` is 0). A carried solve whose answer is
    affine is the closed form (:func:`_carried_affine`)."""
    if carry != 0 and o == 0:
        ok, a = _carried_affine(p, s, ux, uy, carry, Z)
        if ok:
            return a
    cr1, cr2, cr3 = carry & 1, (carry >> 1) & 1, (carry >> 2) & 1
    # predictor: each element goes on as it was (sliding on along z, sticking), the increment
    # split by those compliances
    dux, duy = ux - s[o] - s[o + 2] - s[o + 4], uy - s[o + 1] - s[o + 3] - s[o + 5]
    p1, q1, r1 = _committed(p, 0, s, o, dux, duy)
    p2, q2, r2 = _committed(p, 1, s, o, dux, duy)
    p3, q3, r3 = _committed(p, 2, s, o, dux, duy)
    kxx, kxy, kyy = _inverse(p1 + p2 + p3, q1 + q2 + q3, r1 + r2 + r3)
    gx, gy = kxx * dux + kxy * duy, kxy * dux + kyy * duy
    d1x, d1y = s[o] + p1 * gx + q1 * gy, s[o + 1] + q1 * gx + r1 * gy
    d2x, d2y = s[o + 2] + p2 * gx + q2 * gy, s[o + 3] + q2 * gx + r2 * gy
    d3x, d3y = ux - d1x - d2x, uy - d1y - d2y
    f1x, f1y, a1, b1, c1, e1, z1x, z1y, s1, k1 = _element(p, 0, s, o, d1x, d1y, cr1, Z, tau)
    f2x, f2y, a2, b2, c2, e2, z2x, z2y, s2, k2 = _element(p, 1, s, o, d2x, d2y, cr2, Z, tau)
    f3x, f3y, a3, b3, c3, e3, z3x, z3y, s3, k3 = _element(p, 2, s, o, d3x, d3y, cr3, Z, tau)
    energy = e1 + e2 + e3
    tight = TOLERANCE * (np.sqrt(ux * ux + uy * uy) + p[_SCALE])
    size = np.inf
    fx = fy = kxx = kxy = kyy = np.nan
    iterations = 0
    for iterations in range(1, MAX_ITERATIONS + 1):
        # Newton's step of the constrained minimum: F = (Σ C_i)⁻¹ Σ C_i f_i, Δd_i = C_i (F − f_i)
        p1, q1, r1 = _inverse(a1, b1, c1)
        p2, q2, r2 = _inverse(a2, b2, c2)
        p3, q3, r3 = _inverse(a3, b3, c3)
        kxx, kxy, kyy = _inverse(p1 + p2 + p3, q1 + q2 + q3, r1 + r2 + r3)
        gx = (p1 * f1x + q1 * f1y) + (p2 * f2x + q2 * f2y) + (p3 * f3x + q3 * f3y)
        gy = (q1 * f1x + r1 * f1y) + (q2 * f2x + r2 * f2y) + (q3 * f3x + r3 * f3y)
        fx = kxx * gx + kxy * gy
        fy = kxy * gx + kyy * gy
        s1x, s1y = p1 * (fx - f1x) + q1 * (fy - f1y), q1 * (fx - f1x) + r1 * (fy - f1y)
        s2x, s2y = p2 * (fx - f2x) + q2 * (fy - f2y), q2 * (fx - f2x) + r2 * (fy - f2y)
        size = max(abs(s1x), abs(s1y), abs(s2x), abs(s2y), abs(s1x + s2x), abs(s1y + s2y))
        if size <= tight or not size < np.inf:  # converged, or a NaN or infinite trial
            break
        # Armijo backtracking on Φ along the step (slope Σ f_i·Δd_i < 0, with Δd_3 = −Δd_1 − Δd_2)
        slope = (f1x - f3x) * s1x + (f1y - f3y) * s1y + (f2x - f3x) * s2x + (f2y - f3y) * s2y
        alpha = 1.0
        for _ in range(40):
            n1x, n1y = d1x + alpha * s1x, d1y + alpha * s1y
            n2x, n2y = d2x + alpha * s2x, d2y + alpha * s2y
            n3x, n3y = ux - n1x - n2x, uy - n1y - n2y
            g1 = _element(p, 0, s, o, n1x, n1y, cr1, Z, tau)
            g2 = _element(p, 1, s, o, n2x, n2y, cr2, Z, tau)
            g3 = _element(p, 2, s, o, n3x, n3y, cr3, Z, tau)
            trial = g1[5] + g2[5] + g3[5]
            if trial <= energy + 1e-4 * alpha * slope + 1e-15 * abs(energy):  # (rounding of Φ)
                break
            alpha *= 0.5
        d1x, d1y, d2x, d2y, d3x, d3y = n1x, n1y, n2x, n2y, n3x, n3y
        f1x, f1y, a1, b1, c1, e1, z1x, z1y, s1, k1 = g1
        f2x, f2y, a2, b2, c2, e2, z2x, z2y, s2, k2 = g2
        f3x, f3y, a3, b3, c3, e3, z3x, z3y, s3, k3 = g3
        energy = trial
    if not size <= ACCEPT * (np.sqrt(ux * ux + uy * uy) + p[_SCALE]):  # (tight < this)
        fx = fy = kxx = kxy = kyy = np.nan
    branch = s1 + 2 * s2 + 4 * s3 + 8 * k1 + 16 * k2 + 32 * k3
    return (fx, fy, kxx, kxy, kyy, d1x, d1y, d2x, d2y, d3x, d3y,
            z1x, z1y, z2x, z2y, z3x, z3y, float(iterations), float(branch))


@njit(cache=True, inline="always")
def _store(s, o, r):
    """Write the internal state of a :func:`series_solve` result ``r`` into ``s`` from slot
    ``o`` on (0: commit it)."""
    for j in range(12):
        s[o + j] = r[5 + j]


# ---- in plan ------------------------------------------------------------------------------------


@njit(cache=True, inline="always")
def _write_trial(r, f, k, c):
    """A series result ``r``'s force and tangent into ``f`` (2,), ``k`` (2, 2); ``c`` = 0 (the
    force reads no velocity: module docstring)."""
    f[0] = r[0]
    f[1] = r[1]
    k[0, 0] = r[2]
    k[0, 1] = r[3]
    k[1, 0] = r[3]
    k[1, 1] = r[4]
    c[0, 0] = 0.0
    c[0, 1] = 0.0
    c[1, 0] = 0.0
    c[1, 1] = 0.0


@njit(cache=True)
def _path(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau, pieces):
    """The :func:`series_solve` result at the end (ux, uy) [in] of a step of duration ``tau``
    [s] from the committed state ``s`` (start (u0x, u0y) [in] and velocity (v0x, v0y) [in/s],
    end velocity (vx, vy)): one solve along the chord if the path is straight (tau = 0, a zero
    increment, or both velocities and every committed internal vector along the chord: e.g. on
    one axis), else the step's cubic Hermite path cut into ``pieces`` pieces at equal steps of
    its parameter, each a series solve from the previous piece's end state, which the scratch
    slots hold (the committed part of ``s`` is not modified)."""
    dx, dy = ux - u0x, uy - u0y
    cross = abs(dx * v0y - dy * v0x) + abs(dx * vy - dy * vx)
    for j in range(0, 12, 2):
        cross += abs(dx * s[j + 1] - dy * s[j])
    if tau <= 0.0 or cross == 0.0 or pieces <= 1:
        return _series(p, s, 0, ux, uy, 0, s, tau)
    for j in range(12):
        s[_PIECE + j] = s[j]
    piece = tau / pieces
    for n in range(1, pieces):
        th = n / pieces
        _store(s, _PIECE, _series(p, s, _PIECE, _hermite(th, tau, u0x, v0x, ux, vx),
                                  _hermite(th, tau, u0y, v0y, uy, vy), 0, s, piece))
    return _series(p, s, _PIECE, ux, uy, 0, s, piece)


@njit(cache=True)
def plan_trial(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau, f, k, c):
    """Force ``f`` [kip] (2,), ∂f/∂u ``k`` [kip/in] and ∂f/∂v ``c`` [kip·s/in] (2, 2), written in
    place, at the end (ux, uy) [in] of a step of duration ``tau`` [s] from the committed state
    ``s`` (start velocity (v0x, v0y), end velocity (vx, vy) [in/s]): the series state followed
    along the step's path (:func:`_path`; the chord for tau = 0). The committed state is not
    modified (the walk uses the scratch slots). The tangent is the last piece's; c = 0 (the
    velocities only shape the path, which the tangent ignores; velocity-dependent friction reads
    the slip over the duration, in k)."""
    r = _path(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau, PIECES)
    _write_trial(r, f, k, c)


@njit(cache=True)
def plan_commit(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau):
    """Advance the committed state ``s`` in place to the converged end (ux, uy) [in] of the
    step, along its path (as :func:`plan_trial`)."""
    _store(s, 0, _path(p, s, u0x, u0y, v0x, v0y, ux, uy, vx, vy, tau, PIECES))


@njit(cache=True)
def plan_energy(p, s):
    """Recoverable energy [kip·in] at the committed state (module docstring)."""
    energy = 0.0
    for i in range(3):
        b = _E0 + 4 * i
        kr, q, uyi, gap = p[b], p[b + 1], p[b + 2], p[b + 3]
        dx, dy, zx, zy = s[2 * i], s[2 * i + 1], s[6 + 2 * i], s[7 + 2 * i]
        r = np.sqrt(dx * dx + dy * dy)
        energy += 0.5 * kr * r * r + 0.5 * q * uyi * (zx * zx + zy * zy)
        if r > gap:
            energy += 0.5 * p[_K0] * (r - gap) * (r - gap)
    return energy


@njit(cache=True)
def plan_branch(p, s, ux, uy):
    """The branch of the trial (ux, uy) [in] from the committed state: which elements slide and
    which touch their restrainer, Σ_i (sliding_i·2^i + contact_i·2^(3+i)) (the solver lands a
    step where it changes). Read from the solve of no duration: for velocity-dependent friction
    that is elastic up to μ_fast (:func:`_rate_return`), not the step's return, so where it
    lands a step is approximate (an element may be seen to slide, or touch its restrainer, a
    step early or late; the run's accuracy is measured: benchmarks/tfp_velocity.py)."""
    return int(series_solve(p, s, ux, uy)[18])


@njit(cache=True)
def plan_turn_direction(s):
    """The committed friction direction z_i of the first sliding element (on the unit circle),
    (0, 0) when none slides: a velocity along it that turns negative unloads the bearing (all
    elements carry the same force, so they all stop sliding when it turns back)."""
    for i in range(3):
        zx, zy = s[6 + 2 * i], s[7 + 2 * i]
        if zx * zx + zy * zy >= 1.0 - 1e-9:
            return zx, zy
    return 0.0, 0.0


# ---- in plan, the rate form (the coupled-friction step, femoat.integration.methods.ark5) -------

N_RATE_PLAN = 6
"""The rate form's state: the three elements' hysteretic vectors (z_1x, z_1y, z_2x, z_2y, z_3x,
z_3y) [-] (the inner element's first: its direction is the bearing's turning direction)."""

_CARRY = _PIECE
"""Scratch slot: the bit mask of the elements a step carries (bit i: element i), written by
:func:`plan_rate_active` at the step's start (no path is walked while a step carries them)."""

_CONTACT = _PIECE + 1
"""Scratch slot: the bit mask of the elements that touch their restrainer at the step's start,
written by :func:`plan_rate_active`: the rate form's compliances hold it for the step (the
restrainer's tangent jumps by k_0 at its gap; a rate that switched with each stage's d had no
root in the stage solve when a carried element slid along its gap; where it changes the kink
search lands the step, as for a sticking element)."""


@njit(cache=True, inline="always")
def _touching(p, s):
    """The bit mask of the elements whose committed displacement is past their gap."""
    contact = 0
    for i in range(3):
        dx, dy, gap = s[2 * i], s[2 * i + 1], p[_E0 + 4 * i + 3]
        if dx * dx + dy * dy > gap * gap:
            contact |= 1 << i
    return contact


@njit(cache=True, inline="always")
def _on_rim(s, i):
    zx, zy = s[6 + 2 * i], s[7 + 2 * i]
    return zx * zx + zy * zy >= 1.0 - 1e-9


LOADING = 1e-6
"""[-] A sliding element is carried only while the cosine of the angle between its friction
direction z_i and its own displacement rate ḋ_i exceeds this (:func:`plan_rate_active`): one that
moves within this of perpendicular to z_i counts as unloading. A turn search that landed a hair
before the element unloads leaves it there with z_i·ḋ_i a round-off above zero, and its crossing
in the next step too close to the start to land on (below the driver's smallest step); carried,
it would slide backwards for a whole step. Counted as unloading, the step takes the radial
return from the committed state, whose error over the sliver is of the order of this squared."""


SNAP = 1e-9
"""[s] An element whose hysteretic vector sits a hair inside its rim (|z_i|² within 1e-6 of 1)
but would reach it at its sticking rate sooner than this counts as sliding at a step's start
(:func:`plan_rate_active`; its z put on the rim moves its friction force by μ_i·W·(1 − |z_i|),
less than μ_i·W·SNAP·ḋ_r/u_y,i with ḋ_r its outward rate while sticking). The kink search resolves a switch no closer to a step's start
than 2^-24 of it (6e-10 s at a 10 ms step) and the driver lands no step shorter than its smallest
(1e-10 s by default): left sticking, such an element would start to slide inside the step by the
radial return from the committed state, first order in the step, and its slip error stays in
the force for the rest of the run. Such states follow a sliver landed on another element's
switch, which can leave a sliding element's z just inside its rim."""


@njit(cache=True)
def plan_rate_active(p, s, vx, vy):
    """True when some element slides at the committed state and the velocity (vx, vy) [in/s]
    keeps loading it (z_i·ḋ_i > LOADING·|ḋ_i|, ḋ_i its own displacement rate in the series,
    :func:`_series_rate`, :data:`LOADING`): over a step from here the sliding, loaded elements'
    hysteretic vectors are states with the rate :func:`plan_rate`. Marks which elements the step
    carries in the scratch slot ``_CARRY``; the others stick, their z the radial return from the
    committed state (exact while they stick; where one starts to slide the kink search lands the
    step). Any element may be carried alone: in plan the outer element of L2 can slide while the
    inner one sticks (the inner element's force turned away from its own slip), and a step
    that left that to the path form was first order in the step (benchmarks/README.md, issue
    28). An element within :data:`SNAP` of its rim counts as on it (its z put there in ``s``)."""
    if p[_RATE + 1] > 0.0:
        return _viscous_active(p, s)
    carry = 0
    for i in range(3):
        if _on_rim(s, i):
            carry |= 1 << i
    z = s[6:12]
    ux, uy = s[0] + s[2] + s[4], s[1] + s[3] + s[5]
    contact = _touching(p, s)
    # an element a hair inside its rim that reaches it sooner than SNAP at its sticking rate
    # slides (no step can land that close to its start): its z put on the rim
    r = _contact_series(p, s, ux, uy, carry, z, contact)
    kxx, kxy, kyy, comp = _series_rate(p, s, r, carry, z, contact)
    fx, fy = kxx * vx + kxy * vy, kxy * vx + kyy * vy
    for i in range(3):
        zx, zy = z[2 * i], z[2 * i + 1]
        zz = zx * zx + zy * zy
        if (carry >> i) & 1 or zz < 1.0 - 1e-6:
            continue
        ci = comp[i]
        ddx, ddy = ci[0] * fx + ci[1] * fy, ci[1] * fx + ci[2] * fy
        norm = np.sqrt(zz)
        out = (zx * ddx + zy * ddy) / norm  # [in/s] its rate away from the disk's centre
        if out > 0.0 and (1.0 - norm) * p[_E0 + 4 * i + 2] < SNAP * out:
            z[2 * i], z[2 * i + 1] = zx / norm, zy / norm
            carry |= 1 << i
    if carry == 0:
        return False
    for _ in range(3):
        r = _contact_series(p, s, ux, uy, 0, s, contact)
        kxx, kxy, kyy, comp = _series_rate(p, s, r, carry, z, contact)
        fx, fy = kxx * vx + kxy * vy, kxy * vx + kyy * vy
        keep = 0
        for i in range(3):
            if (carry >> i) & 1:
                ci = comp[i]
                ddx, ddy = ci[0] * fx + ci[1] * fy, ci[1] * fx + ci[2] * fy
                if z[2 * i] * ddx + z[2 * i + 1] * ddy > LOADING * np.sqrt(ddx * ddx + ddy * ddy):
                    keep |= 1 << i
        if keep == carry:
            break
        carry = keep
    if carry == 0:
        return False
    s[_CARRY] = float(carry)
    s[_CONTACT] = float(contact)
    return True


RATE_CAP = 30.0
"""[-] Velocity-dependent friction in the rate form: beyond the slip rate w at which a·fact·w
reaches this, the friction law's inverse w(|z|) (:func:`_slip_rate`) goes on along its tangent
there. The friction is then within e^-30 (1e-13) of μ_fast: the exact inverse would need |z|
to resolve μ_fast − μ(w) ~ e^(−a·fact·w), below double precision's 1e-16 at a·fact·w ≈ 36
(w = 31 in/s on an outer surface of a = 1 s/in), where w(|z|) overflows."""

CARRY_INSIDE = 1e-4
"""[-] Velocity-dependent friction: an element whose |z| is within this of its rim is carried
(inside it the viscoplastic rate is the sticking one, exact: carrying it costs a wider stage
solve, never accuracy), so that the onset of sliding is landed on only from further inside
(the kink search resolves no switch closer to a step's start than 2^-24 of it: at
u_y = 0.01 in, 1e-6 in inside the rim)."""


@njit(cache=True, inline="always")
def _slip_rate(p, i, rho):
    """Element ``i``'s slip rate w [in/s] and dw/d|z| at |z| = ``rho`` [-] (its friction force over
    μ_slow·W), the inverse of the friction law μ_i(fact_i·w)·W = |z|·μ_i·W:
    w = −ln(1 − (|z| − 1)/(r − 1))/b, r = μ_fast/μ_slow, b = a·fact_i; 0 inside the disk
    (|z| ≤ 1: sticking); beyond :data:`RATE_CAP` along its tangent."""
    if rho <= 1.0:
        return 0.0, 0.0
    q, qf, b = p[_E0 + 4 * i + 1], p[_RATE + 2 * i], p[_RATE + 2 * i + 1]
    rm1 = (qf - q) / q
    x = (rho - 1.0) / rm1
    tail = np.exp(-RATE_CAP)
    if x < 1.0 - tail:
        return -np.log1p(-x) / b, 1.0 / (b * rm1 * (1.0 - x))
    return (RATE_CAP + (x - (1.0 - tail)) / tail) / b, 1.0 / (b * rm1 * tail)


@njit(cache=True)
def _viscous_active(p, s):
    """:func:`plan_rate_active` for velocity-dependent friction: carry each element within
    :data:`CARRY_INSIDE` of its rim or beyond it, loading or not (a viscoplastic element
    unloads smoothly: no turn to land on); True when one is."""
    carry = 0
    for i in range(3):
        zx, zy = s[6 + 2 * i], s[7 + 2 * i]
        if np.sqrt(zx * zx + zy * zy) >= 1.0 - CARRY_INSIDE:
            carry |= 1 << i
    if carry == 0:
        return False
    s[_CARRY] = float(carry)
    s[_CONTACT] = float(_touching(p, s))
    return True


@njit(cache=True, inline="always")
def _slip(p, i, z):
    """Element ``i``'s slip-rate vector m = w·n (n = z_i/|z_i|) [in/s] and the coefficients of
    ∂m/∂z_i = w′·n nᵀ + (w/|z_i|)·(I − n nᵀ): (mx, my, w′, w/|z_i|, nx, ny)."""
    zx, zy = z[2 * i], z[2 * i + 1]
    rho = np.sqrt(zx * zx + zy * zy)
    w, wp = _slip_rate(p, i, rho)
    if w == 0.0 and wp == 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    nx, ny = zx / rho, zy / rho
    return w * nx, w * ny, wp, w / rho, nx, ny


@njit(cache=True, inline="always")
def _rate_start(p, s, ux, uy, z, g, J):
    """(carry mask, contact mask, the series result the compliances read) of a rate evaluation
    at (ux, uy) [in] with the carried z, ``g`` and ``J`` zeroed (the rows of the elements not
    carried stay zero)."""
    carry, contact = int(s[_CARRY]), int(s[_CONTACT])
    r = _contact_series(p, s, ux, uy, carry, z, contact)
    for a in range(N_RATE_PLAN):
        g[a] = 0.0
        for b in range(N_RATE_PLAN):
            J[a, b] = 0.0
    return carry, contact, r


@njit(cache=True)
def _viscous_rate(p, s, ux, uy, vx, vy, z, g, J):
    """:func:`plan_rate` for velocity-dependent friction, each carried element an
    elastic-viscoplastic friction disk (module docstring): its friction force Q_i = μ_i·W·z_i
    moves by Q̇_i = k_e,i·(ḋ_i − w_i·n_i), k_e,i = μ_i·W/u_y,i, at the slip rate w_i(|z_i|) that
    the friction law gives (:func:`_slip_rate`), so ż_i = (ḋ_i − m_i)/u_y,i, m_i = w_i·n_i. With
    each element's sticking compliance C_i (:func:`_rate_compliance` of no carried element: its
    spring, restrainer and k_e), F = W·d_i/L̄_i + Q_i (+ restrainer) gives
    ḋ_i = C_i·(Ḟ + k_e,i·m_i), and Σ ḋ_i = v gives Ḟ = S⁻¹·(v − Σ_j k_e,j·C_j·m_j), S = Σ C_i.
    The Jacobian is exact with the compliances held (the restrainers' tangents taken as
    constant, as in :func:`plan_rate`): ∂g_i/∂z_j = (C_i·∂Ḟ/∂z_j + δ_ij·(k_e,i·C_i − I)·M_j)/u_y,i,
    ∂Ḟ/∂z_j = −S⁻¹·k_e,j·C_j·M_j, M_j = ∂m_j/∂z_j. Stiff where the law flattens (its eigenvalue
    −w′/u_y grows as e^(a·fact·w)): the implicit part of the step."""
    carry, contact, r = _rate_start(p, s, ux, uy, z, g, J)
    kxx, kxy, kyy, comp = _series_rate(p, s, r, 0, z, contact)
    slips = (_slip(p, 0, z) if carry & 1 else (0.0,) * 6,
             _slip(p, 1, z) if (carry >> 1) & 1 else (0.0,) * 6,
             _slip(p, 2, z) if (carry >> 2) & 1 else (0.0,) * 6)
    bx, by = vx, vy
    for j in range(3):
        mj, cj = slips[j], comp[j]
        kj = p[_E0 + 4 * j + 1] / p[_E0 + 4 * j + 2]
        bx -= kj * (cj[0] * mj[0] + cj[1] * mj[1])
        by -= kj * (cj[1] * mj[0] + cj[2] * mj[1])
    fx, fy = kxx * bx + kxy * by, kxy * bx + kyy * by  # Ḟ
    for i in range(3):
        if not (carry >> i) & 1:
            continue
        mi, ci = slips[i], comp[i]
        uyi = p[_E0 + 4 * i + 2]
        ki = p[_E0 + 4 * i + 1] / uyi
        hx, hy = fx + ki * mi[0], fy + ki * mi[1]
        g[2 * i] = (ci[0] * hx + ci[1] * hy - mi[0]) / uyi
        g[2 * i + 1] = (ci[1] * hx + ci[2] * hy - mi[1]) / uyi
    for j in range(3):
        mj, cj = slips[j], comp[j]
        if not (carry >> j) & 1 or (mj[2] == 0.0 and mj[3] == 0.0):
            continue  # (inside its disk: no slip, its z enters no rate)
        kj = p[_E0 + 4 * j + 1] / p[_E0 + 4 * j + 2]
        wp, wr, nx, ny = mj[2], mj[3], mj[4], mj[5]
        for k in range(2):
            nk = nx if k == 0 else ny
            dmx = wp * nx * nk + wr * ((1.0 if k == 0 else 0.0) - nx * nk)  # M_j·e_k
            dmy = wp * ny * nk + wr * ((1.0 if k == 1 else 0.0) - ny * nk)
            cx = kj * (cj[0] * dmx + cj[1] * dmy)
            cy = kj * (cj[1] * dmx + cj[2] * dmy)
            dfx, dfy = -(kxx * cx + kxy * cy), -(kxy * cx + kyy * cy)  # ∂Ḟ
            for i in range(3):
                if not (carry >> i) & 1:
                    continue
                ci = comp[i]
                uyi = p[_E0 + 4 * i + 2]
                ex, ey = ci[0] * dfx + ci[1] * dfy, ci[1] * dfx + ci[2] * dfy  # ∂ḋ_i
                if i == j:
                    ex += cx - dmx
                    ey += cy - dmy
                J[2 * i, 2 * j + k] = ex / uyi
                J[2 * i + 1, 2 * j + k] = ey / uyi


@njit(cache=True)
def plan_rate_fsal(p, s):
    """−1 for constant friction (each step evaluates its first stage's rate); for
    velocity-dependent friction, whose rate is stiff where the law flattens (:func:`_viscous_rate`),
    the regime of this step's rate, carry + 8·contact (the masks :func:`plan_rate_active` wrote):
    a step that starts where the last accepted one ended, in the same regime, takes that step's
    end-stage rate (:data:`femoat.bearings.registry.RATE_KERNELS`). Its committed z lies on the
    slow manifold of that stage's structure values, not of the step's end values (the pair's
    explicit last stage is not its solution); the rate evaluated there adds the relaxation
    between the two, (Δ of the element's displacement rate)/u_y,i, which the stages then carry
    as a transient (benchmarks/README.md, issue 28, stop 42)."""
    if p[_RATE + 1] > 0.0:
        return int(s[_CARRY]) + 8 * int(s[_CONTACT])
    return -1


@njit(cache=True)
def plan_rate_state(p, s, z):
    """The committed hysteretic vectors (z_1, z_2, z_3) [-] into ``z``; returns 6."""
    for j in range(N_RATE_PLAN):
        z[j] = s[6 + j]
    return N_RATE_PLAN


@njit(cache=True)
def _carried_solve(p, s, ux, uy, z):
    """(the :func:`series_solve` result at (ux, uy) [in] with the carried elements' z given in
    ``z``, the carried mask): an element whose trial from the committed state is back inside
    its disk (the stage moved back: it unloads) is released to its radial return, as the one-axis
    element does (along a line: the one-axis force, whatever the signs of a tableau's
    coefficients)."""
    carry = int(s[_CARRY])
    r = _series(p, s, 0, ux, uy, carry, z, 0.0)
    if p[_RATE + 1] > 0.0:  # a viscoplastic z is the state itself, inside its disk too
        return r, carry
    for _ in range(3):
        back = 0
        for i in range(3):
            if (carry >> i) & 1:
                uyi = p[_E0 + 4 * i + 2]
                tx = s[6 + 2 * i] + (r[5 + 2 * i] - s[2 * i]) / uyi
                ty = s[7 + 2 * i] + (r[6 + 2 * i] - s[2 * i + 1]) / uyi
                if tx * tx + ty * ty <= 1.0:
                    back |= 1 << i
        if back == 0:
            break
        carry &= ~back
        r = _series(p, s, 0, ux, uy, carry, z, 0.0)
    return r, carry


@njit(cache=True, inline="always")
def _rate_compliance(p, i, s, r, carry, z, contact):
    """Element ``i``'s compliance (cxx, cxy, cyy) [in/kip] in the rate of the series state: the
    inverse of ∂f_i/∂d_i at its displacement in the series result ``r``: W/L̄_i·I plus its
    restrainer's tangent if bit i of ``contact`` is set (the contact at the step's start,
    :data:`_CONTACT`), plus, for a carried element (its z moving by the sliding rule
    ż = (I − z zᵀ)·ḋ/u_y,i), μ_i·W/u_y,i·(I − z zᵀ), and for any other element its sticking
    stiffness μ_i·W/u_y,i·I (an element that is not carried sticks; where it starts to slide
    the kink search lands the step, and the rate does not switch inside a stage's solve)."""
    b = _E0 + 4 * i
    kr, q, uyi, gap, ks = p[b], p[b + 1], p[b + 2], p[b + 3], p[_K0]
    g = q / uyi
    kxx, kxy, kyy = kr + g, 0.0, kr + g
    if (carry >> i) & 1:
        zx, zy = z[2 * i], z[2 * i + 1]
        kxx -= g * zx * zx
        kxy -= g * zx * zy
        kyy -= g * zy * zy
    if (contact >> i) & 1:  # its restrainer's tangent at the stage's d, held on for the step
        dx, dy = r[5 + 2 * i], r[6 + 2 * i]
        rr = np.sqrt(dx * dx + dy * dy)
        ex, ey = dx / rr, dy / rr
        a = ks * gap / rr
        kxx += ks - a + a * ex * ex
        kxy += a * ex * ey
        kyy += ks - a + a * ey * ey
    return _inverse(kxx, kxy, kyy)


_NO_SERIES = (0.0,) * 19
"""A series result's shape with nothing in it (:func:`_contact_series`)."""


@njit(cache=True, inline="always")
def _contact_series(p, s, ux, uy, carry, Z, contact):
    """The series result at (ux, uy) [in] (carrying ``carry`` at ``Z``) that :func:`_series_rate`
    reads, which is only the displacements of the elements in ``contact`` (their restrainers'
    tangents): without contact the rate's compliances depend on z alone and no series solve is
    made (``_NO_SERIES``)."""
    if contact == 0:
        return _NO_SERIES
    return _series(p, s, 0, ux, uy, carry, Z, 0.0)


@njit(cache=True)
def _series_rate(p, s, r, carry, z, contact):
    """(S⁻¹ as (kxx, kxy, kyy) [kip/in], the elements' compliances C_i [in/kip]) at the series
    result ``r``, the carried mask ``carry`` and their z: Ḟ = S⁻¹·v, S = Σ_i C_i, and
    ḋ_i = C_i·Ḟ (:func:`_rate_compliance`)."""
    comp = (_rate_compliance(p, 0, s, r, carry, z, contact),
            _rate_compliance(p, 1, s, r, carry, z, contact),
            _rate_compliance(p, 2, s, r, carry, z, contact))
    kxx, kxy, kyy = _inverse(comp[0][0] + comp[1][0] + comp[2][0],
                             comp[0][1] + comp[1][1] + comp[2][1],
                             comp[0][2] + comp[1][2] + comp[2][2])
    return kxx, kxy, kyy, comp


@njit(cache=True)
def plan_rate(p, s, ux, uy, vx, vy, z, g, J):
    """The rate ż = g(z; u, v) [1/s] of the carried hysteretic vectors into ``g`` (6,) and
    ∂g/∂z into ``J`` (6 × 6) at the bearing's displacement (ux, uy) [in] and velocity (vx, vy)
    [in/s]: the series carries one force F, so Ḟ = (Σ_i C_i)⁻¹·v and ḋ_i = C_i·Ḟ with each
    element's compliance C_i (:func:`_rate_compliance`), and a carried element's z moves by the
    sliding rule ż_i = (ḋ_i − (z_i·ḋ_i)·z_i)/u_y,i (the single pendulum's, with its own
    displacement rate). Elements not carried have zero rows. The Jacobian differentiates z's
    direct part and C_i's dependence on z_i (the restrainers' tangents taken as constant:
    Newton needs it approximately). Along a line through the z_i (v and every z_i along it,
    |z_i| = 1) g is exactly zero. (Every flagged element is carried here: the release of an
    element whose stage moved back is the force's and the commit's, as the single pendulum's;
    a rate that switched with it would stall the stage's Newton.) Velocity-dependent friction:
    :func:`_viscous_rate`."""
    if p[_RATE + 1] > 0.0:
        _viscous_rate(p, s, ux, uy, vx, vy, z, g, J)
        return
    carry, contact, r = _rate_start(p, s, ux, uy, z, g, J)
    kxx, kxy, kyy, comp = _series_rate(p, s, r, carry, z, contact)
    fx, fy = kxx * vx + kxy * vy, kxy * vx + kyy * vy  # Ḟ
    for i in range(3):
        if not (carry >> i) & 1:
            continue
        ci = comp[i]
        ddx, ddy = ci[0] * fx + ci[1] * fy, ci[1] * fx + ci[2] * fy  # ḋ_i
        zx, zy = z[2 * i], z[2 * i + 1]
        uyi = p[_E0 + 4 * i + 2]
        gi = p[_E0 + 4 * i + 1] / uyi
        zd = zx * ddx + zy * ddy
        g[2 * i] = (ddx - zd * zx) / uyi
        g[2 * i + 1] = (ddy - zd * zy) / uyi
        for k in range(2):
            ddk = ddx if k == 0 else ddy
            # ∂(B_i)/∂z_ik·ḋ_i, B_i = C_i⁻¹: w = −μW/u_y·(e_k·(z·ḋ) + z·ḋ_k)
            wx = -gi * ((zd if k == 0 else 0.0) + zx * ddk)
            wy = -gi * ((zd if k == 1 else 0.0) + zy * ddk)
            cwx, cwy = ci[0] * wx + ci[1] * wy, ci[1] * wx + ci[2] * wy
            dfx, dfy = kxx * cwx + kxy * cwy, kxy * cwx + kyy * cwy  # ∂Ḟ = S⁻¹·C_i·w
            for m in range(3):
                if not (carry >> m) & 1:
                    continue
                cm = comp[m]
                ex, ey = cm[0] * dfx + cm[1] * dfy, cm[1] * dfx + cm[2] * dfy  # ∂ḋ_m
                if m == i:
                    ex -= cwx
                    ey -= cwy
                zmx, zmy = z[2 * m], z[2 * m + 1]
                uym = p[_E0 + 4 * m + 2]
                ze = zmx * ex + zmy * ey
                jx = (ex - ze * zmx) / uym
                jy = (ey - ze * zmy) / uym
                if m == i:  # the rule's own dependence on z_i
                    jx -= (ddk * zx + (zd if k == 0 else 0.0)) / uyi
                    jy -= (ddk * zy + (zd if k == 1 else 0.0)) / uyi
                J[2 * m, 2 * i + k] = jx
                J[2 * m + 1, 2 * i + k] = jy


TURN_PROBE = 1e-7
"""[s] The time step of :func:`plan_rate_turn`'s difference quotient for ṙ."""


@njit(cache=True, inline="always")
def _loading(p, s, ux, uy, vx, vy, z, carry, which):
    """(min over the carried elements of z_i·Ḟ, its element) at (ux, uy) [in], (vx, vy) [in/s]
    and the carried z (``which`` >= 0: that element's z_i·Ḟ)."""
    contact = int(s[_CONTACT])
    r = _contact_series(p, s, ux, uy, carry, z, contact)
    kxx, kxy, kyy, _ = _series_rate(p, s, r, carry, z, contact)
    fx, fy = kxx * vx + kxy * vy, kxy * vx + kyy * vy
    least, at = np.inf, -1
    for i in range(3):
        if (carry >> i) & 1 and (which < 0 or i == which):
            ri = z[2 * i] * fx + z[2 * i + 1] * fy
            if ri < least:
                least, at = ri, i
    return least, at


@njit(cache=True)
def plan_rate_turn(p, s, ux, uy, vx, vy, ax, ay, z, g, J):
    """(r, ṙ): r = min over the carried elements of z_i·Ḟ, the first of them to unload (a
    sliding element's own displacement rate along z_i is z_i·Ḟ/(W/L̄_i) away from its
    restrainer: the sign of z_i·Ḟ is its loading; the bearing's velocity along z_1 can be
    negative while it loads, when the outer elements slide too), and that element's ṙ at the
    acceleration (ax, ay) [in/s²], a difference quotient over TURN_PROBE along (v, a, ż) (Ḟ's
    rate has the compliances' own rates in it: an estimate without them set the landing off by
    O(h²), the order of the whole step on orbits where the outer elements turn). ``J``'s first
    row is scratch. Along a line through the z_i (every rate exactly zero) it is the single
    pendulum's z_1·v with ṙ = z_1·a: there loading is the motion along z_1, and the turn search
    is the one-axis bearing's to the bit. Velocity-dependent friction has no turn to land on
    (a viscoplastic element's rate is continuous where its force re-enters its disk): r = 1,
    ṙ = 0."""
    if p[_RATE + 1] > 0.0:
        return 1.0, 0.0
    carry = int(s[_CARRY])
    plan_rate(p, s, ux, uy, vx, vy, z, g, J)
    still = True
    for q in range(N_RATE_PLAN):
        if g[q] != 0.0:
            still = False
    if still:
        return turn_along(z, g, vx, vy, ax, ay)
    r0, at = _loading(p, s, ux, uy, vx, vy, z, carry, -1)
    e = TURN_PROBE
    for q in range(N_RATE_PLAN):
        J[0, q] = z[q] + e * g[q]
    r1, _ = _loading(p, s, ux + e * vx, uy + e * vy, vx + e * ax, vy + e * ay, J[0], carry, at)
    return r0, (r1 - r0) / e


@njit(cache=True)
def plan_rate_branch(p, s, ux, uy, z):
    """The branch at the trial (ux, uy) [in] of a step that carries the sliding elements' z,
    given in ``z`` there: the carried solve's (:func:`_carried_solve`), Σ_i (sliding_i·2^i +
    contact_i·2^(3+i)). It changes where an element that sticks starts to slide (its trial
    from the committed state, with the carried elements' z at that point, leaves its disk),
    where a restrainer engages, and where a carried element moves back."""
    r, _ = _carried_solve(p, s, ux, uy, z)
    return int(r[18])


@njit(cache=True)
def plan_rate_force(p, s, ux, uy, vx, vy, z, f, k, c):
    """Force ``f`` [kip] (2,), ∂f/∂u ``k`` [kip/in] and ∂f/∂v ``c`` (zero) (2, 2) in place at
    (ux, uy) [in] with the carried elements' hysteretic vectors given in ``z`` (a stage's): the
    series solve with those elements sliding at their given friction force (no friction
    stiffness), the others from the committed state (:func:`_carried_solve`)."""
    r, _ = _carried_solve(p, s, ux, uy, z)
    _write_trial(r, f, k, c)


@njit(cache=True)
def plan_rate_commit(p, s, ux, uy, vx, vy, z):
    """Commit the end (ux, uy) [in] of a step that carried the sliding elements' z, ``z`` their
    end values: each carried z put on the rim (the rate form leaves |z| − 1 at the step's
    truncation error; normalised in ``z`` in place), then the series state there with those z
    (:func:`_carried_solve`), so that the committed internal state is in equilibrium with its
    z (else a solve from it at the same displacement finds the element just inside its disk and
    the kink search lands a sliver at the next step's start). A velocity-dependent z is kept as
    it is (|z| is its friction over μ_slow·W: :func:`_viscous_rate`)."""
    carry = int(s[_CARRY])
    for i in range(3):
        if (carry >> i) & 1 and p[_RATE + 1] == 0.0:
            zx, zy = z[2 * i], z[2 * i + 1]
            norm = np.sqrt(zx * zx + zy * zy)
            z[2 * i] = zx / norm
            z[2 * i + 1] = zy / norm
    r, _ = _carried_solve(p, s, ux, uy, z)
    _store(s, 0, r)


# ---- on one axis: the plan element with u_y = v_y = 0 -------------------------------------------


@njit(cache=True)
def axis_trial(p, s, u, v):
    """Force [kip], df/du [kip/in] and df/dv [kip·s/in] at the trial (u [in], v [in/s]) from the
    committed state ``s`` (not modified): the plan element's x row at (u, 0), reached in the
    duration [s] held in the state row's last entry (read by velocity-dependent friction only;
    the loop writes it: :data:`femoat.structure.materials.kernels.DURATION`)."""
    r = _series(p, s, 0, u, 0.0, 0, s, s[s.size - 1])
    return r[0], r[2], 0.0


@njit(cache=True)
def axis_commit(p, s, u, v):
    """Advance the committed state ``s`` in place to the converged (u, v) (the plan element at
    (u, 0), reached in the duration held in the row's last entry, as :func:`axis_trial`)."""
    _store(s, 0, _series(p, s, 0, u, 0.0, 0, s, s[s.size - 1]))


@njit(cache=True)
def axis_energy(p, s):
    """Recoverable energy [kip·in] at the committed state (the plan element's)."""
    return plan_energy(p, s)


# ---- the dataclass ------------------------------------------------------------------------------


@dataclass(frozen=True)
class TripleFrictionPendulum(BearingFaces):
    """Triple friction-pendulum bearing, on one axis and in plan (one class: the 1D bearing is the
    plan bearing on one axis). Defaults: a typical bearing, see below.

    Parameters (OpenSees' notation; module docstring for Fenz & Constantinou's)
    ----------
    W : float
        Weight carried by the bearing [kip], > 0 (default 33: the paper building's bearing).
    L1 : float
        Effective radius R − h of each inner surface [in], > 0.
    L2, L3 : float
        Effective radii of the two outer surfaces [in], > L1.
    d1 : float
        Displacement capacity of the inner slider on each inner surface [in], > 0: the actual
        one, nominal·L/R (a manufacturer's R, h, nominal d: :meth:`from_geometry`).
    d2, d3 : float
        Displacement capacities on the outer surfaces of L2 and L3 [in], > 0 (actual).
    mu1 : float
        Friction coefficient of the inner surfaces [-], > 0.
    mu2, mu3 : float
        Friction coefficients of the outer surfaces of L2 and L3 [-], μ1 < μ2 ≤ μ3 < 1.
    u_y : float
        Displacement at which the bearing starts to slide [in], > 0 (≈ 0.01: each series
        element's sticking stiffness is 3·μ1·W/u_y), below 3·μ1·min(2·L1, L2 − L1, L3 − L1).
    mu1_fast, mu2_fast, mu3_fast : float or None
        Friction coefficients at high sliding speed [-] in [μ_i, 1) (Constantinou's
        μ_i(v) = μ_fast,i − (μ_fast,i − μ_i)·e^(−a·v), v the surface's own sliding speed; μ_i is
        then the value at rest, μ_slow): all three or none (None: constant friction).
    a : float
        Rate parameter of the velocity dependence [s/in], > 0 with the μ_fast; 0 without.

    Velocity-dependent friction runs on Newmark's step in 1D and on the coupled-friction step
    (ark5) in plan (module docstring).

    The defaults are a typical bearing: inner L1 = 12 in and outer L2 = L3 = 88 in (the
    isolated period of the large-displacement regime III, 2π·sqrt((L2 + L3)/g), is 4.2 s),
    capacities d1 = 2 in and d2 = d3 = 16 in (an ultimate displacement of 36 in), and frictions
    μ1 = 0.012 < μ2 = 0.052 < μ3 = 0.12 far enough apart for the five regimes to be distinct:
    u* = 0.96 in, u** = 7.76 in, u_dr1 = 27.8 in, u_dr4 = 34.6 in.
    """

    W: float = 33.0
    L1: float = 12.0
    L2: float = 88.0
    L3: float = 88.0
    d1: float = 2.0
    d2: float = 16.0
    d3: float = 16.0
    mu1: float = 0.012
    mu2: float = 0.052
    mu3: float = 0.12
    u_y: float = 0.01
    mu1_fast: float | None = None
    mu2_fast: float | None = None
    mu3_fast: float | None = None
    a: float = 0.0

    def __post_init__(self):
        _checks.positive("W", self.W, "[kip]")
        for name in ("L1", "L2", "L3"):
            _checks.positive(name, getattr(self, name), "[in]")
        for name in ("L2", "L3"):
            if not getattr(self, name) > self.L1:
                raise ValueError(
                    f"{name} = {getattr(self, name)!r} [in]: must be > L1 = {self.L1!r} (the "
                    "outer surfaces are the flatter ones: their series element's radius is "
                    f"{name} − L1).")
        for name in ("d1", "d2", "d3"):
            _checks.positive(name, getattr(self, name), "[in]")
        for name in ("mu1", "mu2", "mu3"):
            _checks.in_range(name, getattr(self, name), "[-]", 0.0, 1.0,
                             lo_open=True, hi_open=True)
        if not self.mu1 < self.mu2:
            raise ValueError(f"mu2 = {self.mu2!r} [-]: must be > mu1 = {self.mu1!r} (the inner "
                             "slider is the least rough: it slides first).")
        if not self.mu2 <= self.mu3:
            raise ValueError(f"mu3 = {self.mu3!r} [-]: must be >= mu2 = {self.mu2!r} (name the "
                             "outer surface of lower friction L2, d2, mu2).")
        _checks.positive("u_y", self.u_y, "[in]")
        limit = 3.0 * self.mu1 * min(2.0 * self.L1, self.L2 - self.L1, self.L3 - self.L1)
        if not self.u_y < limit:
            raise ValueError(
                f"u_y = {self.u_y!r} [in]: must be < 3·mu1·min(2·L1, L2 − L1, L3 − L1) = "
                f"{limit!r} (the series elements' sticking stiffness 3·mu1·W/u_y must exceed "
                "their pendulum stiffness); use a smaller u_y (≈ 0.01 in).")
        fast = [getattr(self, f"mu{i}_fast") for i in (1, 2, 3)]
        if all(f is None for f in fast):
            _checks.finite("a", self.a, "[s/in]")
            if self.a != 0.0:
                raise ValueError(f"a = {self.a!r} [s/in]: the rate of the velocity dependence "
                                 "needs mu1_fast, mu2_fast, mu3_fast; give them, or leave a = 0 "
                                 "(constant friction).")
            return
        for i, f in enumerate(fast, start=1):
            if f is None:
                raise ValueError(f"mu{i}_fast = None: give all three of mu1_fast, mu2_fast, "
                                 "mu3_fast (velocity-dependent friction on every surface) or "
                                 "none (constant friction).")
            slow = getattr(self, f"mu{i}")
            _checks.finite(f"mu{i}_fast", f, "[-]")
            if not slow <= f < 1.0:
                raise ValueError(f"mu{i}_fast = {f!r} [-]: must lie in [mu{i}, 1) = [{slow!r}, "
                                 f"1) (mu{i} is the friction at rest, mu{i}_fast at high speed).")
        _checks.positive("a", self.a, "[s/in] (needed with mu1_fast, mu2_fast, mu3_fast)")

    @classmethod
    def from_geometry(cls, *, R1, R2, R3, h1, h2, h3, d1_nominal, d2_nominal, d3_nominal,
                      mu1=mu1, mu2=mu2, mu3=mu3, u_y=u_y, W=W, mu1_fast=None, mu2_fast=None,
                      mu3_fast=None, a=0.0):
        """The bearing of a manufacturer's geometry (module docstring): effective radii
        L_i = R_i − h_i [in] and actual capacities d_i = d_i,nominal·L_i/R_i [in].

        Parameters (OpenSees' indices: 1 the two inner surfaces, 2 and 3 the outer ones)
        ----------
        R1, R2, R3 : float
            Radii of curvature of the inner surfaces (each) and of the outer surfaces [in], > 0.
        h1, h2, h3 : float
            Heights of the slider's pivot above those surfaces [in], 0 < h_i < R_i.
        d1_nominal, d2_nominal, d3_nominal : float
            Nominal displacement capacities on those surfaces (the slider's travel along the
            surface to its restrainer) [in], > 0.
        mu1, mu2, mu3, u_y, W, mu1_fast, mu2_fast, mu3_fast, a
            As the class's fields (their defaults), μ [-], u_y [in], W [kip], a [s/in].

        The class then checks the effective bearing (e.g. μ1 < μ2 ≤ μ3); R2 − h2 and R3 − h3
        must exceed R1 − h1 (the outer surfaces are the flatter ones).
        """
        # (the keyword defaults are the dataclass's: the class body's field names)
        geometry = ((1, R1, h1, d1_nominal), (2, R2, h2, d2_nominal), (3, R3, h3, d3_nominal))
        for i, radius, height, nominal in geometry:
            _checks.positive(f"R{i}", radius, "[in]")
            _checks.positive(f"h{i}", height, "[in]")
            if not height < radius:
                raise ValueError(
                    f"h{i} = {height!r} [in]: must be < R{i} = {radius!r} [in] (h is the height "
                    "of the slider's pivot above the surface, R the surface's radius of "
                    f"curvature: the effective radius R{i} − h{i} must be > 0); check R{i} and "
                    f"h{i}.")
            _checks.positive(f"d{i}_nominal", nominal, "[in]")
        L1, L2, L3 = R1 - h1, R2 - h2, R3 - h3
        for i, radius in ((2, L2), (3, L3)):
            if not radius > L1:
                raise ValueError(
                    f"R{i} − h{i} = {radius!r} [in]: must be > R1 − h1 = {L1!r} [in] (R1, h1 are "
                    f"the inner surfaces', R{i}, h{i} an outer surface's, the flatter one: its "
                    "effective radius is the larger); check which surface is which.")
        return cls(W=W, L1=L1, L2=L2, L3=L3, d1=d1_nominal * L1 / R1, d2=d2_nominal * L2 / R2,
                   d3=d3_nominal * L3 / R3, mu1=mu1, mu2=mu2, mu3=mu3, u_y=u_y,
                   mu1_fast=mu1_fast, mu2_fast=mu2_fast, mu3_fast=mu3_fast, a=a)

    # ---- derived quantities (the series model) ----

    @property
    def radii(self) -> tuple:
        """The series elements' radii L̄_i [in]: 2·L1, L2 − L1, L3 − L1."""
        return (2.0 * self.L1, self.L2 - self.L1, self.L3 - self.L1)

    @property
    def frictions(self) -> tuple:
        """The series elements' friction coefficients [-]: μ1, μ2, μ3."""
        return (self.mu1, self.mu2, self.mu3)

    @property
    def velocity_dependent(self) -> bool:
        """Whether the surfaces' friction depends on their sliding speed (the μ_fast given)."""
        return self.mu1_fast is not None

    @property
    def rate_factors(self) -> tuple:
        """Each series element's surface sliding speed per unit of its own slip rate [-]: 1/2
        (the inner slider's two surfaces share its element), L2/(L2 − L1), L3/(L3 − L1) (an
        outer element's displacement is (L − L1)/L of its surface's), OpenSees' v1Fact,
        v3Fact, v5Fact."""
        return (0.5, self.L2 / (self.L2 - self.L1), self.L3 / (self.L3 - self.L1))

    @property
    def gaps(self) -> tuple:
        """The series elements' gaps g_i [in] (their restrainers; module docstring)."""
        m = min(self.d2 / self.L2, self.d3 / self.L3)
        return (2.0 * (self.d1 + self.L1 * m), self.d2 * (1.0 - self.L1 / self.L2),
                self.d3 * (1.0 - self.L1 / self.L3))

    @property
    def sticking_stiffness(self) -> float:
        """k_0 = 3·μ1·W/u_y [kip/in]: each series element's stiffness while it sticks, and its
        restrainer's."""
        return 3.0 * self.mu1 * self.W / self.u_y

    @property
    def element_yield_displacements(self) -> tuple:
        """u_y,i = μ_i·W/(k_0 − W/L̄_i) [in]: each series element's friction yield displacement."""
        k0 = self.sticking_stiffness
        return tuple(mu * self.W / (k0 - self.W / r) for mu, r in zip(self.frictions, self.radii))

    @property
    def yield_deformation(self) -> float:
        """Displacement at which the bearing starts to slide, from rest [in]: 3·u_y,1 (three
        elements of stiffness k_0 in series until the inner one slides), ≈ u_y."""
        return 3.0 * self.element_yield_displacements[0]

    @property
    def capacity(self) -> float:
        """Ultimate displacement [in]: 2·d1 + d2 + d3 − L1·|d2/L2 − d3/L3|, the sum of the gaps,
        where the inner slider reaches its restrainer (module docstring: OpenSees' formula when
        d3/L3 ≤ d2/L2)."""
        return float(sum(self.gaps))

    def params(self) -> np.ndarray:
        k0 = self.sticking_stiffness
        p = [self.W, self.u_y, k0]
        for r, mu, uyi, gap in zip(self.radii, self.frictions, self.element_yield_displacements,
                                   self.gaps):
            p += [self.W / r, mu * self.W, uyi, gap]
        p.append(self.capacity)
        fast = (self.mu1_fast, self.mu2_fast, self.mu3_fast)
        for mu, f, fact in zip(self.frictions, fast, self.rate_factors):
            p += [mu * self.W, 0.0] if f is None else [f * self.W, self.a * fact]
        return np.array(p, dtype=np.float64)


def rate_form_covers(params):
    """Whether the rate form (the coupled-friction step's) covers a bearing of these params:
    constant friction, or velocity-dependent friction on all three elements (μ_fast > μ_slow
    on each: :func:`_viscous_rate`); a bearing with μ_fast = μ_slow on some surface and not on
    the others follows each step's path (Newmark)."""
    if not reads_duration(params):
        return True
    return all(params[_RATE + 2 * i + 1] > 0.0 and params[_RATE + 2 * i] > params[_E0 + 4 * i + 1]
               for i in range(3))


def reads_duration(params):
    """Whether a bearing of these params reads each step's duration (velocity-dependent
    friction, a backward-Euler return over the step: module docstring), so that its runs take
    Newmark's step, in 1D and in plan."""
    return bool(params[_RATE + 1] > 0.0)


AXIS_CLASS = TripleFrictionPendulum
"""The bearing on one axis (the isolator of a 1D building)."""

PLAN_CLASS = TripleFrictionPendulum
"""The bearing in plan (the isolator of a plan building): the same class."""


# ---- the OpenSees twin -------------------------------------------------------------------------

OPENSEES_AXIAL_LOAD = True
"""The plan twin takes its normal force from its vertical material: the j node's vertical DOF is
free and a static gravity step puts N = W on it before the analysis (:func:`opensees_plan_element`).
There is no 1D twin (OpenSees' TripleFrictionPendulum is a 3D element, not a uniaxial
material): check the bearing in plan."""

AXIAL_STIFFNESS = 1.0e6
"""Stiffness [kip/in, kip·in/rad] of the twin's vertical (compression) material and of its
rotational ones."""


def opensees_plan_element(bearing, ele_tag, i_node, j_node, mat_tag, tol=1e-7):
    """The openseespy calls that build ``bearing``'s twin, OpenSees' ``TripleFrictionPendulum``,
    between nodes ``i_node`` (below) and ``j_node`` (above) of a ``-ndm 3 -ndf 6`` model: shear in
    global x and y, axis global z. Returns (commands, next_mat_tag): commands as tuples
    ``("function name", *args)``; three ``Coulomb`` friction models and four ``Elastic``
    materials take the tags mat_tag, mat_tag + 1, ... (friction models and materials are
    separate name spaces in OpenSees; one counter keeps both free of clashes).

    Axial load: the element's friction and pendulum forces are proportional to its axial force
    N from the vertical material (not to ``bearing.W``, which only seeds its first trial), so the
    model must carry N = W: ``j_node`` free in z with a load −W in z on it (a static step before
    the analysis, then held constant: :data:`OPENSEES_AXIAL_LOAD`).

    The twin equals this module's series model (module docstring): OpenSees' friction inputs
    are μ_i·k_0/(k_0 − W/L̄_i) and its u_y is u_y·μ1_OS/μ1, which make its hardening elements
    the spring plus friction disk of stiffness k_0 here; its outer surfaces are listed so that
    the one of smaller d/L is its third (OpenSees' inner gap uses d3/L3). Velocity-dependent
    friction: ``frictionModel VelDependent`` with both coefficients scaled so and the rate
    parameter a; OpenSees reads it at its element's whole deformation rate over the step
    (times the same factors), from its previous iteration, where this module reads the slip
    rate (module docstring).

    Its tension stiffness kvt = 1 kip/in and minimum axial force minFv = 0.1 kip only act on
    uplift, which this module does not model.

    ``tol`` is the element's convergence tolerance, relative to the step: at 1e-5 a step that
    crosses a transition can leave its internal split off by 1e-5 of the step (a lasting
    offset of ~1e-9 of the force on one axis); 1e-7 to 1e-9 agree with this module to rounding
    on one axis; 1e-11 stalls its iteration (a wrong state, a hundred times slower). Its first
    step from rest must stay below about 3·u_y (a larger one ends in a wrong state).
    """
    b = bearing
    k0 = b.sticking_stiffness
    fast = (b.mu1_fast, b.mu2_fast, b.mu3_fast)
    outer = [(b.L2, b.d2, b.mu2, fast[1]), (b.L3, b.d3, b.mu3, fast[2])]
    if b.d3 / b.L3 > b.d2 / b.L2:
        outer.reverse()
    (l2, d2, mu2, f2), (l3, d3, mu3, f3) = outer
    radii = (2.0 * b.L1, l2 - b.L1, l3 - b.L1)
    scales = [k0 / (k0 - b.W / r) for r in radii]
    mus = [mu * c for mu, c in zip((b.mu1, mu2, mu3), scales)]
    u_y = b.u_y * mus[0] / b.mu1
    friction = [mat_tag, mat_tag + 1, mat_tag + 2]
    vertical, rot_z, rot_x, rot_y = mat_tag + 3, mat_tag + 4, mat_tag + 5, mat_tag + 6
    if b.velocity_dependent:
        commands = [("frictionModel", "VelDependent", tag, mu, f * c, b.a)
                    for tag, mu, f, c in zip(friction, mus, (fast[0], f2, f3), scales)]
    else:
        commands = [("frictionModel", "Coulomb", tag, mu) for tag, mu in zip(friction, mus)]
    commands += [("uniaxialMaterial", "Elastic", tag, AXIAL_STIFFNESS)
                 for tag in (vertical, rot_z, rot_x, rot_y)]
    commands.append(("element", "TripleFrictionPendulum", ele_tag, i_node, j_node, *friction,
                     vertical, rot_z, rot_x, rot_y, b.L1, l2, l3, b.d1, d2, d3, b.W, u_y,
                     1.0, 0.1, tol))
    return commands, mat_tag + 7

"""Peaks of the continuous solution, kept inside the compiled loop as the samples are recorded.

The same quantities and the same interpolants as :mod:`femoat.dense_peaks` reads from a
recorded history (so a run's peaks need no Python pass over its history), sample by sample:

* base displacement, each story's drift, each wall's displacement at its impact point: the
  crest of the cubic Hermite interpolant of (x, ẋ) between consecutive samples;
* the base mat's velocity: the crest of v with the acceleration linear in an interval;
* the absolute accelerations of the base mat and the floors: the samples, and with the
  fifth-order open phase the crest of the quintic Hermite interpolant of (u, v, a) on an
  interval integrated by it: every gap open at its start, and at its end too or closing there
  under a law whose force vanishes at δ = 0⁺ (the step before a located closure; a dashpot law's
  force jumps on at closure, so its end sample holds the acceleration after the jump);
* the largest indentation, at the samples.

An interval is judged once the sample after it is recorded: an event at a committed state may
still change the contact flags of the last sample (``recorder.mark_last_sample``). The last
interval is judged by :func:`finish_peaks` after the loop.

Layout of ``state.pk`` for ns building DOFs and nc contacts: ``[0:ns]`` each building DOF's
displacement against its reference (``settings.err_ref``: the floor below along the same
axis, none for the base mat): in 1D ``[0]`` the base displacement and ``[1:ns]`` the story
drifts, in plan the same per axis in the DOF order of :mod:`femoat.plan.model`;
``[ns:ns+nc]`` wall displacements [in], ``[ns+nc:2ns+nc]`` absolute accelerations [in/s²]
(each building DOF along its axis, ``model.dof_axis``), ``[2ns+nc]`` base velocity [in/s]
(DOF 0), ``[2ns+nc+1]`` indentation [in], ``[2ns+nc+2]`` the base mat's plan displacement
√(u_x² + u_y²) [in] (plan models, ``model.base_xy``; 0 in 1D). ``state.pk_ring`` holds the
last two samples (t, u, v, a, a_g per ground component); ``state.pk_n[0]`` how many.
"""

import numpy as np

from femoat.compilation.jit import njit
from femoat.contact._dispatch import acts_at_zero
from femoat.integration.recording.rows import row
from femoat.integration.codes import S_NOUT


def size(ns, nc):
    """Length of the peaks array for ns building DOFs and nc contacts."""
    return 2 * ns + nc + 3


@njit(cache=True, inline="always")
def _hermite3(th, x0, d0, x1, d1):
    """The cubic Hermite interpolant (end values x0, x1, end slopes d0, d1 in θ) at ``th``
    and its first and second derivatives in θ."""
    t2 = th * th
    t3 = t2 * th
    x = (2 * t3 - 3 * t2 + 1) * x0 + (t3 - 2 * t2 + th) * d0 + (-2 * t3 + 3 * t2) * x1 \
        + (t3 - t2) * d1
    dx = (6 * t2 - 6 * th) * x0 + (3 * t2 - 4 * th + 1) * d0 + (-6 * t2 + 6 * th) * x1 \
        + (3 * t2 - 2 * th) * d1
    ddx = (12 * th - 6) * x0 + (6 * th - 4) * d0 + (-12 * th + 6) * x1 + (6 * th - 2) * d1
    return x, dx, ddx


PLAN_SAMPLES = 16
"""Points of an interval where the plan crest's search starts (then Newton on d|u|²/dθ = 0)."""


@njit(cache=True, inline="always")
def _plan_crest(h, x0, vx0, x1, vx1, y0, vy0, y1, vy1, best):
    """max(best, the crest of |(x(θ), y(θ))| inside an interval of length h, each component
    its cubic Hermite interpolant): the largest of PLAN_SAMPLES points, refined by Newton on
    the stationarity of |u|² (a polynomial of degree 6)."""
    dx0, dx1, dy0, dy1 = h * vx0, h * vx1, h * vy0, h * vy1
    bx = max(abs(x0), abs(x1)) + (4.0 / 27.0) * (abs(dx0) + abs(dx1))
    by = max(abs(y0), abs(y1)) + (4.0 / 27.0) * (abs(dy0) + abs(dy1))
    if bx * bx + by * by <= best * best:
        return best
    th_best, r2_best = 0.0, -1.0
    for j in range(1, PLAN_SAMPLES):
        th = j / PLAN_SAMPLES
        x, _, _ = _hermite3(th, x0, dx0, x1, dx1)
        y, _, _ = _hermite3(th, y0, dy0, y1, dy1)
        if x * x + y * y > r2_best:
            th_best, r2_best = th, x * x + y * y
    th = th_best
    for _ in range(6):
        x, dx, ddx = _hermite3(th, x0, dx0, x1, dx1)
        y, dy, ddy = _hermite3(th, y0, dy0, y1, dy1)
        g = x * dx + y * dy
        dg = dx * dx + x * ddx + dy * dy + y * ddy
        if dg >= 0.0:  # not a crest's neighbourhood: keep the sample
            break
        th = min(1.0, max(0.0, th - g / dg))
    x, _, _ = _hermite3(th, x0, dx0, x1, dx1)
    y, _, _ = _hermite3(th, y0, dy0, y1, dy1)
    r2 = max(r2_best, x * x + y * y)
    return max(best, np.sqrt(r2))


@njit(cache=True, inline="always")
def _unit_roots(qa, qb, qc):
    """The (up to two) real roots of qa·θ² + qb·θ + qc, NaN where there is none (the stable
    pair of ``dense_peaks._roots_in_unit_interval``; the caller keeps those in (0, 1))."""
    scale = max(max(abs(qa), abs(qb)), abs(qc))
    if abs(qa) <= 1e-12 * scale:
        if qb == 0.0:
            return np.nan, np.nan
        return -qc / qb, np.nan
    disc = qb * qb - 4.0 * qa * qc
    if not disc >= 0.0:
        return np.nan, np.nan
    sq = np.sqrt(disc)
    q = -0.5 * (qb + (sq if qb >= 0.0 else -sq))
    return q / qa, qc / q


@njit(cache=True, inline="always")
def _roots_max(qa, qb, qc, x0, d0, x1, d1, best):
    """max(best, |cubic Hermite x(θ)|) at the roots in (0, 1) of qa·θ² + qb·θ + qc."""
    for s in _unit_roots(qa, qb, qc):
        if s > 0.0 and s < 1.0:
            s2 = s * s
            s3 = s2 * s
            x = ((2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * d0
                 + (-2 * s3 + 3 * s2) * x1 + (s3 - s2) * d1)
            if abs(x) > best:
                best = abs(x)
    return best


@njit(cache=True, inline="always")
def _hermite_crest(h, x0, v0, x1, v1, best):
    """max(best, the crest of the cubic Hermite interpolant inside an interval of length h)."""
    d0, d1 = h * v0, h * v1
    # |x(θ)| ≤ max(|x0|, |x1|) + 4/27·(|d0| + |d1|) (the Hermite basis): no crest above best
    if max(abs(x0), abs(x1)) + (4.0 / 27.0) * (abs(d0) + abs(d1)) <= best:
        return best
    qa = 6.0 * (x0 - x1) + 3.0 * (d0 + d1)
    qb = 6.0 * (x1 - x0) - 4.0 * d0 - 2.0 * d1
    return _roots_max(qa, qb, d0, x0, d0, x1, d1, best)


@njit(cache=True, inline="always")
def _cubic_max(al0, al1, al2, al3, best):
    """max(best, |α0 + α1θ + α2θ² + α3θ³|) at its stationary points in (0, 1)."""
    for s in _unit_roots(3.0 * al3, 2.0 * al2, al1):
        if s > 0.0 and s < 1.0:
            val = abs(al0 + s * (al1 + s * (al2 + s * al3)))
            if val > best:
                best = val
    return best


@njit(cache=True, inline="always")
def _quintic_accel_crest(h, u0, v0, a0, ag0, u1, v1, a1, ag1, best):
    """max(best, the crest of a(θ) + a_g(θ) from the quintic Hermite interpolant of
    (u, v, a)); an interval too short for its coefficients keeps its samples (the same
    coefficients and test as ``dense_peaks.quintic_accel_abs_max``, tied by
    tests/test_kernel_peaks.py)."""
    h2 = h * h
    c1 = h * v0
    c2 = 0.5 * h2 * a0
    r0 = u1 - u0 - c1 - c2
    r1 = h * v1 - c1 - 2.0 * c2
    r2 = h2 * a1 - 2.0 * c2
    al0 = a0 + ag0
    al1 = 6.0 * (10.0 * r0 - 4.0 * r1 + 0.5 * r2) / h2 + (ag1 - ag0)
    al2 = 12.0 * (-15.0 * r0 + 7.0 * r1 - r2) / h2
    al3 = 20.0 * (6.0 * r0 - 3.0 * r1 + 0.5 * r2) / h2
    roundoff = 120.0 * 2.220446049250313e-16 * (abs(u0) + abs(u1)) / h2
    if roundoff > 1e-6 * (abs(al0) + abs(a1) + 1.0):
        return best
    if abs(al0) + abs(al1) + abs(al2) + abs(al3) <= best:  # |cubic| ≤ Σ|α_k| on [0, 1]
        return best
    return _cubic_max(al0, al1, al2, al3, best)


@njit(cache=True, inline="always")
def _wall(c_B, c, x, ns):
    """A wall's displacement (or velocity) at its impact point: −Σ_i b_ci·x_i over its DOFs."""
    w = 0.0
    for i in range(ns, x.size):
        if c_B[c, i] != 0.0:
            w += -c_B[c, i] * x[i]
    return w


@njit(cache=True, inline="always")
def _endpoint(t, model, settings, u, v, a, ag, c_d, pk):
    """The sample's own values into the running maxima."""
    ns = settings.n_struct
    nc = model.c_gap.size
    ref, axis = settings.err_ref, model.dof_axis
    for k in range(ns):
        j = ref[k]
        pk[k] = max(pk[k], abs(u[k] - u[j]) if j >= 0 else abs(u[k]))
    for c in range(nc):
        pk[ns + c] = max(pk[ns + c], abs(_wall(model.c_B, c, u, ns)))
    for i in range(ns):
        pk[ns + nc + i] = max(pk[ns + nc + i], abs(a[i] + ag[axis[i]]))
    pk[2 * ns + nc] = max(pk[2 * ns + nc], abs(v[0]))
    for c in range(nc):
        pk[2 * ns + nc + 1] = max(pk[2 * ns + nc + 1], c_d[c])
    bx, by = model.base_xy[0], model.base_xy[1]
    if bx >= 0:
        pk[2 * ns + nc + 2] = max(pk[2 * ns + nc + 2], np.sqrt(u[bx] * u[bx] + u[by] * u[by]))


@njit(cache=True)
def _interval(smooth, quintic, n, ns, nc, ref, axis, c_B, base_xy, ring, pk):
    """The crests inside the interval between the two samples of ``ring``: its own compiled
    function (called once per recorded sample, with arrays, not the bundles), so that the
    crest helpers are compiled once, not again inside every kernel that records."""
    t0, t1 = ring[0, 0], ring[1, 0]
    h = t1 - t0
    if not h > 0.0:
        return
    u0, u1 = ring[0, 1:1 + n], ring[1, 1:1 + n]
    v0, v1 = ring[0, 1 + n:1 + 2 * n], ring[1, 1 + n:1 + 2 * n]
    a0, a1 = ring[0, 1 + 2 * n:1 + 3 * n], ring[1, 1 + 2 * n:1 + 3 * n]
    ag0, ag1 = ring[0, 1 + 3 * n:], ring[1, 1 + 3 * n:]
    for k in range(ns):
        j = ref[k]
        if j >= 0:
            pk[k] = _hermite_crest(h, u0[k] - u0[j], v0[k] - v0[j], u1[k] - u1[j],
                                   v1[k] - v1[j], pk[k])
        else:
            pk[k] = _hermite_crest(h, u0[k], v0[k], u1[k], v1[k], pk[k])
    for c in range(nc):
        pk[ns + c] = _hermite_crest(h, _wall(c_B, c, u0, ns), _wall(c_B, c, v0, ns),
                                    _wall(c_B, c, u1, ns), _wall(c_B, c, v1, ns), pk[ns + c])
    # the base velocity with the acceleration linear inside (Newmark's own interpolant)
    if a0[0] != a1[0]:
        th = a0[0] / (a0[0] - a1[0])
        if th > 0.0 and th < 1.0:
            pk[2 * ns + nc] = max(pk[2 * ns + nc], abs(v0[0] + 0.5 * h * a0[0] * th))
    if smooth and quintic:
        for i in range(ns):
            pk[ns + nc + i] = _quintic_accel_crest(h, u0[i], v0[i], a0[i], ag0[axis[i]], u1[i],
                                                   v1[i], a1[i], ag1[axis[i]], pk[ns + nc + i])
    bx, by = base_xy[0], base_xy[1]
    if bx >= 0:
        pk[2 * ns + nc + 2] = _plan_crest(h, u0[bx], v0[bx], u1[bx], v1[bx], u0[by], v0[by],
                                          u1[by], v1[by], pk[2 * ns + nc + 2])


@njit(cache=True, inline="always")
def _open(closed_row):
    for c in range(closed_row.size):
        if closed_row[c]:
            return False
    return True


@njit(cache=True, inline="always")
def _closes_smoothly(closed_row, c_code):
    """No contact is closed at this sample whose law acts at δ = 0⁺ (a dashpot, whose force
    jumps on at closure): an open interval ending here, on a located closure, has a smooth
    acceleration up to its end, and its end sample's acceleration is that end's."""
    for c in range(closed_row.size):
        if closed_row[c] and acts_at_zero(c_code[c]):
            return False
    return True


@njit(cache=True, inline="always")
def _keep(t, model, state, settings):
    """The committed state at time ``t`` as the ring's newest sample, and its own values."""
    ring = state.pk_ring
    n = state.u.size
    row = state.pk_n[0]
    ring[row, 0] = t
    for i in range(n):
        ring[row, 1 + i] = state.u[i]
        ring[row, 1 + n + i] = state.v[i]
        ring[row, 1 + 2 * n + i] = state.a[i]
    for k in range(state.ag_now.size):
        ring[row, 1 + 3 * n + k] = state.ag_now[k]
    state.pk_n[0] = row + 1
    _endpoint(t, model, settings, state.u, state.v, state.a, state.ag_now, state.c_d,
              state.pk)


@njit(cache=True, inline="always")
def _judge_older(k, model, state, settings, rec):
    """With two samples kept (recorder samples k − 2 and k − 1, in their rows modulo the
    recorder's length; −1 the initial state with every gap open), judge the interval between them and keep only the newer."""
    if state.pk_n[0] < 2:
        return
    ring = state.pk_ring
    rows = rec.closed.shape[0]
    open0 = True if k - 2 < 0 else _open(rec.closed[row(k - 2, rows)])
    open1 = True if k - 1 < 0 else _closes_smoothly(rec.closed[row(k - 1, rows)], model.c_code)
    _interval(open0 and open1, settings.quintic_peaks, model.M.shape[0], settings.n_struct,
              model.c_gap.size, settings.err_ref, model.dof_axis, model.c_B, model.base_xy, ring,
              state.pk)
    for j in range(ring.shape[1]):
        ring[0, j] = ring[1, j]
    state.pk_n[0] = 1


@njit(cache=True, inline="always")
def push_sample(t, k, model, state, settings, rec):
    """Sample ``k`` of the recorder (time ``t``, the committed state) was just written: judge
    the interval before the previous sample (its flags are final now), then keep this one."""
    _judge_older(k, model, state, settings, rec)
    _keep(t, model, state, settings)


@njit(cache=True)
def start_peaks(model, state, settings):
    """Reset the running maxima and keep the initial state (time 0) as the first sample."""
    for j in range(state.pk.size):
        state.pk[j] = 0.0
    state.pk_n[0] = 0
    _keep(0.0, model, state, settings)


@njit(cache=True)
def finish_peaks(model, state, settings, rec):
    """Judge the last interval (after the loop; every flag is final)."""
    _judge_older(state.stats[S_NOUT], model, state, settings, rec)

"""Peaks of the continuous solution inside each step, not only at the step ends.

The implicit step joins its end states by the cubic Hermite interpolant of displacement and
velocity (the same interpolant the solver's event search uses) and by a linear acceleration
(Newmark's average-acceleration step: v₁ = v₀ + h·(a₀ + a₁)/2). A crest between two step ends
is read from those interpolants: displacements and drifts from the cubic's stationary points,
velocities from the parabola ∫a. Accelerations are linear inside a Newmark step, so their peaks are at
step ends. The explicit fifth-order step of the open phase (``Integrator(method="dp5")``) is
smooth inside: its accelerations are read from the quintic Hermite interpolant of (u, v, a) at
the step's ends (:func:`quintic_accel_abs_max`). With ``Integrator(record_every=k > 1)`` the
interpolants span k steps and are an approximation.
"""

import numpy as np


def hermite_abs_max(t, x, v):
    """max |x(t)| of the piecewise cubic Hermite interpolant through (t, x, ẋ = v).

    t [s] (m samples); x and v of shape (m,) or (m, k) for k channels at once (v in x's unit
    per second); returns a float, or k floats. Intervals of zero length (an event recorded twice
    at one instant) are skipped.
    """
    t = np.asarray(t, dtype=float)
    x, v = np.asarray(x, dtype=float), np.asarray(v, dtype=float)
    if x.ndim == 2:  # column by column: contiguous 1-D work is faster than one 2-D pass
        return [hermite_abs_max(t, x[:, k], v[:, k]) for k in range(x.shape[1])]
    one = True
    x, v = x[:, None], v[:, None]
    if x.shape[0] == 0:
        return 0.0 if one else [0.0] * x.shape[1]
    ax = np.abs(x)
    peak = ax.max(axis=0)
    if x.shape[0] >= 2:
        h = np.diff(t)[:, None]
        hv0, hv1 = np.abs(h * v[:-1]), np.abs(h * v[1:])
        # |x(θ)| ≤ max(|x₀|, |x₁|) + 4/27·(h|v₀| + h|v₁|) (the Hermite basis: h00 + h01 = 1,
        # |h10|, |h11| ≤ 4/27): only intervals whose bound passes the largest sample can hold
        # the crest, and only those are searched
        bound = np.maximum(ax[:-1], ax[1:]) + (4.0 / 27.0) * (hv0 + hv1)
        candidate = (bound > peak) & (h > 0.0)
        for k in range(x.shape[1]):
            i = np.flatnonzero(candidate[:, k])
            if i.size == 0:
                continue
            hk = h[i, 0]
            x0, x1, v0, v1 = x[i, k], x[i + 1, k], hk * v[i, k], hk * v[i + 1, k]
            # dx/dθ = A·θ² + B·θ + C on θ ∈ [0, 1]
            a = 6.0 * (x0 - x1) + 3.0 * (v0 + v1)
            b = 6.0 * (x1 - x0) - 4.0 * v0 - 2.0 * v1
            for s in _roots_in_unit_interval(a, b, v0):
                s2, s3 = s * s, s * s * s
                xs = ((2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * v0
                      + (-2 * s3 + 3 * s2) * x1 + (s3 - s2) * v1)
                peak[k] = np.fmax(peak[k], np.nanmax(np.abs(xs), initial=0.0))
    return float(peak[0]) if one else [float(p) for p in peak]


def smooth_intervals(closed, closes_smoothly):
    """Which intervals between samples the open phase integrated smoothly: every contact open
    at the start, and at the end too or closing there under a law whose force vanishes at
    δ = 0⁺ (``closes_smoothly``, per contact; a dashpot law's force jumps on at closure).
    ``closed`` (m, contacts): 1 while a contact episode is open. Returns (m − 1,) booleans (the
    rule of the solver's running peaks, ``femoat.integration.recording.peaks``)."""
    closed = np.asarray(closed).astype(bool)
    if closed.ndim != 2 or closed.shape[1] == 0:
        return np.ones(max(closed.shape[0] - 1, 0), dtype=bool)
    open_now = ~closed.any(axis=1)
    jumps = closed & ~np.asarray(closes_smoothly, dtype=bool)[None, :]
    return open_now[:-1] & (open_now[1:] | ~jumps[1:].any(axis=1))


def quintic_accel_abs_max(t, u, v, a, ag, smooth):
    """max |a(t) + a_g(t)| per column, a(t) the second derivative of the quintic Hermite
    interpolant through (u, u̇ = v, ü = a) at both ends of every interval marked ``smooth``
    (elsewhere only the samples count), a_g linear in an interval.

    t [s] (m samples); u [in], v [in/s], a [in/s²] of shape (m, k); ag [in/s²] (m,); smooth a
    boolean (m − 1,). Returns k floats [in/s²]. (The solver keeps the same crests as it records,
    ``femoat.integration.recording.peaks._quintic_accel_crest``; tests/test_kernel_peaks.py ties the two.)
    """
    t = np.asarray(t, dtype=float)
    u, v, a = (np.asarray(q, dtype=float) for q in (u, v, a))
    ag = np.asarray(ag, dtype=float)
    total = a + ag[:, None]
    peak = np.abs(total).max(axis=0) if total.shape[0] else np.zeros(total.shape[1])
    h = np.diff(t)
    ok = np.asarray(smooth, dtype=bool) & (h > 0.0)
    if not ok.any():
        return [float(p) for p in peak]
    hk = np.where(ok, h, 1.0)[:, None]  # (slices, not gathers: every interval at once)
    dag = np.diff(ag)[:, None]
    # x(θ) = Σ c_k θ^k on θ ∈ [0, 1]: c0..c2 from the start, c3..c5 from the end's residuals
    h2 = hk * hk
    c1, c2 = hk * v[:-1], 0.5 * h2 * a[:-1]
    r0 = u[1:] - u[:-1] - c1 - c2
    r1 = hk * v[1:] - c1 - 2.0 * c2
    r2 = h2 * a[1:] - 2.0 * c2
    # a(θ) + a_g(θ) = α0 + α1·θ + α2·θ² + α3·θ³ (α_k = k(k−1)·c_k/h², a_g linear)
    al0 = total[:-1]
    al1 = 6.0 * (10.0 * r0 - 4.0 * r1 + 0.5 * r2) / h2 + dag
    al2 = 12.0 * (-15.0 * r0 + 7.0 * r1 - r2) / h2
    al3 = 20.0 * (6.0 * r0 - 3.0 * r1 + 0.5 * r2) / h2
    # an interval too short for its coefficients (round-off of u divided by h² would exceed a
    # millionth of the accelerations) keeps its end values: it is a landing step of
    # nanoseconds, in which the acceleration cannot turn
    eps = np.finfo(float).eps
    roundoff = 120.0 * eps * (np.abs(u[:-1]) + np.abs(u[1:])) / h2
    usable = ok[:, None] & (roundoff <= 1e-6 * (np.abs(al0) + np.abs(a[1:]) + 1.0))
    # |α0 + α1·θ + α2·θ² + α3·θ³| ≤ Σ|α_k| on [0, 1]: only intervals whose bound passes the
    # largest sample can hold the crest, and only those are searched
    bound = np.abs(al0) + np.abs(al1) + np.abs(al2) + np.abs(al3)
    candidate = usable & (bound > peak[None, :])
    for k in range(total.shape[1]):
        j = np.flatnonzero(candidate[:, k])
        if j.size == 0:
            continue
        a0, a1, a2, a3 = al0[j, k], al1[j, k], al2[j, k], al3[j, k]
        for s in _roots_in_unit_interval(3.0 * a3, 2.0 * a2, a1):
            vals = np.abs(a0 + s * (a1 + s * (a2 + s * a3)))
            peak[k] = np.fmax(peak[k], np.nanmax(vals, initial=0.0))
    return [float(p) for p in peak]


def linear_accel_velocity_abs_max(t, v, a):
    """max |v(t)| with the acceleration linear inside each interval (v₁ = v₀ + h(a₀ + a₁)/2)."""
    t, v, a = (np.asarray(q, dtype=float) for q in (t, v, a))
    peak = float(np.abs(v).max()) if v.size else 0.0
    if v.size < 2:
        return peak
    h = np.diff(t)
    a0, a1 = a[:-1], a[1:]
    with np.errstate(divide="ignore", invalid="ignore"):
        th = a0 / (a0 - a1)  # where the linear acceleration crosses zero
    ok = (th > 0.0) & (th < 1.0) & (h > 0.0)
    if ok.any():
        vs = v[:-1][ok] + 0.5 * h[ok] * a0[ok] * th[ok]
        peak = max(peak, float(np.abs(vs).max()))
    return peak


def _roots_in_unit_interval(a, b, c):
    """The (up to two) real roots of a·θ² + b·θ + c in (0, 1), NaN where there is none."""
    scale = np.maximum(np.maximum(np.abs(a), np.abs(b)), np.abs(c))
    with np.errstate(divide="ignore", invalid="ignore"):
        linear = np.abs(a) <= 1e-12 * scale
        disc = b * b - 4.0 * a * c
        sq = np.sqrt(np.where(disc >= 0.0, disc, np.nan))
        # the numerically stable pair: q = −(b + sign(b)·√disc)/2, roots q/a and c/q
        q = -0.5 * (b + np.where(b >= 0.0, sq, -sq))
        r1 = np.where(linear, -c / b, q / a)
        r2 = np.where(linear, np.nan, c / q)
    out = []
    for r in (r1, r2):
        out.append(np.where((r > 0.0) & (r < 1.0), r, np.nan))
    return out


def parabolic_peak(t, f, k):
    """Peak of f near sample k refined by the parabola through its neighbours (an impact's peak
    force between recorded samples)."""
    if k <= 0 or k >= f.size - 1:
        return f[k]
    t0, t1, t2 = t[k - 1], t[k], t[k + 1]
    f0, f1, f2 = f[k - 1], f[k], f[k + 1]
    if f0 <= 0.0 or f2 <= 0.0:
        return f1
    # vertex of the interpolating parabola (non-uniform spacing)
    d1, d2 = (f1 - f0) / (t1 - t0), (f2 - f1) / (t2 - t1)
    a = (d2 - d1) / (t2 - t0)
    if a >= 0:
        return f1
    b = d1 - a * (t0 + t1)
    tv = -b / (2 * a)
    if not (t0 <= tv <= t2):
        return f1
    return max(f1, f0 + (tv - t0) * (d1 + a * (tv - t1)))

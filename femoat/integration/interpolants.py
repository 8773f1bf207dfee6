"""The dense output the events, the kinks and the peaks read inside a step: cubic and quintic
Hermite interpolants on a step's end values, and the crossing of zero of the cubic one."""

from femoat.compilation.jit import njit


@njit(cache=True, inline="always")
def hermite(th, h, x0, dx0, x1, dx1):
    """The cubic Hermite interpolant of a step of length ``h`` (values x0, x1 and time
    derivatives dx0, dx1 at its ends) at fraction ``th``, and its derivative in ``th``."""
    t2 = th * th
    t3 = t2 * th
    x = (2 * t3 - 3 * t2 + 1) * x0 + (t3 - 2 * t2 + th) * h * dx0 \
        + (-2 * t3 + 3 * t2) * x1 + (t3 - t2) * h * dx1
    dx = (6 * t2 - 6 * th) * x0 + (3 * t2 - 4 * th + 1) * h * dx0 \
        + (-6 * t2 + 6 * th) * x1 + (3 * t2 - 2 * th) * h * dx1
    return x, dx


@njit(cache=True, inline="always")
def quintic(th, h, x0, dx0, ddx0, x1, dx1, ddx1):
    """The quintic Hermite interpolant of a step of length ``h`` (values, first and second time
    derivatives at its ends) at fraction ``th`` (the coefficients of
    :func:`femoat.dense_peaks.quintic_accel_abs_max`)."""
    c1 = h * dx0
    c2 = 0.5 * h * h * ddx0
    r0 = x1 - x0 - c1 - c2
    r1 = h * dx1 - c1 - 2.0 * c2
    r2 = h * h * ddx1 - 2.0 * c2
    c3 = 10.0 * r0 - 4.0 * r1 + 0.5 * r2
    c4 = -15.0 * r0 + 7.0 * r1 - r2
    c5 = 6.0 * r0 - 3.0 * r1 + 0.5 * r2
    return x0 + th * (c1 + th * (c2 + th * (c3 + th * (c4 + th * c5))))


@njit(cache=True)
def crossing(d0, dd0, d1, dd1, h):
    """Fraction θ in [0, 1] where the cubic Hermite interpolant of δ crosses zero.

    Safeguarded Newton on the bracket [0, 1] (the endpoints have opposite signs); without a sign
    change the crossing is taken at the start of the step (θ = 0).
    """
    if d0 == 0.0 or d0 * d1 > 0.0:
        return 0.0
    lo, hi = 0.0, 1.0
    th = d0 / (d0 - d1)
    for _ in range(100):
        p, dp = hermite(th, h, d0, dd0, d1, dd1)
        if p == 0.0:
            return th
        if (p > 0.0) == (d0 > 0.0):
            lo = th
        else:
            hi = th
        th_new = th - p / dp if dp != 0.0 else 0.5 * (lo + hi)
        if not (lo < th_new < hi):
            th_new = 0.5 * (lo + hi)
        if hi - lo < 1e-15 or abs(th_new - th) < 1e-16:
            return th_new
        th = th_new
    return th

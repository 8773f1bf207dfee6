"""Helpers the bearing kinds' rate forms share (:data:`femoat.bearings.registry.RATE_KERNELS`): a
rate and its Jacobian from a kind's tuple into the loop's arrays, and the loading measure of a
bearing whose friction state is one direction z."""

from femoat.compilation.jit import njit


@njit(cache=True, inline="always")
def write_rate(r, g, J):
    """(g_x, g_y, ∂g_x/∂z_x, ∂g_x/∂z_y, ∂g_y/∂z_x, ∂g_y/∂z_y) ``r`` into ``g`` (2,) and ``J``
    (at least 2 × 2)."""
    g[0] = r[0]
    g[1] = r[1]
    J[0, 0] = r[2]
    J[0, 1] = r[3]
    J[1, 0] = r[4]
    J[1, 1] = r[5]


@njit(cache=True, inline="always")
def turn_along(z, g, vx, vy, ax, ay):
    """(r, ṙ): r = z·v, whose crossing of zero downwards unloads a bearing whose friction state
    is the direction z, and ṙ = g·v + z·a, g = ż (the rate at v), at the acceleration (ax, ay)."""
    return (z[0] * vx + z[1] * vy), (z[0] * ax + z[1] * ay) + (g[0] * vx + g[1] * vy)

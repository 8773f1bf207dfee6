"""Limit states as data: a limit is a row (quantity, index, bound, runaway, criterion), checked
by one small compiled dispatcher after every accepted step.

A :class:`Limit` names a response quantity of the run (:data:`QUANTITIES`), which one (an
element, a contact or a DOF: ``index``) and a bound on it. The solver records the first time
each row is exceeded (at a step end); a *runaway* row always ends the run there (the response
means nothing beyond it), a criterion row ends it only when the run stops at its first
criterion. ``criterion`` names the criterion a row belongs to; the solver does not read it
(:mod:`femoat.collapse` groups the rows' times by it).

A new criterion on one of these quantities is Python only: rows from
:class:`Limit`. A new quantity is its entry in :data:`QUANTITIES` and its branch in
:func:`limit_quantity`.

Units: kip, in, s.
"""

import math
from dataclasses import dataclass

import numpy as np

from femoat.compilation.jit import njit

# quantity codes (the compiled dispatcher branches on them)
ELEMENT_DEFORMATION, WALL_DISPLACEMENT, CONTACT_FORCE, DISPLACEMENT, VELOCITY, \
    ABSOLUTE_ACCELERATION, PLAN_DISPLACEMENT = range(7)

QUANTITIES = {
    "element_deformation": (ELEMENT_DEFORMATION, "in", "element"),
    "wall_displacement": (WALL_DISPLACEMENT, "in", "contact"),
    "contact_force": (CONTACT_FORCE, "kip", "contact"),
    "displacement": (DISPLACEMENT, "in", "dof"),
    "velocity": (VELOCITY, "in/s", "dof"),
    "absolute_acceleration": (ABSOLUTE_ACCELERATION, "in/s^2", "building dof"),
    "plan_displacement": (PLAN_DISPLACEMENT, "in", "bearing"),
}
"""name: (code, unit of the bound, what ``index`` counts). The quantities, each at the end of
an accepted step: an element's |deformation| (a story's drift, the isolator's displacement); a
wall's |displacement| at the impact point; a contact's force (compression positive); a DOF's
|relative displacement| and |relative velocity| (``PoundingModel.dof_names()``: base, floors,
wall modes); a building DOF's |absolute acceleration| (base mat, floors, along the DOF's
axis); a plan bearing's plan displacement √(u_x² + u_y²) (:mod:`femoat.plan`)."""

# columns of the packed limits array (one row per limit; all float64 for the compiled loop)
L_QUANTITY, L_INDEX, L_BOUND, L_RUNAWAY = range(4)
N_COLUMNS = 4

# what check_limits returns
NONE_EXCEEDED, CRITERION_EXCEEDED, RUNAWAY_EXCEEDED = 0, 1, 2


@dataclass(frozen=True)
class Limit:
    """One limit state: ``quantity`` number ``index`` above ``bound``.

    Parameters
    ----------
    quantity : str
        One of :data:`QUANTITIES`.
    index : int
        Which one, >= 0: the element, contact or DOF (see :data:`QUANTITIES`).
    bound : float
        Positive bound, in the quantity's unit ([in], [kip], [in/s] or [in/s²]).
    runaway : bool
        A runaway bound (the run always ends there) rather than a criterion.
    criterion : str
        Name of the criterion (or runaway bound) the row belongs to.
    """

    quantity: str
    index: int
    bound: float
    runaway: bool = False
    criterion: str = ""

    def __post_init__(self):
        if self.quantity not in QUANTITIES:
            raise ValueError(f"quantity = {self.quantity!r}: choose one of "
                             f"{sorted(QUANTITIES)}.")
        if not (isinstance(self.index, (int, np.integer)) and not isinstance(self.index, bool)
                and self.index >= 0):
            raise ValueError(f"index = {self.index!r}: the {QUANTITIES[self.quantity][2]} "
                             "number must be a whole number >= 0.")
        unit = QUANTITIES[self.quantity][1]
        if not (isinstance(self.bound, (int, float)) and not isinstance(self.bound, bool)
                and math.isfinite(self.bound) and self.bound > 0):
            raise ValueError(f"bound = {self.bound!r}: must be a finite positive {self.quantity} "
                             f"[{unit}] (leave the row out for no limit).")
        if not isinstance(self.runaway, bool):
            raise ValueError(f"runaway = {self.runaway!r} must be true or false.")
        if not isinstance(self.criterion, str):
            raise ValueError(f"criterion = {self.criterion!r} must be a name (str).")


def pack_limits(limits, packed):
    """The (m, N_COLUMNS) float64 array of ``limits`` (a sequence of :class:`Limit`) for the
    compiled loop, each index checked against ``packed``."""
    counts = {"element": packed.el_code.size, "contact": packed.c_code.size,
              "dof": packed.n, "building dof": packed.n_struct,
              "bearing": packed.bearing_dofs.shape[0]}
    out = np.zeros((len(limits), N_COLUMNS))
    for r, lim in enumerate(limits):
        if not isinstance(lim, Limit):
            raise ValueError(f"limits[{r}] = {lim!r}: expected a femoat.integration.limits.Limit.")
        code, _, what = QUANTITIES[lim.quantity]
        if lim.index >= counts[what]:
            raise ValueError(f"limits[{r}] ({lim.criterion or lim.quantity}): {lim.quantity} "
                             f"index {lim.index}, but the model has {counts[what]} {what}s.")
        out[r, L_QUANTITY], out[r, L_INDEX], out[r, L_BOUND] = code, lim.index, lim.bound
        out[r, L_RUNAWAY] = 1.0 if lim.runaway else 0.0
    return out


@njit(cache=True, inline="always")
def limit_quantity(code, k, n_struct, model, state):
    """The value of quantity ``code`` number ``k`` at the committed state (see QUANTITIES)."""
    if code == ELEMENT_DEFORMATION:
        return abs(state.el_d[k])
    if code == WALL_DISPLACEMENT:
        w = 0.0
        for i in range(n_struct, state.u.size):
            w -= model.c_B[k, i] * state.u[i]
        return abs(w)
    if code == CONTACT_FORCE:
        return state.c_f[k]
    if code == DISPLACEMENT:
        return abs(state.u[k])
    if code == VELOCITY:
        return abs(state.v[k])
    if code == PLAN_DISPLACEMENT:
        ix, iy = model.b_dofs[k, 0], model.b_dofs[k, 1]
        return np.sqrt(state.u[ix] * state.u[ix] + state.u[iy] * state.u[iy])
    return abs(state.a[k] + state.ag_now[model.dof_axis[k]])  # ABSOLUTE_ACCELERATION


@njit(cache=True, python=False)
def check_limits(t, n_struct, model, state, limits, first):
    """Record in ``first`` the time ``t`` at which each row of ``limits`` is first exceeded
    (−1: not yet); return RUNAWAY_EXCEEDED when a runaway row is exceeded now, else
    CRITERION_EXCEEDED when a criterion row is, else NONE_EXCEEDED."""
    hit = NONE_EXCEEDED
    for r in range(limits.shape[0]):
        x = limit_quantity(int(limits[r, L_QUANTITY]), int(limits[r, L_INDEX]), n_struct,
                           model, state)
        if x > limits[r, L_BOUND]:
            if first[r] < 0.0:
                first[r] = t
            if limits[r, L_RUNAWAY] != 0.0:
                hit = RUNAWAY_EXCEEDED
            elif hit == NONE_EXCEEDED:
                hit = CRITERION_EXCEEDED
    return hit

"""The result of a plan run: histories, the impact table per wall, the peaks per direction and
in plan, save and load.

:class:`PlanRunResult` is driven by plain arrays (:meth:`PlanRunResult.from_arrays`), so that
femoat's plan solver and the OpenSees twin in 3D (:meth:`PlanRunResult.from_opensees`) give the
same object and the same peaks, read the same way. Conventions (docs/plan.md §2, §8): plan axes
x, y; the DOF layout of :meth:`femoat.plan.PlanModel.layout`; walls in the order +x, −x, +y,
−y. In the peak summary's keys a wall is named ``px``, ``mx``, ``py``, ``my`` (:data:`SIDE_KEYS`:
"+x" → "px", "−x" → "mx", ...), names that are safe as column and variable names.

Peaks of the continuous solution (as :mod:`femoat.results` in 1D): displacements, drifts and
wall displacements inside each recorded interval from the cubic Hermite interpolant of the
displacements and velocities (:mod:`femoat.dense_peaks`); the base mat's plan displacement
|u| = |(u_x, u_y)| from the same interpolant in both directions at once
(:func:`hermite_norm_max`), not the larger of the two directions' peaks (those are reached at
different times). Accelerations at the samples, and inside the fifth-order steps of a ``dp5``
run from the quintic interpolant. A run that kept no history (``run(..., history=False)``, what
a suite does) has arrays of no rows: its peaks are the solver's running peaks
(:mod:`femoat.integration.recording.peaks`: the same interpolants evaluated inside the loop, the
plan crest by Newton from 16 points of each interval rather than the roots of its degree-5
polynomial), and its history accessors raise. The plan figures and the top-view render read a
result through :meth:`femoat.plotting.plan_history.PlanHistory.from_result` (figures are a
higher layer than results: tests/test_imports.py). Files: ``.npz`` with a JSON ``meta``, as
:class:`femoat.results.RunResult` (a run without history too: its arrays have no rows).
"""

from dataclasses import dataclass, field

import numpy as np

from femoat.contact._dispatch import acts_at_zero
from femoat.integration.recording import peaks as running_layout
from femoat.plan.building import AXES
from femoat.plan.moat import SIDES, wall_side
from femoat.results.base import Result, impact_table
from femoat.units import G

SIDE_KEYS = {"+x": "px", "-x": "mx", "+y": "py", "-y": "my"}
"""The name of each wall in the peak summary's keys (``peak_impact_force_px``, ...)."""

ARRAY_UNITS = {
    "time": "s",
    "displacement": "in (relative to ground, per DOF)",
    "velocity": "in/s (relative, per DOF)",
    "acceleration": "in/s^2 (relative, per DOF)",
    "ground_acceleration": "in/s^2 (x, y)",
    "element_force": "kip (per uniaxial element)",
    "element_deformation": "in (per uniaxial element)",
    "bearing_force": "kip (x, y; the bidirectional bearing's)",
    "contact_force": "kip (per wall; compression positive)",
    "indentation": "in (per wall; negative = open gap)",
    "indentation_rate": "in/s (per wall; positive = approaching)",
    "contact_closed": "1 while a contact episode is open (per wall)",
}
"""The arrays of a plan run, one row per recorded sample, and their units: the one list that
:meth:`PlanRunResult.from_arrays`, :meth:`~PlanRunResult.save` and the file's ``meta`` read."""

_OPTIONAL = ("velocity", "acceleration", "element_force", "element_deformation", "bearing_force")
"""Arrays that may have 0 columns: the channel was not recorded (or, for ``bearing_force``, the
isolator is not a friction pendulum)."""

IMPACT_FIELDS = ("side", "start", "duration", "approach_velocity", "peak_force",
                 "max_indentation", "impulse")
"""The columns of the impact table (as :attr:`femoat.results.RunResult.impacts`)."""


def hermite_norm_max(t, u, v):
    """max |u(t)| of the piecewise cubic Hermite interpolant through (t, u, u̇ = v), u a vector.

    t [s] (m samples); u (m, d) and v (m, d), v in u's unit per second. Returns a float (the
    largest Euclidean norm). Intervals of zero length are skipped.

    In an interval of length h, θ = (t − t₀)/h ∈ [0, 1], each component is the cubic
    u(θ) = c₀ + c₁θ + c₂θ² + c₃θ³ with c₀ = u₀, c₁ = h·v₀, c₂ = 3(u₁ − u₀) − 2h·v₀ − h·v₁,
    c₃ = 2(u₀ − u₁) + h·v₀ + h·v₁; |u|² is of degree 6 and its crests are roots of
    ½·d|u|²/dθ = Σ u·u′ (degree 5). Every root's real part clipped to [0, 1] is a point of the
    interpolant, so evaluating there never overestimates the crest. Only intervals whose bound
    |u(θ)| ≤ max(|u₀|, |u₁|) + 4/27·(h|v₀| + h|v₁|) (the Hermite basis: h₀₀ + h₀₁ = 1, both in
    [0, 1], so the first part is a convex combination; |h₁₀|, |h₁₁| ≤ 4/27) passes the largest
    value found so far are searched, largest bound first.
    """
    t = np.asarray(t, dtype=float)
    u, v = np.asarray(u, dtype=float), np.asarray(v, dtype=float)
    if u.shape[0] == 0:
        return 0.0
    norm = np.sqrt(np.sum(u * u, axis=1))
    peak = float(norm.max())
    if u.shape[0] < 2:
        return peak
    h = np.diff(t)
    speed = np.sqrt(np.sum(v * v, axis=1))
    bound = np.maximum(norm[:-1], norm[1:]) + (4.0 / 27.0) * h * (speed[:-1] + speed[1:])
    for i in np.argsort(-bound):
        if bound[i] <= peak:
            break
        if h[i] <= 0.0:
            continue
        u0, u1, hv0, hv1 = u[i], u[i + 1], h[i] * v[i], h[i] * v[i + 1]
        c = np.array([u0, hv0, 3.0 * (u1 - u0) - 2.0 * hv0 - hv1,
                      2.0 * (u0 - u1) + hv0 + hv1])  # (4, d), ascending powers
        dc = c[1:] * np.array([1.0, 2.0, 3.0])[:, None]  # u′(θ), (3, d)
        crest = sum(np.convolve(c[:, k], dc[:, k]) for k in range(u.shape[1]))  # degree 5
        roots = np.roots(crest[::-1]) if np.any(crest) else np.zeros(0)
        theta = np.clip(roots.real, 0.0, 1.0)
        if theta.size:
            powers = theta[:, None] ** np.arange(4)[None, :]  # (roots, 4)
            values = np.sqrt(np.sum((powers @ c) ** 2, axis=1))
            peak = max(peak, float(values.max()))
    return peak


def _axis(axis):
    if axis not in AXES:
        raise ValueError(f"axis = {axis!r}: use 'x' or 'y' (the building's plan axes).")
    return AXES.index(axis)


@dataclass
class PlanRunResult(Result):
    """A plan run (units in brackets on each accessor; arrays as :data:`ARRAY_UNITS`; the
    per-axis accessors of :class:`~femoat.results.base.Result` take the axis, "x" or "y")."""

    AXES = AXES
    ARRAY_NAMES = tuple(ARRAY_UNITS)
    FILE_KIND = "femoat plan result file"

    time: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    ground_acceleration: np.ndarray
    element_force: np.ndarray
    element_deformation: np.ndarray
    bearing_force: np.ndarray
    contact_force: np.ndarray
    indentation: np.ndarray
    indentation_rate: np.ndarray
    contact_closed: np.ndarray
    meta: dict = field(default_factory=dict)

    # ---- construction -------------------------------------------------------------------
    @classmethod
    def from_arrays(cls, arrays, packed, meta, running_peaks=None):
        """Assemble from a plan solver's recorded arrays.

        Parameters
        ----------
        arrays : dict of array
            One row per recorded sample (m rows), every name of :data:`ARRAY_UNITS`: ``time``
            (m,) [s]; ``displacement``, ``velocity``, ``acceleration`` (m, n) relative to the
            ground; ``ground_acceleration`` (m, 2) (x, y); ``element_force``,
            ``element_deformation`` (m, elements); ``bearing_force`` (m, 2); ``contact_force``,
            ``indentation``, ``indentation_rate``, ``contact_closed`` (m, walls). Velocity,
            acceleration, element and bearing arrays may have 0 columns (not recorded; no
            friction pendulum).
        packed : PackedPlanModel
            :meth:`femoat.plan.PlanModel.pack` of the model that ran.
        meta : dict
            At least ``impacts`` (rows with the keys :data:`IMPACT_FIELDS`, ``side`` a wall of
            the model), ``stats`` (with ``steps`` and ``cpu_seconds``), ``energy`` (with
            ``residual``, or None when the run kept no balance) and ``info``; other keys
            (``collapse``, ``runaway``, ...) are kept as given.
        running_peaks : array or None
            The solver's running peaks (``History.peaks``, the layout of
            :mod:`femoat.integration.recording.peaks`) of a run that kept no history: the peaks
            are read from them, and the arrays have no rows (m = 0). None: the peaks are read
            from the arrays, which then hold at least one sample.
        """
        lay = packed.layout
        names = [wall_side(s) for s in packed.c_names]
        arrays = _checked_arrays(arrays, lay.n, len(packed.el_roles), len(names),
                                 history=running_peaks is None)
        if running_peaks is not None:
            running_peaks = _checked_running(running_peaks, lay.n_struct, len(names))
        meta = _checked_meta(meta, names)
        walls = []
        for c, cols in enumerate(lay.wall_dofs):
            walls.append(dict(cols=list(cols), phi=[float(-packed.c_B[c, i]) for i in cols],
                              k=[float(packed.K[i, i]) for i in cols],
                              c=[float(packed.C[i, i]) for i in cols],
                              closes_smoothly=not acts_at_zero(int(packed.c_code[c]))))
        meta = dict(
            meta,
            dof_names=list(lay.names),
            floor_dofs=lay.floor_dofs[:, :2].tolist(),
            element_names=[r.name for r in packed.el_roles],
            element_axes=[AXES[int(a)] for a in packed.el_axis],
            contact_names=names,
            gaps=[float(g) for g in packed.c_gap],
            story_heights=[float(h) for h in packed.story_heights],
            walls=walls,
            units=ARRAY_UNITS,
        )
        r = cls(**arrays, meta=meta)
        r.meta["peaks"] = r._peaks(running_peaks)
        return r

    @classmethod
    def from_opensees(cls, result, model, pair, v0=None):
        """The result of an OpenSees twin run: ``result`` from
        :func:`femoat.opensees.plan.opensees_plan_run` of ``model`` under ``pair`` (the
        PlanModel and RecordPair it ran, for the layout and the ground motion; ``v0`` the
        initial velocities given to it [in/s], default zero).

        The twin records displacements, absolute accelerations of the building and contact
        forces. The velocities are its Newmark step's (γ = 1/2, β = 1/4):
        u₁ − u₀ = h·(v₀ + v₁)/2, so v₁ = 2(u₁ − u₀)/h − v₀ from v₀, exact to rounding; the
        walls' accelerations likewise from a₁ = 2(v₁ − v₀)/h − a₀ (a₀ the initial equilibrium's,
        as the twin sets it). Not recorded: element and bearing forces (0 columns). The impact
        table is read from the history (contact while the indentation is > 0, as the twin
        counts); the energy residual is None (no balance).
        """
        packed = model.pack()
        lay, sides = packed.layout, [w.side for w in model.walls]
        if list(result["walls"]) != sides:
            raise ValueError(f"the run's walls {tuple(result['walls'])} are not the model's "
                             f"{tuple(sides)}: give the PlanModel the run was made with.")
        t = np.asarray(result["time"], dtype=float)
        m, n, dt = t.size, packed.n, float(result["dt"])
        ag = G * np.array([np.interp(t, pair.time, row, right=0.0)
                           for row in np.asarray(pair.accel_g)]).T
        u = np.zeros((m, n))
        floors = np.concatenate([np.asarray(result["base_displacement"])[:, None, :],
                                 np.asarray(result["floor_displacement"])], axis=1)
        u[:, lay.floor_dofs[:, :2].reshape(-1)] = floors.reshape(m, -1)
        for c, cols in enumerate(lay.wall_dofs):  # an SDOF wall: one mode, q = w/φ
            u[:, cols[0]] = result["wall_displacement"][:, c] / -packed.c_B[c, cols[0]]
        v = _newmark_rate(u, np.zeros(n) if v0 is None else np.asarray(v0, dtype=float), dt)
        a = _newmark_rate(v, np.linalg.solve(packed.M, -packed.R @ ag[0] - packed.C @ v[0]), dt)
        struct = lay.floor_dofs[:, :2]
        relative = np.asarray(result["acceleration"]) - ag[:, None, :]
        a[:, struct.reshape(-1)] = relative.reshape(m, -1)
        el_top = np.where(packed.el_i >= 0, u[:, packed.el_i], 0.0)
        el_bottom = np.where(packed.el_j >= 0, u[:, np.maximum(packed.el_j, 0)], 0.0)
        indentation = np.asarray(result["indentation"], dtype=float)
        closed = (indentation > 0.0).astype(np.int8)
        force = np.asarray(result["contact_force"], dtype=float)
        rate = v @ packed.c_B.T
        empty = np.zeros((m, 0))
        arrays = dict(time=t, displacement=u, velocity=v, acceleration=a, ground_acceleration=ag,
                      element_force=empty, element_deformation=el_top - el_bottom,
                      bearing_force=empty, contact_force=force, indentation=indentation,
                      indentation_rate=rate, contact_closed=closed)
        meta = dict(impacts=impact_table(t, closed, force, indentation, rate, sides),
                    stats=dict(steps=int(result["steps"]),
                               cpu_seconds=float(result["cpu_seconds"])),
                    energy=dict(residual=None),
                    info=dict(solver="opensees", method="newmark", dt=dt))
        return cls.from_arrays(arrays, packed, meta)

    # ---- the layout (femoat.results.base) -------------------------------------------------
    def _array(self, name):
        return getattr(self, name)

    @classmethod
    def _from_file(cls, arrays, meta):
        return cls(**arrays, meta=meta)

    def _cols(self, axis):
        return [row[_axis(axis)] for row in self.meta["floor_dofs"]]

    def _ground(self, axis):
        return self.ground_acceleration[:, _axis(axis)]

    def _side(self, side):
        side = wall_side(side)
        if side not in self.sides:
            raise ValueError(f"side = {side!r}: the moat has no wall there (its walls: "
                             f"{', '.join(self.sides) or 'none'}).")
        return side

    # ---- derived channels ----------------------------------------------------------------
    @property
    def sides(self):
        """The walls of the moat ("+x", ...), in the order of every per-wall column."""
        return list(self.meta["contact_names"])

    @property
    def base_displacement(self):
        """The base mat's displacement (x, y) relative to the ground [in], shape (m, 2)."""
        self._require("displacement")
        return self.displacement[:, self.meta["floor_dofs"][0]]

    @property
    def base_velocity(self):
        """The base mat's velocity (x, y) relative to the ground [in/s], shape (m, 2)."""
        self._require("velocity")
        return self.velocity[:, self.meta["floor_dofs"][0]]

    @property
    def plan_base_displacement(self):
        """The base mat's plan displacement |u| = √(u_x² + u_y²) [in], shape (m,)."""
        return np.hypot(*self.base_displacement.T)

    # ---- peaks ---------------------------------------------------------------------------
    def _continuous(self, running=None):
        """The peaks of the continuous solution: {"plan": the base mat's |u| [in], "base": its
        |u_x|, |u_y| [in], "drift": {axis: per story [in]}, "acceleration": {axis: absolute,
        base mat then floors [in/s²], or None when not recorded}, "wall": per wall [in]}. From
        the solver's running peaks ``running`` when given, else from the recorded arrays."""
        floors = self.meta["floor_dofs"]
        if running is not None:  # the layout of femoat.integration.recording.peaks
            ns, nc = 2 * len(floors), len(self.sides)
            pk = [float(x) for x in running]
            return dict(
                plan=pk[2 * ns + nc + 2],
                base=[pk[i] for i in floors[0]],
                drift={axis: [pk[row[a]] for row in floors[1:]] for a, axis in enumerate(AXES)},
                acceleration={axis: [pk[ns + nc + row[a]] for row in floors]
                              for a, axis in enumerate(AXES)},
                wall=pk[ns:ns + nc])
        has_v = self.velocity.shape[1] > 0
        base = self.base_displacement
        base_v = self.base_velocity if has_v else None
        drift = {}
        for axis in AXES:
            drift_v = np.diff(self.velocity[:, self._cols(axis)], axis=1) if has_v else None
            drift[axis] = self._hermite_peaks(self.story_drifts(axis), drift_v)
        return dict(
            plan=(hermite_norm_max(self.time, base, base_v) if has_v
                  else float(self.plan_base_displacement.max(initial=0.0))),
            base=[self._hermite_peaks(base[:, a:a + 1],
                                      None if base_v is None else base_v[:, a:a + 1])[0]
                  for a in range(len(AXES))],
            drift=drift,
            acceleration={axis: (self._acceleration_peaks(axis) if self.acceleration.shape[1]
                                 else None) for axis in AXES},
            wall=self._hermite_peaks(self.wall_displacement(),
                                     self.wall_velocity() if has_v else None))

    def _peaks(self, running=None):
        """The peak summary (:attr:`peaks`), from the running peaks ``running`` when given
        (:meth:`_continuous`)."""
        peak = self._continuous(running)
        out = {"peak_plan_base_displacement": peak["plan"]}
        for a, axis in enumerate(AXES):
            out[f"peak_base_displacement_{axis}"] = peak["base"][a]
        heights = self.meta["story_heights"]
        for axis in AXES:
            drift = peak["drift"][axis]
            out[f"peak_drift_{axis}"] = drift
            out[f"peak_drift_ratio_{axis}"] = [d / h for d, h in zip(drift, heights)]
        for axis in AXES:
            acc = peak["acceleration"][axis]
            out[f"peak_base_acceleration_{axis}"] = None if acc is None else acc[0] / G
            out[f"peak_floor_acceleration_{axis}"] = (None if acc is None
                                                      else [x / G for x in acc[1:]])
        imp = self.meta["impacts"]
        for side in SIDES:  # the same keys for every moat: None where there is no wall
            key = SIDE_KEYS[side]
            here = side in self.sides
            rows = [r for r in imp if r["side"] == side]
            out[f"peak_impact_force_{key}"] = (max((r["peak_force"] for r in rows), default=0.0)
                                               if here else None)
            out[f"impacts_{key}"] = len(rows) if here else None
            out[f"peak_wall_displacement_{key}"] = (peak["wall"][self.sides.index(side)] if here
                                                    else None)
        out.update(
            peak_impact_force=max((r["peak_force"] for r in imp), default=0.0),
            peak_impulse=max((r["impulse"] for r in imp), default=0.0),
            energy_residual=self.meta["energy"]["residual"],
            steps=self.meta["stats"]["steps"],
            cpu_seconds=self.meta["stats"]["cpu_seconds"],
        )
        return out

    @property
    def peaks(self):
        """Peak summary (JSON-ready; docs/plan.md §8): ``peak_plan_base_displacement`` [in]
        (the largest |u| of the base mat), ``peak_base_displacement_x``/``_y`` [in],
        ``peak_drift_x``/``_y`` [in] and ``peak_drift_ratio_x``/``_y`` [-] (lists per story),
        ``peak_base_acceleration_x``/``_y`` and ``peak_floor_acceleration_x``/``_y`` [g]
        (absolute; None when accelerations were not recorded), per wall (:data:`SIDE_KEYS`)
        ``peak_impact_force_{key}`` [kip], ``impacts_{key}`` and
        ``peak_wall_displacement_{key}`` [in] (None where the moat has no wall),
        ``peak_impact_force`` [kip], ``peak_impulse`` [kip·s], ``energy_residual`` [-],
        ``steps``, ``cpu_seconds`` [s]."""
        return self.meta["peaks"]


def _newmark_rate(x, rate0, h):
    """The rates ẋ of the samples x (m, k) of a Newmark average-acceleration run at the step h
    from ẋ₀ = ``rate0``: x₁ − x₀ = h(ẋ₀ + ẋ₁)/2, so ẋ_{j+1} = 2(x_{j+1} − x_j)/h − ẋ_j. With
    w_j = (−1)^j·ẋ_j the recursion is w_{j+1} = w_j + (−1)^{j+1}·2(x_{j+1} − x_j)/h, a
    cumulative sum."""
    sign = np.where(np.arange(1, x.shape[0]) % 2 == 1, -1.0, 1.0)[:, None]
    w = np.cumsum(np.vstack([rate0[None, :], sign * 2.0 * np.diff(x, axis=0) / h]), axis=0)
    return w * np.where(np.arange(x.shape[0]) % 2 == 1, -1.0, 1.0)[:, None]


def _checked_arrays(arrays, n, n_elements, n_walls, history=True):
    """The arrays as float (``contact_closed`` int8) numpy arrays of the expected shapes, or a
    ValueError naming the array; ``history``: at least one sample, else none (a run that kept
    no history)."""
    if not isinstance(arrays, dict):
        raise ValueError("arrays must be a dict of numpy arrays named as "
                         "femoat.results.plan.ARRAY_UNITS.")
    missing = [k for k in ARRAY_UNITS if k not in arrays]
    if missing:
        raise ValueError(f"arrays is missing {', '.join(repr(k) for k in missing)}: give every "
                         "array of femoat.results.plan.ARRAY_UNITS (an unrecorded channel as "
                         "an (m, 0) array).")
    width = dict(displacement=n, velocity=n, acceleration=n, ground_acceleration=2,
                 element_force=n_elements, element_deformation=n_elements, bearing_force=2,
                 contact_force=n_walls, indentation=n_walls, indentation_rate=n_walls,
                 contact_closed=n_walls)
    try:
        t = np.asarray(arrays["time"], dtype=float)
    except (TypeError, ValueError):
        raise ValueError("arrays['time'] must be an array of numbers [s].") from None
    if t.ndim != 1 or np.any(np.diff(t) < 0) or not np.all(np.isfinite(t)):
        raise ValueError(f"arrays['time'] must be a 1-D array of finite, non-decreasing times "
                         f"[s] (got shape {t.shape}).")
    if history and t.size == 0:
        raise ValueError("arrays['time'] is empty: a plan result needs at least one sample "
                         "(or, for a run that kept no history, its running_peaks).")
    if not history and t.size:
        raise ValueError(f"arrays['time'] has {t.size} samples: with running_peaks (a run that "
                         "kept no history) the arrays have no rows; give running_peaks=None "
                         "to read the peaks from the samples.")
    out, m = {"time": t}, t.size
    for name, cols in width.items():
        dtype = np.int8 if name == "contact_closed" else float
        try:
            a = np.asarray(arrays[name], dtype=dtype)
        except (TypeError, ValueError):
            raise ValueError(f"arrays[{name!r}] must be an array of numbers.") from None
        allowed = f"({m}, {cols})" + (f" or ({m}, 0) (not recorded)" if name in _OPTIONAL
                                      else "")
        if a.ndim != 2 or a.shape[0] != m or not (
                a.shape[1] == cols or (name in _OPTIONAL and a.shape[1] == 0)):
            raise ValueError(f"arrays[{name!r}] has shape {a.shape}; it must be {allowed}: "
                             "one row per sample of arrays['time'].")
        if not np.all(np.isfinite(a)):
            raise ValueError(f"arrays[{name!r}] holds values that are not finite (NaN or inf).")
        out[name] = a
    return out


def _checked_running(running, ns, nc):
    """The running peaks as a float array of the layout's length for ns building DOFs and nc
    walls, or a ValueError naming ``running_peaks``."""
    want = running_layout.size(ns, nc)
    try:
        pk = np.asarray(running, dtype=float)
    except (TypeError, ValueError):
        raise ValueError("running_peaks must be an array of numbers (History.peaks).") from None
    if pk.shape != (want,) or not np.all(np.isfinite(pk)):
        raise ValueError(f"running_peaks has shape {pk.shape}; it must be ({want},) finite "
                         "values, the layout of femoat.integration.recording.peaks for this "
                         "model (the History.peaks of its run).")
    return pk


def _checked_meta(meta, sides):
    """``meta`` with its impact table as JSON-ready rows, or a ValueError naming the key."""
    if not isinstance(meta, dict):
        raise ValueError("meta must be a dict with impacts, stats, energy and info.")
    missing = [k for k in ("impacts", "stats", "energy", "info") if k not in meta]
    if missing:
        raise ValueError(f"meta is missing {', '.join(repr(k) for k in missing)}.")
    if not isinstance(meta["info"], dict):
        raise ValueError("meta['info'] must be a dict (the solver's settings, e.g. method).")
    for key, inner in (("stats", ("steps", "cpu_seconds")), ("energy", ("residual",))):
        if not isinstance(meta[key], dict) or any(k not in meta[key] for k in inner):
            raise ValueError(f"meta[{key!r}] must be a dict with {', '.join(inner)}.")
    rows = []
    for i, row in enumerate(meta["impacts"]):
        if not isinstance(row, dict) or any(k not in row for k in IMPACT_FIELDS):
            raise ValueError(f"meta['impacts'][{i}] must be a dict with the keys "
                             f"{', '.join(IMPACT_FIELDS)}.")
        side = wall_side(row["side"])
        if side not in sides:
            raise ValueError(f"meta['impacts'][{i}]: side {side!r} is not a wall of the model "
                             f"({', '.join(sides) or 'no walls'}).")
        rows.append(dict(side=side, **{k: float(row[k]) for k in IMPACT_FIELDS[1:]}))
    return dict(meta, impacts=rows)

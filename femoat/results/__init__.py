"""Results of a building run: histories, the impact table, the peak summary, save and load.

This package holds both results: :class:`RunResult` here (a run along one axis) and
:class:`~femoat.results.plan.PlanRunResult` (a run in plan), one layer above the solver whose
recording layer they read; what they share (impacts, peaks, energy, collapse, runaway, the
per-axis and wall histories, save and load) is :class:`femoat.results.base.Result`.

Files are NumPy ``.npz`` archives: every array is stored under a descriptive name, and a JSON
document (``meta``) holds the units of each array, the DOF/element/contact names, the impact
table, the peak summary, the energy balance and solver statistics. We chose it over NetCDF to keep
the core free of xarray/netCDF4 (heavy, and not needed elsewhere), while staying self-describing:
``numpy.load`` reads it anywhere and ``meta`` says what each array is.
"""

import numpy as np

from femoat.contact._dispatch import acts_at_zero
from femoat.dense_peaks import linear_accel_velocity_abs_max
from femoat.integration.recording.channels import CHANNELS, UNITS
from femoat.results.base import Result
from femoat.structure.pounding import wall_side
from femoat.structure.roles import STORY, role_of
from femoat.units import G

ARRAY_UNITS = UNITS
"""{history: unit} (:mod:`femoat.integration.recording.channels`), carried in every file."""


class RunResult(Result):
    """A building run along x: its histories, one attribute per channel of
    :mod:`femoat.integration.recording.channels` (``time`` [s], ``displacement`` [in], ...;
    one row per recorded sample, none when the run kept no history), and ``meta`` (names,
    impacts, peaks, energies, solver statistics). Units in brackets on each accessor; the
    per-axis accessors of :class:`~femoat.results.base.Result` take ``axis="x"`` or nothing."""

    AXES = ("x",)
    ARRAY_NAMES = tuple(c.name for c in CHANNELS)

    def __init__(self, arrays, meta=None):
        missing = [c.name for c in CHANNELS if c.name not in arrays]
        if missing:
            raise ValueError(f"RunResult: the histories {missing} are missing.")
        self.arrays = {c.name: arrays[c.name] for c in CHANNELS}
        self.meta = {} if meta is None else meta

    # ---- construction -------------------------------------------------------------------
    @classmethod
    def from_history(cls, hist, packed, info=None):
        """Assemble from the solver's raw history and the packed model it ran on."""
        ncon = packed.c_code.size
        wall_cols = []
        for c in range(ncon):
            cols = [i for i in range(packed.n_struct, packed.n) if packed.c_B[c, i] != 0.0]
            wall_cols.append(dict(cols=cols, phi=[-packed.c_B[c, i] for i in cols],
                                  k=[packed.K[i, i] for i in cols],
                                  c=[packed.C[i, i] for i in cols],
                                  closes_smoothly=not acts_at_zero(int(packed.c_code[c]))))
        story_c = [float(-packed.C[e_i, e_j]) if e_j >= 0 else 0.0
                   for e_i, e_j in zip(packed.el_i, packed.el_j)]
        meta = dict(
            dof_names=list(packed.dof_names),
            n_struct=int(packed.n_struct),
            element_names=list(packed.el_names),
            element_dashpots=story_c,
            contact_names=list(packed.c_names),
            gaps=[float(g) for g in packed.c_gap],
            story_heights=[float(h) for h in packed.story_heights],
            walls=wall_cols,
            stats=hist.stats,
            energy=hist.energy,
            units=ARRAY_UNITS,
            info=info or {},
        )
        r = cls(hist.arrays, meta)
        r.meta["impacts"] = impact_rows(hist.impacts, meta["contact_names"])
        r.meta["peaks"] = r._peaks(hist.peaks)
        return r

    # ---- the layout (femoat.results.base) -------------------------------------------------
    def _array(self, name):
        return self.arrays[name]

    @classmethod
    def _from_file(cls, arrays, meta):
        return cls(arrays, meta)

    def _cols(self, axis):
        return list(range(self.meta["n_struct"]))

    def _ground(self, axis):
        return self.ground_acceleration

    def _side(self, side):
        if side in ("pos", "+", "neg", "-"):
            return "pos" if side in ("pos", "+") else "neg"
        name = wall_side(side)  # ±1, "+x", "-x" (and names a bad side)
        if name not in ("+x", "-x"):
            raise ValueError(f"side = {side!r}: a 1D run's walls are 'pos' (+1, '+x') and 'neg' "
                             "(-1, '-x').")
        return "pos" if name == "+x" else "neg"

    # ---- derived channels ----------------------------------------------------------------
    @property
    def base_displacement(self):
        """Base-mat displacement relative to the ground [in]."""
        return self.displacement[:, 0]

    def story_shears(self):
        """Story shear: spring force plus parallel dashpot force [kip], one column per story."""
        self._require("velocity")
        self._require("element_force")
        names = self.meta["element_names"]
        cols = [i for i, nm in enumerate(names) if role_of(nm).kind == STORY]
        if not cols:
            return np.zeros((self.time.size, 0))
        drift_rate = np.diff(self.velocity[:, : self.meta["n_struct"]], axis=1)
        dash = np.array([self.meta["element_dashpots"][i] for i in cols])
        return self.element_force[:, cols] + drift_rate * dash[None, :]

    # ---- impacts and peaks ---------------------------------------------------------------
    def _continuous(self, kernel):
        """(base displacement, drifts, walls, absolute accelerations or None, base velocity or
        None, indentation): from the solver's running peaks (``kernel``, the layout of
        :mod:`femoat.integration.recording.peaks`) when given, else from the recorded history."""
        ns, nc = self.meta["n_struct"], len(self.meta["contact_names"])
        if kernel is not None:
            kernel = [float(x) for x in kernel]
            return (kernel[0], kernel[1:ns], kernel[ns:ns + nc], kernel[ns + nc:2 * ns + nc],
                    kernel[2 * ns + nc], kernel[2 * ns + nc + 1])
        wall = self.wall_displacement()
        has_v = self.velocity.shape[1] > 0
        vel = self.velocity[:, :ns] if has_v else None
        drift_v = np.diff(vel, axis=1) if has_v else None
        wall_v = self.wall_velocity() if has_v else None
        base = self._hermite_peaks(self.displacement[:, :1],
                                   None if vel is None else vel[:, :1])[0]
        velocity = (linear_accel_velocity_abs_max(self.time, vel[:, 0], self.acceleration[:, 0])
                    if has_v and self.acceleration.shape[1] else None)
        indentation = float(max(0.0, self.indentation.max())) if self.indentation.size else 0.0
        return (base, self._hermite_peaks(self.story_drifts(), drift_v),
                self._hermite_peaks(wall, wall_v),
                self._acceleration_peaks() if self.acceleration.shape[1] else None, velocity,
                indentation)

    def _peaks(self, kernel=None):
        """Peaks of the continuous solution: displacements and drifts inside each step from the
        Hermite interpolant; accelerations at the step ends, and inside the fifth-order steps
        from the quintic interpolant. ``kernel``: the solver's own running peaks
        (:mod:`femoat.integration.recording.peaks`, the same interpolants sample by sample),
        else they are read from the recorded history (:mod:`femoat.dense_peaks`)."""
        imp = self.meta["impacts"]
        base, peak_drift, peak_wall, peak_acc, velocity, indentation = self._continuous(kernel)
        if self.acceleration.shape[1] == 0:
            peak_acc = None
        if self.velocity.shape[1] == 0 or self.acceleration.shape[1] == 0:
            velocity = None
        hits = impact_summary(imp)
        out = {
            **{k: hits[k] for k in ("peak_impact_force", "peak_impact_force_pos",
                                    "peak_impact_force_neg", "impacts_pos", "impacts_neg")},
            "peak_base_displacement": base,
            "peak_base_velocity": velocity,
            "peak_wall_displacement": max(peak_wall, default=0.0),
            **{f"peak_wall_displacement_{name}": peak_wall[c]
               for c, name in enumerate(self.meta["contact_names"])},
            "peak_indentation": indentation,
            "peak_impulse": hits["peak_impulse"],
            "peak_drift": peak_drift,
            "peak_drift_ratio": [x / h for x, h in
                                 zip(peak_drift, self.meta.get("story_heights", []))],
            "peak_floor_acceleration": [float(x) / G for x in peak_acc[1:]]
            if peak_acc is not None else None,
            "peak_base_acceleration": float(peak_acc[0]) / G if peak_acc is not None else None,
            "energy_residual": self.meta["energy"]["residual"],
            "cpu_seconds": self.meta["stats"]["cpu_seconds"],
            "steps": self.meta["stats"]["steps"],
        }
        return out


def _channel(name, unit):
    def get(self):
        return self.arrays[name]
    get.__doc__ = f"The {name.replace('_', ' ')} history [{unit}]."
    return property(get)


for _c in CHANNELS:
    setattr(RunResult, _c.name, _channel(_c.name, _c.unit))
del _c


def impact_rows(table, contact_names):
    """The impact table (dicts, by start, ties in contact order) from the solver's episode rows
    (columns :data:`femoat.integration.recording.episodes.IMPACT_FIELDS`)."""
    rows = [dict(side=contact_names[int(c)], start=float(start), duration=float(duration),
                 approach_velocity=float(v), peak_force=float(f), max_indentation=float(d),
                 impulse=float(p))
            for c, start, duration, v, f, d, p in table.tolist()]
    order = sorted(range(len(rows)), key=lambda i: (rows[i]["start"], int(table[i, 0])))
    return [rows[i] for i in order]


def impact_summary(impacts):
    """The impact entries of the peak summary from an impact table (dicts with ``side``,
    ``peak_force`` [kip], ``impulse`` [kip·s]): the largest force overall and per side, the
    number of impacts per side, the largest impulse. Shared with the OpenSees twin."""
    return {
        "peak_impact_force": max((r["peak_force"] for r in impacts), default=0.0),
        "peak_impact_force_pos": max((r["peak_force"] for r in impacts if r["side"] == "pos"),
                                     default=0.0),
        "peak_impact_force_neg": max((r["peak_force"] for r in impacts if r["side"] == "neg"),
                                     default=0.0),
        "impacts_pos": sum(r["side"] == "pos" for r in impacts),
        "impacts_neg": sum(r["side"] == "neg" for r in impacts),
        "peak_impulse": max((r["impulse"] for r in impacts), default=0.0),
    }

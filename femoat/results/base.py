"""What every run's result holds, whatever its axes: the impact table, the peak summary, the
energy balance, the collapse and runaway records, the histories along an axis, the walls'
histories, and the file.

:class:`RunResult` (a run along x) and :class:`~femoat.results.plan.PlanRunResult` (a run in
plan, x and y) are this one result over their own array layouts: a subclass names its arrays
(``ARRAY_NAMES``), its plan axes (``AXES``), the state vector's columns of the base mat and
the floors along an axis (:meth:`~Result._cols`), the ground acceleration along an axis
(:meth:`~Result._ground`) and how it reads a wall's side (:meth:`~Result._side`). The
per-axis accessors take the axis ("x" or "y"); on a result of one axis it may be left out.

Units: kip, in, s; accelerations in the peak summary in g.
"""

import json

import numpy as np

from femoat.atomic import atomic_path
from femoat.dense_peaks import (
    hermite_abs_max,
    parabolic_peak,
    quintic_accel_abs_max,
    smooth_intervals,
)
from femoat.integration.methods import QUINTIC_METHODS


class Result:
    """The members every run's result shares (see the module docstring); units in brackets on
    each accessor."""

    AXES = ()
    """The plan axes the run moved along ("x", or "x" and "y")."""
    ARRAY_NAMES = ()
    """The recorded arrays, one row per sample, in the order of the file."""
    FILE_KIND = "femoat result file"
    """What :meth:`load` says a file is not."""

    # ---- what a subclass gives ----------------------------------------------------------
    def _array(self, name):
        """The recorded array ``name``."""
        raise NotImplementedError

    @classmethod
    def _from_file(cls, arrays, meta):
        """The result of the arrays and ``meta`` read back from a file."""
        raise NotImplementedError

    def _cols(self, axis):
        """The state vector's columns of the base mat and the floors along ``axis``."""
        raise NotImplementedError

    def _ground(self, axis):
        """The ground acceleration along ``axis`` [in/s²], one value per sample."""
        raise NotImplementedError

    def _side(self, side):
        """The contact name of the wall ``side`` (as the subclass spells sides)."""
        raise NotImplementedError

    # ---- shared -------------------------------------------------------------------------
    def _axis(self, axis):
        """``axis`` checked against :attr:`AXES`; None stands for the only axis of a run along
        one."""
        if axis is None and len(self.AXES) == 1:
            return self.AXES[0]
        if axis not in self.AXES:
            raise ValueError(f"axis = {axis!r}: use {' or '.join(map(repr, self.AXES))} (the "
                             "axes this run moved along).")
        return axis

    @property
    def n_floors(self):
        """Number of floors above the base mat."""
        return len(self._cols(self.AXES[0])) - 1

    def _require(self, name):
        if self.time.size == 0:
            raise ValueError("the run kept no history (history=False): its peaks and impacts "
                             "are in result.peaks and result.impacts; run with history=True "
                             "for its histories.")
        if getattr(self, name).shape[1] == 0:
            raise ValueError(f"the {name} channel was not recorded: run with it in channels.")

    def floor_displacement(self, axis=None):
        """Displacements of the base mat and the floors along ``axis`` relative to the ground
        [in], columns base, floor 1, ..."""
        self._require("displacement")
        return self.displacement[:, self._cols(self._axis(axis))]

    def story_drifts(self, axis=None):
        """Interstory drifts along ``axis``, u_k − u_{k−1} [in], one column per story (story 1
        over the base mat)."""
        return np.diff(self.floor_displacement(axis), axis=1)

    def absolute_acceleration(self, axis=None):
        """Absolute accelerations along ``axis`` of the base mat and the floors [in/s²]
        (columns base, floor 1, ...)."""
        self._require("acceleration")
        name = self._axis(axis)
        return self.acceleration[:, self._cols(name)] + self._ground(name)[:, None]

    def _wall_index(self, side):
        return self.meta["contact_names"].index(self._side(side))

    def _wall_columns(self, values, side):
        """Σ over a wall's modes of φ·values[:, mode] per wall, or one wall's column."""
        out = np.zeros((self.time.size, len(self.meta["walls"])))
        for c, w in enumerate(self.meta["walls"]):
            for col, phi in zip(w["cols"], w["phi"]):
                out[:, c] += phi * values[:, col]
        return out if side is None else out[:, self._wall_index(side)]

    def wall_displacement(self, side=None):
        """Wall displacement at the impact point, away from the building [in]: one column per
        wall, or the wall ``side``'s history."""
        self._require("displacement")
        return self._wall_columns(self.displacement, side)

    def wall_velocity(self, side=None):
        """Wall velocity at the impact point, away from the building [in/s] (as
        :meth:`wall_displacement`)."""
        self._require("velocity")
        return self._wall_columns(self.velocity, side)

    def wall_force(self, side=None):
        """Force in the wall's spring and dashpot [kip] (Σ over modes of (k·q + c·q̇)/φ,
        weighted by the impact-point shape): the 'vibrational spring' of the paper's Fig. 7;
        one column per wall, or the wall ``side``'s. The contact force is ``contact_force``."""
        self._require("velocity")
        out = np.zeros((self.time.size, len(self.meta["walls"])))
        for c, w in enumerate(self.meta["walls"]):
            for col, phi, k, cc in zip(w["cols"], w["phi"], w["k"], w["c"]):
                out[:, c] += (k * self.displacement[:, col] + cc * self.velocity[:, col]) / phi
        return out if side is None else out[:, self._wall_index(side)]

    # ---- impacts and peaks --------------------------------------------------------------
    def _impact_table(self):
        """The impact table read from the recorded history (:func:`impact_table`)."""
        return impact_table(self.time, self.contact_closed, self.contact_force,
                            self.indentation, self.indentation_rate,
                            self.meta["contact_names"])

    def _hermite_peaks(self, x, v):
        """max |x| per column over the run: inside the recorded intervals from the cubic
        Hermite interpolant when the velocities v are given, else at the samples."""
        if v is None:
            return [float(p) for p in np.abs(x).max(axis=0)] if x.size else [0.0] * x.shape[1]
        return hermite_abs_max(self.time, x, v)

    def _acceleration_peaks(self, axis=None):
        """Peak absolute accelerations along ``axis`` [in/s²] of the base mat and the floors:
        inside the smooth steps of a fifth-order run (``dp5``, ``ark5``; the intervals of
        :func:`~femoat.dense_peaks.smooth_intervals`) from the quintic interpolant of (u, v, a),
        else at the samples (a Newmark step's acceleration is linear)."""
        acc = self.absolute_acceleration(axis)
        if (self.meta.get("info", {}).get("method") not in QUINTIC_METHODS
                or self.velocity.shape[1] == 0):
            return [float(x) for x in np.abs(acc).max(axis=0)]
        name = self._axis(axis)
        cols = self._cols(name)
        smooth = smooth_intervals(self.contact_closed.reshape(self.time.size, -1),
                                  [w.get("closes_smoothly", False) for w in self.meta["walls"]])
        return quintic_accel_abs_max(self.time, self.displacement[:, cols],
                                     self.velocity[:, cols], self.acceleration[:, cols],
                                     self._ground(name), smooth)

    @property
    def impacts(self):
        """The impact table: one dict per contact episode (side, start [s], duration [s],
        approach_velocity [in/s], peak_force [kip], max_indentation [in], impulse [kip·s]), by
        start."""
        return self.meta["impacts"]

    @property
    def peaks(self):
        """The peak summary (JSON-ready; its keys: the subclass's ``peaks``)."""
        return self.meta["peaks"]

    @property
    def energy(self):
        """Energy balance [kip·in] and its relative residual, as the solver gave it."""
        return self.meta["energy"]

    @property
    def collapse(self):
        """Collapse criteria reached (:func:`femoat.collapse.collapse_summary`): the first
        time [s] of each (None: not reached), ``collapsed`` and ``stopped``; None when the run
        checked no criteria."""
        return self.meta.get("collapse")

    @property
    def runaway(self):
        """None, or the runaway bound that ended the run (:func:`femoat.collapse.runaway_summary`:
        ``time`` [s], ``element``, ``bound`` [in], ``reason``): the structure had collapsed and
        its response beyond the bound means nothing, so the run stopped there."""
        return self.meta.get("runaway")

    # ---- persistence --------------------------------------------------------------------
    def save(self, path):
        """Write to ``path`` (.npz), atomically: every array under its name, and ``meta``."""
        arrays = {name: self._array(name) for name in self.ARRAY_NAMES}
        with atomic_path(path) as tmp:
            with open(tmp, "wb") as fh:
                np.savez_compressed(fh, meta=np.array(json.dumps(self.meta)), **arrays)

    @classmethod
    def load(cls, path):
        """Read a file written by :meth:`save`."""
        try:
            with np.load(path, allow_pickle=False) as z:
                meta = json.loads(str(z["meta"]))
                arrays = {name: z[name] for name in cls.ARRAY_NAMES}
        except (OSError, KeyError, ValueError) as exc:
            raise ValueError(f"{path}: not a {cls.FILE_KIND} ({exc}).") from None
        return cls._from_file(arrays, meta)


def impact_table(time, closed, force, indentation, rate, contact_names):
    """The impact table (dicts by start: side, start [s], duration [s], approach_velocity
    [in/s], peak_force [kip], max_indentation [in], impulse [kip·s]) read from a recorded
    history: ``time`` (m,) [s] and per contact (columns) ``closed`` (1 while an episode is
    open), ``force`` [kip], ``indentation`` [in] and its ``rate`` [in/s]. The solver keeps the
    same table sample by sample (:mod:`femoat.integration.recording.episodes`): this is its
    reference; the OpenSees twins' tables are read with it too."""
    rows = []
    t = time
    closed = np.asarray(closed).reshape(t.size, -1)
    force = np.asarray(force).reshape(t.size, -1)
    indentation = np.asarray(indentation).reshape(t.size, -1)
    rate = np.asarray(rate).reshape(t.size, -1)
    for c, name in enumerate(contact_names):
        shut = closed[:, c].astype(bool)
        f = force[:, c]
        starts = np.flatnonzero(shut & ~np.r_[False, shut[:-1]])
        # first sample after each closed run (the located separation), or the last sample
        ends = np.minimum(np.flatnonzero(shut & ~np.r_[shut[1:], False]) + 1, t.size - 1)
        for s, e in zip(starts, ends):
            seg = slice(s, e + 1)
            fs = f[seg]
            k = s + int(np.argmax(fs))
            # the episode ends at separation (δ back to 0, a located event) or earlier where
            # a tension-free law's force has fallen to zero
            zero = np.flatnonzero(f[k:e + 1] <= 0.0)
            last = k + zero[0] if zero.size else e
            rows.append(dict(
                side=name,
                start=float(t[s]),
                duration=float(t[last] - t[s]),
                approach_velocity=float(rate[s, c]),
                peak_force=float(parabolic_peak(t, f, k)),
                max_indentation=float(indentation[seg, c].max()),
                impulse=float(np.trapezoid(fs, t[seg])),
            ))
    rows.sort(key=lambda r: r["start"])
    return rows

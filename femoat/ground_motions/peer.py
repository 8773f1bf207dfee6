"""Readers for ground-motion files: PEER NGA ``.AT2`` and plain-text columns.

A PEER NGA AT2 file has 4 header lines, then the accelerations in g, several per line::

    PEER NGA STRONG MOTION DATABASE RECORD
    Northridge-01, 1/17/1994, Rinaldi Receiving Sta, 228
    ACCELERATION TIME SERIES IN UNITS OF G
    NPTS=   1991, DT=   .0100 SEC,   0 POLE @    30.00000 HZ,  -5 POLE @      .05000
      -.2556093E-02  -.2534838E-02  -.2450926E-02  -.2152656E-02  -.1770125E-02
      ...

The 4th line is ``NPTS= n, DT= dt SEC`` in NGA-West2 files, optionally followed by filter
corners. Older PEER files write ``  4156    .0050    NPTS, DT`` instead; both are accepted.
Line endings may be LF or CRLF. Any problem with the file raises :class:`RecordFormatError`,
which names the file, the line and what was expected.
"""

import re
from pathlib import Path

import numpy as np

from femoat.units import G

from .record import GroundMotion


class RecordFormatError(ValueError):
    """A ground-motion file does not have the expected layout."""

    def __init__(self, path, line, message):
        self.path = str(path)
        self.line = line
        where = f"{self.path}, line {line}" if line is not None else self.path
        super().__init__(f"{where}: {message}")


_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?"
# NPTS has at most 9 digits: a longer run of digits is no count (and int() refuses > 4300 digits)
_NGA_WEST2 = re.compile(rf"NPTS\s*=\s*(\d{{1,9}})\s*,?\s*DT\s*=\s*({_NUMBER})",
                        re.IGNORECASE | re.ASCII)
_OLD_PEER = re.compile(rf"^\s*(\d{{1,9}})\s*,?\s+({_NUMBER})\s+NPTS\s*,?\s*DT\b",
                       re.IGNORECASE | re.ASCII)


def read_at2(path):
    """Read a PEER NGA ``.AT2`` acceleration file.

    Parameters
    ----------
    path : str or Path
        The ``.AT2`` file. Values are in g.

    Returns
    -------
    GroundMotion
        Named after the file stem; ``source`` holds the path and the event line of the header.

    Raises
    ------
    RecordFormatError
        Fewer than 4 header lines, no NPTS/DT on line 4, a token that is not a finite number (or
        is larger in magnitude than :data:`MAX_ABS_VALUE`), or a value count different from NPTS.
        The message names the file and the line (lines counted from 1, as an editor does).
    """
    path = Path(path)
    with open(path, encoding="latin-1", newline=None) as f:
        # lines as an editor counts them: universal newlines, then "\n" only (str.splitlines
        # would also break at form feeds and other control characters and shift line numbers)
        lines = f.read().split("\n")
    if lines[-1] == "":
        lines.pop()
    if len(lines) < 4:
        raise RecordFormatError(
            path, len(lines) + 1, f"expected 4 header lines, the file has only {len(lines)} lines"
        )
    npts, dt = _parse_npts_dt(path, lines[3])

    values = []
    for lineno, line in enumerate(lines[4:], start=5):
        tokens = line.split()
        if len(values) + len(tokens) > npts:
            raise RecordFormatError(
                path,
                lineno,
                f"more values than NPTS={npts} (header line 4); the file has extra data or NPTS "
                "is wrong",
            )
        values.extend(_to_float(path, lineno, token) for token in tokens)
    if len(values) != npts:
        raise RecordFormatError(
            path,
            len(lines),
            f"file ends after {len(values)} values, expected NPTS={npts} (header line 4); the "
            "file is truncated or NPTS is wrong",
        )

    event = lines[1].strip()
    return GroundMotion(values, dt, name=path.stem, source=f"PEER NGA AT2 file {path} ({event})")


def _parse_npts_dt(path, line):
    match = _NGA_WEST2.search(line) or _OLD_PEER.search(line)
    if match is None:
        raise RecordFormatError(
            path,
            4,
            f"expected 'NPTS= <n>, DT= <dt> SEC' (or '<n> <dt> NPTS, DT'), got {line.strip()!r}",
        )
    npts = int(match.group(1))
    dt = float(match.group(2).replace("D", "E").replace("d", "e"))
    if npts < 2:
        raise RecordFormatError(path, 4, f"expected NPTS >= 2, got NPTS={npts}")
    if not (np.isfinite(dt) and dt > 0.0):
        raise RecordFormatError(path, 4, f"expected a positive DT [s], got DT={match.group(2)}")
    return npts, dt


MAX_ABS_VALUE = 1e6
"""Largest magnitude a reader accepts in a file, in the file's units (g, cm/s², ...): a million
is far beyond any acceleration record (the largest recorded are a few g, a few thousand cm/s²), so
a larger value means a corrupt file or wrong units, and would overflow later arithmetic."""


def _to_float(path, lineno, token):
    try:
        value = float(token)
    except ValueError:
        raise RecordFormatError(path, lineno, f"expected a number, got {token!r}") from None
    if not np.isfinite(value):
        raise RecordFormatError(path, lineno, f"expected a finite number, got {token!r}")
    if abs(value) > MAX_ABS_VALUE:
        raise RecordFormatError(
            path, lineno, f"expected an acceleration, got {token!r} (magnitude above "
            f"{MAX_ABS_VALUE:g} in the file's units: a corrupt file or the wrong units)")
    return value


_TO_G = {
    "g": 1.0,
    "in/s2": 1.0 / G,
    "cm/s2": 1.0 / (2.54 * G),
    "m/s2": 100.0 / (2.54 * G),
}


def read_text(path, dt, units="g", column=0, skip_rows=None, comment="%#", max_rows=None):
    """Read one column of a plain-text acceleration file (one or more columns per line).

    Columns are separated by whitespace or commas. Blank lines and lines whose first
    non-blank character is in ``comment`` are skipped.

    Parameters
    ----------
    path : str or Path
        The text file.
    dt : float  [s]
        Sampling interval (plain text carries none we can trust).
    units : {"g", "cm/s2", "in/s2", "m/s2"}
        Units of the values in the file. They are converted to g with femoat's
        ``G = 386.09 in/s²`` (= 980.669 cm/s²).
    column : int
        Which column to read, counting from 0.
    skip_rows : int or None
        Number of lines to skip at the top before anything else (None: none).
    comment : str
        Characters that start a comment line.
    max_rows : int or None
        Read at most this many data rows (None: all).

    Returns
    -------
    GroundMotion
        Acceleration in g, named after the file stem.

    Raises
    ------
    RecordFormatError
        A data line without the column, a token that is not a finite number (or is larger in
        magnitude than :data:`MAX_ABS_VALUE`), or fewer than 2 data rows; the message names the
        file and the line.
    ValueError
        An argument out of range (``units``, ``column``, ``skip_rows``, ``max_rows``, ``dt``).
    """
    path = Path(path)
    key = str(units).strip().lower().replace("^2", "2").replace("²", "2").replace("sec", "s")
    if key not in _TO_G:
        raise ValueError(f"units must be one of {sorted(_TO_G)}; got {units!r}.")
    if not (isinstance(column, (int, np.integer)) and column >= 0):
        raise ValueError(f"column must be a column index >= 0 (0 is the first); got {column!r}.")
    skip_rows = 0 if skip_rows is None else int(skip_rows)
    if skip_rows < 0:
        raise ValueError(f"skip_rows must be >= 0 or None; got {skip_rows!r}.")
    if max_rows is not None and int(max_rows) < 1:
        raise ValueError(f"max_rows must be >= 1 or None (all rows); got {max_rows!r}.")

    values = []
    with open(path, encoding="latin-1", newline=None) as f:
        for lineno, line in enumerate(f, start=1):
            if lineno <= skip_rows:
                continue
            stripped = line.strip()
            if not stripped or stripped[0] in comment:
                continue
            if max_rows is not None and len(values) >= int(max_rows):
                break
            tokens = [tok for tok in re.split(r"[,\s]+", stripped) if tok]
            if column >= len(tokens):
                raise RecordFormatError(
                    path, lineno, f"expected at least {column + 1} columns, got {len(tokens)}"
                )
            values.append(_to_float(path, lineno, tokens[column]))
    if len(values) < 2:
        raise RecordFormatError(path, None, f"expected at least 2 data rows, found {len(values)}")

    return GroundMotion(
        np.asarray(values) * _TO_G[key],
        dt,
        name=path.stem,
        source=f"text file {path}, column {column}, {len(values)} rows, {units}",
    )

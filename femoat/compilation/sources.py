"""Which of femoat's source files decide its compiled code and its results, and their fingerprint.

One list for the two checks that must agree on it: numba's on-disk cache (a kernel's cached
code is dropped when a source it may inline changed, :mod:`~femoat.compilation.numba_cache`)
and the suite's code version (:func:`femoat.suite.definition.code_version`). Two scopes:

* ``"kernels"``: what numba compiles. Whole folders, because a kernel inlines its siblings'
  kernels and reads their constants (option slots, law and material codes, bundles), plus the
  compile options in :mod:`femoat.compilation.jit` and what numba's cache holds of a kernel
  compiled for its callers (:mod:`femoat.compilation.machine_code`, installed on the numba
  versions :mod:`femoat.compilation.numba_version` accepts).
* ``"results"``: everything that can change a run's result: the package but the command line,
  plotting, rendering, OpenSees, the studies and the suite machinery besides its run path.

Nothing is read at import. :func:`fingerprint` reads a scope's files once per process, when first
asked; given a memo folder it also keeps the value with the files' sizes and modification times,
and later processes reuse it without reading a source file while those match (the trust Python's
own bytecode cache and numba's cache place in them).
"""

import hashlib
from pathlib import Path

from femoat.atomic import write_text

PACKAGE = Path(__file__).resolve().parents[1]
"""femoat's package folder (the default root of every scope)."""

KERNELS = ("bearings", "checks.py", "compilation/jit.py", "compilation/machine_code.py",
           "compilation/numba_version.py", "contact", "integration", "structure/materials",
           "units.py")
"""The kernel sources, relative to the package folder: a file, or a folder's ``*.py`` files."""

NOT_RESULTS = ("commands", "plotting", "render", "opensees", "studies", "suite")
"""Top-level parts of the package that cannot change a run's result (a study's suite
definitions are in their suites' hashes, its tables read finished runs) ..."""

SUITE_RUN_PATH = ("suite/columns.py", "suite/huntfill.py", "suite/model.py", "suite/records.py",
                  "suite/runs.py", "suite/scaling.py", "suite/variations.py")
"""... except these files of the suite machinery, which build and run a suite's runs."""

SCOPES = ("kernels", "results")


def sources(scope="kernels", root=PACKAGE):
    """The source files of ``scope`` (``"kernels"`` or ``"results"``) under ``root`` (a copy
    of femoat's package folder), sorted. Lists folders; reads no file."""
    root = Path(root)
    if scope == "kernels":
        files = []
        for entry in KERNELS:
            p = root / entry
            files += p.rglob("*.py") if p.is_dir() else [p]
    elif scope == "results":
        files = [p for p in root.rglob("*.py") if p.relative_to(root).parts[0] not in NOT_RESULTS]
        files += [root / name for name in SUITE_RUN_PATH]
    else:
        raise ValueError(f"scope = {scope!r}: use one of {SCOPES}")
    return tuple(sorted(set(files)))


def fingerprint(scope="kernels", root=PACKAGE, memo=None):
    """sha256 (hex) of ``scope``'s files under ``root``: their names relative to it and their
    contents. Computed once per process; with ``memo`` (a folder) reused across processes while
    the files' names, sizes and modification times are unchanged (see the module docstring)."""
    root = Path(root)
    known = _digests.get((scope, root))
    if known is not None:
        return known
    files = sources(scope, root)
    if memo is None:
        digest = _content_hash(files, root)
    else:
        digest = _remembered(files, root, Path(memo) / f"sources-{scope}-{_short(root)}")
    _digests[(scope, root)] = digest
    return digest


_digests = {}
"""{(scope, root): fingerprint} of this process."""


def _remembered(files, root, path):
    """The fingerprint remembered at ``path`` for these files' stats, else hashed and kept."""
    stamp = _stat_hash(files, root)
    try:
        seen, digest = path.read_text().split()
        if seen == stamp:
            return digest
    except (OSError, ValueError):
        pass
    digest = _content_hash(files, root)
    try:
        write_text(path, f"{stamp} {digest}\n")
    except OSError:
        pass  # a read-only cache folder: hashed again by the next process
    return digest


def _short(root):
    """A short name for the package folder ``root`` (two checkouts keep separate memos)."""
    return hashlib.sha1(str(root).encode()).hexdigest()[:12]


def _content_hash(files, root):
    h = hashlib.sha256()
    for f in files:
        h.update(f.relative_to(root).as_posix().encode() + b"\0")
        h.update(f.read_bytes())
        h.update(b"\0")
    return h.hexdigest()


def _stat_hash(files, root):
    h = hashlib.sha256()
    for f in files:
        st = f.stat()
        h.update(f"{f.relative_to(root).as_posix()} {st.st_size} {st.st_mtime_ns}\n".encode())
    return h.hexdigest()

"""Atomic file writes: a reader never sees a half-written file.

Every file femoat writes goes through :func:`atomic_path`: the content is written to a temporary
file in the destination folder and moved into place with :func:`os.replace` only when complete.
"""

import contextlib
import os
import tempfile
from pathlib import Path


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path beside ``path``; on success, move it onto ``path``.

    Use it with writers that want a file name (matplotlib, meshio, pyvista, netCDF):

        with atomic_path("fig.png") as tmp:
            fig.savefig(tmp)

    The temporary name keeps the destination's suffix so that writers choosing a format from the
    extension still work. On an exception the temporary file is removed and ``path`` is untouched.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        # mkstemp creates the file private (0600); give it the mode an ordinary write would:
        # the replaced file's, or 0666 less the umask for a new one
        try:
            mode = path.stat().st_mode & 0o777
        except FileNotFoundError:
            mode = 0o666 & ~_umask()
        os.chmod(tmp, mode)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.remove(tmp)
        raise


def write_text(path, text):
    """Write ``text`` to ``path`` atomically (UTF-8)."""
    with atomic_path(path) as tmp:
        Path(tmp).write_text(text, encoding="utf-8")


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask

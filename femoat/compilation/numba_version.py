"""Which numba femoat's replacements of numba internals were read against, and their switches.

:mod:`~femoat.compilation.inlining`, :mod:`~femoat.compilation.ssa`,
:mod:`~femoat.compilation.liveness`, :mod:`~femoat.compilation.call_types` and
:mod:`~femoat.compilation.flags` each replace a piece of numba's compiler by code that gives
the same answer; each is installed only on the numba versions whose source it was read and
tested against, and each has an environment switch (``=0``) that leaves numba's own.
"""

import os


def minor():
    """numba's (major, minor) version."""
    import numba

    major, minor_ = numba.__version__.split(".")[:2]
    return int(major), int(minor_)


def supported(versions):
    """Whether this numba lies in ``versions``, the first and last (major, minor) read and
    tested (both ends included)."""
    low, high = versions
    return low <= minor() <= high


def wanted(switch, versions):
    """Whether to install a replacement: this numba is one of ``versions`` and the environment
    variable ``switch`` is not ``0``."""
    return os.environ.get(switch, "1") != "0" and supported(versions)

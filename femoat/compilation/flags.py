"""numba's compile flags read as one dict, not option by option.

numba keys the implementations of its overloaded functions by the compile flags in force
(``_OverloadFunctionTemplate._get_impl``), so a cold compile of femoat's loop hashes and
compares flags about half a million times. Both go through ``TargetConfig.values()``, which
builds the dict of every option by reading each one through its property (about forty
options, each a default looked up when unset); and since ``__hash__`` hashes the sorted
*names* of the options, every set of flags hashes alike and each lookup also compares values.

:func:`values` builds the same dict (the same keys in the same order, each value the one its
property returns: the value set, else the option's default) from the class's defaults and
the values set, in one step. Nothing else changes: hashing and comparing call it as before.

Installed by :func:`install` when femoat first imports numba (:mod:`femoat.compilation.jit`),
on the numba versions whose ``targetconfig`` module was read and tested
(:data:`NUMBA_VERSIONS`); ``FEMOAT_FAST_FLAGS=0`` leaves numba's own.
"""

from femoat.compilation import numba_version

NUMBA_VERSIONS = ((0, 68), (0, 68))
"""The first and last numba minor versions whose ``TargetConfig`` this module was read and
tested against (both ends included)."""

_installed = []
_defaults = {}


def install():
    """Make numba's ``TargetConfig.values`` :func:`values` (once a process). Returns whether it
    is installed (False on an unknown numba, or with ``FEMOAT_FAST_FLAGS=0``)."""
    if _installed:
        return True
    if not numba_version.wanted("FEMOAT_FAST_FLAGS", NUMBA_VERSIONS):
        return False
    from numba.core.targetconfig import TargetConfig

    values.__wrapped__ = TargetConfig.values
    TargetConfig.values = values
    _installed.append(True)
    return True


def values(self):
    """The dict of every option of the flags ``self``: numba's ``TargetConfig.values()``."""
    cls = type(self)
    defaults = _defaults.get(cls)
    if defaults is None:
        defaults = _defaults[cls] = {name: option.default for name, option in cls.options.items()}
    if not self._values.keys() <= defaults.keys():  # never seen; numba's own then
        return values.__wrapped__(self)
    return {**defaults, **self._values}

"""numba's error messages marked up without wrapping the standard streams each time.

numba builds an exception's message through its colour scheme (``numba.core.errors``:
``HighlightColorScheme._markup``, used by every ``NumbaError`` and by ``typeof``'s
"Cannot determine Numba type"), also for the exceptions type inference raises and catches while
it tries its templates: about 90,000 of them in a cold compile of femoat's loop. With
colorama installed, each markup initializes colorama (wrapping ``sys.stdout`` and
``sys.stderr``) and de-initializes it again, though nothing is written in between: most of the
cost of those exceptions.

:func:`markup` returns the same string (the scheme's colour and style, the message, colorama's
reset code) without touching the streams. Installed by :func:`install` when femoat first
imports numba (:mod:`femoat.compilation.jit`), on the numba versions whose ``errors`` module
was read and tested (:data:`NUMBA_VERSIONS`); ``FEMOAT_FAST_ERROR_MARKUP=0`` leaves numba's own.
"""

from femoat.compilation import numba_version

NUMBA_VERSIONS = ((0, 68), (0, 68))
"""The first and last numba minor versions whose ``errors`` module this module was read and
tested against (both ends included)."""

_installed = []


def install():
    """Make numba's ``HighlightColorScheme._markup`` :func:`markup` (once a process). Returns
    whether it is installed (False on an unknown numba, without colorama, or with
    ``FEMOAT_FAST_ERROR_MARKUP=0``)."""
    if _installed:
        return True
    if not numba_version.wanted("FEMOAT_FAST_ERROR_MARKUP", NUMBA_VERSIONS):
        return False
    from numba.core import errors

    scheme = getattr(errors, "HighlightColorScheme", None)
    if scheme is None:  # numba without colorama: its plain scheme does no markup
        return False
    from colorama import Style

    markup.__wrapped__ = scheme._markup
    markup.__defaults__ = (None, Style.BRIGHT)
    _reset.append(Style.RESET_ALL)
    scheme._markup = markup
    _installed.append(True)
    return True


_reset = []


def markup(self, msg, color=None, style=None):
    """``msg`` with the colour ``color`` and the style ``style`` (colorama codes) and
    colorama's reset code after it: numba's ``HighlightColorScheme._markup``."""
    return f"{color or ''}{style or ''}{msg}{_reset[0]}"

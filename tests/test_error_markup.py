"""numba's error messages marked up without wrapping the streams (femoat.compilation.error_markup).

What must hold: every scheme's markup is numba's string, character for character, and the
standard streams are left as they were.
"""

import sys

import pytest


def test_every_markup_of_every_theme_is_numbas_string():
    from femoat.compilation import error_markup, jit

    jit._register()
    if not error_markup._installed:
        pytest.skip("femoat.compilation.error_markup is not installed here (numba version, "
                    "colorama missing, or FEMOAT_FAST_ERROR_MARKUP=0)")
    from numba.core import errors

    numbas = error_markup.markup.__wrapped__
    messages = ["Cannot determine Numba type of <class 'object'>", "", "two\nlines é ∑",
                "\x1b[31m already coloured"]
    stdout, stderr = sys.stdout, sys.stderr
    for theme in errors.themes.values():
        scheme = errors.HighlightColorScheme(theme)
        for msg in messages:
            for method in ("code", "errmsg", "filename", "indicate", "highlight", "reset"):
                ours = getattr(scheme, method)(msg)
                color = theme[method]
                assert ours == numbas(scheme, msg, color), (method, msg)
                assert ours.endswith("\x1b[0m") and msg in ours
            # the style argument as numba's: none, and another one
            assert error_markup.markup(scheme, msg, None, None) == numbas(scheme, msg, None, None)
            assert (error_markup.markup(scheme, msg, theme["code"], "\x1b[2m")
                    == numbas(scheme, msg, theme["code"], "\x1b[2m"))
    assert sys.stdout is stdout and sys.stderr is stderr
    # numba's exceptions carry it: the message of a typing error is the marked-up text
    err = errors.TypingError("no such function")
    assert str(err).startswith("\x1b[1mno such function\x1b[0m")

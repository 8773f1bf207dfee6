"""VTK's off-screen backend, chosen before the first plotter.

On Linux without a display (no ``DISPLAY`` or ``WAYLAND_DISPLAY``) VTK first tries X, prints
"bad X server connection" and only then falls back. femoat picks the backend itself before the
first plotter: EGL when libEGL is installed, else OSMesa, through VTK's
``VTK_DEFAULT_OPENGL_WINDOW``. A backend the user chose (that variable already set) is kept, and
a machine with a display is left alone.
"""

import ctypes.util
import os
import sys

_WINDOWS = (("EGL", "vtkEGLRenderWindow"), ("OSMesa", "vtkOSOpenGLRenderWindow"))


def choose_offscreen_backend(environ=None):
    """Set ``VTK_DEFAULT_OPENGL_WINDOW`` in ``environ`` (default ``os.environ``) when rendering
    would otherwise try a missing X display; return the render window class in use (or None when
    VTK keeps its own choice)."""
    env = os.environ if environ is None else environ
    if "VTK_DEFAULT_OPENGL_WINDOW" in env:
        return env["VTK_DEFAULT_OPENGL_WINDOW"]
    if not sys.platform.startswith("linux") or env.get("DISPLAY") or env.get("WAYLAND_DISPLAY"):
        return None
    for library, window in _WINDOWS:
        if ctypes.util.find_library(library):
            env["VTK_DEFAULT_OPENGL_WINDOW"] = window
            return window
    return None


def import_pyvista():
    """``pyvista``, with the off-screen backend chosen first (see the module docstring)."""
    choose_offscreen_backend()
    import pyvista

    return pyvista

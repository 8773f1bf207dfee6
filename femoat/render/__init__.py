"""Renders of building runs and finite-element walls (pyvista, off-screen). Never imported by the
core: pyvista is imported inside the functions that draw.

Off-screen rendering needs an OpenGL backend. Without a display, femoat chooses EGL (or
OSMesa) itself before the first plotter (:mod:`femoat.render.backend`); set
``VTK_DEFAULT_OPENGL_WINDOW`` to choose another. Without any backend VTK may crash the process, so
callers that must survive render in a subprocess.

Modules: backend (the off-screen backend), fe_wall (a finite-element wall's mesh regions and
mode shapes, drawn as its wall kind says), wall (the wall's deformed shape at the peak impact of
a building run with a modal wall), animation (a GIF of a building run: base mat, floors, both
walls), plan (a top view of the base mat in its rectangular moat, walls flashing on impact).
"""

"""Renders of building runs and finite-element walls (pyvista, off-screen). Never imported by the
core: pyvista is imported inside the functions that draw.

Off-screen rendering needs an OpenGL backend; on a headless machine set
``VTK_DEFAULT_OPENGL_WINDOW=vtkEGLRenderWindow`` before Python starts. Without any backend VTK
may crash the process, so callers that must survive render in a subprocess.

Modules: wall (the wall's deformed shape at the peak impact of a building run with a modal
wall), animation (a GIF of a building run: base mat, floors, both walls).
"""

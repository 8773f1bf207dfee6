"""Pictures of wall models with pyvista, off-screen, to PNG. Never imported by the core.

Off-screen rendering needs an OpenGL backend; on a headless machine set
``VTK_DEFAULT_OPENGL_WINDOW=vtkEGLRenderWindow`` (EGL) before Python starts. Without any
backend VTK may crash the process, so callers that must survive run this in a subprocess.
"""

import numpy as np

from femoat.atomic import atomic_path
from femoat.render.backend import import_pyvista

REGION_COLORS = {"base": "royalblue", "impact": "red", "back": "orange"}
"""Colour of each named boundary; other names are drawn in grey."""


def _grid(mesh, point_vectors=None):
    """pyvista UnstructuredGrid of a scikit-fem mesh in the 3D wall frame."""
    pv = import_pyvista()
    from skfem.io.meshio import to_meshio

    from femoat.walls.fe.mesh_io import _embed

    mio = to_meshio(mesh, encode_cell_data=False)
    mio.points = _embed(mesh.p)
    grid = pv.from_meshio(mio)
    if point_vectors is not None:
        grid.point_data["u"] = point_vectors
    return grid


def _facet_polydata(mesh, facets):
    """Boundary facets as polydata: points (1D), lines (2D) or planar polygons (3D).

    Lines and polygons are lifted off the grid's surface by 0.3 % of the mesh size, away from
    their cell, so that they are not hidden by the coplanar grid faces (z-fighting).
    """
    pv = import_pyvista()

    from femoat.walls.fe.mesh_io import _embed

    points = _embed(mesh.p)
    f = mesh.facets[:, facets]
    if f.shape[0] == 1:
        return pv.PolyData(points[f[0]])
    cells = mesh.f2t[0, facets]
    outward = points[f].mean(axis=0) - points[mesh.t[:, cells]].mean(axis=0)
    outward /= np.linalg.norm(outward, axis=1, keepdims=True)
    lift = 0.003 * np.ptp(points, axis=0).max() * outward
    xyz = points[f] + lift  # (corner, facet, 3)
    n_corners, n_facets = f.shape
    local = np.arange(n_corners * n_facets).reshape(n_facets, n_corners)
    flat = xyz.transpose(1, 0, 2).reshape(-1, 3)
    if n_corners == 2:
        lines = np.column_stack([np.full(n_facets, 2), local]).ravel()
        return pv.PolyData(flat, lines=lines)
    faces = []
    for k in range(n_facets):  # scikit-fem may store facet vertices sorted: make them cyclic
        c = xyz[:, k] - xyz[:, k].mean(axis=0)
        _, _, vt = np.linalg.svd(c)
        order = np.argsort(np.arctan2(c @ vt[1], c @ vt[0]))
        faces.append([n_corners, *local[k, order]])
    return pv.PolyData(flat, faces=np.concatenate(faces))


def _camera(plotter, mesh, side="moat"):
    """Look at the wall from the moat (impact face, slightly from below to show the base) or
    from the backfill; 1D/2D models are seen in the x-z plane."""
    if mesh.dim() < 3:
        plotter.view_xz()
        return
    lo, hi = mesh.p.min(axis=1), mesh.p.max(axis=1)
    centre, size = (lo + hi) / 2, np.max(hi - lo)
    direction = np.array([-1.0, -0.7, -0.25]) if side == "moat" else np.array([1.0, -0.7, 0.4])
    plotter.camera_position = [tuple(centre + 2.5 * size * direction), tuple(centre), (0, 0, 1)]


def render_regions(mesh, path, window_size=(800, 800)):
    """PNG of the mesh (grey, edges shown) with its named boundaries coloured, and a legend.

    A 3D wall is drawn twice: from the moat side (impact face and base) and from the backfill.
    """
    pv = import_pyvista()
    sides = ("moat", "backfill") if mesh.dim() == 3 else ("moat",)
    plotter = pv.Plotter(off_screen=True, shape=(1, len(sides)),
                         window_size=(window_size[0] * len(sides), window_size[1]))
    grid = _grid(mesh)
    for k, side in enumerate(sides):
        plotter.subplot(0, k)
        plotter.set_background("white")
        if mesh.dim() == 1:
            plotter.add_mesh(grid, color="dimgrey", line_width=4)
        else:
            plotter.add_mesh(grid, color="lightgrey", show_edges=True, edge_color="dimgrey")
        legend = []
        for name, facets in (mesh.boundaries or {}).items():
            color = REGION_COLORS.get(name, "grey")
            poly = _facet_polydata(mesh, facets)
            if mesh.dim() == 1:
                plotter.add_mesh(poly, color=color, point_size=18, render_points_as_spheres=True)
            else:
                plotter.add_mesh(poly, color=color, line_width=6, show_edges=mesh.dim() == 3,
                                 edge_color="dimgrey")
            legend.append([name, color])
        if legend:
            plotter.add_legend(legend, bcolor="white", face="rectangle", size=(0.3, 0.15), loc="lower left")
        if mesh.dim() == 3:
            plotter.add_text(f"seen from the {side}", font_size=12, color="black")
        _camera(plotter, mesh, side)
    with atomic_path(path) as tmp:
        plotter.screenshot(str(tmp))
    plotter.close()
    return path


def render_modes(model, result, path, n_modes=4, amplitude=0.1, window_size=(400, 700)):
    """PNG of the first ``n_modes`` mode shapes, warped and coloured by displacement.

    amplitude : float  peak displacement drawn, as a fraction of the wall height [-]
    """
    pv = import_pyvista()

    n = min(n_modes, result.shapes.shape[1])
    plotter = pv.Plotter(off_screen=True, shape=(1, n),
                         window_size=(window_size[0] * n, window_size[1]))
    for i in range(n):
        plotter.subplot(0, i)
        plotter.set_background("white")
        u = model.vertex_vectors(result.shapes[:, i])
        peak = np.abs(u).max()
        scale = amplitude * model.geometry.height / peak if peak > 0 else 0.0
        grid = _grid(model.mesh, u)
        grid.point_data["|u|"] = np.linalg.norm(u, axis=1) / (peak if peak > 0 else 1.0)
        warped = grid.warp_by_vector("u", factor=scale)
        plotter.add_mesh(grid, style="wireframe", color="lightgrey", opacity=0.4)
        plotter.add_mesh(warped, scalars="|u|", cmap="viridis", show_edges=model.kind != "beam",
                         edge_color="grey", line_width=5 if model.kind == "beam" else 1,
                         show_scalar_bar=False)
        plotter.add_text(f"mode {i + 1}: {result.frequencies[i]:.1f} Hz", font_size=12,
                         color="black")
        _camera(plotter, model.mesh)
    with atomic_path(path) as tmp:
        plotter.screenshot(str(tmp))
    plotter.close()
    return path

"""Pictures of finite-element wall models (pyvista, off-screen, PNG): the mesh with its named
boundaries, the mode shapes, and the pieces the picture of a run's wall shares with them.

How a model is drawn (its camera views, its line width) is its wall kind's
(:mod:`femoat.walls.kinds`); points are placed in the wall frame by
:func:`femoat.walls.fe.mesh_io.wall_frame_points`.
"""

import numpy as np

from femoat.atomic import atomic_path
from femoat.render.backend import import_pyvista
from femoat.walls.kinds import kind_of_mesh, wall_kind

REGION_COLORS = {"base": "royalblue", "impact": "red", "back": "orange"}
"""Colour of each named boundary; other names are drawn in grey."""


def wall_grid(mesh, point_vectors=None):
    """pyvista UnstructuredGrid of a scikit-fem mesh in the 3D wall frame; ``point_vectors``
    (n_vertices, 3) [in] become its point data "u"."""
    pv = import_pyvista()
    from skfem.io.meshio import to_meshio

    from femoat.walls.fe.mesh_io import wall_frame_points

    mio = to_meshio(mesh, encode_cell_data=False)
    mio.points = wall_frame_points(mesh)
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

    from femoat.walls.fe.mesh_io import wall_frame_points

    points = wall_frame_points(mesh)
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


def look(plotter, mesh, view):
    """Point the camera: "elevation" looks along y at the x-z plane; "moat" at the impact face
    (slightly from below, to show the base); "backfill" at the back face."""
    if view == "elevation":
        plotter.view_xz()
        return
    from femoat.walls.fe.mesh_io import wall_frame_points

    points = wall_frame_points(mesh)
    lo, hi = points.min(axis=0), points.max(axis=0)
    centre, size = (lo + hi) / 2, np.max(hi - lo)
    direction = np.array([-1.0, -0.7, -0.25]) if view == "moat" else np.array([1.0, -0.7, 0.4])
    plotter.camera_position = [tuple(centre + 2.5 * size * direction), tuple(centre), (0, 0, 1)]


def impact_point(model):
    """The impact point in the wall frame [in]: on the impact face (x = 0) at the impact height,
    mid-length where the model spans the length (y) of the wall."""
    g = model.geometry
    spans_length = 1 in wall_kind(model.kind).axes
    return np.array([0.0, g.length / 2 if spans_length else 0.0, g.impact_height])


def line_style(kind):
    """``add_mesh`` keywords drawing a model of wall kind ``kind`` (a name): cell edges where
    there are faces, lines of the kind's width."""
    row = wall_kind(kind)
    return dict(show_edges=row.dimension > 1, line_width=row.line_width)


def render_regions(mesh, path, window_size=(800, 800), kind=None):
    """PNG of the mesh (grey, edges shown) with its named boundaries coloured, and a legend.

    kind : str or None  the wall kind drawn (default: the kind the mesh makes); one panel per
        view of the kind (a 3D wall from the moat side, impact face and base, and from the
        backfill)
    """
    pv = import_pyvista()
    row = kind_of_mesh(mesh, kind)
    views = row.views
    plotter = pv.Plotter(off_screen=True, shape=(1, len(views)),
                         window_size=(window_size[0] * len(views), window_size[1]))
    grid = wall_grid(mesh)
    for k, view in enumerate(views):
        plotter.subplot(0, k)
        plotter.set_background("white")
        plotter.add_mesh(grid, color="dimgrey" if mesh.dim() == 1 else "lightgrey",
                         edge_color="dimgrey", **line_style(row.name))
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
        if len(views) > 1:
            plotter.add_text(f"seen from the {view}", font_size=12, color="black")
        look(plotter, mesh, view)
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
        grid = wall_grid(model.mesh, u)
        grid.point_data["|u|"] = np.linalg.norm(u, axis=1) / (peak if peak > 0 else 1.0)
        warped = grid.warp_by_vector("u", factor=scale)
        plotter.add_mesh(grid, style="wireframe", color="lightgrey", opacity=0.4)
        plotter.add_mesh(warped, scalars="|u|", cmap="viridis", edge_color="grey",
                         show_scalar_bar=False, **line_style(model.kind))
        plotter.add_text(f"mode {i + 1}: {result.frequencies[i]:.1f} Hz", font_size=12,
                         color="black")
        look(plotter, model.mesh, wall_kind(model.kind).views[0])
    with atomic_path(path) as tmp:
        plotter.screenshot(str(tmp))
    plotter.close()
    return path

"""The finite-element wall at the peak impact of a building run with a :class:`ModalWall`.

The run records the wall's modal coordinates q_i [in] (one DOF per mode, positive away from the
building); the wall's displacement field at the peak-force instant is u = Σ ψ_i·q_i, with ψ_i
the finite-element shapes of the modal wall (unit impact displacement), in the wall's own frame
(x from the impact face toward the backfill, whichever side of the building the wall is on).
"""

import numpy as np

from femoat.atomic import atomic_path
from femoat.render.backend import import_pyvista
from femoat.render.fe_wall import impact_point, line_style, look, wall_grid
from femoat.walls.kinds import wall_kind


def peak_state(result, side=None, at="force"):
    """The instant of the largest contact force on one wall of a building run.

    result : RunResult
    side : "pos", "neg" or None (the wall with the larger peak force)
    at : "force" (the peak impact) or "displacement" (the wall's largest impact-point
        displacement away from the building, which comes later in the contact)
    Returns a dict: side, index (sample), time [s], force [kip] (at that instant), peak_force
    [kip] (the wall's largest), q (modal coordinates [in]), impact_displacement [in] (Σ φ_i·q_i).
    """
    if at not in ("force", "displacement"):
        raise ValueError(f"at = {at!r}: choose 'force' (the peak impact) or 'displacement'")
    names = result.meta["contact_names"]
    if not names:
        raise ValueError("the run has no moat wall: nothing to render")
    if side is None:
        c = int(np.argmax(result.contact_force.max(axis=0)))
    else:
        key = {"+": "pos", "1": "pos", "-": "neg", "-1": "neg"}.get(str(side), str(side))
        if key not in names:
            raise ValueError(f"side = {side!r}: this run has walls {names}; choose one of them")
        c = names.index(key)
    force = result.contact_force[:, c]
    k = int(np.argmax(force))
    peak = float(force[k])
    if peak <= 0.0:
        raise ValueError(f"the {names[c]} wall is never hit in this run: choose the other side or "
                         "a stronger motion")
    if at == "displacement":
        k = int(np.argmax(result.wall_displacement()[:, c]))
    wall = result.meta["walls"][c]
    q = result.displacement[k, wall["cols"]]
    return dict(side=names[c], index=k, time=float(result.time[k]), force=float(force[k]),
                peak_force=peak,
                q=np.asarray(q, float), impact_displacement=float(np.dot(wall["phi"], q)),
                stiffnesses=np.asarray(wall["k"], float), at=at)


def wall_field(modal_wall, state):
    """Displacement of every wall DOF [in] at ``state`` (from :func:`peak_state`)."""
    if modal_wall.shapes is None:
        raise ValueError("the modal wall has no finite-element shapes: build it with "
                         "ModalWall.from_fe")
    q = state["q"]
    if q.size != modal_wall.n_modes or not np.allclose(state["stiffnesses"],
                                                       modal_wall.modal_stiffnesses, rtol=1e-6):
        raise ValueError(f"the run's {state['side']} wall has {q.size} modes with stiffnesses "
                         f"{np.round(state['stiffnesses'], 4).tolist()} kip/in; the modal wall "
                         f"given has {modal_wall.n_modes} with "
                         f"{np.round(modal_wall.modal_stiffnesses, 4).tolist()}: render with the "
                         "modal wall the run used")
    return modal_wall.shapes @ q


def render_wall_peak(model, modal_wall, result, path, side=None, at="force", drawn_fraction=0.1,
                     window_size=(900, 900)):
    """PNG of the wall deformed at the peak impact of ``result`` (a run with ``modal_wall``).

    model : WallModel  the finite-element wall the modal wall was built from
    modal_wall : ModalWall  (from :meth:`ModalWall.from_fe` on ``model``)
    result : RunResult  a building run whose walls are ``modal_wall``
    side : "pos", "neg" or None (the wall with the larger peak force)
    at : "force" (default) or "displacement", see :func:`peak_state`
    drawn_fraction : float  the largest displacement is drawn as this fraction of the wall
        height [-]; the magnification is printed on the picture
    Returns (path, state) with state from :func:`peak_state` plus the magnification.
    """
    pv = import_pyvista()

    if not 0 < drawn_fraction <= 1:
        raise ValueError(f"drawn_fraction = {drawn_fraction!r} must be in (0, 1]")
    state = peak_state(result, side, at)
    u = model.vertex_vectors(wall_field(modal_wall, state))
    peak = float(np.abs(u).max())
    height = model.geometry.height
    scale = drawn_fraction * height / peak if peak > 0 else 1.0
    grid = wall_grid(model.mesh, u)
    grid.point_data["displacement [in]"] = np.linalg.norm(u, axis=1)
    warped = grid.warp_by_vector("u", factor=scale)

    plotter = pv.Plotter(off_screen=True, window_size=window_size)
    plotter.set_background("white")
    style = line_style(model.kind)
    plotter.add_mesh(grid, style="wireframe", color="grey", opacity=0.35,
                     line_width=style["line_width"] // 2 + 1)
    bar = dict(title="displacement [in]", color="black", vertical=True, position_x=0.85,
               position_y=0.2, height=0.6)
    plotter.add_mesh(warped, scalars="displacement [in]", cmap="viridis", edge_color="dimgrey",
                     scalar_bar_args=bar, **style)
    tip = impact_point(model) + scale * np.array([state["impact_displacement"], 0.0, 0.0])
    arrow = pv.Arrow(start=tip - np.array([0.25 * height, 0, 0]), direction=(1, 0, 0),
                     scale=0.25 * height, tip_length=0.3, tip_radius=0.08, shaft_radius=0.03)
    plotter.add_mesh(arrow, color="red")
    what = "peak impact" if at == "force" else "largest displacement"
    plotter.add_text(
        f"{state['side']} wall at its {what}: t = {state['time']:.4f} s, "
        f"F = {state['force']:.2f} kip\n"
        f"impact-point displacement {state['impact_displacement']:.4f} in, "
        f"{modal_wall.n_modes} modes, displacements x{scale:.3g}",
        font_size=11, color="black", position="upper_left")
    view = wall_kind(model.kind).views[0]
    look(plotter, model.mesh, view)
    if view == "elevation":
        plotter.camera.zoom(0.9)
    with atomic_path(path) as tmp:
        plotter.screenshot(str(tmp))
    plotter.close()
    state["magnification"] = scale
    return path, state

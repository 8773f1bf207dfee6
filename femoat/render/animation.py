"""An animated GIF of a building run: ground, base mat on its isolators, floors, both moat walls.

Only the frames shown are computed: the run is decimated to the frame times t_k = t0 + k·Δ,
Δ = speed/fps (displacements interpolated in time; a contact flag and the largest contact force
are kept over each frame interval, so that a 3 ms impact between two frames still shows). The
drawing is schematic and true to scale in the horizontal displacements (``scale`` magnifies
them): blocks [in] from :class:`BuildingLayout`, walls as cantilevers deflected in the static
tip-load shape ψ(ζ) = ζ²(3 − ζ)/2 (ζ = height/wall height) through their impact-point
displacement. Frames are written with Pillow (GIF), so no ffmpeg or imageio is needed.
"""

from dataclasses import dataclass

import numpy as np

from femoat.atomic import atomic_path
from femoat.render.backend import import_pyvista
from femoat.units import G


@dataclass(frozen=True)
class BuildingLayout:
    """Schematic dimensions of the picture [in] (not used by any computation).

    width : float  base mat and floor plan along the motion
    depth : float  plan dimension across the motion
    base_thickness, slab_thickness, story_height : float
    isolator_height : float  bearings between the pedestal and the base mat
    wall_height, wall_thickness : float  the moat walls; their impact point is at the base mat's
        mid-height, ``impact_below_top`` below the wall top
    """

    width: float = 120.0
    depth: float = 60.0
    base_thickness: float = 12.0
    slab_thickness: float = 6.0
    story_height: float = 40.0
    isolator_height: float = 8.0
    wall_height: float = 84.0
    wall_thickness: float = 6.0
    impact_below_top: float = 2.0

    def __post_init__(self):
        for name, value in self.__dict__.items():
            if not (np.isfinite(value) and value >= 0) or (value == 0 and name != "impact_below_top"):
                raise ValueError(f"BuildingLayout.{name} = {value!r} must be a positive length [in]")
        if self.impact_below_top >= self.wall_height:
            raise ValueError("BuildingLayout.impact_below_top must be below the wall height [in]")


def frame_times(t, fps, speed, start, end, max_frames):
    """The frame times [s] of a GIF of the run sampled at ``t`` [s], from ``start`` to ``end``
    (None: the run's end), ``fps`` frames per second of GIF showing ``speed`` simulated seconds
    per second; the checks name the argument and the fix."""
    end = float(t[-1]) if end is None else end
    for name, value in (("fps", fps), ("speed", speed)):
        if not (isinstance(value, (int, float)) and np.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r} must be a positive number")
    if not (isinstance(start, (int, float)) and isinstance(end, (int, float))
            and t[0] <= start < end <= t[-1] + 1e-12):
        raise ValueError(f"start = {start!r} and end = {end!r} [s] must satisfy "
                         f"{t[0]:g} <= start < end <= {t[-1]:g} (the run)")
    step = speed / fps
    n = int(np.floor((end - start) / step + 1e-9)) + 1
    if n > max_frames:
        need = (end - start) * fps / max_frames
        raise ValueError(f"{n} frames for {end - start:.3g} s at fps {fps:g} and speed {speed:g}: "
                         f"more than max_frames = {max_frames}; raise --speed (e.g. --speed "
                         f"{max(need, speed * 1.01):.3g}), lower --fps, show a shorter "
                         "--start/--end window or raise --max-frames (femoat render run; in "
                         "Python: speed, fps, start, end, max_frames)")
    return start + step * np.arange(n)


def frame_states(result, fps=20, speed=1.0, start=0.0, end=None, max_frames=400):
    """Decimate a run to the frame times.

    fps : float  frames per second of the GIF [1/s]
    speed : float  simulated seconds per second of GIF [-] (1 = real time, 0.5 = half speed)
    start, end : float  the part of the run shown [s] (end None: to the end)
    Returns a dict of arrays over the frames: time [s], displacement (n_frames, n_dofs) [in],
    wall (n_frames, n_walls) impact-point wall displacement [in], ground_acceleration [in/s²],
    force (n_frames, n_walls) largest contact force since the previous frame [kip], contact
    (bool, same shape).
    """
    t = result.time
    times = frame_times(t, fps, speed, start, end, max_frames)
    n = times.size
    disp = np.column_stack([np.interp(times, t, result.displacement[:, j])
                            for j in range(result.displacement.shape[1])])
    wall = result.wall_displacement()
    wall = np.column_stack([np.interp(times, t, wall[:, j]) for j in range(wall.shape[1])]) \
        if wall.shape[1] else np.zeros((n, 0))
    ag = np.interp(times, t, result.ground_acceleration)
    nw = result.contact_force.shape[1]
    force = np.zeros((n, nw))
    contact = np.zeros((n, nw), dtype=bool)
    # every sample belongs to the frame at or after it: frame k covers (t_{k-1}, t_k]
    owner = np.searchsorted(times, t, side="left")
    inside = owner < n
    for c in range(nw):
        np.maximum.at(force[:, c], owner[inside], result.contact_force[inside, c])
        np.logical_or.at(contact[:, c], owner[inside], result.contact_closed[inside, c] > 0)
    return dict(time=times, displacement=disp, wall=wall, ground_acceleration=ag, force=force,
                contact=contact)


def _box(x0, x1, y0, y1, z0, z1):
    pv = import_pyvista()

    return pv.Box(bounds=(x0, x1, y0, y1, z0, z1))


def _cantilever(x_face, thickness, y0, y1, z0, height, nz=24):
    """Structured grid of a wall, its face at x_face, growing in +x by ``thickness`` (negative:
    toward −x); returns the grid and ψ at its points."""
    pv = import_pyvista()

    x = np.array(sorted([x_face, x_face + thickness]))
    z = np.linspace(z0, z0 + height, nz + 1)
    X, Y, Z = np.meshgrid(x, np.array([y0, y1]), z, indexing="ij")
    grid = pv.StructuredGrid(X, Y, Z)
    zeta = (grid.points[:, 2] - z0) / height
    return grid, zeta**2 * (3 - zeta) / 2


def animate_run(result, path, fps=20, speed=1.0, start=0.0, end=None, layout=None, scale=1.0,
                window_size=(960, 600), max_frames=400, title=None):
    """Write an animated GIF of ``result`` (a RunResult) to ``path``.

    fps, speed, start, end, max_frames : see :func:`frame_states`
    layout : BuildingLayout or None  schematic dimensions [in]
    scale : float  magnification of the horizontal displacements in the picture [-]
    Returns (path, number of frames).
    """
    pv = import_pyvista()
    from PIL import Image

    if str(path).lower().endswith(".gif") is False:
        raise ValueError(f"path = {str(path)!r}: the animation is written as GIF; use a .gif name")
    if not (np.isfinite(scale) and scale > 0):
        raise ValueError(f"scale = {scale!r} must be a positive magnification [-]")
    lay = layout or BuildingLayout()
    frames = frame_states(result, fps, speed, start, end, max_frames)
    meta = result.meta
    ns = meta["n_struct"]
    names, gaps = meta["contact_names"], meta["gaps"]

    B, D = lay.width, lay.depth
    y0, y1 = -D / 2, D / 2
    z_imp = lay.wall_height - lay.impact_below_top
    base_z0 = z_imp - lay.base_thickness / 2
    pedestal_top = base_z0 - lay.isolator_height

    plotter = pv.Plotter(off_screen=True, window_size=window_size)
    plotter.set_background("white")
    span = B / 2 + max(gaps, default=4.0) + lay.wall_thickness + 40.0
    plotter.add_mesh(_box(-span, span, y0 - 30, y1 + 30, -10.0, 0.0), color="tan")
    plotter.add_mesh(_box(-B / 2 + 10, B / 2 - 10, y0 + 5, y1 - 5, 0.0, pedestal_top),
                     color="gainsboro")
    # moving blocks: base mat and floors, translated in x by their displacement
    blocks = [_box(-B / 2, B / 2, y0, y1, base_z0, base_z0 + lay.base_thickness)]
    level = base_z0 + lay.base_thickness
    for _ in range(ns - 1):
        level += lay.story_height
        blocks.append(_box(-B / 2, B / 2, y0, y1, level - lay.slab_thickness, level))
    rest = [b.points.copy() for b in blocks]
    for i, b in enumerate(blocks):
        plotter.add_mesh(b, color="steelblue" if i == 0 else "lightsteelblue", show_edges=True,
                         edge_color="dimgrey")
    # columns (corner lines between consecutive blocks) and isolators (pedestal → base mat)
    corners = [(x, y) for x in (-B / 2 + 3, 0.0, B / 2 - 3) for y in (y0 + 3, y1 - 3)]
    tops = [base_z0 + lay.base_thickness]
    bottoms = []
    level = base_z0 + lay.base_thickness
    for _ in range(ns - 1):
        level += lay.story_height
        bottoms.append(level - lay.slab_thickness)
        tops.append(level)
    seg_pts = []
    seg_owner = []  # (dof of the lower end or -1 for ground, dof of the upper end)
    for (x, y) in corners:
        seg_pts += [(x, y, pedestal_top), (x, y, base_z0)]
        seg_owner.append((-1, 0))
        for k in range(ns - 1):
            seg_pts += [(x, y, tops[k]), (x, y, bottoms[k])]
            seg_owner.append((k, k + 1))
    seg_pts = np.array(seg_pts, float)
    n_seg = len(seg_owner)
    lines = pv.PolyData(seg_pts.copy(), lines=np.column_stack(
        [np.full(n_seg, 2), np.arange(0, 2 * n_seg, 2), np.arange(1, 2 * n_seg, 2)]).ravel())
    plotter.add_mesh(lines, color="black", line_width=3)
    # walls: face at side·(B/2 + gap), deflecting away from the building
    walls = []
    for c, name in enumerate(names):
        side = 1.0 if name == "pos" else -1.0
        face = side * (B / 2 + gaps[c])
        grid, psi = _cantilever(face, side * lay.wall_thickness, y0 - 10, y1 + 10, 0.0,
                                lay.wall_height)
        psi_imp = (z_imp / lay.wall_height) ** 2 * (3 - z_imp / lay.wall_height) / 2
        actor = plotter.add_mesh(grid, color="silver")
        walls.append((grid, grid.points.copy(), psi / psi_imp, side, actor))
    # a front view, slightly from the left and above, fitted to the scene at rest
    top = tops[-1]
    plotter.camera_position = [(-0.25 * span, -3.0 * span, 0.5 * top + 0.6 * span),
                               (0.0, 0.0, 0.45 * top), (0.0, 0.0, 1.0)]
    plotter.reset_camera()
    plotter.camera.zoom(1.2)
    header = title or meta.get("info", {}).get("motion", "")
    if scale != 1.0:
        header += f"   (displacements drawn x{scale:g})"

    images, text = [], None
    for k, t in enumerate(frames["time"]):
        u = scale * frames["displacement"][k]
        for b, p0, dof in zip(blocks, rest, range(ns)):
            p = p0.copy()
            p[:, 0] += u[dof]
            b.points = p
        p = seg_pts.copy()
        for s, (lo, hi) in enumerate(seg_owner):
            p[2 * s, 0] += u[lo] if lo >= 0 else 0.0
            p[2 * s + 1, 0] += u[hi]
        lines.points = p
        info = [f"{header}", f"t = {t:6.3f} s   ground {frames['ground_acceleration'][k] / G:+.2f} g"
                f"   base mat {frames['displacement'][k][0]:+.2f} in"]
        for c, (grid, p0, shape, side, actor) in enumerate(walls):
            w = scale * frames["wall"][k, c]
            p = p0.copy()
            p[:, 0] += side * w * shape
            grid.points = p
            hit = frames["contact"][k, c]
            actor.prop.color = "red" if hit else "silver"
            info.append(f"{names[c]} wall: {frames['wall'][k, c]:+.3f} in"
                        + (f", impact {frames['force'][k, c]:.1f} kip" if hit else ""))
        if text is None:
            text = plotter.add_text("\n".join(info), font_size=10, color="black",
                                    position="upper_left")
        else:
            text.set_text("upper_left", "\n".join(info))
        plotter.render()
        images.append(Image.fromarray(plotter.screenshot(return_img=True)))
    plotter.close()
    duration_ms = max(int(round(1000.0 / fps)), 20)
    frames_p = _shared_palette(images)
    with atomic_path(path) as tmp:
        frames_p[0].save(tmp, format="GIF", save_all=True, append_images=frames_p[1:],
                         duration=duration_ms, loop=0, optimize=False)
    return path, len(images)


def _shared_palette(images, colors=192):
    """Quantise every frame to one palette built from a few frames (steady colours, and much
    faster than a median cut per frame)."""
    from PIL import Image

    picks = [images[i] for i in np.unique(np.linspace(0, len(images) - 1, 5).astype(int))]
    w, h = picks[0].size
    montage = Image.new("RGB", (w, h * len(picks)))
    for i, im in enumerate(picks):
        montage.paste(im.convert("RGB"), (0, i * h))
    palette = montage.quantize(colors=colors, method=Image.Quantize.MEDIANCUT)
    return [im.convert("RGB").quantize(palette=palette, dither=Image.Dither.NONE) for im in images]

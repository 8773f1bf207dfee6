"""A top-view animated GIF of a plan run: the base mat moving in its rectangular moat, each wall
flashing red while it is in contact (its force > 0).

Driven by a :class:`~femoat.plotting.plan_history.PlanHistory` (plain arrays: the OpenSees twin
in 3D today, femoat's plan solver later). Only the frames shown are computed: the run is
decimated to t_k = start + k·Δ, Δ = speed/fps, the base mat's (x, y) interpolated in time and a
wall's contact flag and largest force kept over each frame interval (t_{k−1}, t_k], so that a
3 ms impact between two frames still flashes (as :mod:`femoat.render.animation` does in 1D).

The picture is seen from above (+z toward the viewer, +x right, +y up) with a parallel
projection, true to scale in the horizontal displacements (``scale`` magnifies them): the base
mat is its schematic footprint (:class:`PlanViewLayout`) centred at its displacement, each wall
a block whose face stands ``gap`` from the mat's face at rest. The ±y walls run the full width,
corners included; the ±x walls stand between them. The trail of the mat's centre is drawn. Frames
are written with Pillow (GIF), as the 1D animation, so no ffmpeg is needed. Each wall is
labelled by its side just outside it ("+x", "−x", "+y", "−y", the outward normal), and two axes
in inches run below and to the left of the moat (:func:`plan_annotations`).
"""

from dataclasses import dataclass

import numpy as np

from femoat.atomic import atomic_path
from femoat.plotting.plan_history import check_history
from femoat.render.animation import _shared_palette, frame_times
from femoat.render.backend import import_pyvista

WALL_IDLE, WALL_HIT, MAT_COLOR = "silver", "red", "steelblue"
"""A wall at rest, a wall in contact, the base mat."""

WALL_LABELS = {"+x": "+x", "-x": "\u2212x", "+y": "+y", "-y": "\u2212y"}
"""A wall's label in the picture: its side, the outward normal, with a typographic minus."""
AXIS_TITLES = ("x [in]", "y [in]")
"""The titles of the top view's two axes."""


@dataclass(frozen=True)
class PlanViewLayout:
    """Schematic dimensions of the top view [in] (not used by any computation).

    width : float  the base mat's footprint along x
    depth : float  the base mat's footprint along y
    wall_thickness : float  the moat walls, in plan
    base_thickness, wall_height : float  heights of the mat and walls (the walls stand higher,
        so a mat indenting a wall does not hide it)
    """

    width: float = 40.0
    depth: float = 40.0
    wall_thickness: float = 6.0
    base_thickness: float = 12.0
    wall_height: float = 24.0

    def __post_init__(self):
        for name, value in self.__dict__.items():
            if not (isinstance(value, (int, float)) and np.isfinite(value) and value > 0):
                raise ValueError(f"PlanViewLayout.{name} = {value!r} must be a positive length "
                                 "[in]")


def plan_frames(history, fps=20, speed=1.0, start=0.0, end=None, max_frames=400):
    """Decimate a plan history to the frame times.

    fps : float  frames per second of the GIF [1/s]
    speed : float  simulated seconds per second of GIF [-] (1 = real time)
    start, end : float  the part of the run shown [s] (end None: to the end)
    Returns a dict over the frames: ``time`` [s], ``base`` (frames, 2) [in], ``force``
    (frames, walls) the largest contact force since the previous frame [kip], ``contact`` (bool,
    same shape: a force > 0 in that interval).
    """
    h = check_history(history)
    t = h.time
    times = frame_times(t, fps, speed, start, end, max_frames)
    n = times.size
    base = np.column_stack([np.interp(times, t, h.base[:, j]) for j in range(2)])
    nw = len(h.sides)
    force = np.zeros((n, nw))
    # every sample belongs to the frame at or after it: frame k covers (t_{k-1}, t_k]; samples
    # before start belong to no frame
    owner = np.searchsorted(times, t, side="left")
    inside = (owner < n) & (t >= start - 1e-12)
    for c in range(nw):
        np.maximum.at(force[:, c], owner[inside], np.maximum(h.wall_force[inside, c], 0.0))
    return dict(time=times, base=base, force=force, contact=force > 0.0)


def wall_rectangles(history, layout=None):
    """Each wall's block in plan [in], {side: (x0, x1, y0, y1)}, at rest."""
    h = check_history(history)
    lay = layout or PlanViewLayout()
    hx, hy, t = lay.width / 2, lay.depth / 2, lay.wall_thickness
    r = h.reach()
    out = {}
    for side in h.sides:
        if side == "+x":
            out[side] = (hx + r["+x"], hx + r["+x"] + t, -hy - r["-y"], hy + r["+y"])
        elif side == "-x":
            out[side] = (-hx - r["-x"] - t, -hx - r["-x"], -hy - r["-y"], hy + r["+y"])
        elif side == "+y":
            out[side] = (-hx - r["-x"] - t, hx + r["+x"] + t, hy + r["+y"], hy + r["+y"] + t)
        else:
            out[side] = (-hx - r["-x"] - t, hx + r["+x"] + t, -hy - r["-y"] - t, -hy - r["-y"])
    return out


def plan_annotations(history, layout=None):
    """Where the top view writes its wall labels and draws its axes, in plan [in]:

    ``labels``: {side: (text, (x, y))}, each wall's :data:`WALL_LABELS` text centred one wall
    thickness beyond its outer face, on the wall's middle line;
    ``x_axis``, ``y_axis``: (start, end, range), an axis line from start to end (x, y) with its
    tick values ``range`` [in] (the plan coordinate along it): the x axis two wall
    thicknesses below the moat's outer face, left to right (ticks below it), the y axis as far
    to the left, top to bottom (ticks to its left); their titles :data:`AXIS_TITLES`.
    """
    h = check_history(history)
    lay = layout or PlanViewLayout()
    r, t = h.reach(), lay.wall_thickness
    hx, hy = lay.width / 2, lay.depth / 2
    outer = {"+x": hx + r["+x"] + t, "-x": -hx - r["-x"] - t, "+y": hy + r["+y"] + t,
             "-y": -hy - r["-y"] - t}  # the moat's outer faces (walls there or not)
    mid = ((outer["+x"] + outer["-x"]) / 2, (outer["+y"] + outer["-y"]) / 2)
    labels = {}
    for side in h.sides:
        sign = 1.0 if side[0] == "+" else -1.0
        at = outer[side] + sign * t
        labels[side] = (WALL_LABELS[side], (at, mid[1]) if side[1] == "x" else (mid[0], at))
    y_line, x_line = outer["-y"] - 2 * t, outer["-x"] - 2 * t
    x0, x1, y0, y1 = outer["-x"], outer["+x"], outer["-y"], outer["+y"]
    return dict(labels=labels, x_axis=((x0, y_line), (x1, y_line), (x0, x1)),
                y_axis=((x_line, y1), (x_line, y0), (y1, y0)))


def plan_camera(history, layout=None, window_size=(640, 640), scale=1.0):
    """The top view's camera: {"center": (x, y) [in], "parallel_scale": half the picture's
    height [in]} framing the moat, the walls, the orbit, the wall labels and the axes
    (:func:`plan_annotations`) with a margin."""
    h = check_history(history)
    lay = layout or PlanViewLayout()
    rect = wall_rectangles(h, lay)
    xs = [lay.width / 2 + scale * h.base[:, 0].max(), -lay.width / 2 + scale * h.base[:, 0].min()]
    ys = [lay.depth / 2 + scale * h.base[:, 1].max(), -lay.depth / 2 + scale * h.base[:, 1].min()]
    for x0, x1, y0, y1 in rect.values():
        xs += [x0, x1]
        ys += [y0, y1]
    notes = plan_annotations(h, lay)
    for _, (x, y) in notes["labels"].values():
        xs.append(x)
        ys.append(y)
    for start, end, _ in (notes["x_axis"], notes["y_axis"]):
        xs += [start[0], end[0]]
        ys += [start[1], end[1]]
    cx, cy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2
    half_h = (max(ys) - min(ys)) / 2
    half_w = (max(xs) - min(xs)) / 2
    aspect = window_size[0] / window_size[1]
    return dict(center=(cx, cy), parallel_scale=1.25 * max(half_h, half_w / aspect))


def world_to_pixel(camera, window_size, x, y):
    """The (column, row) pixel of the plan point (x, y) [in] in a frame of ``window_size``
    (width, height) taken with ``camera`` (:func:`plan_camera`); row 0 is the top."""
    w, hgt = window_size
    per_in = (hgt / 2) / camera["parallel_scale"]
    cx, cy = camera["center"]
    return round(w / 2 + (x - cx) * per_in), round(hgt / 2 - (y - cy) * per_in)


def plan_scene(history, layout=None, window_size=(640, 640), scale=1.0, n_trail=2):
    """The top view's off-screen plotter and its parts, before any frame: the moat's floor, the
    walls (silver), the base mat at rest, its trail (``n_trail`` points), the wall labels and
    the two axes [in] (:func:`plan_annotations`), the camera of :func:`plan_camera`.

    Returns (plotter, parts): parts ``walls`` (one actor per side of the history), ``mat`` and
    its ``rest`` points, ``trail``, ``labels`` {side: text}, ``label_actor``, ``axes`` (the x
    and y axis actors, vtkAxisActor2D, titled :data:`AXIS_TITLES`).
    """
    h = check_history(history)
    lay = layout or PlanViewLayout()
    pv = import_pyvista()
    camera = plan_camera(h, lay, window_size, scale)
    plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
    plotter.set_background("white")
    rects = wall_rectangles(h, lay)
    r = h.reach()
    hx, hy = lay.width / 2, lay.depth / 2
    plotter.add_mesh(pv.Box(bounds=(-hx - r["-x"], hx + r["+x"], -hy - r["-y"], hy + r["+y"],
                                    -2.0, -1.0)), color="whitesmoke", lighting=False)
    walls = []
    for side in h.sides:
        x0, x1, y0, y1 = rects[side]
        actor = plotter.add_mesh(pv.Box(bounds=(x0, x1, y0, y1, 0.0, lay.wall_height)),
                                 color=WALL_IDLE, lighting=False)
        walls.append(actor)
    mat = pv.Box(bounds=(-hx, hx, -hy, hy, 0.0, lay.base_thickness))
    rest = mat.points.copy()
    plotter.add_mesh(mat, color=MAT_COLOR, lighting=False, show_edges=True, edge_color="black")
    trail = pv.lines_from_points(np.zeros((max(n_trail, 2), 3)) + [0, 0, lay.base_thickness
                                                                    + 1.0])
    plotter.add_mesh(trail, color="black", line_width=2, lighting=False)
    notes = plan_annotations(h, lay)
    labels = {side: text for side, (text, _) in notes["labels"].items()}
    label_actor = None
    if labels:
        points = np.array([[x, y, lay.wall_height + 1.0] for _, (x, y) in
                           notes["labels"].values()])
        label_actor = plotter.add_point_labels(
            points, list(labels.values()), font_size=14, text_color="black", shape=None,
            show_points=False, always_visible=True, justification_horizontal="center",
            justification_vertical="center")
    axes = []
    for (start, end, span), title in zip((notes["x_axis"], notes["y_axis"]), AXIS_TITLES):
        ruler = plotter.add_ruler([*start, 0.0], [*end, 0.0], title=title, label_color="black",
                                  tick_color="black", label_format="%.0f")
        ruler.SetRange(*span)  # the plan coordinate along the axis, not the distance along it
        axes.append(ruler)
    cx, cy = camera["center"]
    plotter.camera_position = [(cx, cy, 1000.0), (cx, cy, 0.0), (0.0, 1.0, 0.0)]
    plotter.enable_parallel_projection()
    plotter.camera.parallel_scale = camera["parallel_scale"]
    plotter.camera.clipping_range = (1.0, 2000.0)
    return plotter, dict(walls=walls, mat=mat, rest=rest, trail=trail, labels=labels,
                         label_actor=label_actor, axes=axes)


def animate_plan(history, path, fps=20, speed=1.0, start=0.0, end=None, layout=None, scale=1.0,
                 window_size=(640, 640), max_frames=400):
    """Write a top-view animated GIF of ``history`` (a PlanHistory) to ``path``.

    fps, speed, start, end, max_frames : see :func:`plan_frames`
    layout : PlanViewLayout or None  schematic dimensions [in]
    scale : float  magnification of the displacements in the picture [-]
    window_size : (int, int)  frame width and height [pixels]
    Returns (path, number of frames).
    """
    h = check_history(history)
    if not str(path).lower().endswith(".gif"):
        raise ValueError(f"path = {str(path)!r}: the animation is written as GIF; use a .gif name")
    if not (isinstance(scale, (int, float)) and np.isfinite(scale) and scale > 0):
        raise ValueError(f"scale = {scale!r} must be a positive magnification [-]")
    lay = layout or PlanViewLayout()
    frames = plan_frames(h, fps, speed, start, end, max_frames)
    from PIL import Image

    plotter, scene = plan_scene(h, lay, window_size, scale, len(frames["time"]))
    mat, rest, trail, walls = scene["mat"], scene["rest"], scene["trail"], scene["walls"]

    images, text = [], None
    for k, t in enumerate(frames["time"]):
        u = scale * frames["base"][k]
        mat.points = rest + [u[0], u[1], 0.0]
        pts = trail.points.copy()
        pts[: k + 1, :2] = scale * frames["base"][: k + 1]
        pts[k + 1:, :2] = u
        trail.points = pts
        info = [h.title, f"t = {t:6.3f} s   base mat ({frames['base'][k][0]:+.2f}, "
                f"{frames['base'][k][1]:+.2f}) in"
                + (f"   (drawn x{scale:g})" if scale != 1.0 else "")]
        for c, actor in enumerate(walls):
            hit = frames["contact"][k, c]
            actor.prop.color = WALL_HIT if hit else WALL_IDLE
            if hit:
                info.append(f"{h.sides[c]} wall: impact {frames['force'][k, c]:.1f} kip")
        message = "\n".join(line for line in info if line)
        if text is None:
            text = plotter.add_text(message, font_size=9, color="black", position="upper_left")
        else:
            text.set_text("upper_left", message)
        plotter.render()
        images.append(Image.fromarray(plotter.screenshot(return_img=True)))
    plotter.close()
    duration_ms = max(round(1000.0 / fps), 20)
    frames_p = _shared_palette(images)
    with atomic_path(path) as tmp:
        frames_p[0].save(tmp, format="GIF", save_all=True, append_images=frames_p[1:],
                         duration=duration_ms, loop=0, optimize=False)
    return path, len(images)

"""The top-view animation of a plan run (femoat.render.plan).

The decimation and the camera are plain computations, tested here directly. Drawing runs in a
subprocess (a missing OpenGL backend can crash VTK outright), skipped only when plain pyvista
cannot render a sphere off-screen; any other failure fails the test.

The orbit (as in tests/test_plan_figures.py): the base mat once around a circle of radius 5 in
at one sample per degree over 3.6 s (θ = 100°/s · t), in a square moat with 4 in gaps, a
wall's force 100 kip/in times the mat's overshoot past its line: the +x wall is in contact
while |θ| < 36.87° (t < 0.37 s or t > 3.23 s), the +y wall while |θ − 90°| < 36.87°
(0.53 s < t < 1.27 s).
"""

import json
import textwrap

import numpy as np
import pytest
from conftest import run_python

from femoat.plotting.plan_history import PlanHistory
from femoat.render.plan import (AXIS_TITLES, PlanViewLayout, plan_annotations, plan_camera,
                                plan_frames, wall_rectangles)

SETUP = textwrap.dedent("""
    import numpy as np
    from femoat.plotting.plan_history import PlanHistory
    theta = np.radians(np.arange(360.0))
    base = 5.0 * np.column_stack([np.cos(theta), np.sin(theta)])
    over = np.column_stack([base[:, 0] - 4, -base[:, 0] - 4, base[:, 1] - 4, -base[:, 1] - 4])
    history = PlanHistory(np.arange(360) * 0.01, base, 100.0 * np.maximum(over, 0.0),
                          (4.0, 4.0, 4.0, 4.0), title="circle")
""")


@pytest.fixture(scope="module")
def history():
    scope = {}
    exec(SETUP, scope)  # noqa: S102 - the same lines the render subprocess runs
    return scope["history"]


def test_frames_decimate_the_orbit(history):
    # Δ = speed/fps = 0.1 s over [0, 3.5] s: 36 frames at 0.0, 0.1, ..., 3.5 s.
    f = plan_frames(history, fps=10, speed=1.0, end=3.5)
    np.testing.assert_allclose(f["time"], 0.1 * np.arange(36), atol=1e-12)
    # Frame 5 is t = 0.5 s, θ = 50°: the mat at 5·(cos 50°, sin 50°) (a sample, no interpolation).
    np.testing.assert_allclose(f["base"][5], 5 * np.array([np.cos(np.radians(50)),
                                                           np.sin(np.radians(50))]), atol=1e-12)
    # Frame 6 covers (0.5, 0.6] s, θ = 51°..60°: +y contact (5 sin 60° = 4.33 > 4), its largest
    # force 100·(4.330 − 4) = 33.0 kip; frame 5 covers θ = 41°..50°: 5 sin 50° = 3.83 < 4, none.
    assert f["contact"][6, 2] and not f["contact"][5, 2]
    assert f["force"][6, 2] == pytest.approx(100 * (5 * np.sin(np.radians(60)) - 4))
    # An impact shorter than a frame still shows: a 0.02 s force spike between two frame times.
    spike = np.zeros((360, 4))
    spike[[151, 152], 1] = 7.0  # t = 1.51, 1.52 s, inside frame 16's (1.5, 1.6]
    h = PlanHistory(history.time, history.base, spike, history.gaps)
    g = plan_frames(h, fps=10, speed=1.0, end=3.5)
    assert np.flatnonzero(g["contact"][:, 1]).tolist() == [16] and g["force"][16, 1] == 7.0
    with pytest.raises(ValueError, match="more than max_frames") as err:
        plan_frames(history, fps=1000)
    # the error names every option that fixes it, as femoat render run spells them
    for option in ("--speed", "--fps", "--start/--end", "--max-frames"):
        assert option in str(err.value)
    with pytest.raises(ValueError, match="start = 2.0 and end = 1.0"):
        plan_frames(history, start=2.0, end=1.0)
    with pytest.raises(ValueError, match="fps = 0 must be a positive number"):
        plan_frames(history, fps=0)


def test_walls_stand_at_their_gaps(history):
    # Mat footprint 40 × 30 in, walls 6 in thick, gaps 4 in: the +x wall's face is at
    # 20 + 4 = 24 in and it spans y between the ±y walls' faces, ±(15 + 4) = ±19 in.
    lay = PlanViewLayout(width=40.0, depth=30.0)
    rect = wall_rectangles(history, lay)
    assert rect["+x"] == (24.0, 30.0, -19.0, 19.0)
    assert rect["-y"] == (-30.0, 30.0, -25.0, -19.0)
    cam = plan_camera(history, lay, window_size=(400, 400))
    # The walls fill x ∈ [−30, 30], y ∈ [−25, 25]; the labels stand one thickness beyond,
    # x = ±36, y = ±31, the axes two below and left, y = −25 − 12 = −37, x = −30 − 12 = −42:
    # x ∈ [−42, 36], y ∈ [−37, 31], centred at (−3, −3); a square window shows the larger
    # half-extent, 39 in, with a 25 % margin: half-height 48.75 in.
    assert cam == dict(center=(-3.0, -3.0), parallel_scale=48.75)
    with pytest.raises(ValueError, match="PlanViewLayout.width = -1"):
        PlanViewLayout(width=-1)


def test_walls_are_labelled_by_side_and_the_axes_span_the_moat_in_inches(history):
    # the same moat: outer faces at x = ±30, y = ±25 [in], walls 6 in thick
    notes = plan_annotations(history, PlanViewLayout(width=40.0, depth=30.0))
    # each wall's label is its outward normal, one thickness (6 in) beyond its outer face, on
    # its middle line
    assert notes["labels"] == {"+x": ("+x", (36.0, 0.0)), "-x": ("\u2212x", (-36.0, 0.0)),
                               "+y": ("+y", (0.0, 31.0)), "-y": ("\u2212y", (0.0, -31.0))}
    # the x axis runs left to right 12 in below the moat with ticks −30 ... 30 in, the y axis
    # top to bottom 12 in to its left with ticks 25 ... −25 in
    assert notes["x_axis"] == ((-30.0, -37.0), (30.0, -37.0), (-30.0, 30.0))
    assert notes["y_axis"] == ((-42.0, 25.0), (-42.0, -25.0), (25.0, -25.0))
    assert AXIS_TITLES == ("x [in]", "y [in]")
    # a moat without its −x wall labels the three walls it has
    h = PlanHistory(history.time, history.base, history.wall_force[:, [0, 2, 3]],
                    (4.0, 4.0, 4.0), sides=("+x", "+y", "-y"))
    assert sorted(plan_annotations(h)["labels"]) == ["+x", "+y", "-y"]


def test_a_frame_draws_the_wall_labels_and_the_axes(tmp_path, render_backend):
    script = SETUP + textwrap.dedent("""
        import json
        import numpy as np
        from femoat.render.plan import (plan_annotations, plan_camera, plan_scene,
                                        world_to_pixel)
        size = (320, 320)
        plotter, parts = plan_scene(history, window_size=size)
        image = plotter.screenshot(return_img=True)
        plotter.close()
        cam = plan_camera(history, window_size=size)
        dark = {}
        for side, (text, (x, y)) in plan_annotations(history)["labels"].items():
            col, row = world_to_pixel(cam, size, x, y)
            box = image[row - 8:row + 9, col - 12:col + 13]
            dark[side] = int((box.max(axis=2) < 80).sum())  # black text pixels around it
        print(json.dumps(dict(labels=parts["labels"], dark=dark,
                              titles=[a.GetTitle() for a in parts["axes"]],
                              ranges=[list(a.GetRange()) for a in parts["axes"]])))
    """)
    done = run_python(script, tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    info = json.loads(done.stdout.strip().splitlines()[-1])
    # the frame's labels are the four sides, the minus typographic; the axes titled in inches
    # over the moat's outer faces: x from −(20 + 4 + 6) = −30 to 30, y from 30 down to −30
    assert info["labels"] == {"+x": "+x", "-x": "\u2212x", "+y": "+y", "-y": "\u2212y"}
    assert info["titles"] == ["x [in]", "y [in]"]
    assert info["ranges"] == [[-30.0, 30.0], [30.0, -30.0]]
    # each label is drawn where plan_annotations puts it: dark text on the white margin
    assert all(n > 5 for n in info["dark"].values()), info["dark"]


def test_plan_animation_flashes_the_wall_in_contact(tmp_path, render_backend, history):
    script = SETUP + textwrap.dedent("""
        import json
        from femoat.render.plan import animate_plan, plan_camera, world_to_pixel
        size = (320, 320)
        path, n = animate_plan(history, "plan.gif", fps=10, end=3.5, window_size=size)
        cam = plan_camera(history, window_size=size)
        # the +x wall's middle (20 + 4 + 6/2 = 27 in, 0), the +y wall's, the mat's centre
        print(json.dumps(dict(frames=n, px=world_to_pixel(cam, size, 27.0, 0.0),
                              py=world_to_pixel(cam, size, 0.0, 27.0),
                              mat=world_to_pixel(cam, size, 0.0, 0.0))))
    """)
    done = run_python(script, tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    info = json.loads(done.stdout.strip().splitlines()[-1])
    from PIL import Image

    gif = Image.open(tmp_path / "plan.gif")
    assert info["frames"] == 36 and gif.n_frames == 36  # 0.0 ... 3.5 s at 0.1 s

    def rgb(frame, pixel):
        gif.seek(frame)
        col, row = pixel
        return np.asarray(gif.convert("RGB"), dtype=int)[row, col]

    def red(c):
        return c[0] > 200 and c[1] < 60 and c[2] < 60

    # Frame 0 (θ = 0°): the mat at (5, 0) is in contact with +x, not +y.
    # Frame 9 (0.8 s, θ = 71°..80° in its interval): +y in contact, +x not.
    assert red(rgb(0, info["px"])) and not red(rgb(0, info["py"]))
    assert red(rgb(9, info["py"])) and not red(rgb(9, info["px"]))
    idle = rgb(9, info["px"])
    assert abs(idle[0] - idle[1]) < 20 and idle[0] > 120  # silver: a grey
    # The base mat (steel blue, 70, 130, 180) covers its own centre in every frame (it moves
    # 5 in, its half-width is 20 in).
    for frame in (0, 9, 20):
        c = rgb(frame, info["mat"])
        assert c[2] > c[0] + 60


def test_femoat_render_run_draws_a_plan_run_in_top_view(tmp_path, render_backend):
    """``femoat render run run.npz`` on a plan run's file (femoat's own plan solver) writes the
    top view: as many frames as the plan decimation gives for the run (1.5 s at 10 fps over
    0..1.4 s: 15), not the 1D animation (which would refuse the file)."""
    from femoat.ground_motions.pair import fema_p695_pair
    from femoat.run import run
    from femoat.scenario import defaults, model_from_dict

    model = model_from_dict(defaults(plan=True))
    result = run(model, fema_p695_pair("farfield", 1, scale=3.0), duration=1.5)
    result.save(tmp_path / "run.npz")
    frames = plan_frames(PlanHistory.from_result(result), fps=10, end=1.4)
    assert len(frames["time"]) == 15
    script = textwrap.dedent("""
        import sys
        from femoat.cli import main
        sys.exit(main(["render", "run", "run.npz", "--gif", "plan.gif", "--fps", "10",
                       "--end", "1.4", "--size", "200x200"]))
    """)
    done = run_python(script, tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    assert "(15 frames)" in done.stdout
    from PIL import Image

    gif = Image.open(tmp_path / "plan.gif")
    assert gif.n_frames == 15 and gif.size == (200, 200)


def test_femoat_render_help_names_the_plan_top_view(capsys):
    from femoat.cli import main

    with pytest.raises(SystemExit):
        main(["render", "--help"])
    assert "top view" in capsys.readouterr().out

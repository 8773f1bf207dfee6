"""Renders of building runs: the wall at the peak impact (PNG) and the run animation (GIF).

The decimation and the peak state are plain computations, tested here directly. Everything that
draws runs in a subprocess (a missing OpenGL backend can crash VTK outright), which is skipped
only when plain pyvista cannot render a sphere off-screen; any other failure fails the test.
"""

import json
import textwrap
from pathlib import Path

import numpy as np
import pytest
from conftest import run_python

from femoat.render.animation import frame_states
from femoat.render.wall import peak_state, wall_field

ROOT = Path(__file__).resolve().parents[1]


# A building run with the 8-mode modal concrete wall (beam model) on both sides; shared by the
# in-process tests and, verbatim, by the render subprocess.
SETUP = textwrap.dedent("""
    from femoat.paper import paper_model, paper_motion
    from femoat.run import run
    from femoat.structure.pounding import MoatWall, PoundingModel
    from femoat.units import G
    from femoat.walls import ModalWall
    from femoat.walls.fe import beam_model, load_geometry, modal_analysis
    from femoat.walls.modal import contact_time
    model = beam_model(load_geometry({toml!r}))
    modes = modal_analysis(model, 40)
    paper = paper_model("concrete", "H", damping="consistent")
    law = paper.walls[0].law
    wall = ModalWall.from_fe(modes, contact_duration=contact_time(law, 10.0 / G, modes.M1),
                             damping_ratio=paper.walls[0].wall.damping_ratio)
    walls = tuple(MoatWall(w.law, wall, w.gap, w.side) for w in paper.walls)
    result = run(PoundingModel(paper.building, walls), paper_motion(quick=True), duration=3.0)
""").format(toml=str(ROOT / "meshes" / "concrete_wall.toml"))


@pytest.fixture(scope="module")
def modal_run():
    scope = {}
    exec(SETUP, scope)  # noqa: S102 - the same lines the render subprocess runs
    return scope["model"], scope["wall"], scope["result"]


def test_peak_state_is_the_largest_contact_force(modal_run):
    _, wall, result = modal_run
    state = peak_state(result)
    # The state's force is the run's largest sampled contact force (the impact table refines it
    # by a parabola, so it can only be a hair larger).
    assert state["force"] == pytest.approx(result.peaks["peak_impact_force"], rel=1e-3)
    assert state["force"] <= result.peaks["peak_impact_force"]
    # The impact-point displacement of the FE field equals Σ q_i (unit impact shapes, ψ = φ/p).
    model, _, _ = modal_run
    u = wall_field(wall, state)
    assert model.impact @ u == pytest.approx(state["impact_displacement"], rel=1e-10)
    with pytest.raises(ValueError, match="side = 'up'"):
        peak_state(result, "up")
    with pytest.raises(ValueError, match="render with the modal wall the run used"):
        wall_field(wall.truncated(3), state)


def test_frames_decimate_the_run(modal_run):
    _, _, result = modal_run
    f = frame_states(result, fps=10, speed=0.5, start=1.0, end=3.0)
    # Δ = speed/fps = 0.05 s over [1, 3] s: 41 frames at 1.00, 1.05, ..., 3.00.
    np.testing.assert_allclose(f["time"], 1.0 + 0.05 * np.arange(41), atol=1e-12)
    # Frame 20 is t = 2.0 s, interpolated linearly between the run's samples.
    np.testing.assert_allclose(
        f["displacement"][20],
        [np.interp(2.0, result.time, col) for col in result.displacement.T], atol=1e-14)
    # Every impact shows in the frame interval that holds its peak, with its peak force.
    for imp in result.impacts:
        if 1.0 < imp["start"] < 3.0:
            c = result.meta["contact_names"].index(imp["side"])
            assert f["contact"][:, c].any()
    assert f["force"].max() == pytest.approx(result.contact_force[result.time > 1.0].max())
    with pytest.raises(ValueError, match="more than max_frames"):
        frame_states(result, fps=1000, speed=0.01)
    with pytest.raises(ValueError, match="start = 2.0 and end = 1.0"):
        frame_states(result, start=2.0, end=1.0)


# ---- drawing, in a subprocess --------------------------------------------------------------




def _rgb(path):
    import matplotlib.image

    return matplotlib.image.imread(path)[..., :3]


def test_wall_peak_and_animation_render(tmp_path, render_backend):
    script = SETUP + textwrap.dedent("""
        import json
        from femoat.render.animation import animate_run, frame_states
        from femoat.render.wall import render_wall_peak
        _, state = render_wall_peak(model, wall, result, "wall_peak.png")
        animate_run(result, "run.gif", fps=10, speed=0.5, start=1.5, end=2.5,
                    window_size=(480, 300))
        f = frame_states(result, fps=10, speed=0.5, start=1.5, end=2.5)
        print(json.dumps(dict(frames=len(f["time"]),
                              hit=[int(k) for k in f["contact"].any(axis=1).nonzero()[0]],
                              quiet=[int(k) for k in (~f["contact"].any(axis=1)).nonzero()[0]],
                              magnification=state["magnification"])))
    """)
    done = run_python(script, tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    info = json.loads(done.stdout.strip().splitlines()[-1])
    png = _rgb(tmp_path / "wall_peak.png")
    assert png.std() > 0.05, "wall_peak.png is blank"
    # The deformed wall is coloured with viridis: its dark end (0.27, 0.00, 0.33) at the base.
    assert np.mean(np.all(np.abs(png - (0.27, 0.0, 0.33)) < 0.12, axis=-1)) > 1e-4
    # The impact arrow is red.
    assert np.mean(np.all(np.abs(png - (0.8, 0.0, 0.0)) < 0.25, axis=-1)) > 1e-4

    from PIL import Image, ImageSequence

    gif = Image.open(tmp_path / "run.gif")
    frames = [np.asarray(f.convert("RGB"), float) / 255 for f in ImageSequence.Iterator(gif)]
    # Δ = 0.5/10 = 0.05 s over [1.5, 2.5] s: 21 frames, all of them written.
    assert info["frames"] == 21 and len(frames) == 21
    assert frames[0].shape == (300, 480, 3)
    assert not np.array_equal(frames[0], frames[-1]), "the building does not move"
    # A wall in contact is drawn red (≈ 0.69, 0, 0 lit); walls out of contact are grey.
    red = [np.mean((f[..., 0] > 0.5) & (f[..., 1] < 0.2) & (f[..., 2] < 0.2)) for f in frames]
    assert info["hit"], "no impact between 1.5 and 2.5 s: the test run changed"
    assert min(red[k] for k in info["hit"]) > 1e-3
    assert max(red[k] for k in info["quiet"]) < 1e-4


def test_render_command(tmp_path, render_backend):
    toml = ROOT / "meshes" / "concrete_wall.toml"
    script = textwrap.dedent(f"""
        import argparse
        from femoat.commands import render
        parser = argparse.ArgumentParser(prog="femoat")
        render.add_parser(parser.add_subparsers(dest="command"))
        def call(*argv):
            args = parser.parse_args(["render", *argv])
            assert render.run(args) == 0
        call("wall", {str(toml)!r}, "--modes", "4", "--out", "wall.png", "--save-run", "run.npz")
        call("run", "run.npz", "--gif", "run.gif", "--fps", "5", "--start", "2", "--end", "3",
             "--size", "320x200")
        try:
            call("run", "run.npz", "--gif", "run.mp4")
        except ValueError as err:
            print("refused:", err)
    """)
    done = run_python(script, tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    assert "4 modes" in done.stdout
    assert "refused: --gif run.mp4" in done.stdout
    assert _rgb(tmp_path / "wall.png").std() > 0.05

    from PIL import Image

    gif = Image.open(tmp_path / "run.gif")
    # 5 frames per simulated second over [2, 3] s: 6 frames of 320 × 200.
    assert gif.n_frames == 6 and gif.size == (320, 200)

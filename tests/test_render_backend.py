"""femoat picks VTK's off-screen backend itself on a machine without a display: ``femoat
render`` used to print VTK's "bad X server connection" warning there before falling back."""

import os
import subprocess
import sys
from pathlib import Path

from femoat.render import backend

ROOT = Path(__file__).resolve().parents[1]


def test_headless_linux_gets_egl_or_osmesa(monkeypatch):
    monkeypatch.setattr(backend.sys, "platform", "linux")
    found = {"EGL": "libEGL.so.1", "OSMesa": "libOSMesa.so.8"}
    monkeypatch.setattr(backend.ctypes.util, "find_library", lambda name: found.get(name))
    env = {}
    assert backend.choose_offscreen_backend(env) == "vtkEGLRenderWindow"
    assert env == {"VTK_DEFAULT_OPENGL_WINDOW": "vtkEGLRenderWindow"}
    del found["EGL"]  # no libEGL: OSMesa
    env = {}
    assert backend.choose_offscreen_backend(env) == "vtkOSOpenGLRenderWindow"
    found.clear()  # neither: VTK keeps its own choice
    env = {}
    assert backend.choose_offscreen_backend(env) is None and env == {}


def test_a_display_or_the_users_choice_is_left_alone(monkeypatch):
    monkeypatch.setattr(backend.sys, "platform", "linux")
    monkeypatch.setattr(backend.ctypes.util, "find_library", lambda name: "lib.so")
    for env in ({"DISPLAY": ":0"}, {"WAYLAND_DISPLAY": "wayland-0"}):
        before = dict(env)
        assert backend.choose_offscreen_backend(env) is None and env == before
    env = {"VTK_DEFAULT_OPENGL_WINDOW": "vtkOSOpenGLRenderWindow"}
    assert backend.choose_offscreen_backend(env) == "vtkOSOpenGLRenderWindow"
    monkeypatch.setattr(backend.sys, "platform", "darwin")  # native windows off Linux
    assert backend.choose_offscreen_backend({}) is None


def test_render_command_on_a_headless_machine_prints_no_x_warning(tmp_path, render_backend):
    # a fresh process as a user starts it on a server: no DISPLAY, no VTK variable set
    env = {k: v for k, v in os.environ.items()
           if k not in ("DISPLAY", "WAYLAND_DISPLAY", "VTK_DEFAULT_OPENGL_WINDOW")}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    toml = ROOT / "meshes" / "concrete_wall.toml"
    code = ("from femoat.cli import main; raise SystemExit(main(['render', 'wall', "
            f"{str(toml)!r}, '--modes', '4', '--out', 'wall.png']))")
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=600, check=False)
    assert done.returncode == 0, done.stderr[-3000:]
    assert (tmp_path / "wall.png").stat().st_size > 1000
    assert "bad X server" not in done.stderr + done.stdout

"""Optional pieces that are missing make tests skip with one reason saying what to install, and
make commands fail with that sentence: never a collection error or a traceback.

Without libblas3/liblapack3, ``import openseespy`` raises ``RuntimeError("Failed to import
openseespy on Linux.")``, which ``pytest.importorskip`` does not catch. A fake ``openseespy`` first
on the path, whose import raises exactly that, stands in for such a machine.
"""

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
OPENSEES_TESTS = ["tests/test_materials_opensees.py", "tests/test_opensees_single_impact.py",
                  "tests/test_opensees_building.py"]


@pytest.fixture
def broken_opensees_env(tmp_path):
    fake = tmp_path / "fake" / "openseespy"
    (fake / "opensees").mkdir(parents=True)
    (fake / "__init__.py").write_text(
        'raise RuntimeError("Failed to import openseespy on Linux.")\n')
    (fake / "opensees" / "__init__.py").write_text("")
    path = [str(tmp_path / "fake"), str(ROOT), os.environ.get("PYTHONPATH", "")]
    return {**os.environ, "PYTHONPATH": os.pathsep.join(path)}


def _run(args, env, cwd=ROOT):
    return subprocess.run([sys.executable, *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=600, check=False)


def test_the_fake_openseespy_fails_like_a_machine_without_blas(broken_opensees_env):
    done = _run(["-c", "import openseespy.opensees"], broken_opensees_env)
    assert done.returncode != 0
    assert "RuntimeError: Failed to import openseespy on Linux." in done.stderr


def test_whole_test_folder_collects_without_errors(broken_opensees_env):
    # exit code 0 and no "error" line; before the fix: 2 collection errors, exit code 2.
    # --assert=plain: pytest's assertion rewriting (5 of the 8 s this collection takes) rewrites
    # assert statements only, never what a module imports, so it changes nothing checked here
    done = _run(["-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider",
                 "--assert=plain", "tests"], broken_opensees_env)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert "ERROR collecting" not in done.stdout
    assert "error" not in done.stdout.strip().splitlines()[-1]  # "N tests collected in ..."


@pytest.fixture(scope="module")
def opensees_tests_run(tmp_path_factory):
    """``pytest -m opensees`` on the OpenSees test files, openseespy broken: one run for them
    all (a Python start and a collection each cost about a second), its JUnit XML telling the
    files apart (the -rs summary lists a module's skip at the line of conftest.py that raised
    it). (the run, its test cases as (file stem, outcome tags, skip texts))"""
    tmp = tmp_path_factory.mktemp("broken")
    fake = tmp / "fake" / "openseespy"
    (fake / "opensees").mkdir(parents=True)
    (fake / "__init__.py").write_text(
        'raise RuntimeError("Failed to import openseespy on Linux.")\n')
    (fake / "opensees" / "__init__.py").write_text("")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(fake.parent), str(ROOT), os.environ.get("PYTHONPATH", "")])}
    done = _run(["-m", "pytest", "-q", "-rs", "-m", "opensees", "-p", "no:cacheprovider",
                 f"--junitxml={tmp / 'junit.xml'}", *OPENSEES_TESTS], env)
    import xml.etree.ElementTree as ET

    cases = []
    if (tmp / "junit.xml").is_file():
        for case in ET.parse(tmp / "junit.xml").iter("testcase"):
            module = case.get("classname") or case.get("name")  # a module's skip: its name
            cases.append((module.split(".")[-1], [c.tag for c in case],
                          [(c.text or "") + c.get("message", "") for c in case
                           if c.tag == "skipped"]))
    return done, cases


@pytest.mark.parametrize("test_file", OPENSEES_TESTS, ids=lambda f: Path(f).stem)
def test_opensees_tests_skip_with_one_reason(opensees_tests_run, test_file):
    done, cases = opensees_tests_run
    # pytest exits 5 ("no tests ran") when every module skips as a whole at collection
    assert done.returncode in (0, 5), done.stdout[-3000:] + done.stderr[-3000:]
    last = done.stdout.strip().splitlines()[-1]
    assert " skipped" in last and not any(w in last for w in ("passed", "failed", "error")), last
    mine = [c for c in cases if c[0] == Path(test_file).stem]
    assert mine, done.stdout
    for _, tags, texts in mine:  # skipped, each with one reason: the packages, the command,
        assert tags == ["skipped"], (tags, done.stdout)  # and what the import raised
        (text,) = texts
        assert "libblas3 and liblapack3" in text and "apt-get install libblas3 liblapack3" in text
        assert "RuntimeError: Failed to import openseespy on Linux." in text
    skips = [line for line in done.stdout.splitlines() if line.startswith("SKIPPED")]
    for line in skips:  # the summary the user reads says the same
        assert "libblas3 and liblapack3" in line and "apt-get install libblas3 liblapack3" in line
        assert "RuntimeError: Failed to import openseespy on Linux." in line


def test_opensees_command_explains_what_to_install(broken_opensees_env, tmp_path):
    scenario = ROOT / "studies" / "scenarios" / "paper_concrete_H.toml"
    done = _run(["-c", "from femoat.cli import main; raise SystemExit(main(['opensees', "
                 f"{str(scenario)!r}]))"], broken_opensees_env, cwd=tmp_path)
    assert done.returncode == 2
    assert "Traceback" not in done.stderr
    assert "apt-get install libblas3 liblapack3" in done.stderr
    assert "pip install femoat[verify]" in done.stderr


def test_render_tests_skip_with_one_reason_without_an_opengl_backend(tmp_path):
    # a pyvista whose import fails as it does without libGL stands in for a machine without any
    # OpenGL backend; the render tests skip (never crash or fail) and say what to install
    fake = tmp_path / "fake" / "pyvista"
    fake.mkdir(parents=True)
    (fake / "__init__.py").write_text(
        'raise ImportError("libGL.so.1: cannot open shared object file: No such file")\n')
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(tmp_path / "fake"), str(ROOT), os.environ.get("PYTHONPATH", "")])}
    done = _run(["-m", "pytest", "-q", "-rs", "-p", "no:cacheprovider",
                 "tests/test_wall_fe_render.py",
                 "tests/test_plan_render.py::test_plan_animation_flashes_the_wall_in_contact",
                 "tests/test_render_backend.py::"
                 "test_render_command_on_a_headless_machine_prints_no_x_warning"], env)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    skips = [line for line in done.stdout.splitlines() if line.startswith("SKIPPED")]
    assert skips and " passed" not in done.stdout and " failed" not in done.stdout
    for line in skips:
        assert "no off-screen render backend" in line and "apt-get install libegl1" in line

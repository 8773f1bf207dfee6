"""Processes starting together compile the solver one at a time: the first use of the solver in
a process holds a lock beside numba's cache (femoat.compilation.numba_cache.first_compile_lock),
so that the others wait and then load the kernels the first one wrote, instead of compiling the
same kernels side by side. Checked by the order of what two processes write, not by timing."""

import subprocess
import sys
import time

import pytest

from femoat.compilation import numba_cache

_HOLD = (
    "import sys, time\n"
    "from femoat.compilation.numba_cache import first_compile_lock\n"
    "log, module, tag, hold = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])\n"
    "with first_compile_lock(module):\n"
    "    with first_compile_lock(module):  # reentrant: a nested use passes through\n"
    "        open(log, 'a').write(tag + '-in\\n')\n"
    "        time.sleep(hold)\n"
    "        open(log, 'a').write(tag + '-out\\n')\n"
)


@pytest.mark.skipif(numba_cache.fcntl is None, reason="no fcntl: the lock is POSIX only")
def test_a_second_process_waits_for_the_first_compile(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba"))
    module = tmp_path / "pkg" / "driver.py"
    module.parent.mkdir()
    module.write_text("")
    log = tmp_path / "log.txt"
    first = subprocess.Popen([sys.executable, "-c", _HOLD, str(log), str(module), "a", "1.0"])
    deadline = time.monotonic() + 60
    while not (log.exists() and "a-in" in log.read_text()):  # a holds the lock now
        assert time.monotonic() < deadline and first.poll() is None, "the first never started"
        time.sleep(0.02)
    second = subprocess.run([sys.executable, "-c", _HOLD, str(log), str(module), "b", "0"],
                            timeout=120, check=True)
    assert first.wait(timeout=120) == 0 and second.returncode == 0
    # b entered only after a left: the two never held the lock together
    assert log.read_text().split() == ["a-in", "a-out", "b-in", "b-out"]
    # the lock lives beside numba's cache of that module, not in the working folder
    assert list((tmp_path / "numba").rglob("femoat-compile.lock"))

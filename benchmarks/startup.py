"""Start-up: what a fresh install and a new process pay before the solver runs.

    python benchmarks/startup.py [--skip-cold] [--compare-inliner] [--compare-ssa]
                                 [--compare-typing] [--compare-machine-code] [--compare-helper]

Prints, each in a fresh Python process:

1. **cold compile**: the solver's entry points compiled by numba from an empty cache (a private
   NUMBA_CACHE_DIR), in one process (no compile helper): CPU per top-level kernel (numba's
   compile events) and in all;
2. **a plan run after it**: the extra kernels a first plan run compiles (signatures that are
   not the 1D probe's), from the same cache;
3. **warm start**: a new process that finds the cache: wall and CPU from process start to a
   loaded solver (the probe run), and to a finished paper run; how many signatures it
   compiled (0: the cache served every one);
4. **first femoat paper** on empty caches (``--quick`` skipped: the whole study and its
   figures), end to end, wall clock, with the compile helper of
   :mod:`femoat.compilation.compile_plan` (``--compare-helper``: also without it).

``--compare-inliner``: step 1 again with numba's own inliner (``FEMOAT_FAST_INLINE=0``:
:mod:`femoat.compilation.inlining` not installed), side by side with femoat's (a few more
minutes). ``--compare-ssa``: step 1 again with numba's own SSA reconstruction
(``FEMOAT_FAST_SSA=0``: :mod:`femoat.compilation.ssa` not installed). ``--compare-typing``:
step 1 again with numba's own liveness analysis, call typing and flags
(``FEMOAT_FAST_LIVENESS=0 FEMOAT_CALL_TYPES_MEMO=0 FEMOAT_FAST_FLAGS=0``:
:mod:`femoat.compilation.liveness`, :mod:`~femoat.compilation.call_types` and
:mod:`~femoat.compilation.flags` not installed). ``--compare-machine-code``: step 1 again
with every kernel compiled to machine code at once, as numba does
(``FEMOAT_LAZY_MACHINE_CODE=0``: :mod:`femoat.compilation.machine_code` builds nothing late).

Numbers go to docs/startup.md and the README; nothing here is asserted.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

_COLD = r"""
import json, time
from numba.core import event as ev
top = {}
class L(ev.Listener):
    def __init__(s): s.depth = 0
    def on_start(s, e):
        s.depth += 1
        if s.depth == 1:
            s.t = time.process_time()
            d = e.data.get('dispatcher')
            s.name = d.py_func.__qualname__ if d else '?'
    def on_end(s, e):
        if s.depth == 1:
            top[s.name] = top.get(s.name, 0.0) + time.process_time() - s.t
        s.depth -= 1
ev.register("numba:compile", L())
from femoat.startup.warmup import warm_up
total = warm_up()
t = time.process_time()
from femoat.ground_motions.pair import fema_p695_pair
from femoat.plan import PlanModel
from femoat.run import run
pair = fema_p695_pair("farfield", 1)
before = dict(top)
run(PlanModel(), pair, duration=1.0)
plan = time.process_time() - t
print(json.dumps({"total": total, "top": before, "plan_extra": plan,
                  "plan_kernels": {k: v - before.get(k, 0.0) for k, v in top.items()
                                   if v - before.get(k, 0.0) > 0.05}}))
"""

_WARM = r"""
import json, time
from femoat.startup.warmup import warm_up
from femoat.compilation.exports import EXPORTS
from femoat.integration.solve import kernels
cpu = warm_up()
k = kernels()
misses = sum(sum(getattr(k, n).dispatcher.stats.cache_misses.values()) for n in EXPORTS)
print(json.dumps({"warm_up_cpu": cpu, "compiled": misses}))
"""

_PAPER_RUN = ("from femoat.paper import paper_model, paper_motion; from femoat.run import run; "
              "run(paper_model('steel', 'J'), paper_motion())")


def _python(code, env):
    t0 = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=env, cwd=ROOT, check=False)
    wall = time.perf_counter() - t0
    if done.returncode != 0:
        raise SystemExit(done.stderr[-3000:])
    return done.stdout, wall


def _cpu_of_children(fn):
    before = os.times()
    out = fn()
    after = os.times()
    return out, (after.children_user - before.children_user
                 + after.children_system - before.children_system)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--skip-cold", action="store_true",
                    help="only the warm start (the cold compile takes minutes)")
    ap.add_argument("--compare-inliner", action="store_true",
                    help="also the cold compile with numba's own inliner (FEMOAT_FAST_INLINE=0)")
    ap.add_argument("--compare-ssa", action="store_true",
                    help="also the cold compile with numba's own SSA reconstruction "
                         "(FEMOAT_FAST_SSA=0)")
    ap.add_argument("--compare-typing", action="store_true",
                    help="also the cold compile with numba's own liveness analysis, call "
                         "typing and flags (FEMOAT_FAST_LIVENESS=0 FEMOAT_CALL_TYPES_MEMO=0 "
                         "FEMOAT_FAST_FLAGS=0)")
    ap.add_argument("--compare-helper", action="store_true",
                    help="also the first femoat paper without the compile helper "
                         "(FEMOAT_COMPILE_HELPER=0)")
    ap.add_argument("--compare-machine-code", action="store_true",
                    help="also the cold compile with every kernel compiled to machine code at "
                         "once (FEMOAT_LAZY_MACHINE_CODE=0)")
    args = ap.parse_args(argv)
    base = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT),
                                                         os.environ.get("PYTHONPATH", "")])}
    print(f"load average before: {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    if not args.skip_cold:
        with tempfile.TemporaryDirectory(prefix="femoat-startup-") as cache:
            env = {**base, "NUMBA_CACHE_DIR": cache, "FEMOAT_COMPILE_HELPER": "0"}
            out, wall = _python(_COLD, env)
            cold = json.loads(out.strip().splitlines()[-1])
            print(f"1. cold compile of the solver's entry points: {cold['total']:.1f} s CPU "
                  f"({wall:.1f} s wall for the process)")
            for name, cpu in sorted(cold["top"].items(), key=lambda kv: -kv[1]):
                if cpu > 0.5:
                    print(f"     {name:28s}{cpu:8.1f} s")
            typing = ("FEMOAT_FAST_LIVENESS", "FEMOAT_CALL_TYPES_MEMO", "FEMOAT_FAST_FLAGS")
            for wanted, switches, what in (
                    (args.compare_inliner, ("FEMOAT_FAST_INLINE",), "inliner"),
                    (args.compare_ssa, ("FEMOAT_FAST_SSA",), "SSA reconstruction"),
                    (args.compare_typing, typing, "liveness, call typing and flags"),
                    (args.compare_machine_code, ("FEMOAT_LAZY_MACHINE_CODE",),
                     "machine code for every kernel")):
                if wanted:
                    off = dict.fromkeys(switches, "0")
                    with tempfile.TemporaryDirectory(prefix="femoat-startup-") as plain:
                        out, wall = _python(_COLD, {**env, "NUMBA_CACHE_DIR": plain, **off})
                    own = json.loads(out.strip().splitlines()[-1])
                    print(f"   with numba's own {what} ({'=0 '.join(switches)}=0): "
                          f"{own['total']:.1f} s CPU ({wall:.1f} s wall); run_chunk "
                          f"{own['top'].get('run_chunk', 0):.1f} s")
            print(f"2. a first plan run after it: {cold['plan_extra']:.1f} s CPU in all "
                  f"(kernels compiled for it: {cold['plan_kernels'] or 'none'})")
            (out, wall), cpu = _cpu_of_children(lambda: _python(_WARM, env))
            warm = json.loads(out.strip().splitlines()[-1])
            print(f"3. warm start (new process, numba's cache): {wall:.2f} s wall, {cpu:.2f} s "
                  f"CPU from process start to a loaded solver; signatures compiled: "
                  f"{warm['compiled']}")
            (_, wall), cpu = _cpu_of_children(lambda: _python(_PAPER_RUN, env))
            print(f"   ... to a finished paper run: {wall:.2f} s wall, {cpu:.2f} s CPU")
        for helper in ("1", "0") if args.compare_helper else ("1",):
            with tempfile.TemporaryDirectory(prefix="femoat-paper-") as work:
                env = {**base, "NUMBA_CACHE_DIR": str(Path(work) / "numba"),
                       "FEMOAT_CACHE": str(Path(work) / "cache"), "FEMOAT_COMPILE_HELPER": helper}
                code = ("from femoat.cli import main; raise SystemExit(main(['paper', '--out', "
                        f"{str(Path(work) / 'paper')!r}]))")
                (_, wall), cpu = _cpu_of_children(lambda: _python(code, env))
                how = ("the compile helper beside it" if helper == "1"
                       else "no helper: FEMOAT_COMPILE_HELPER=0")
                print(f"4. first femoat paper on empty caches ({how}): {wall:.1f} s wall, "
                      f"{cpu:.1f} s CPU (compile, 10 runs, figures)")
                if helper == "1":
                    (_, wall), cpu = _cpu_of_children(lambda: _python(code, env))
                    print(f"   a second femoat paper: {wall:.1f} s wall, {cpu:.1f} s CPU")
    else:
        (out, wall), cpu = _cpu_of_children(lambda: _python(_WARM, base))
        warm = json.loads(out.strip().splitlines()[-1])
        print(f"warm start (new process, numba's cache): {wall:.2f} s wall, {cpu:.2f} s CPU; "
              f"signatures compiled: {warm['compiled']}")
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()

"""Where a run's CPU goes inside the compiled loop: ``perf`` samples with femoat's kernels named.

numba's JIT code has no symbols ``perf`` can see (a report shows bare addresses or one
anonymous block). This script compiles the kernels in a private numba cache (a library loaded
from numba's cache keeps no LLVM module to list its functions from: about two minutes of
compile first), writes ``/tmp/perf-<pid>.map`` (the address and size of every compiled function,
demangled: ``integration.methods.ark5.coupled_step``, ...), which ``perf report`` reads for JIT
code, then runs the chosen model over and over while ``perf record`` samples this process, and
prints perf's table by function (self time; what LLVM inlined is counted in its caller).

    python benchmarks/jit_profile.py [--isolator fp|lrb|tfp] [--pair 12] [--angle 0]
                                     [--oned] [--seconds 15] [--top 25]

The model: the paper building in plan in the concrete moat (law H, 4 in gaps) on the given
isolator, FEMA P695 far-field pair ``--pair`` at the MCE (time x 0.5, as ``plan_speed.py
--mce``), at its default method, no history (a suite's run); ``--oned``: the 1D model along x
under the pair's x component. Needs ``perf`` (linux-tools) and permission to sample a process
(``kernel.perf_event_paranoid`` <= 1, or root). It reads numba's internals (a library's
``_final_module`` and its codegen's engine, as of numba 0.68): a benchmark tool, not the API.
"""

import argparse
import gc
import os
import shutil
import subprocess
import sys
import tempfile
import time


def demangle(name):
    """``_ZN6femoat11integration...`` → ``integration...`` (numba's Itanium-style names: each
    part its length then its text; the leading ``femoat`` dropped)."""
    if not name.startswith("_ZN"):
        return name
    i, parts = 3, []
    while i < len(name) and name[i].isdigit():
        j = i
        while name[j].isdigit():
            j += 1
        n = int(name[i:j])
        parts.append(name[j:j + n])
        i = j + n
    return ".".join(parts[1:] if parts and parts[0] == "femoat" else parts) or name


def write_perf_map(path):
    """Every compiled function of every numba dispatcher in this process, as perf's JIT map
    (``start size name`` in hex, sorted; a function's size is the distance to the next one)."""
    from numba.core.registry import CPUDispatcher

    syms = {}
    for obj in gc.get_objects():
        if not isinstance(obj, CPUDispatcher):
            continue
        for cres in obj.overloads.values():
            lib = cres.library
            module = getattr(lib, "_final_module", None)
            if module is None:  # loaded from numba's cache: no module to list
                continue
            for f in module.functions:
                if f.is_declaration:
                    continue
                try:
                    address = lib._codegen._engine.get_function_address(f.name)
                except Exception:  # noqa: BLE001 (a symbol the engine does not export)
                    continue
                if address:
                    syms[address] = demangle(f.name)
    starts = sorted(syms)
    with open(path, "w", encoding="utf-8") as fh:
        for i, a in enumerate(starts):
            size = min(starts[i + 1] - a if i + 1 < len(starts) else 1 << 16, 1 << 20)
            fh.write(f"{a:x} {size:x} {syms[a]}\n")
    return len(starts)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--isolator", choices=("fp", "lrb", "tfp"), default="fp")
    ap.add_argument("--pair", type=int, default=12)
    ap.add_argument("--angle", type=float, default=0.0)
    ap.add_argument("--oned", action="store_true", help="the 1D model along x instead")
    ap.add_argument("--seconds", type=float, default=15.0, help="sampling time [s]")
    ap.add_argument("--top", type=int, default=25)
    args = ap.parse_args()
    perf = shutil.which("perf")
    if perf is None:
        sys.exit("jit_profile: perf is not installed (linux-tools); nothing to sample with.")
    cache = tempfile.mkdtemp(prefix="femoat-jit-profile-")
    os.environ["NUMBA_CACHE_DIR"] = cache  # before numba is imported: a fresh compile

    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from plan_speed import _pairs

    from femoat.plan import PlanBuilding, PlanModel, rectangular_moat
    from femoat.run import run

    building = PlanBuilding()
    if args.isolator == "lrb":
        from femoat.bearings.lead_rubber import LeadRubberBearing

        building = PlanBuilding(isolator=LeadRubberBearing())
    elif args.isolator == "tfp":
        from femoat.bearings.triple_friction_pendulum import TripleFrictionPendulum

        building = PlanBuilding(isolator=TripleFrictionPendulum())
    model = PlanModel(building, rectangular_moat("concrete", "H", gap=4.0))
    ns = argparse.Namespace(mce=True, pairs=[args.pair], angles=[args.angle], seconds=12,
                            factor=2)
    label, pair = list(_pairs(ns))[0]
    if args.oned:
        model, motion = model.along("x"), pair.x
    else:
        motion = pair
    duration = pair.duration + 1
    t0 = time.process_time()
    run(model, motion, duration=duration, history=False)
    print(f"compiled in {time.process_time() - t0:.0f} s of CPU (cache {cache})", flush=True)
    n = write_perf_map(f"/tmp/perf-{os.getpid()}.map")
    data = os.path.join(cache, "perf.data")
    rec = subprocess.Popen([perf, "record", "-q", "-F", "999", "-p", str(os.getpid()), "-o", data,
                            "--", "sleep", str(args.seconds)],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    runs, t_end = 0, time.time() + args.seconds
    while time.time() < t_end:
        run(model, motion, duration=duration, history=False)
        runs += 1
    rec.wait()
    if rec.returncode != 0:
        sys.exit(f"jit_profile: perf record failed: {rec.stderr.read().decode().strip()}")
    what = f"{'1D along x' if args.oned else 'plan'} {args.isolator} pair {label}"
    print(f"{what}: {runs} runs in {args.seconds:g} s ({1e3 * args.seconds / max(runs, 1):.1f} "
          f"ms a run, Python included); {n} compiled functions mapped")
    report = subprocess.run([perf, "report", "-i", data, "--no-children", "--sort", "symbol",
                             "--stdio"], capture_output=True, text=True, check=False)
    rows = [r for r in report.stdout.splitlines() if "%" in r and not r.startswith("#")]
    for r in rows[:args.top]:
        print(" ".join(r.split()[:1] + r.split()[2:3]))
    shutil.rmtree(cache, ignore_errors=True)
    os.remove(f"/tmp/perf-{os.getpid()}.map")


if __name__ == "__main__":
    main()

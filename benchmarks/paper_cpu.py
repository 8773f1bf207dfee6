"""CPU time per paper run (the compiled loop only, best of N), for before/after comparisons.

    python benchmarks/paper_cpu.py [--repeat 5] [--damping published]

A reduced :mod:`paper_runs` (no accuracy reference, no second process): prints one line per run
and the total, and a JSON line for scripts. To compare two checkouts in one session, run it
with ``PYTHONPATH`` set to each in turn, alternating, and compare the best of the rounds.
"""

import argparse
import json

from femoat.paper import LAWS, WALLS, paper_model, paper_motion
from femoat.run import run


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--damping", default="published")
    args = ap.parse_args(argv)
    motion = paper_motion()
    run(paper_model("concrete", "H"), motion)  # compile / load first
    out = {}
    for wall in WALLS:
        for law in LAWS:
            model = paper_model(wall, law, args.damping)
            best = min(run(model, motion).meta["stats"]["cpu_seconds"]
                       for _ in range(args.repeat))
            out[f"{wall}/{law}"] = best
            print(f"{wall:9s}{law:3s}{best * 1e3:9.2f} ms", flush=True)
    print(f"total {sum(out.values()) * 1e3:.1f} ms")
    print(json.dumps(out))


if __name__ == "__main__":
    main()

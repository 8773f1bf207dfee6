"""``femoat compile``: compile the solver's kernels into numba's on-disk cache, now."""


def add_parser(sub):
    p = sub.add_parser(
        "compile",
        help="compile the building solver's kernels into numba's cache (once per install)",
        description="Compile the building solver's kernels with numba and keep them in numba's "
        "on-disk cache (the __pycache__ folders beside femoat's sources, or $NUMBA_CACHE_DIR), "
        "so that every later process (a run, the paper study, each Dask worker of a suite) "
        "loads them in about a second. Any first run does the same on its own; this command "
        "does it ahead, e.g. before a cluster's workers start from a shared install.",
    )
    p.add_argument("--bearings", default=None,
                   help="the bearing kinds the loop carries: 'all' (default; what a Python "
                   "session and any model of another bearing use) or 'fp' (the loop that the "
                   "paper study and the single pendulum's scenarios and suites compile, "
                   "smaller); default: $FEMOAT_BEARINGS, else all")
    return p


def run(args):
    import os

    from femoat.bearings import registry
    from femoat.startup.warmup import warm_up

    chosen = args.bearings or os.environ.get(registry.ENV, "").strip() or "all"
    kinds = registry.select(chosen)
    cpu = warm_up()
    names = ", ".join(registry.keys()[k] for k in kinds)
    print(f"solver kernels (bearing kinds {names}) compiled or loaded from numba's cache in "
          f"{cpu:.1f} s of CPU")
    return 0

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
    return p


def run(args):
    from femoat.startup.warmup import warm_up

    cpu = warm_up()
    print(f"solver kernels compiled or loaded from numba's cache in {cpu:.1f} s of CPU")
    return 0

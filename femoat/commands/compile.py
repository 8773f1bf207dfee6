"""``femoat compile``: build the solver's ahead-of-time kernels (fast process start)."""


def add_parser(sub):
    p = sub.add_parser(
        "compile",
        help="compile the building solver ahead of time so that new processes start fast",
        description="Compile the building solver's kernels with numba.pycc into femoat's cache "
        "folder ($FEMOAT_CACHE or ~/.cache/femoat/aot). Later processes load them without "
        "importing numba (about 1 s saved per process). femoat paper and femoat run do this "
        "once on their own; FEMOAT_AOT=0 switches it off.",
    )
    p.add_argument("--force", action="store_true", help="rebuild even if it is up to date")
    p.add_argument("--check", action="store_true",
                   help="only say whether the compiled kernels are up to date (exit 1 if not)")
    return p


def run(args):
    import time

    from femoat.compilation import aot, aot_build

    path = aot.module_path()
    if args.check:
        ok = path.is_file() and aot.load() is not None
        state = "up to date" if ok else "not built for this femoat, Python and numba"
        print(f"{path}: {state}{'' if aot.enabled() else ' (switched off: FEMOAT_AOT=0)'}")
        return 0 if ok else 1
    if not aot.enabled():
        raise ValueError("ahead-of-time kernels are switched off (FEMOAT_AOT=0 or "
                         "FEMOAT_CACHE=off); unset it to compile")
    clock = time.perf_counter()
    try:
        path = aot_build.build(force=args.force)
    except RuntimeError as err:
        raise ValueError(str(err)) from None
    print(f"wrote {path} ({time.perf_counter() - clock:.1f} s)")
    return 0

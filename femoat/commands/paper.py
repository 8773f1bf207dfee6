"""``femoat paper``: the paper study (5 laws × 2 walls) with Figs. 4-7 and a summary table."""

from pathlib import Path

from femoat.integration.settings import DEFAULT_RTOL, METHODS, Integrator
from femoat.walls.presets import DAMPING_CHOICES


def add_parser(sub):
    p = sub.add_parser(
        "paper",
        help="reproduce the paper study: Figs. 4-7, global response, summary table",
        description="Run the default quarter-scale building between two moat walls (gap 4 in) "
        "for the five contact laws and both wall presets under Erzincan N-S (PGA 0.91 g, time "
        "scale 0.5); write Figs. 4-7, the global response, summary.csv and impacts.csv.",
    )
    p.add_argument("--damping", default="published", choices=DAMPING_CHOICES,
                   help="wall dashpot C_imp: 'published' (Table 3) or 'consistent' "
                   "(2·xi_imp·sqrt(K1·M1)) (default: published)")
    p.add_argument("--quick", action="store_true",
                   help="only the first 4 s of the record (all impacts of the default model)")
    p.add_argument("--calibrate", action="store_true",
                   help="calibrate each damped law to reach e = 0.70 exactly at 10 in/s")
    p.add_argument("--method", default=Integrator().method, choices=METHODS,
                   help="integration method of the open phase: 'dp5' (fifth order, the "
                   "default), 'tsit5' (the same step with Tsitouras' pair), 'ark5' (dp5 on "
                   "these 1D models) or 'newmark' (Newmark throughout); contact is always "
                   "Newmark")
    p.add_argument("--rtol", type=float, default=None,
                   help="solver accuracy (local error / DOF scale; default: the method's, "
                   + ", ".join(f"{m} {r:g}" for m, r in DEFAULT_RTOL.items()) + ")")
    p.add_argument("--no-figures", action="store_true", help="skip the figures")
    p.add_argument("--out", type=Path, default=None,
                   help="output folder (default: ./femoat_output/paper for the headline study, "
                   "./femoat_output/paper-<options> for a variant, e.g. paper-consistent-quick, "
                   "so that a variant never overwrites the headline study)")
    return p


def default_folder(args):
    """femoat_output/paper, with the non-default options appended: one folder per variant."""
    parts = [args.damping] if args.damping != "published" else []
    parts += [name for name in ("quick", "calibrate") if getattr(args, name)]
    if args.method != Integrator().method:
        parts.append(args.method)
    if args.rtol is not None and args.rtol != Integrator(method=args.method).rtol:
        parts.append(f"rtol{args.rtol:g}")
    return Path("femoat_output") / "-".join(["paper", *parts])


def run(args):
    from femoat.startup.bearing_kinds import select_for
    from femoat.structure.building import Building

    select_for([Building()])  # the paper's building: its loop carries the pendulum alone
    from femoat.paper import run_paper_study
    from femoat.report import format_table, summary_rows, write_outputs

    runs, motion = run_paper_study(damping=args.damping, quick=args.quick,
                                   calibrate=args.calibrate,
                                   integrator=Integrator(method=args.method, rtol=args.rtol))
    out = args.out or default_folder(args)
    paths = write_outputs(runs, motion, out, args.damping, figures=not args.no_figures)
    print(f"Paper study, C_imp = {args.damping}: {motion.name}, PGA {motion.pga:.2f} g")
    print(format_table(summary_rows(runs)))
    for p in paths:
        print(f"wrote {p}")
    return 0

"""``femoat contact-curves``: the paper's Fig. 1 (force-indentation loops of all five laws)."""

from pathlib import Path

from femoat.walls.presets import DAMPING_CHOICES, PRESETS


def add_parser(sub):
    p = sub.add_parser(
        "contact-curves",
        help="Fig. 1: force-indentation loops of the five contact laws",
        description="Simulate one impact of m_eff per contact law against a rigid stop (the "
        "default; --sdof-wall for the preset's wall) and write the force-indentation loops "
        "(PNG) and the histories (CSV).",
    )
    p.add_argument("--wall", default="concrete", choices=PRESETS,
                   help="wall preset giving the contact parameters (default: concrete)")
    p.add_argument("--v0", type=float, default=10.0, help="impact speed [in/s] (default: 10)")
    p.add_argument("--sdof-wall", action="store_true",
                   help="hit the preset's SDOF wall (default: a rigid stop)")
    p.add_argument("--damping", default="published", choices=DAMPING_CHOICES,
                   help="C_imp choice when --sdof-wall is given (default: published)")
    p.add_argument("--calibrate", action="store_true",
                   help="calibrate each damped law to reach e exactly at v0")
    p.add_argument("--out", default="femoat_output", type=Path,
                   help="output folder (default: ./femoat_output)")
    return p


def run(args):
    from femoat.impact.study import impact_all_laws  # scipy.integrate: imported when used

    from femoat.plotting.contact_curves import plot_contact_curves, write_contact_curves_csv

    results = impact_all_laws(args.wall, args.v0, rigid=not args.sdof_wall,
                              calibrate=args.calibrate, damping=args.damping)
    stem = f"fig1_contact_curves_{args.wall}_v{args.v0:g}" + ("_cal" if args.calibrate else "")
    png, csv_path = args.out / f"{stem}.png", args.out / f"{stem}.csv"
    target = "SDOF wall" if args.sdof_wall else "rigid stop"
    plot_contact_curves(results, png, title=f"{args.wall} contact parameters, v0 = {args.v0:g} "
                        f"in/s, {target}" + (", calibrated" if args.calibrate else ""))
    write_contact_curves_csv(results, csv_path)
    print(f"{args.wall} contact parameters, v0 = {args.v0:g} in/s into a {target}"
          + ("" if args.sdof_wall else " (default; --sdof-wall for the preset's wall)"))
    print(f"{'law':4s}{'peak force [kip]':>18s}{'max indent. [in]':>18s}{'duration [ms]':>15s}"
          f"{'e [-]':>9s}")
    for kind, r in results.items():
        print(f"{kind:4s}{r.peak_force:18.4f}{r.max_indentation:18.6f}"
              f"{r.contact_duration * 1e3:15.4f}{r.restitution:9.4f}")
    print(f"wrote {png}\nwrote {csv_path}")
    return 0

"""SDOF and modal walls against the full finite-element wall, for single impacts.

A mass W/g hits the paper's calibrated walls (meshes/<wall>_wall.toml, beam model, undamped)
through the Hertzdamp law of the wall's Table 3 contact set, at speed v0. For each case the full
FE wall (Newmark, femoat.walls.fe.transient) is the reference; the table gives the contact
duration t_c against the wall's first two periods, the SDOF wall's errors (K1, M1 of mode 1) and
the error of the modal wall with N chosen automatically (flexibility >= 0.99 and every mode below
4/t_c, t_c = femoat.walls.modal.contact_time of the mass and the wall's M1), plus the
residual-flexibility vector of the modes left out ("modal N" counts the eigenmodes).

    python studies/sdof_vs_fe.py            # the table (about a minute)
    python studies/sdof_vs_fe.py --csv out.csv
"""

import argparse
import csv
import sys
import time

import numpy as np

WEIGHTS = (0.29, 3.0, 10.0, 33.0)  # [kip]: the contact's m_eff·g, a light base mat, the default
# building's base mat and the whole default building
SPEEDS = (0.01, 0.1, 1.0, 10.0)  # [in/s]
COLUMNS = ("wall", "law", "W [kip]", "v0 [in/s]", "t_c [ms]", "t_c/T1", "t_c/T2",
           "FE peak force [kip]", "SDOF peak force err", "SDOF wall disp err", "SDOF t_c err",
           "SDOF e - FE e", "modal N", "modal peak force err", "modal history err", "FE [s]")


def case(wall, law_kind, weight, v0, model=None, modes=None):
    """One row: FE reference, SDOF wall and automatic modal wall for one impact."""
    from femoat.contact import make_law
    from femoat.impact import simulate_impact
    from femoat.units import G
    from femoat.walls import ModalWall, SdofWall, wall_preset
    from femoat.walls.fe.transient import fe_impact, impact_errors
    from femoat.walls.modal import contact_time

    law = make_law(law_kind, wall_preset(wall).contact)
    mass = weight / G
    clock = time.perf_counter()
    fe = fe_impact(model, law, v0, mass=mass, steps_per_contact=500)
    seconds = time.perf_counter() - clock
    sdof = simulate_impact(law, v0, wall=SdofWall(modes.K1, modes.M1, 0.0), mass=mass)
    modal_wall = ModalWall.from_fe(modes, contact_duration=contact_time(law, mass, modes.M1))
    modal = simulate_impact(law, v0, wall=modal_wall, mass=mass)
    es, em = impact_errors(sdof, fe), impact_errors(modal, fe)
    t1, t2 = 1.0 / modes.frequencies[0], 1.0 / modes.frequencies[1]
    return {
        "wall": wall, "law": law_kind, "W [kip]": weight, "v0 [in/s]": v0,
        "t_c [ms]": 1e3 * fe.contact_duration, "t_c/T1": fe.contact_duration / t1,
        "t_c/T2": fe.contact_duration / t2, "FE peak force [kip]": fe.peak_force,
        "SDOF peak force err": es["peak_force"], "SDOF wall disp err": es["peak_wall_displacement"],
        "SDOF t_c err": es["contact_duration"], "SDOF e - FE e": es["restitution"],
        "modal N": modal_wall.n_modes - modal_wall.residual, "modal peak force err": em["peak_force"],
        "modal history err": em["force_history"], "FE [s]": seconds,
    }


def study(walls=("concrete", "steel"), law="H", weights=WEIGHTS, speeds=SPEEDS):
    from femoat.walls.fe import beam_model, load_geometry, modal_analysis

    rows = []
    for wall in walls:
        model = beam_model(load_geometry(f"meshes/{wall}_wall.toml"))
        modes = modal_analysis(model, 40)
        for weight in weights:
            for v0 in speeds:
                rows.append(case(wall, law, weight, v0, model, modes))
                print(_format(rows[-1]), file=sys.stderr, flush=True)
    return sorted(rows, key=lambda r: (r["wall"], r["t_c/T2"]))


def _format(row):
    cells = []
    for key in COLUMNS:
        value = row[key]
        if isinstance(value, str) or key == "modal N":
            cells.append(f"{value}")
        elif "err" in key or key.startswith("SDOF e"):
            cells.append(f"{100 * value:+.1f}%" if "modal" not in key else f"{100 * value:.2f}%")
        else:
            cells.append(f"{value:.3g}")
    return " | ".join(cells)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--csv", default=None, help="also write the rows to this CSV file")
    parser.add_argument("--law", default="H", help="contact law letter (default H)")
    args = parser.parse_args(argv)
    np.set_printoptions(precision=4)
    rows = study(law=args.law)
    print("| " + " | ".join(COLUMNS) + " |")
    print("|" + "---|" * len(COLUMNS))
    for row in rows:
        print("| " + _format(row) + " |")
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            writer = csv.DictWriter(fh, fieldnames=COLUMNS)
            writer.writeheader()
            writer.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())

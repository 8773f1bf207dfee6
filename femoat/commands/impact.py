"""``femoat impact``: one impact of m_eff through one contact law."""

import json

from femoat.contact.laws import LAW_CODES, LAW_NAMES, make_law
from femoat.walls.presets import DAMPING_CHOICES, PRESETS, wall_preset


def add_parser(sub):
    p = sub.add_parser(
        "impact",
        help="simulate one impact through one contact law",
        description="Simulate the effective mass m_eff of a wall preset hitting a rigid stop or "
        "the preset's SDOF wall (Masroor element; the default) at speed v0 through one contact "
        "law. "
        "Prints peak force [kip], max indentation [in], contact duration [s], achieved "
        "restitution and dissipated energy [kip·in].",
    )
    p.add_argument("--law", required=True, choices=list(LAW_CODES),
                   help="contact law: " + ", ".join(f"{k} {v}" for k, v in LAW_NAMES.items()))
    p.add_argument("--wall", default="concrete", choices=PRESETS,
                   help="wall preset of the paper's Table 3 (default: concrete)")
    p.add_argument("--v0", type=float, default=10.0, help="impact speed [in/s] (default: 10)")
    p.add_argument("--rigid", action="store_true",
                   help="hit a rigid stop (default: the preset's SDOF wall, Masroor element)")
    p.add_argument("--calibrate", action="store_true",
                   help="calibrate the law's damping parameter so that a rigid-stop impact at "
                   "v0 reaches the preset's e exactly")
    p.add_argument("--damping", default="published", choices=DAMPING_CHOICES,
                   help="wall dashpot C_imp: 'published' (Table 3: 3.3 / 5.1 kip·s/in) or "
                   "'consistent' (2·xi_imp·sqrt(K1·M1)) (default: published)")
    p.add_argument("--allow-tension", action="store_true",
                   help="Kelvin-Voigt only: keep contact and pull until the indentation is zero")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    return p


def run(args):
    from femoat.impact.calibration import achieved_restitution, calibrate
    from femoat.impact.single import simulate_impact  # scipy.integrate: imported when used

    preset = wall_preset(args.wall, damping=args.damping)
    law = make_law(args.law, preset.contact, allow_tension=args.allow_tension)
    uncalibrated_e = None
    if args.calibrate and law.calibratable:
        uncalibrated_e = achieved_restitution(law, args.v0)
        law = calibrate(law, args.v0)
    wall = None if args.rigid else preset.wall
    r = simulate_impact(law, args.v0, wall=wall)
    out = r.summary()
    out.update(
        wall=preset.name,
        damping=args.damping if wall is not None else None,
        wall_damping=wall.damping if wall is not None else None,
        calibrated=bool(args.calibrate and law.calibratable),
        target_restitution=preset.contact.e,
        uncalibrated_restitution_rigid=uncalibrated_e,
        delta_me=law.params.delta_me,
        units=dict(peak_force="kip", max_indentation="in", contact_duration="s",
                   dissipated_energy="kip*in", v0="in/s", wall_damping="kip*s/in"),
    )
    if args.json:
        print(json.dumps(out))
    else:
        where = "a rigid stop" if wall is None else (
            f"the {preset.name} SDOF wall (C_imp = {wall.damping:.4g} kip·s/in, {args.damping})")
        print(f"Law {law.kind} ({law.name}), v0 = {args.v0} in/s into {where}:")
        print(f"  peak force        {r.peak_force:10.4f} kip")
        print(f"  max indentation   {r.max_indentation:10.6f} in")
        print(f"  contact duration  {r.contact_duration * 1e3:10.4f} ms")
        print(f"  restitution       {r.restitution:10.5f}")
        print(f"  dissipated energy {r.dissipated_energy:10.4e} kip·in (contact)")
        if wall is not None:
            print(f"  wall dashpot      {r.wall_dissipated_energy:10.4e} kip·in")
            print(f"  peak wall disp.   {r.peak_wall_displacement:10.6f} in")
    return 0

"""``femoat render``: off-screen pictures of building runs (pyvista).

    femoat render wall meshes/concrete_wall.toml --model beam --out wall_peak.png
    femoat render wall meshes/concrete_wall.vtu --scenario my.toml --save-run run.npz
    femoat render run run.npz --gif run.gif --speed 0.5 --start 1.5 --end 3
    femoat render run studies/scenarios/paper_concrete_H.toml --gif run.gif
    femoat render run examples/plan_building.toml --gif plan.gif   (a plan run: the top view)

``render wall`` builds a modal wall from the finite-element wall (N from the flexibility target
and the contact time of the base mat on the wall, or ``--modes``), runs the building with it on
both sides (the scenario's building, law, gap and motion, or the paper model under the first 4 s
of Erzincan), and draws the wall's deformed shape at the peak impact. ``render run`` animates a
run (a saved run.npz, or a scenario that is run first) as a GIF; a building in plan in top view
(the base mat moving in its moat, each wall red while in contact).

Headless machines: set VTK_DEFAULT_OPENGL_WINDOW=vtkEGLRenderWindow.
"""

from pathlib import Path

from femoat.walls import kinds


def add_parser(sub):
    p = sub.add_parser(
        "render",
        help="pictures of runs: the wall at the peak impact (PNG), a run animation (GIF; a "
        "building in plan: the top view of the base mat in its moat)",
        description=__doc__.split("\n\n")[2].replace("\n", " "),
    )
    what = p.add_subparsers(dest="what", metavar="WHAT")
    what.required = True

    w = what.add_parser(
        "wall", help="the finite-element wall deformed at the peak impact of a building run",
        description="Modal wall from a geometry TOML or a mesh, building run with it, PNG of the "
        "wall's displacement field u = sum(psi_i q_i) at the largest contact force.")
    w.add_argument("source", type=Path,
                   help="wall geometry .toml, or a mesh (.vtu/.msh) with a geometry TOML beside it")
    w.add_argument("--model", choices=kinds.names(), default=None,
                   help=f"wall model (default: {kinds.default_kind().name} for a TOML, the "
                   "mesh's dimension for a mesh)")
    w.add_argument("--geometry", type=Path, default=None,
                   help="geometry TOML for a mesh source (default: the mesh path with .toml)")
    w.add_argument("--scenario", type=Path, default=None,
                   help="scenario TOML for building, law, gap and motion (default: the paper "
                   "model, Hertzdamp law, first 4 s of Erzincan N-S plus 1 s)")
    w.add_argument("--run", type=Path, default=None,
                   help="use this saved run (made with the same modal wall) instead of running")
    w.add_argument("--modes", type=int, default=None,
                   help="number of wall modes (default: automatic, see --flexibility)")
    w.add_argument("--flexibility", type=float, default=0.99,
                   help="flexibility fraction the modes must capture (default 0.99); the modes up "
                   "to 4/t_c are kept as well, t_c the contact time of base mat and wall")
    w.add_argument("--no-residual", action="store_true",
                   help="leave out the residual-flexibility vector of the modes not kept (by "
                   "default it is added as one more mode)")
    w.add_argument("--damping-ratio", type=float, default=None,
                   help="damping ratio of every wall mode [-] (default: xi_imp of the "
                   "scenario's SDOF wall; 2.0 for the paper's concrete wall, 'consistent')")
    w.add_argument("--side", choices=("pos", "neg"), default=None,
                   help="which wall (default: the one with the larger peak force)")
    w.add_argument("--at", choices=("force", "displacement"), default="force",
                   help="draw the wall at its peak impact force (default) or at its largest "
                   "displacement")
    w.add_argument("--out", type=Path, default=Path("femoat_output/wall_peak.png"),
                   help="PNG path (default: femoat_output/wall_peak.png)")
    w.add_argument("--save-run", type=Path, default=None,
                   help="also save the building run (.npz) for 'femoat render run'")

    r = what.add_parser(
        "run", help="animated GIF of a building run: base mat, floors, both walls; a plan run in "
        "top view",
        description="Animate a run (a plan run in top view; a run.npz written by 'femoat run' or 'femoat render wall "
        "--save-run', or a scenario TOML that is run first). Only the frames shown are computed.")
    r.add_argument("source", type=Path, help="run .npz or scenario .toml")
    r.add_argument("--gif", type=Path, default=None,
                   help="GIF path (default: femoat_output/<source name>.gif)")
    r.add_argument("--fps", type=float, default=20.0, help="frames per second (default 20)")
    r.add_argument("--speed", type=float, default=1.0,
                   help="simulated seconds per second of animation (default 1: real time)")
    r.add_argument("--start", type=float, default=0.0, help="first time shown [s]")
    r.add_argument("--end", type=float, default=None, help="last time shown [s] (default: end)")
    r.add_argument("--scale", type=float, default=1.0,
                   help="magnification of the displacements in the picture (default 1: true scale)")
    r.add_argument("--max-frames", type=int, default=400, help="refuse longer animations")
    r.add_argument("--size", default="960x600", help="frame size WIDTHxHEIGHT in pixels")
    r.add_argument("--save-run", type=Path, default=None,
                   help="scenario source: also save the run (.npz)")
    return p


def _size(text):
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        raise ValueError(f"--size {text!r}: give WIDTHxHEIGHT in pixels, e.g. 960x600") from None
    if not (64 <= w <= 4096 and 64 <= h <= 4096):
        raise ValueError(f"--size {text!r}: width and height must be in [64, 4096] pixels")
    return w, h


def _building_and_motion(scenario):
    """(PoundingModel, motion, integrator, extra_time) of a scenario, or the paper defaults."""
    if scenario is not None:
        from femoat.scenario import load_scenario

        sc = load_scenario(scenario)
        if not sc.model.walls:
            raise ValueError(f"{scenario}: the scenario has no moat wall ([walls] sides)")
        return sc.model, sc.motion, sc.integrator, sc.extra_time
    from femoat.integration.settings import Integrator
    from femoat.paper import paper_model, paper_motion

    return paper_model("concrete", "H", damping="consistent"), paper_motion(quick=True), \
        Integrator(), 1.0


def _render_wall(args):
    from femoat.commands.wall import _build, _load
    from femoat.render.wall import render_wall_peak
    from femoat.results import RunResult
    from femoat.run import run as run_model
    from femoat.structure.pounding import MoatWall, PoundingModel
    from femoat.units import G
    from femoat.walls.modal import ModalWall, contact_time

    geometry, mesh, kind = _load(args)
    model = _build(kind, geometry, mesh, False)
    building, motion, integrator, extra_time = _building_and_motion(args.scenario)
    if args.run is None:
        from femoat.startup.bearing_kinds import select_for

        select_for([building])  # the loop of this model's bearing kind (before the run)
    first = building.walls[0]
    xi = args.damping_ratio
    if xi is None:
        xi = getattr(first.wall, "damping_ratio", 0.0)
    base_mass = building.building.base_weight / G
    t_c = lambda result: contact_time(first.law, base_mass, result.M1)  # noqa: E731
    wall = ModalWall.from_fe(model, n_modes=args.modes, flexibility_target=args.flexibility,
                             contact_duration=t_c, damping_ratio=xi,
                             residual=not args.no_residual)
    if args.run is not None:
        result = RunResult.load(args.run)
    else:
        walls = tuple(MoatWall(w.law, wall, w.gap, w.side) for w in building.walls)
        result = run_model(PoundingModel(building.building, walls), motion, integrator,
                           extra_time=extra_time)
        if args.save_run is not None:
            result.save(args.save_run)
            print(f"wrote {args.save_run}")
    path, state = render_wall_peak(model, wall, result, args.out, side=args.side, at=args.at)
    count = f"{wall.n_modes - wall.residual} modes" + (" + residual-flexibility vector"
                                                      if wall.residual else "")
    print(f"{kind} wall, {count} ({wall.source}), damping {wall.damping_source}")
    what = "peak impact" if args.at == "force" else "largest displacement"
    print(f"{what} of the {state['side']} wall: t = {state['time']:.4f} s, F = "
          f"{state['force']:.3f} kip (peak {state['peak_force']:.3f} kip), impact-point displacement "
          f"{state['impact_displacement']:.4f} in (drawn x{state['magnification']:.3g})")
    print(f"wrote {path}")
    return 0


def _load_run(path):
    """A saved run: a plan run's file (it holds the bidirectional bearing's force) as a
    :class:`~femoat.results.plan.PlanRunResult`, any other as a RunResult."""
    import numpy as np

    from femoat.results.plan import PlanRunResult
    from femoat.results import RunResult

    try:
        with np.load(path, allow_pickle=False) as z:
            plan = "bearing_force" in z.files
    except (OSError, ValueError) as exc:
        raise ValueError(f"{path}: not a femoat result file ({exc}).") from None
    return (PlanRunResult if plan else RunResult).load(path)


def _animate(result, gif, args):
    """The 1D animation of a RunResult, the top view of a plan run (walls flashing on impact)."""
    from femoat.results.plan import PlanRunResult

    kw = dict(fps=args.fps, speed=args.speed, start=args.start, end=args.end, scale=args.scale,
              window_size=_size(args.size), max_frames=args.max_frames)
    if isinstance(result, PlanRunResult):
        from femoat.plotting.plan_history import PlanHistory
        from femoat.render.plan import animate_plan

        return animate_plan(PlanHistory.from_result(result), gif, **kw)
    from femoat.render.animation import animate_run

    return animate_run(result, gif, **kw)


def _render_run(args):
    source = args.source
    gif = args.gif or Path("femoat_output") / f"{source.stem}.gif"
    if gif.suffix.lower() != ".gif":
        raise ValueError(f"--gif {gif}: the animation is written as GIF; use a .gif name")
    if not source.is_file():
        raise ValueError(f"{source} does not exist: give a run .npz or a scenario .toml")
    if source.suffix.lower() == ".npz":
        result = _load_run(source)
    elif source.suffix.lower() == ".toml":
        from femoat.run import run as run_model
        from femoat.scenario import load_scenario

        sc = load_scenario(source)
        result = run_model(sc.model, sc.motion, sc.integrator, extra_time=sc.extra_time)
        if args.save_run is not None:
            result.save(args.save_run)
            print(f"wrote {args.save_run}")
    else:
        raise ValueError(f"{source}: give a run .npz (femoat run) or a scenario .toml")
    path, n = _animate(result, gif, args)
    print(f"wrote {path} ({n} frames)")
    return 0


def run(args):
    if args.what == "wall":
        return _render_wall(args)
    return _render_run(args)

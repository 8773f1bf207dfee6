"""``femoat wall``: modes and SDOF idealisation (K1, M1) of a finite-element moat wall."""

import json
from pathlib import Path

from femoat.walls import kinds


def add_parser(sub):
    p = sub.add_parser(
        "wall",
        help="finite-element wall: modes, K1 [kip/in], M1 [kip*s^2/in], static stiffness",
        description=f"Build a model ({', '.join(kinds.names())}) of a moat wall from a geometry "
        "TOML (or from a mesh file with a geometry TOML of the same name beside it), compute its "
        "lowest modes and the SDOF wall of the paper (mode 1 normalised to unit displacement "
        "at the impact point: M1 = phi'M phi, K1 = w1^2 M1), and write the mesh with the mode "
        "shapes as point data.",
    )
    p.add_argument("source", type=Path,
                   help="geometry .toml, or a mesh (.vtu/.msh with named boundaries base, "
                   "impact, back)")
    p.add_argument("--model", choices=kinds.names(), default=None,
                   help=f"wall model (default: {kinds.default_kind().name} for a TOML, the "
                   "mesh's dimension for a mesh)")
    p.add_argument("--geometry", type=Path, default=None,
                   help="geometry TOML for a mesh source (default: the mesh path with .toml)")
    p.add_argument("--modes", type=int, default=6, help="number of modes (default: 6)")
    p.add_argument("--timoshenko", action="store_true",
                   help=f"{' and '.join(_with_option('timoshenko'))} model only: add shear "
                   "deformation and rotary inertia")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--out", type=Path, default=Path("femoat_output"),
                   help="folder for the mesh with mode shapes (default: ./femoat_output)")
    return p


def _load(args):
    from femoat.walls.fe.geometry import load_geometry
    from femoat.walls.fe.mesh_io import read_mesh

    source = args.source
    if source.suffix.lower() == ".toml":
        return load_geometry(source), None, args.model or kinds.default_kind().name
    geometry_path = args.geometry or source.with_suffix(".toml")
    if not geometry_path.is_file():
        raise ValueError(f"mesh {source} needs a geometry TOML (material, fixity, impact "
                         f"height): none at {geometry_path}; pass --geometry")
    mesh = read_mesh(source)
    kind = kinds.kind_of_mesh(mesh).name
    if args.model is not None and kinds.wall_kind(args.model).dimension != mesh.dim():
        raise ValueError(f"{source} is a {mesh.dim()}D mesh, which makes a {kind} model, not "
                         f"--model {args.model}")
    return load_geometry(geometry_path), mesh, args.model or kind


def _with_option(option):
    """The names of the kinds whose builder takes ``option``."""
    return [k.name for k in kinds.registered() if option in k.options]


def _build(kind, geometry, mesh, timoshenko):
    row = kinds.wall_kind(kind)
    if timoshenko and "timoshenko" not in row.options:
        raise ValueError(f"--timoshenko applies to the {' and '.join(_with_option('timoshenko'))} "
                         "model only")
    options = dict(timoshenko=timoshenko) if "timoshenko" in row.options else {}
    return row.build(geometry, mesh=mesh, **options)


def _write_modes(model, result, path):
    import numpy as np

    from femoat.walls.fe.mesh_io import write_mesh

    point_data = {}
    for i in range(result.shapes.shape[1]):
        u = model.vertex_vectors(result.shapes[:, i])
        scale = np.abs(u).max()
        point_data[f"mode_{i + 1}"] = u / scale if scale > 0 else u
    return write_mesh(path, model.mesh, point_data=point_data)


def run(args):
    from dataclasses import asdict

    from femoat.walls.fe.modal import impact_modes, modal_analysis

    geometry, mesh, kind = _load(args)
    model = _build(kind, geometry, mesh, args.timoshenko)
    result = modal_analysis(model, args.modes)
    modes = impact_modes(result)
    path = _write_modes(model, result, args.out / f"{args.source.stem}_{kind}_modes.vtu")
    out = {
        "model": kind,
        "n_dofs": int(model.n_dofs),
        "K1": result.K1,
        "M1": result.M1,
        "modal_weight": result.modal_weight,
        "frequencies": result.frequencies.tolist(),
        "static_stiffness": result.static_stiffness,
        "sdof_mode": result.sdof_mode + 1,
        "effective_masses": result.effective_masses.tolist(),
        "total_mass": result.total_mass,
        "impact_modes": {
            "mode_numbers": (modes.mode_numbers + 1).tolist(),
            "modal_masses": modes.modal_masses.tolist(),
            "modal_stiffnesses": modes.modal_stiffnesses.tolist(),
            "ground_factors": modes.ground_factors.tolist(),
            "flexibility_fraction": modes.flexibility_fraction,
        },
        "geometry": asdict(geometry),
        "mesh_file": str(path),
        "units": {"K1": "kip/in", "M1": "kip*s^2/in", "modal_weight": "kip", "frequencies": "Hz",
                  "static_stiffness": "kip/in", "effective_masses": "kip*s^2/in",
                  "total_mass": "kip*s^2/in", "modal_masses": "kip*s^2/in",
                  "modal_stiffnesses": "kip/in", "ground_factors": "kip*s^2/in",
                  "mode numbers": "1-based",
                  "mode shapes": "point data mode_<n>, scaled to unit peak displacement"},
    }
    if args.json:
        print(json.dumps(out))
        return 0
    print(f"{kind} model, {model.n_dofs} DOFs")
    print(f"K1 = {result.K1:.4g} kip/in, M1 = {result.M1:.4g} kip*s^2/in "
          f"(M1*g = {result.modal_weight:.4g} kip), from mode {result.sdof_mode + 1}")
    print(f"static stiffness at the impact point = {result.static_stiffness:.4g} kip/in")
    print(f"{'mode':>4s}{'f [Hz]':>12s}{'eff. mass [kip*s^2/in]':>26s}")
    for i, (f, m) in enumerate(zip(result.frequencies, result.effective_masses)):
        print(f"{i + 1:4d}{f:12.3f}{m:26.4g}")
    print(f"first {len(result.frequencies)} modes hold {modes.flexibility_fraction:.4f} of the "
          "impact-point static flexibility")
    print(f"wrote {path}")
    return 0

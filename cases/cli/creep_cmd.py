"""`rollcontact creep-curve`: creep-force curves of a [rolling] scene, as CSV and PNG (+ PDF).

    rollcontact creep-curve SCENE [--of xi|eta|phi] [--points 20] [--max 4] [--fidelity MODEL ...]
                            [--set KEY=VALUE] [-o DIR]

The scene's [rolling] creepages are replaced by a range of the one given with --of (the others zero): --points
values geometrically from 0.02 to --max times its saturation creepage (cases.run.creep_curve), on each model given
with --fidelity (repeatable: bem, fastsim, fastrip, drawn side by side; default the scene's [solver] fidelity, or
bem). Writes DIR/<scene>_creep_<of>.csv (the exact theory; <scene>_creep_<of>_<model>.csv for a fast model) and
the figure .png/.pdf (default DIR: results/creep/ in the current folder, which git ignores) and prints their paths. Exit codes: 0 written, 2
bad input (the scene has no [rolling] or a transient one, coupled materials, a file exists), 1 a file that could
not be written. Over `rollcontact.creep_curve` (cases.run.creep_curve).
"""
from __future__ import annotations


def register(subparsers):
    p = subparsers.add_parser(
        "creep-curve", help="creep-force curve of a [rolling] scene: CSV + PNG, with the linear theory and a "
                            "saturation model",
        description="Steady rolling over a range of one creepage, from the linear range to full sliding, each "
                    "solution the warm start of the next: -F/(mu Fn) against the creepage, with Kalker's linear "
                    "theory and Vermeulen-Johnson's saturation model. Kalker's convention (forces on the rolling "
                    "sphere). Units: mm, N, MPa; phi in 1/mm.")
    p.add_argument("scene", help="scene TOML file with a [rolling] section")
    p.add_argument("--of", default="xi", choices=("xi", "eta", "phi"), help="the creepage varied (default xi)")
    p.add_argument("--points", type=int, default=20, help="number of creepages (default 20)")
    p.add_argument("--max", type=float, default=4.0, help="largest creepage / saturation creepage (default 4)")
    p.add_argument("--fidelity", action="append", choices=("bem", "fastsim", "fastrip"), metavar="MODEL",
                   help="model of the curve: bem (exact theory), fastsim, fastrip; repeat to draw several side by "
                        "side (default: the scene's solver.fidelity, or bem)")
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="SECTION.KEY=VALUE",
                   help="override a scene key (repeatable)")
    p.add_argument("-o", "--output", default="results/creep",
                   help="output folder (default: results/creep/)")
    p.add_argument("--overwrite", action="store_true", help="replace files that exist")
    p.set_defaults(func=creep_curve_handler)
    return p


def creep_curve_handler(args) -> int:
    from rollcontact.cases import api
    print(api.creep_curve(args.scene, of=args.of, points=args.points, max_ratio=args.max, fidelity=args.fidelity,
                          overrides=args.overrides, output=args.output, overwrite=args.overwrite).report())
    return 0

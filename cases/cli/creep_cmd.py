"""`rollcontact creep-curve`: creep-force curves of a [rolling] scene, as CSV and PNG (+ PDF).

    rollcontact creep-curve SCENE [--of xi|eta|phi] [--points 20] [--max 4] [--set KEY=VALUE] [-o DIR]

The scene's [rolling] creepages are replaced by a range of the one given with --of (the others zero): --points
values geometrically from 0.02 to --max times its saturation creepage (cases.run.creep_curve). Writes
DIR/<scene>_creep_<of>.csv and .png/.pdf (default DIR: results/creep/ in the current folder, which git ignores) and
prints their paths.
Exit codes: 0 written, 2 bad input (the scene has no [rolling], coupled materials, a file exists).
"""
from __future__ import annotations

from pathlib import Path
import time


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
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="SECTION.KEY=VALUE",
                   help="override a scene key (repeatable)")
    p.add_argument("-o", "--output", default=str(Path("results") / "creep"),
                   help="output folder (default: results/creep/)")
    p.add_argument("--overwrite", action="store_true", help="replace files that exist")
    p.set_defaults(func=creep_curve_handler)
    return p


def creep_curve_handler(args) -> int:
    import numpy as np
    from rollcontact.bem.errors import InputError, OutputExistsError
    from rollcontact.cases import api
    from rollcontact.cases.plots.creep_figures import plot_curve
    from rollcontact.cases.run.creep_curve import compute_curve, write_csv
    scene = api.load_scene(args.scene, args.overrides)
    if not scene.rolling_on:
        raise InputError(f"creep-curve: scene {args.scene}: no [rolling] section (mode = \"steady\"); add one, or "
                         "--set rolling.mode=\"steady\"")
    if not (args.points >= 2 and 0 < args.max <= 100):
        raise InputError(f"creep-curve: --points {args.points} --max {args.max}: allowed ranges are points >= 2 and "
                         "0 < max <= 100")
    out = Path(args.output)
    stem = f"{scene.name}_creep_{args.of}"
    targets = [out / f"{stem}{ext}" for ext in (".csv", ".png", ".pdf")]
    existing = [t for t in targets if t.exists()]
    if existing and not args.overwrite:
        raise OutputExistsError(f"{existing[0]}: exists; rollcontact does not replace a file unless asked: add "
                                "--overwrite, or give another folder with -o")
    t0 = time.perf_counter()
    table = compute_curve(scene, args.of, np.geomspace(0.02, args.max, args.points))
    wall = time.perf_counter() - t0
    paths = [write_csv(table, targets[0], overwrite=args.overwrite)]
    paths += plot_curve(table, out, stem, overwrite=args.overwrite)
    sweeps = sum(r["sweeps"] for r in table.rows)
    print(f"{args.points} creepages of {args.of} in {wall:.2f} s ({sweeps} sweeps); saturation creepage "
          f"{table.saturation:.6g}{' 1/mm' if args.of == 'phi' else ''}")
    for p in paths:
        print(Path(p).resolve())
    return 0

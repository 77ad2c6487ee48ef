"""`rollcontact stresses RUN.h5 [--step N ...|--all-steps] [--depths z1,z2,...]`: the stresses below the contact.

Computes the stress tensor, von Mises, Tresca (maximum shear) and the first principal stress on the run's grid at
the given depths (mm; default: 30 depths down to 2 a, finer near the surface) for stored steps (default: the last)
from the stored tractions, and adds them to the run file as /subsurface (cases.results.subsurface; docs/hdf5_schema.md; "HDF5
layout"), over `rollcontact.stresses`. Exit codes: 0 written, 2 bad input (missing file, step not stored, bad depths)
or a file another process is writing (its lock), 1 a file that could not be written.
"""
from __future__ import annotations


def add_depth_options(parser):
    """--depths, shared by `stresses` and `run --stresses`."""
    parser.add_argument("--depths", metavar="Z1,Z2,...",
                        help="depths below the surface in mm (default: 30 depths from 0 to 2 a, z_k = 2a (k/29)^1.5)")


def stresses_handler(args) -> int:
    from rollcontact.cases import api
    if args.all_steps and args.step:
        raise api.InputError("give either --step N or --all-steps, not both")
    depths = api.parse_depths(args.depths) if args.depths is not None else None
    steps = "all" if args.all_steps else args.step
    print(api.stresses(args.run, steps=steps, depths=depths, progress=not args.quiet).report())
    return 0


def register(subparsers):
    p = subparsers.add_parser(
        "stresses", help="subsurface stresses of a run's stored steps, added to its file",
        description="The stress tensor below the contact (von Mises, Tresca, first principal stress too) from the "
                    "stored tractions, at the given depths on the run's grid, added to the run file as /subsurface "
                    "(replacing an earlier one). Units: mm, MPa.")
    p.add_argument("run", help="run file (.h5) with field snapshots")
    p.add_argument("--step", type=int, action="append",
                   help="stored step (repeatable; default: the last stored step)")
    p.add_argument("--all-steps", action="store_true", help="every stored step")
    add_depth_options(p)
    p.add_argument("-q", "--quiet", action="store_true", help="no progress lines")
    p.set_defaults(func=stresses_handler)
    return p

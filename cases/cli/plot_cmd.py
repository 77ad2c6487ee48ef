"""`rollcontact plot` and `rollcontact compare`: figures of runs and sweeps (PNG and PDF).

    rollcontact plot RUN.h5 [--step N] [-o DIR]        history (seed Fig. 4), maps (Figs. 5-6), centre lines
                                                      (Figs. 5, 7) at a stored step (default: the last one)
    rollcontact plot OUTDIR [-o DIR]                   sweep: u_sd(f_t) (Fig. 8), limits (Fig. 9), du (Fig. 11)
                                                      ([wheelrail] runs: the patches; a sweep over wheelrail.y:
                                                      the contact-point diagram and the forces against y)
    rollcontact compare A.h5 B.h5 [--step N] [-o DIR]  both runs on shared scales, B - A, overlaid histories

Default output folder: `plots/` next to a run file, `OUTDIR/plots/` for a sweep folder OUTDIR. Every written file
is printed. Runs without fields (output.fields = "none", MDR runs) get the history figure and a note.
Exit codes: 0 written, 2 bad input (missing file, not a run file, step not stored).
"""
from __future__ import annotations

from pathlib import Path
import sys


def _default_dir(target: Path) -> Path:
    return (target if target.is_dir() else target.parent) / "plots"


def _report(paths, notes) -> int:
    for n in notes:
        print(f"note: {n}")
    for p in paths:
        print(Path(p).resolve())
    return 0


def _creep_run(target: Path):
    """The result of a [rolling] run file (its maps are drawn by cases.plots.creep_figures), else None."""
    from rollcontact.cases.plots.common import PlotError
    from rollcontact.cases.plots.creep_figures import is_creep_run
    from rollcontact.cases.results.hdf5 import read_run_file
    if not target.is_file():
        return None
    data = read_run_file(target, PlotError, str(target))
    return data if is_creep_run(data) else None


def _wheelrail_run(target: Path):
    """The result of a [wheelrail] run file (cases.plots.wheelrail_figures), else None."""
    from rollcontact.cases.plots.common import PlotError
    from rollcontact.cases.results.hdf5 import read_run_file, stored_summary
    stored = stored_summary(target) if target.is_file() else None
    if stored is None or "n_patches" not in stored["summary"]:
        return None
    return read_run_file(target, PlotError, str(target))


def plot_handler(args) -> int:
    """`rollcontact plot TARGET`: one run file or a sweep folder."""
    from rollcontact.cases.plots.common import PlotError, open_run
    from rollcontact.cases.plots.run_figures import plot_run
    from rollcontact.cases.plots.sweep_figures import plot_folder
    notes = []
    try:
        target = Path(args.target)
        out_dir = Path(args.output) if args.output else _default_dir(target)
        if target.is_dir():
            if args.step is not None:
                raise PlotError("--step applies to a run file, not to a sweep folder")
            paths = plot_folder(target, out_dir, notes, overwrite=args.overwrite)
        elif (wheelrail := _wheelrail_run(target)) is not None:
            from rollcontact.cases.plots.wheelrail_figures import plot_wheelrail_run
            paths = plot_wheelrail_run(wheelrail, out_dir, target.stem, overwrite=args.overwrite, notes=notes)
        elif _creep_run(target) is not None:
            from rollcontact.cases.plots.creep_figures import plot_creep_run
            paths = plot_creep_run(_creep_run(target), out_dir, target.stem, overwrite=args.overwrite)
        else:
            paths = plot_run(open_run(target), out_dir, args.step, notes, overwrite=args.overwrite)
    except PlotError as exc:
        print(f"rollcontact plot: error: {exc}", file=sys.stderr)
        return 2
    return _report(paths, notes)


def compare_handler(args) -> int:
    """`rollcontact compare A B`."""
    from rollcontact.cases.plots.common import PlotError, open_run
    from rollcontact.cases.plots.run_figures import compare_runs
    notes = []
    try:
        va, vb = open_run(args.a), open_run(args.b)
        out_dir = Path(args.output) if args.output else _default_dir(Path(args.a))
        paths = compare_runs(va, vb, out_dir, args.step, notes, overwrite=args.overwrite)
    except PlotError as exc:
        print(f"rollcontact compare: error: {exc}", file=sys.stderr)
        return 2
    return _report(paths, notes)


def register(subparsers):
    """Add `plot` and `compare` to an argparse subparsers object (handlers set as `func`)."""
    p = subparsers.add_parser(
        "plot", help="figures of a run file or of a sweep folder (PNG + PDF)",
        description="Figures of a run (u versus periods, maps, centre lines; seed Figs. 4-7) or of a sweep "
                    "folder (u_sd versus f_t, limits, ratcheting increment; seed Figs. 8, 9, 11). "
                    "Normalised as in the seed: u = U/U0, f_t = Ft/(mu Fn), w = W/a, tau/(mu p0).")
    p.add_argument("target", help="run file (.h5) or sweep folder")
    p.add_argument("--step", type=int, help="stored step for the maps (default: the last stored step)")
    p.add_argument("-o", "--output", help="output folder (default: plots/ next to the input)")
    p.add_argument("--overwrite", action="store_true", help="replace figures that exist in the output folder")
    p.set_defaults(func=plot_handler)
    c = subparsers.add_parser(
        "compare", help="two runs side by side on shared colour scales, with B - A",
        description="Maps and centre lines of two runs on shared colour scales, the difference B - A, and "
                    "both histories u = U/U0 versus periods on one axis.")
    c.add_argument("a", help="run file A (.h5)")
    c.add_argument("b", help="run file B (.h5)")
    c.add_argument("--step", type=int, help="stored step of both runs (default: the last stored of each)")
    c.add_argument("-o", "--output", help="output folder (default: plots/ next to A)")
    c.add_argument("--overwrite", action="store_true", help="replace figures that exist in the output folder")
    c.set_defaults(func=compare_handler)
    return p, c

"""`rollcontact plot` and `rollcontact compare`: figures of runs and sweeps (PNG and PDF), over `rollcontact.plot` and
`rollcontact.compare` (cases.plots.figures).

    rollcontact plot RUN.h5 [--step N] [-o DIR]        history (seed Fig. 4), maps (Figs. 5-6), centre lines
                                                      (Figs. 5, 7) at a stored step (default: the last one)
    rollcontact plot OUTDIR [-o DIR]                   sweep: u_sd(f_t) (Fig. 8), limits (Fig. 9), du (Fig. 11)
    rollcontact compare A.h5 B.h5 [--step N] [-o DIR]  both runs on shared scales, B - A, overlaid histories

Default output folder: `plots/` next to a run file, `OUTDIR/plots/` for a sweep folder OUTDIR. Every written file
is printed; all figures of a command are written or none. Runs without fields (output.fields = "none", MDR runs) get
the history figure and a note. Exit codes: 0 written, 2 bad input (missing file, not a run file, step not stored, a
figure that exists), 1 a figure that could not be written.
"""
from __future__ import annotations


def plot_handler(args) -> int:
    """`rollcontact plot TARGET`: one run file or a sweep folder."""
    from rollcontact.cases import api
    print(api.plot(args.target, step=args.step, output=args.output, overwrite=args.overwrite).report())
    return 0


def compare_handler(args) -> int:
    """`rollcontact compare A B`."""
    from rollcontact.cases import api
    print(api.compare(args.a, args.b, step=args.step, output=args.output, overwrite=args.overwrite).report())
    return 0


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

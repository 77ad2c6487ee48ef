"""`rollcontact sweep` and `rollcontact limit-search` (engines: cases.sweep.runner, cases.sweep.limit_search).

    rollcontact sweep SCENE.toml --vary load.ft=0.1:0.9:9 --vary motion.w=0.1,0.23,0.4 \
        --vary motion.angle=0,90 -o OUTDIR [--jobs N] [--set k=v ...] [--scheduler ADDRESS]
    rollcontact limit-search SCENE.toml --vary motion.w=0.1,0.23,0.4 [--tol 0.01] -o OUTDIR

One HDF5 file per run in OUTDIR, OUTDIR/summary.{csv,h5} (sweep) or OUTDIR/limits.{csv,h5} (limit-search).
Rerunning the same command resumes: complete runs of the same scene are skipped. Exit codes: 0 every run
complete, 1 some run failed (recorded in the summary), 2 bad input, 130 interrupted (Ctrl-C or SIGTERM;
what finished is kept and summarised). Over `rollcontact.sweep` and `rollcontact.limit_search`.
"""
from __future__ import annotations

import sys



def _common(p):
    p.add_argument("scene", nargs="?", help="scene TOML file (default: the embedded paper scene)")
    p.add_argument("--vary", action="append", default=[], metavar="SECTION.KEY=VALUES",
                   help="varied key: start:stop:count (inclusive) or v1,v2,... (repeatable; Cartesian product)")
    p.add_argument("-o", "--output", required=True, metavar="OUTDIR", help="output folder")
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="SECTION.KEY=VALUE",
                   help="override a scene key for every run, e.g. --set grid.dx=0.4 (repeatable)")
    p.add_argument("--jobs", type=int, default=None,
                   help="local worker processes (default: the number of cores; 1 = in this process)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="Dask distributed scheduler, e.g. tcp://host:8786 (needs the 'dask' extra)")
    p.add_argument("--overwrite", action="store_true",
                   help="replace the summary table of another sweep or search in OUTDIR (a rerun of the same command "
                        "resumes without it)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress lines")


def register(subparsers):
    """Add `sweep` and `limit-search` to an argparse subparsers object; handlers set as `func`."""
    p = subparsers.add_parser(
        "sweep", help="run the Cartesian product of varied scene keys (resumable, parallel)",
        description="Run every combination of the --vary keys, one HDF5 file each, with OUTDIR/summary.csv and "
                    "summary.h5 rewritten as runs finish. Rerun the same command to resume. Units: mm, N, MPa.")
    _common(p)
    p.set_defaults(func=sweep_handler)
    q = subparsers.add_parser(
        "limit-search", help="3D shakedown limit by bisection (f_t,lim(w) or w_lim(f_t))",
        description="For each value of --vary motion.w, bisect in f_t on the run state (shakedown below, "
                    "ratcheting above) to --tol; with --vary load.ft, bisect in w instead. Writes "
                    "OUTDIR/limits.csv and limits.h5 with the 3D bracket and the MDR closed forms for "
                    "kappa = 1, 1.1, 1.5 (seed Eqs. 18-19).")
    _common(q)
    q.add_argument("--tol", type=float, default=0.01, help="bracket width to reach, in f_t or w (default 0.01)")
    q.set_defaults(func=limit_handler)
    return p


def sweep_handler(args) -> int:
    from rollcontact.cases import api
    if not args.vary:
        print("rollcontact sweep: error: give at least one --vary section.key=VALUES, "
              "e.g. --vary load.ft=0.1:0.9:9", file=sys.stderr)
        return 2
    api.stop_on_sigterm(sweep=True)
    try:
        report = api.sweep(api.load_scene(args.scene), args.vary, args.output, overrides=args.overrides,
                           jobs=args.jobs, scheduler=args.scheduler, overwrite=args.overwrite,
                           progress=not args.quiet)
    except KeyboardInterrupt:
        return 130
    print(report.report())
    return 1 if report.failed else 0


def limit_handler(args) -> int:
    from rollcontact.cases import api
    if not args.vary:
        print("rollcontact limit-search: error: give --vary motion.w=... (or --vary load.ft=...)",
              file=sys.stderr)
        return 2
    api.stop_on_sigterm(sweep=True)
    try:
        report = api.limit_search(api.load_scene(args.scene), args.vary, args.output, overrides=args.overrides,
                                  tol=args.tol, jobs=args.jobs, scheduler=args.scheduler, overwrite=args.overwrite,
                                  progress=not args.quiet)
    except KeyboardInterrupt:
        return 130
    print(report.report())
    return 1 if any(r["status"] == "failed" for r in report.rows) else 0

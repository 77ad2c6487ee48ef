"""Benchmark: the seed's Fig. 8 sweep at paper resolution, and kappa fitted to it (seed Eq. 13, docs/theory.md §8.4).

    .venv/bin/python benchmarks/sweep_paper.py [--jobs 2] [--runs results/sweep_paper] [--keep] [-o DIR]

Scene: the paper's Table 1 (cases/paper_perpendicular.toml: dx = dy = 0.2 mm, dW = 0.2 mm, 10 periods),
f_t = 0.1 ... 0.9 by 0.1, w = W/a in {0.1, 0.23, 0.4}, rolling parallel (angle 0) and perpendicular (90) to
Ft: 54 runs through `cases.sweep.runner.run_sweep` on `--jobs` local processes. The run folder is emptied first
(unless --keep), so the wall time is that of the whole sweep, cold worker start included.

Reports: total wall time (s), runs per minute, the states, and for each alignment kappa fitted by least
squares to Eq. 13 over the shakedown runs (solver.mdr.limits.fit_kappa), beside the seed's 1 (parallel) and
1.1 (perpendicular). JSON to DIR/sweep_paper.json (default results/benchmarks/); the run files stay in --runs (ignored by git).
"""
from __future__ import annotations

import os
from pathlib import Path
import platform
import shutil
import sys
import time

import _record
from rollcontact.cases.scene.scene import Scene, shipped_scene_path
from rollcontact.cases.sweep.runner import run_sweep
from rollcontact.solver.mdr import limits as lim

VARY = ["load.ft=0.1:0.9:9", "motion.w=0.1,0.23,0.4", "motion.angle=0,90"]
ROOT = Path(__file__).resolve().parent.parent


def main(argv=None) -> int:
    ap = _record.parser(__doc__)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--runs", default=str(Path("results") / "sweep_paper"), help="folder of the run files")
    ap.add_argument("--keep", action="store_true", help="keep finished runs (resume) instead of starting afresh")
    args = ap.parse_args(argv)
    out = Path(args.runs)
    if out.exists() and not args.keep:
        shutil.rmtree(out)
    base = Scene.from_toml(shipped_scene_path("paper_perpendicular.toml"))
    load_before = os.getloadavg()
    t0 = time.perf_counter()
    report = run_sweep(base, VARY, out, jobs=args.jobs, progress=sys.stderr)
    wall = time.perf_counter() - t0
    load_after = os.getloadavg()
    rows = report.rows
    fits = {}
    for angle, label, seed in ((0, "parallel", lim.KAPPA_PARALLEL), (90, "perpendicular", lim.KAPPA_PERPENDICULAR)):
        sd = [r for r in rows if r["motion.angle"] == angle and r["state"] == "shakedown"]
        states = {s: sum(r["state"] == s for r in rows if r["motion.angle"] == angle)
                  for s in ("shakedown", "ratcheting", "undecided", "gross_sliding", "")}
        fit = lim.fit_kappa([r["f_t"] for r in sd], [r["w"] for r in sd], [r["u_sd"] for r in sd])
        fits[label] = dict(kappa=fit.kappa, stderr=fit.stderr, n=fit.n, residual_rms=fit.residual_rms,
                           seed_kappa=seed, states={k or "failed": v for k, v in states.items()})
    result = dict(
        benchmark="sweep_paper", scene="cases/paper_perpendicular.toml (angle varied)", vary=VARY,
        runs=report.planned, ran=report.ran, skipped=report.skipped, failed=report.failed, jobs=args.jobs,
        wall_time_s=wall, runs_per_minute=60.0 * report.ran / wall if report.ran else None,
        run_wall_time_sum_s=sum(r["wall_time"] or 0.0 for r in rows),
        loadavg_before=load_before, loadavg_after=load_after, cpu_count=os.cpu_count(),
        python=platform.python_version(), kappa_fit=fits,
        rows=[{k: r[k] for k in ("load.ft", "motion.w", "motion.angle", "state", "u_sd", "du",
                                 "periods_to_shakedown", "steps", "iterations", "wall_time", "error")}
              for r in rows])
    _record.write("sweep_paper", result, args.output)
    print(f"{report.planned} runs ({report.ran} run, {report.failed} failed) on {args.jobs} jobs: "
          f"{wall:.1f} s, {result['runs_per_minute'] or 0:.1f} runs/min; load average before/after "
          f"{load_before[0]:.2f}/{load_after[0]:.2f}")
    print("| alignment | fitted kappa | stderr | shakedown runs | rms residual (f_t) | seed kappa | states |")
    print("|---|---|---|---|---|---|---|")
    for label, f in fits.items():
        st = ", ".join(f"{k} {v}" for k, v in f["states"].items() if v)
        print(f"| {label} | {f['kappa']:.4f} | {f['stderr']:.4f} | {f['n']} | {f['residual_rms']:.2e} | "
              f"{f['seed_kappa']:g} | {st} |")
    print("\n| f_t | " + " | ".join(f"w={w} par / perp" for w in (0.1, 0.23, 0.4)) + " |")
    print("|---|---|---|---|")
    table = {(r["load.ft"], r["motion.w"], r["motion.angle"]): r for r in rows}
    for ft in sorted({r["load.ft"] for r in rows}):
        cells = []
        for w in (0.1, 0.23, 0.4):
            pair = []
            for angle in (0, 90):
                r = table[(ft, w, angle)]
                pair.append(f"{r['u_sd']:.4f}" if r["state"] == "shakedown" else (r["state"] or "failed")[:7])
            cells.append(" / ".join(pair))
        print(f"| {ft:g} | " + " | ".join(cells) + " |")
    print(f"JSON: {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

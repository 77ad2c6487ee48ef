"""Parameter sweeps over scenes (seed Fig. 8; theory.md §8).

A sweep is the Cartesian product of a few scene keys ("axes"), each given on the command line as
`--vary section.key=start:stop:count` or `--vary section.key=v1,v2,...` (syntax: `cases.sweep.plan.parse_vary`).

Every combination is turned into a full `Scene` (base scene, then the `--set` overrides, then the varied
values) and validated before any run starts, so a typo or an out-of-range value stops the sweep at once with
the offending combination named. Each run writes one HDF5 file (cases.results.hdf5) named after its varied values
plus a short hash of the full scene TOML:

    OUTDIR/ft=0.3_w=0.15_angle=0__3f9a1c2e.h5

so changing a `--set` (or anything else in the scene) gives new files instead of silently reusing old ones.
After every finished run the sweep rewrites, atomically, `OUTDIR/summary.csv` and `OUTDIR/summary.h5` with one
row per finished run (columns: see `cases.sweep.table.SUMMARY_COLUMNS`); an interrupted sweep therefore always
leaves a valid summary of what finished, and every run file is either complete or absent (run files are atomic
too).

Resuming: a planned run whose file `is_complete` and stores exactly the planned scene TOML is not run again
(its row is read back from the file); missing, partial and failed runs are redone.

Failures: a run that raises a `RollcontactError` (no convergence, grid too large, contact at the grid edge)
is recorded with status 'failed' and its message; the other runs go on.

Parallelism: local processes by default (`concurrent.futures.ProcessPoolExecutor`, 'forkserver' context
with the solver modules preloaded, one BLAS thread per worker; FFTW threads come from the scene,
`[solver] threads`, default 1); `jobs=1` runs in this process; `scheduler=ADDRESS` submits the runs to a Dask
distributed cluster (optional extra `dask`, imported only then).

Modules: the plan (axes, combinations, file names) is `cases.sweep.plan`, the summary tables
`cases.sweep.table`, the pools `cases.sweep.workers`; the shakedown-limit search, which runs its probes like sweep runs,
is `cases.sweep.limit_search`.

Units: the scene's (mm, N, MPa, degrees); f_t = Ft/(mu Fn), w = W/a, u = U/U0 (seed Eq. 9).
"""
from __future__ import annotations

from dataclasses import dataclass, field
import os
from pathlib import Path
import sys
import time
import tomllib

from rollcontact.bem.wisdom import process_exists
from rollcontact.bem.errors import InputError, RollcontactError

from rollcontact.cases.results.hdf5 import is_complete, stored_summary
from rollcontact.cases.results.outputs import output_folder
from rollcontact.cases.scene.scene import Scene
from rollcontact.cases.sweep.plan import PlannedRun, describe, parse_vary, plan_sweep
from rollcontact.cases.sweep.table import write_summary
from rollcontact.cases.sweep.workers import make_pool, raise_if_interrupted, completed, default_jobs, require_dask


# ---------------------------------------------------------------------------------------- one run
def _stored_row(run: PlannedRun, outdir) -> dict:
    """The summary row of a run whose complete file is on disk."""
    return _row(run, {"status": "complete", "error": "", "summary": stored_summary(run.path)["summary"]}, outdir)


def is_done(run: PlannedRun) -> bool:
    """True if the run's file is complete and stores exactly the planned scene (then it is not redone)."""
    if not is_complete(run.path):
        return False
    stored = stored_summary(run.path)
    return stored is not None and stored["scene"] == run.scene_toml


def execute_run(scene_toml: str, scene_name: str, out_path: str) -> dict:
    """Run one scene (given as TOML text, and its name, which the stored TOML's first line carries) to
    `out_path`; never raises a RollcontactError.

    Returns a dict with status, error and the run summary; used by the workers (picklable in and out).
    A run that fails inside the stepping loop has a file with status 'failed' (written by run_scene);
    one that fails before it (e.g. a grid above the element limit) has no file, only the returned error.
    """
    from rollcontact.cases.run.scene_run import run_scene
    t0 = time.perf_counter()
    try:
        scene = Scene.from_toml_text(scene_toml, name=scene_name)
        result = run_scene(scene, out_path)
    except RollcontactError as exc:
        return {"status": "failed", "error": f"{type(exc).__name__}: {exc}", "summary": {},
                "wall_time": time.perf_counter() - t0}
    return {"status": result.status, "error": result.error, "summary": dict(result.summary),
            "wall_time": result.wall_time}


def _row(run: PlannedRun, result: dict, outdir: Path) -> dict:
    s = result.get("summary") or {}
    row = dict(run.values)
    row.update(index=run.index, state=s.get("state") or "", status=result["status"],
               f_t=s.get("f_t"), w=s.get("w"), angle=None, u_sd=s.get("u_sd"), du=s.get("du"),
               U_sd=s.get("U_sd"), dU_per_period=s.get("dU_per_period"), u_stat=s.get("u_stat"),
               periods_to_shakedown=s.get("periods_to_shakedown"), steps=s.get("steps"),
               iterations=s.get("iterations"), wall_time=s.get("wall_time", result.get("wall_time")),
               file=os.path.relpath(run.path, outdir), error=result.get("error") or "")
    try:
        row["angle"] = float(tomllib.loads(run.scene_toml)["motion"]["angle"])
    except (KeyError, tomllib.TOMLDecodeError):
        pass
    return row



class _Progress:
    """One line per finished run on stderr: done/total, failures, elapsed, ETA."""

    def __init__(self, total, skipped, stream):
        self.total, self.done, self.failed, self.stream = total, skipped, 0, stream
        self.to_do = total - skipped
        self.t0 = time.perf_counter()
        self.ran = 0

    def update(self, row):
        self.done += 1
        self.ran += 1
        self.failed += row["status"] != "complete"
        if self.stream is None:
            return
        elapsed = time.perf_counter() - self.t0
        left = self.to_do - self.ran
        eta = elapsed / self.ran * left
        what = row["state"] or "failed"
        if row["status"] == "complete" and row.get("u_sd") is not None:
            what += f" u_sd={row['u_sd']:.4f}"
        elif row["status"] == "complete" and row.get("du") is not None:
            what += f" du={row['du']:.3g}"
        if row["status"] != "complete":
            what = f"FAILED ({row['error'][:120]})"
        print(f"[{self.done}/{self.total}] {self.failed} failed, elapsed {_hms(elapsed)}, ETA {_hms(eta)}  "
              f"{describe({k: row[k] for k in row if '.' in k})}: {what}", file=self.stream, flush=True)


def _hms(seconds):
    seconds = int(round(seconds))
    return f"{seconds // 60}m{seconds % 60:02d}s" if seconds >= 60 else f"{seconds}s"


@dataclass
class SweepReport:
    """What a sweep did: planned runs, how many were skipped (already complete), run now, and failed."""

    outdir: Path
    keys: list
    planned: int
    skipped: int
    ran: int
    failed: int
    rows: list = field(default_factory=list)
    wall_time: float = 0.0
    interrupted: bool = False

    @property
    def summary_csv(self) -> Path:
        return self.outdir / "summary.csv"

    @property
    def summary_h5(self) -> Path:
        return self.outdir / "summary.h5"



def run_sweep(base: Scene, axes, outdir, *, overrides=(), jobs=None, scheduler=None,
              progress=sys.stderr) -> SweepReport:
    """Plan, skip what is done, run the rest in parallel, keep OUTDIR/summary.{csv,h5} up to date.

    base: the scene the axes modify; axes: list of Axis (or `--vary` strings); overrides: `--set` strings
    applied before the varied values; jobs: local worker processes (default: the core count; 1 = run in
    this process); scheduler: Dask scheduler address (then `jobs` is ignored); progress: stream for progress
    lines (None: silent). KeyboardInterrupt (Ctrl-C, or SIGTERM via the CLI) stops the workers, writes the
    summary of what finished and is re-raised.
    """
    t0 = time.perf_counter()
    axes = [parse_vary(a) if isinstance(a, str) else a for a in axes]
    outdir = Path(outdir)
    if jobs is not None and int(jobs) < 1:
        raise InputError(f"--jobs = {jobs!r}: allowed range is jobs >= 1")
    jobs = default_jobs() if jobs is None else int(jobs)
    if scheduler:
        require_dask(scheduler)
    plan = plan_sweep(base, axes, outdir, overrides)
    keys = [a.key for a in axes]
    outdir = output_folder(outdir)
    _remove_stale_temporaries(outdir, plan)
    rows, todo = {}, []
    for run in plan:
        if is_done(run):
            rows[run.index] = _stored_row(run, outdir)
        else:
            todo.append(run)
    skipped = len(plan) - len(todo)
    attrs = {"base_scene": base.to_toml(), "overrides": list(overrides) or [""],
             "rollcontact_sweep": "one row per finished run; see cases.sweep.table.SUMMARY_COLUMNS"}
    write_summary(outdir, keys, rows.values(), attrs=attrs)
    if progress is not None:
        threads = max(tomllib.loads(r.scene_toml)["solver"]["threads"] for r in plan)
        where = f"Dask scheduler {scheduler}" if scheduler else f"{min(jobs, max(len(todo), 1))} process(es)"
        print(f"sweep: {len(plan)} run(s) planned in {outdir}; {skipped} already complete, skipped; "
              f"{len(todo)} to run on {where}", file=progress, flush=True)
        if threads > 1 and jobs > 1 and not scheduler:
            print(f"sweep: warning: [solver] threads = {threads} with {jobs} jobs oversubscribes the cores",
                  file=progress, flush=True)
    report = SweepReport(outdir, keys, len(plan), skipped, 0, 0)
    bar = _Progress(len(plan), skipped, progress)
    pool = make_pool(jobs, scheduler) if todo else None
    try:
        if todo:
            tasks = [(run, execute_run, (run.scene_toml, run.scene_name, str(run.path))) for run in todo]
            for run, result, failure in completed(pool, tasks):
                if failure:
                    result = {"status": "failed", "error": failure, "summary": {}}
                row = _row(run, result, outdir)
                rows[run.index] = row
                report.ran += 1
                report.failed += row["status"] != "complete"
                bar.update(row)
                write_summary(outdir, keys, rows.values(), attrs=attrs)
            pool.close()
        raise_if_interrupted()
    except KeyboardInterrupt:
        report.interrupted = True
        if pool is not None:
            pool.stop()
            _remove_stale_temporaries(outdir, plan)  # a terminated worker cannot clean up its partial file
        for run in todo:  # runs whose file was complete before their result reached this process
            if run.index not in rows and is_done(run):
                rows[run.index] = _stored_row(run, outdir)
        write_summary(outdir, keys, rows.values(), attrs=attrs)
        if progress is not None:
            print(f"sweep: interrupted; {len(rows)} of {len(plan)} run(s) finished are in {outdir}/summary.csv; "
                  "rerun the same command to resume", file=progress, flush=True)
        raise
    report.rows = [rows[i] for i in sorted(rows)]
    report.wall_time = time.perf_counter() - t0
    if progress is not None:
        print(f"sweep: done in {_hms(report.wall_time)}: {report.ran} run(s), {report.failed} failed, "
              f"{report.skipped} skipped; summary in {outdir / 'summary.csv'}", file=progress, flush=True)
    return report


def _remove_stale_temporaries(outdir: Path, plan):
    """Delete temporary files a killed run left behind (`.<name>.<pid>.tmp`, see cases.results.hdf5.write_run)."""
    names = {r.name for r in plan}
    for tmp in outdir.glob(".*.tmp"):
        parts = tmp.name[1:].rsplit(".", 2)
        if len(parts) == 3 and parts[0] in names:
            pid = parts[1]
            if pid.isdigit() and process_exists(int(pid)):
                continue
            tmp.unlink(missing_ok=True)

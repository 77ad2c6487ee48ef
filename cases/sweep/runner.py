"""Parameter sweeps over scenes (seed Fig. 8; docs/theory.md §8).

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

from contextlib import contextmanager
from dataclasses import dataclass, field
import os
from pathlib import Path
import sys
import time
import tomllib

import numpy as np

from rollcontact.bem.errors import (InputError, OutputExistsError, OutputInUseError, OutputWriteError,
                                    RollcontactError)

from rollcontact.cases.results.hdf5 import is_complete, stored_summary
from rollcontact.cases.arguments import arg, flag, on_command_line
from rollcontact.cases.results.lock import OutputLock, holder_of
from rollcontact.cases.results.outputs import output_folder
from rollcontact.cases.scene.scene import Scene
from rollcontact.cases.sweep.plan import PlannedRun, describe, parse_vary, plan_sweep
from rollcontact.cases.sweep.table import (AUTO_COLUMNS, CREEP_COLUMNS, VISCO_COLUMNS, WHEELRAIL_COLUMNS,
                                          write_summary)
from rollcontact.cases.sweep.workers import completed, default_jobs, make_pool, raise_if_interrupted, require_dask

#: seconds between two looks at a run that another process computes, and before saying whom a sweep waits for
CLAIM_POLL = 0.5
CLAIM_NOTICE = 60.0


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


def execute_run(scene_toml: str, scene_name: str, out_path: str, extend_from: str | None = None) -> dict:
    """Run one scene (given as TOML text, and its name, which the stored TOML's first line carries) to
    `out_path`; never raises a RollcontactError. Used by the workers (picklable in and out).

    Returns a dict with status, error and the run summary. The run is claimed first through its file's lock: when
    another process holds it (a second sweep on the same folder), status is 'claimed' and nothing is run; when
    the file turns out complete for this scene once the lock is taken (that process finished it), its summary is
    returned with `elsewhere` set. A run that fails inside the stepping loop has a file with status 'failed'
    (written by run_scene); one that fails before it (e.g. a grid above the element limit) has no file.
    extend_from: a complete run file of the same scene with fewer periods; the run continues it
    (cases.run.restart.extension_source) instead of starting again, when it can.
    """
    from rollcontact.cases.run.restart import extension_source
    from rollcontact.cases.run.scene_run import run_scene
    t0 = time.perf_counter()
    lock = OutputLock(out_path, label=f"run file {out_path}")
    try:
        lock.acquire()
    except OutputInUseError as exc:
        return {"status": "claimed", "error": str(exc), "summary": {}, "wall_time": 0.0}
    except OutputWriteError as exc:
        return {"status": "failed", "error": str(exc), "summary": {}, "wall_time": 0.0, "write_error": True}
    try:
        stored = stored_summary(out_path) if Path(out_path).exists() else None
        if stored is not None and stored["status"] == "complete" and stored["scene"] == scene_toml:
            return {"status": "complete", "error": "", "summary": stored["summary"], "wall_time": 0.0,
                    "elsewhere": True}
        scene = Scene.from_toml_text(scene_toml, name=scene_name)
        source = extension_source(extend_from, scene) if extend_from else None
        attrs = None if source is None else dict(restarted_from=str(Path(extend_from).resolve()),
                                                 restart_step=source.step,
                                                 restart_overrides=[f"motion.periods={scene.motion.periods}"])
        resumed = interrupted_source(out_path, stored, scene_toml)
        if resumed is not None:      # a run of this scene killed or interrupted: continued from its last checkpoint
            source, attrs = resumed, dict(restarted_from=str(Path(out_path).resolve()), restart_step=resumed.step,
                                          restart_overrides=[])
        result = run_scene(scene, out_path, overwrite=True, lock=lock, restart=source, attrs=attrs)
    except OutputWriteError as exc:     # a full disk, a vanished folder: the sweep stops (cases.sweep.runner)
        return {"status": "failed", "error": str(exc), "summary": {}, "wall_time": time.perf_counter() - t0,
                "write_error": True}
    except RollcontactError as exc:
        return {"status": "failed", "error": f"{type(exc).__name__}: {exc}", "summary": {},
                "wall_time": time.perf_counter() - t0}
    finally:
        lock.release()
    return {"status": result.status, "error": result.error, "summary": dict(result.summary),
            "wall_time": result.wall_time}


def interrupted_source(out_path, stored, scene_toml: str):
    """The run file `out_path` as a cases.run.restart.RestartSource when it holds the planned scene (`scene_toml`)
    stopped part-way: a checkpoint of a killed run (status 'incomplete') or a run interrupted by the user (status
    'failed'), with the fields of a stored step to continue from; None otherwise (the run starts from step 0).
    `stored`: its stored_summary (None for no file)."""
    from rollcontact.cases.run.restart import load_restart
    if stored is None or stored["scene"] != scene_toml:
        return None
    if not (stored["status"] == "incomplete" or (stored["status"] == "failed"
                                                  and stored["error"] == "interrupted by the user")):
        return None
    try:
        return load_restart(out_path)
    except (RollcontactError, OSError):
        return None


def wait_for_claimed(run: PlannedRun, poll: float = CLAIM_POLL, notice_after: float = CLAIM_NOTICE) -> dict:
    """The result of a run that another process claimed: waits until its file is complete, and runs it here when
    that process lets go of it without completing it (it failed, or was killed). After `notice_after` seconds it
    says on stderr whom it waits for (a holder on another host whose death this host cannot see, on a file
    system without flock, needs its lock file removed by hand)."""
    start = time.monotonic()
    while True:
        if notice_after is not None and time.monotonic() - start > notice_after:
            print(f"sweep: still waiting for {run.path.name}, claimed by {holder_of(run.path) or 'another process'}; "
                  f"if that process is gone, remove {run.path.name}.lock", file=sys.stderr, flush=True)
            notice_after = None
        if is_done(run):
            return {"status": "complete", "error": "", "summary": stored_summary(run.path)["summary"],
                    "elsewhere": True}
        if holder_of(run.path) is None:
            result = execute_run(run.scene_toml, run.scene_name, str(run.path))
            if result["status"] != "claimed":
                return result
        time.sleep(poll)


def _row(run: PlannedRun, result: dict, outdir: Path) -> dict:
    s = result.get("summary") or {}
    row = dict(run.values)
    row.update(index=run.index, state=s.get("state") or "", status=result["status"],
               f_t=s.get("f_t"), w=s.get("w"), angle=None, u_sd=s.get("u_sd"), du=s.get("du"),
               U_sd=s.get("U_sd"), dU_per_period=s.get("dU_per_period"), U_perp=s.get("U_perp"),
               dU_perp_per_period=s.get("dU_perp_per_period"),
               dissipation_per_period=s.get("dissipation_per_period"), u_stat=s.get("u_stat"),
               periods_to_shakedown=s.get("periods_to_shakedown"), steps=s.get("steps"),
               iterations=s.get("iterations"), wall_time=s.get("wall_time", result.get("wall_time")),
               file=os.path.relpath(run.path, outdir), error=result.get("error") or "")
    if "F_x" in s:                                     # a [rolling] scene (cases.sweep.table.CREEP_COLUMNS)
        row.update({k: s.get(k) for k in CREEP_COLUMNS})
    if "pressure_centroid_x" in s:                     # viscoelastic bodies (cases.sweep.table.VISCO_COLUMNS)
        row.update({k: s.get(k) for k in VISCO_COLUMNS})
    if "n_patches" in s:                               # a [wheelrail] scene (cases.sweep.table.WHEELRAIL_COLUMNS)
        row.update({k: s.get(k) for k in WHEELRAIL_COLUMNS})
    if "predicted_error" in s:                         # solver.fidelity = "auto" (cases.sweep.table.AUTO_COLUMNS)
        row.update({k: s.get(k) for k in AUTO_COLUMNS})
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
    elsewhere: int = 0      # runs another process (a second sweep on the folder) computed meanwhile

    @property
    def summary_csv(self) -> Path:
        return self.outdir / "summary.csv"

    @property
    def summary_h5(self) -> Path:
        return self.outdir / "summary.h5"

    def report(self) -> str:
        """The line `rollcontact sweep` prints."""
        return (f"{self.planned} run(s): {self.ran} run now, {self.skipped} skipped (already complete), "
                f"{self.elsewhere} run by another process, {self.failed} failed; summary: {self.summary_csv}")

    def __repr__(self) -> str:
        return (f"SweepReport({self.planned} planned, {self.ran} ran, {self.skipped} skipped, {self.failed} failed, "
                f"outdir={str(self.outdir)!r})")



def run_sweep(base: Scene, axes, outdir, *, overrides=(), jobs=None, scheduler=None, overwrite=False,
              progress=sys.stderr) -> SweepReport:
    """Plan, skip what is done, run the rest in parallel, keep OUTDIR/summary.{csv,h5} up to date.

    base: the scene the axes modify; axes: list of Axis (or `--vary` strings); overrides: `--set` strings
    applied before the varied values; jobs: local worker processes (default: the core count; 1 = run in
    this process); scheduler: Dask scheduler address (then `jobs` is ignored); overwrite: replace the summary of
    another sweep in OUTDIR (else OutputExistsError); progress: stream for progress lines (None: silent).
    Every run is claimed through its file's lock, so that sweeps started on one folder share the work: a run that
    another process computes is waited for at the end, and run here if that process lets go of it unfinished.
    KeyboardInterrupt (Ctrl-C, or SIGTERM via the CLI) stops the workers, writes the summary of what finished
    and is re-raised.
    """
    t0 = time.perf_counter()
    axes = [parse_vary(a) if isinstance(a, str) else a for a in axes]
    outdir = Path(outdir).absolute()     # the workers (Dask's among them) may run in other folders
    if jobs is not None and int(jobs) < 1:
        raise InputError(f"{arg('jobs')} = {jobs!r}: allowed range is jobs >= 1")
    jobs = default_jobs() if jobs is None else int(jobs)
    if scheduler:
        require_dask(scheduler)
    plan = plan_sweep(base, axes, outdir, overrides)
    keys = [a.key for a in axes]
    outdir = output_folder(outdir)
    attrs = {"base_scene": base.to_toml(), "overrides": list(overrides) or [""],
             "rollcontact_sweep": "one row per finished run; see cases.sweep.table.SUMMARY_COLUMNS"}
    rows, todo = {}, []
    for run in plan:
        if is_done(run):
            rows[run.index] = _stored_row(run, outdir)
        else:
            todo.append(run)
    skipped = len(plan) - len(todo)
    with claimed_table(outdir / "summary.h5", keys, attrs, overwrite):
        write_summary(outdir, keys, rows.values(), attrs=attrs)
    if progress is not None:
        _announce(progress, plan, todo, skipped, outdir, jobs, scheduler)
    report = SweepReport(outdir, keys, len(plan), skipped, 0, 0)
    bar = _Progress(len(plan), skipped, progress)
    pool = make_pool(jobs, scheduler) if todo else None

    def finish(run, result):
        if result.get("write_error"):
            raise OutputWriteError(result["error"])
        row = _row(run, result, outdir)
        rows[run.index] = row
        report.elsewhere += bool(result.get("elsewhere"))
        report.ran += not result.get("elsewhere")
        report.failed += row["status"] != "complete"
        bar.update(row)
        write_summary(outdir, keys, rows.values(), attrs=attrs)

    try:
        claimed = _run_here(pool, todo, finish)
        if claimed and progress is not None:
            print(f"sweep: {len(claimed)} run(s) are being computed by another process ({claimed[0].path.name}: "
                  f"{holder_of(claimed[0].path) or 'just finished'}); waiting for them", file=progress, flush=True)
        for run in claimed:
            finish(run, wait_for_claimed(run))
            raise_if_interrupted()
    except OutputWriteError as exc:
        if pool is not None:
            pool.stop()
        raise stopped_sweep(exc, outdir, "summary", len(rows), len(plan)) from None
    except KeyboardInterrupt:
        report.interrupted = True
        if pool is not None:
            pool.stop()
            if not scheduler:   # a terminated local worker cannot clean up; Dask's may live on other hosts
                _remove_stale_temporaries(outdir, plan)
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
              f"{report.skipped} skipped, {report.elsewhere} by another process; summary in "
              f"{outdir / 'summary.csv'}", file=progress, flush=True)
    return report


def stopped_sweep(exc: OutputWriteError, outdir: Path, stem: str, finished: int, planned: int) -> OutputWriteError:
    """The error of a sweep (or limit search) that could not write (a run file, its summary table): nothing more is
    written; the complete run files stay, and the table as last written."""
    return OutputWriteError(f"{exc}; the {'sweep' if stem == 'summary' else 'limit search'} stopped: its complete "
                            f"run files stay in {outdir}, and {outdir / (stem + '.csv')} as last written ({finished} "
                            f"of {planned} finished); rerun the same command to resume", path=exc.path, errno=exc.errno)


def _run_here(pool, todo, finish) -> list:
    """Run `todo` on the pool, handing each result to finish(run, result); returns the runs that another process
    had claimed (their files' locks were held), to be waited for."""
    claimed = []
    if todo:
        tasks = [(run, execute_run, (run.scene_toml, run.scene_name, str(run.path))) for run in todo]
        for run, result, failure in completed(pool, tasks):
            if failure:
                result = {"status": "failed", "error": failure, "summary": {}}
            if result["status"] == "claimed":
                claimed.append(run)
            else:
                finish(run, result)
        pool.close()
    raise_if_interrupted()
    return claimed


def _announce(progress, plan, todo, skipped, outdir, jobs, scheduler):
    threads = max(tomllib.loads(r.scene_toml)["solver"]["threads"] for r in plan)
    where = f"Dask scheduler {scheduler}" if scheduler else f"{min(jobs, max(len(todo), 1))} process(es)"
    print(f"sweep: {len(plan)} run(s) planned in {outdir}; {skipped} already complete, skipped; "
          f"{len(todo)} to run on {where}", file=progress, flush=True)
    if threads > 1 and jobs > 1 and not scheduler:
        print(f"sweep: warning: [solver] threads = {threads} with {jobs} jobs oversubscribes the cores",
              file=progress, flush=True)


@contextmanager
def claimed_table(table: Path, keys, attrs: dict, overwrite: bool):
    """The check that a sweep (or limit search) may write the summary table `table`, held together with its first
    write under the table's lock (so that two sweeps started at once cannot both pass it): it resumes in a folder
    whose table it wrote itself (the same varied keys, base scene and overrides); the table of another one is not
    replaced unless `overwrite` (OutputExistsError naming the file and --overwrite)."""
    from rollcontact.cases.sweep.table import table_attrs
    lock = OutputLock(table, label=f"{arg('output')} {table.parent}").acquire(wait=True)
    try:
        stored = table_attrs(table) if table.exists() and not overwrite else {}
        mine = {"varied": list(keys), **{k: attrs[k] for k in ("base_scene", "overrides")}}
        differs = [] if stored is None else [k for k, v in mine.items() if k in stored and
                                             list(np.atleast_1d(stored[k])) != list(np.atleast_1d(v))]
        if stored is None or differs:
            what = ("is not a table of rollcontact" if stored is None else
                    f"belongs to another sweep (its {', '.join(differs)} differ)")
            raise OutputExistsError(f"{arg('output')} {table.parent}: {table} {what}; rollcontact does not replace it "
                                    f"unless asked: {'add' if on_command_line() else 'pass'} {flag('overwrite')}, or "
                                    "choose another folder")
        yield
    finally:
        lock.release()


def _remove_stale_temporaries(outdir: Path, plan):
    """Delete the temporary files that killed runs of the plan left behind (cases.run.scene_run)."""
    from rollcontact.cases.run.scene_run import remove_stale_temporaries
    for run in plan:
        remove_stale_temporaries(run.path)

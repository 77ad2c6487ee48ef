"""Parameter sweeps and shakedown-limit searches over scenes (seed Fig. 8; theory.md §8).

A sweep is the Cartesian product of a few scene keys ("axes"), each given on the command line as

    --vary load.ft=0.1:0.9:9        range start:stop:count, both ends included (count >= 2; 1 gives start)
    --vary motion.w=0.1,0.23,0.4    comma list (values parsed as TOML: numbers, or strings such as bem,mdr)

Every combination is turned into a full `Scene` (base scene, then the `--set` overrides, then the varied
values) and validated before any run starts, so a typo or an out-of-range value stops the sweep at once with
the offending combination named. Each run writes one HDF5 file (cases.hdf5) named after its varied values
plus a short hash of the full scene TOML:

    OUTDIR/ft=0.3_w=0.15_angle=0__3f9a1c2e.h5

so changing a `--set` (or anything else in the scene) gives new files instead of silently reusing old ones.
After every finished run the sweep rewrites, atomically, `OUTDIR/summary.csv` and `OUTDIR/summary.h5` with one
row per finished run (columns: see `SUMMARY_COLUMNS`); an interrupted sweep therefore always leaves a valid
summary of what finished, and every run file is either complete or absent (run files are atomic too).

Resuming: a planned run whose file `is_complete` and stores exactly the planned scene TOML is not run again
(its row is read back from the file); missing, partial and failed runs are redone.

Failures: a run that raises a `RollcontactError` (no convergence, grid too large, contact at the grid edge)
is recorded with status 'failed' and its message; the other runs go on.

Parallelism: local processes by default (`concurrent.futures.ProcessPoolExecutor`, 'forkserver' context
with the solver modules preloaded, one BLAS thread per worker; FFTW threads come from the scene,
`[solver] threads`, default 1); `jobs=1` runs in this process; `scheduler=ADDRESS` submits the runs to a Dask
distributed cluster (optional extra `dask`, imported only then).

Limit search (`search_limits`): for each combination of the varied keys, bisection in f_t (or in w when
load.ft is varied) on the state of the run, shakedown below, ratcheting above, to a stated tolerance.

Units: the scene's (mm, N, MPa, degrees); f_t = Ft/(mu Fn), w = W/a, u = U/U0 (seed Eq. 9).
"""
from __future__ import annotations

import csv
from dataclasses import dataclass, field
import hashlib
import itertools
import math
import multiprocessing
import os
from pathlib import Path
import re
import signal
import sys
import threading
import time
import tomllib

import h5py
import numpy as np

from bem.errors import InputError, RollcontactError, SceneError

from .hdf5 import is_complete, summary_from_attrs
from .scene import Scene, key_unit

SUMMARY_COLUMNS = ("index", "state", "status", "f_t", "w", "angle", "u_sd", "du", "U_sd", "dU_per_period",
                   "u_stat", "periods_to_shakedown", "steps", "iterations", "wall_time", "file", "error")
"""Columns of summary.csv / summary.h5 after the varied keys (one column per varied key, named by the key).

index: position in the plan; state: static/shakedown/ratcheting/undecided/gross_sliding ('' if the run
failed before classifying); status: complete/failed; f_t = Ft/(mu Fn); w = W/a; angle: rolling direction
relative to Ft (deg); u_sd, du, u_stat: normalised by U0 (seed Eq. 9); U_sd, dU_per_period: mm;
periods_to_shakedown, steps, iterations: counts; wall_time: s of the run itself; file: run file name
(relative to OUTDIR); error: message of a failed run."""

#: `units` attribute of the summary.h5 / limits.h5 columns ('-': dimensionless, a count or text, as in the
#: run files); a varied key takes its scene unit (cases.scene.key_unit).
COLUMN_UNITS = {"angle": "deg", "U_sd": "mm", "dU_per_period": "mm", "wall_time": "s"}
_FLOAT_COLUMNS = ("f_t", "w", "angle", "u_sd", "du", "U_sd", "dU_per_period", "u_stat", "wall_time")
_INT_COLUMNS = ("index", "periods_to_shakedown", "steps", "iterations")
_RANGE_DIGITS = 12          # range values are rounded to 12 significant digits (0.30000000000000004 -> 0.3)
_HASH_CHARS = 8


# ----------------------------------------------------------------------------------------------- axes
@dataclass(frozen=True)
class Axis:
    """One varied scene key and its values, in the order given."""

    key: str
    values: tuple

    @property
    def label(self) -> str:
        return self.key


def parse_vary(spec: str) -> Axis:
    """Parse one `--vary section.key=VALUES` argument.

    VALUES is either a range `start:stop:count` (count evenly spaced values, both ends included) or a comma
    list `v1,v2,...` (one value is allowed). Raises SceneError naming the argument and the expected syntax.
    """
    syntax = ("expected --vary section.key=start:stop:count (count >= 1, both ends included) or "
              "--vary section.key=v1,v2,... e.g. --vary load.ft=0.1:0.9:9 or --vary motion.w=0.1,0.23,0.4")
    if "=" not in spec:
        raise SceneError(f"--vary {spec!r}: {syntax}")
    key, raw = (s.strip() for s in spec.split("=", 1))
    if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*\.[A-Za-z_][A-Za-z0-9_]*", key):
        raise SceneError(f"--vary {spec!r}: key {key!r} is not of the form section.key; {syntax}")
    if not raw:
        raise SceneError(f"--vary {spec!r}: no values; {syntax}")
    if ":" in raw:
        parts = raw.split(":")
        if len(parts) != 3:
            raise SceneError(f"--vary {spec!r}: a range has three parts start:stop:count; {syntax}")
        try:
            start, stop = float(parts[0]), float(parts[1])
        except ValueError:
            raise SceneError(f"--vary {spec!r}: range start and stop must be numbers; {syntax}") from None
        try:
            count = int(parts[2])
        except ValueError:
            raise SceneError(f"--vary {spec!r}: range count {parts[2]!r} must be an integer >= 1; "
                             f"{syntax}") from None
        if count < 1:
            raise SceneError(f"--vary {spec!r}: range count = {count}: allowed range is count >= 1")
        if not (math.isfinite(start) and math.isfinite(stop)):
            raise SceneError(f"--vary {spec!r}: range start and stop must be finite numbers")
        if count == 1:
            values = (start,)
        else:
            values = tuple(float(f"{v:.{_RANGE_DIGITS}g}") for v in np.linspace(start, stop, count))
        if len(set(values)) != len(values):
            raise SceneError(f"--vary {spec!r}: the range repeats values; use start != stop")
        return Axis(key, values)
    items = [s.strip() for s in raw.split(",")]
    if any(not s for s in items):
        raise SceneError(f"--vary {spec!r}: empty item in the comma list; {syntax}")
    values = tuple(_parse_value(s) for s in items)
    if len(set(map(repr, values))) != len(values):
        raise SceneError(f"--vary {spec!r}: a value is listed twice")
    return Axis(key, values)


def _parse_value(raw: str):
    try:
        return tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        return raw


def _format_value(v) -> str:
    """Value as written in --set and in file names: shortest round-trip form of floats, 0.0 -> 0."""
    if isinstance(v, float):
        if v.is_integer() and abs(v) < 1e15:
            return str(int(v))
        return repr(v)
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return v
    return str(v)


def _toml_literal(v) -> str:
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    return _format_value(v)


# ----------------------------------------------------------------------------------------------- plan
@dataclass(frozen=True)
class PlannedRun:
    """One run of a sweep: its varied values, the full scene (as TOML text, what the run file stores) and
    its output file."""

    index: int
    values: dict
    scene_toml: str
    path: Path
    scene_name: str = "scene"

    @property
    def name(self) -> str:
        return self.path.name


def _short_names(keys) -> dict:
    """Key -> short label for file names: the part after the section when that is unique in the sweep."""
    tails = [k.split(".", 1)[1] for k in keys]
    return {k: (t if tails.count(t) == 1 else k) for k, t in zip(keys, tails)}


def run_file_name(values: dict, scene_toml: str) -> str:
    """Deterministic, filesystem-safe file name: varied values, then 8 hex digits of sha1(scene TOML)."""
    short = _short_names(list(values))
    parts = [f"{short[k]}={_format_value(v)}" for k, v in values.items()]
    stem = re.sub(r"[^A-Za-z0-9._=+-]", "-", "_".join(parts)) or "run"
    digest = hashlib.sha1(scene_toml.encode()).hexdigest()[:_HASH_CHARS]
    return f"{stem}__{digest}.h5"


def build_scene(base: Scene, overrides, values: dict) -> Scene:
    """base + `--set` overrides + the varied values (in that order; later wins). Raises SceneError."""
    assignments = list(overrides) + [f"{k}={_toml_literal(v)}" for k, v in values.items()]
    return base.with_overrides(assignments)


def plan_sweep(base: Scene, axes, outdir, overrides=()) -> list[PlannedRun]:
    """Every combination of the axes (first axis slowest) as a validated PlannedRun.

    All combinations are validated before anything runs; if any is invalid a SceneError lists them (up to
    five, with the key, the value and the allowed range from the scene's own validation).
    """
    axes = list(axes)
    keys = [a.key for a in axes]
    if len(set(keys)) != len(keys):
        dup = sorted({k for k in keys if keys.count(k) > 1})
        raise SceneError(f"--vary: key(s) {dup} given more than once; give each key once with all its values")
    try:
        base_checked = base.with_overrides(list(overrides))
    except SceneError as exc:
        raise SceneError(f"--set: {exc}") from None
    outdir = Path(outdir)
    runs, bad = [], []
    for index, combo in enumerate(itertools.product(*(a.values for a in axes))):
        values = dict(zip(keys, combo))
        try:
            scene = build_scene(base, overrides, values)
        except SceneError as exc:
            bad.append(f"  {_describe(values)}: {exc}")
            continue
        toml = scene.to_toml()
        runs.append(PlannedRun(index, values, toml, outdir / run_file_name(values, toml), scene.name))
    if bad:
        n_total = math.prod(len(a.values) for a in axes)
        more = f"\n  ... and {len(bad) - 5} more" if len(bad) > 5 else ""
        raise SceneError(f"{len(bad)} of {n_total} sweep combination(s) are not valid scenes; nothing was run:\n"
                         + "\n".join(bad[:5]) + more)
    del base_checked
    return runs


def _describe(values: dict) -> str:
    return " ".join(f"{k}={_format_value(v)}" for k, v in values.items()) or "(base scene)"


# ---------------------------------------------------------------------------------------- one run
def stored_summary(path) -> dict | None:
    """Status, error, scene TOML and summary attributes of a run file, without reading the fields."""
    try:
        with h5py.File(path, "r") as h5:
            out = {"status": _str(h5.attrs.get("status", "")), "error": _str(h5.attrs.get("error", "")),
                   "scene": _str(h5.attrs.get("scene", ""))}
            out["summary"] = summary_from_attrs(h5["summary"].attrs) if "summary" in h5 else {}
            return out
    except (OSError, KeyError):
        return None


def _str(v):
    return v.decode() if isinstance(v, bytes) else str(v)


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
    from .run import run_scene
    t0 = time.perf_counter()
    try:
        scene = Scene.from_toml_text(scene_toml, name=scene_name)
        outcome = run_scene(scene, out_path)
    except RollcontactError as exc:
        return {"status": "failed", "error": f"{type(exc).__name__}: {exc}", "summary": {},
                "wall_time": time.perf_counter() - t0}
    d = outcome.data
    return {"status": d.status, "error": d.error, "summary": dict(d.summary), "wall_time": outcome.wall_time}


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


# ------------------------------------------------------------------------------------------ summary
def write_summary(outdir, keys, rows, *, stem="summary", columns=SUMMARY_COLUMNS, attrs=None):
    """Write OUTDIR/<stem>.csv and OUTDIR/<stem>.h5 atomically (temporary file + rename), rows by index.

    CSV: header = varied keys then `columns`; floats in full precision (repr), missing values empty.
    HDF5: group /runs with one dataset per column (floats with NaN for missing, ints with -1 for missing,
    strings UTF-8), attributes `varied` (the keys) and any `attrs` given (e.g. the base scene TOML).
    """
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    rows = sorted(rows, key=lambda r: r.get("index", 0))
    header = list(keys) + [c for c in columns if c not in keys]
    tmp = outdir / f".{stem}.csv.{os.getpid()}.tmp"
    with open(tmp, "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(header)
        for r in rows:
            writer.writerow([_csv_cell(r.get(c)) for c in header])
    os.replace(tmp, outdir / f"{stem}.csv")
    tmp = outdir / f".{stem}.h5.{os.getpid()}.tmp"
    try:
        with h5py.File(tmp, "w") as h5:
            h5.attrs["varied"] = list(keys)
            h5.attrs["columns"] = header
            for k, v in (attrs or {}).items():
                h5.attrs[k] = v
            grp = h5.create_group("runs")
            for c in header:
                vals = [r.get(c) for r in rows]
                ds = grp.create_dataset(c, data=_column_array(c, vals))
                ds.attrs["units"] = COLUMN_UNITS.get(c) or key_unit(c)
        os.replace(tmp, outdir / f"{stem}.h5")
    finally:
        if tmp.exists():
            tmp.unlink()


def _csv_cell(v):
    if v is None:
        return ""
    if isinstance(v, float):
        return "" if math.isnan(v) else repr(v)
    return v


def _column_array(name, vals):
    present = [v for v in vals if v is not None and v != ""]
    if name in _INT_COLUMNS or (present and all(isinstance(v, (int, np.integer)) and not isinstance(v, bool)
                                                for v in present) and name not in _FLOAT_COLUMNS):
        return np.array([-1 if v is None or v == "" else int(v) for v in vals], dtype=np.int64)
    if name in _FLOAT_COLUMNS or (present and all(isinstance(v, (int, float, np.number)) for v in present)):
        return np.array([np.nan if v is None or v == "" else float(v) for v in vals], dtype=np.float64)
    return np.array(["" if v is None else str(v) for v in vals], dtype=h5py.string_dtype())


def read_summary(path) -> list[dict]:
    """Rows of a summary.csv as dicts (numbers parsed, empty cells None), sorted by index."""
    with open(path, newline="") as fh:
        rows = [{k: _csv_parse(k, v) for k, v in r.items()} for r in csv.DictReader(fh)]
    return sorted(rows, key=lambda r: r.get("index") or 0)


def _csv_parse(k, v):
    if v == "":
        return None
    if k in ("state", "status", "file", "error"):
        return v
    for conv in (int, float):
        try:
            return conv(v)
        except ValueError:
            pass
    return v


# ------------------------------------------------------------------------------------- execution
def _worker_init(sweep_pid: int):
    """Worker set-up: one BLAS thread, and exit if the sweep process dies (e.g. SIGKILL).

    numba's thread settings are left alone: the kernels are serial (no parallel=True), and changing
    NUMBA_NUM_THREADS after numba is imported (the fork server preloads it) makes every later compilation in
    the worker fail ("Cannot set NUMBA_NUM_THREADS to a different value once the threads have been
    launched") - which a worker meets whenever numba's on-disk cache misses, e.g. on a fresh install.
    With 'forkserver' the worker's parent is the fork server, which outlives a killed sweep, so the sweep's
    own pid is watched (twice a second) besides the parent's."""
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[var] = "1"
    signal.signal(signal.SIGINT, signal.SIG_IGN)    # Ctrl-C is handled by the parent, which stops us
    parent = os.getppid()

    def watch():
        while True:
            time.sleep(0.5)
            if os.getppid() != parent or not _pid_alive(sweep_pid):
                os._exit(1)
    threading.Thread(target=watch, daemon=True).start()


#: Set by the CLI's SIGTERM handler (`cases.sweep_cmd`), which also raises KeyboardInterrupt. An exception raised
#: by a signal handler while Python runs a weakref callback or a finaliser is only printed ("Exception ignored
#: in ...") and the sweep went on to finish with exit code 0 (the kill-and-resume test failed 2 times in 12 on a
#: loaded machine); the loops below raise it again at their next check.
interrupt_requested = threading.Event()


def _raise_if_interrupted():
    if interrupt_requested.is_set():
        raise KeyboardInterrupt


class _LocalPool:
    """ProcessPoolExecutor with the 'forkserver' context (solver modules preloaded once) or 'spawn'."""

    def __init__(self, jobs):
        from concurrent.futures import ProcessPoolExecutor
        methods = multiprocessing.get_all_start_methods()
        ctx = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
        if ctx.get_start_method() == "forkserver":
            ctx.set_forkserver_preload(["cases.run", "cases.sweep"])
        self.executor = ProcessPoolExecutor(max_workers=jobs, mp_context=ctx, initializer=_worker_init,
                                            initargs=(os.getpid(),))

    def submit(self, fn, *args):
        return self.executor.submit(fn, *args)

    def as_completed(self, futures):
        """The futures as they complete, checking `interrupt_requested` at least every 0.5 s."""
        from concurrent.futures import FIRST_COMPLETED, wait
        pending = set(futures)
        while pending:
            done, pending = wait(pending, timeout=0.5, return_when=FIRST_COMPLETED)
            _raise_if_interrupted()
            yield from done

    def stop(self):
        """Cancel what has not started and terminate running workers (their runs are redone on resume)."""
        procs = list(getattr(self.executor, "_processes", {}).values())
        self.executor.shutdown(wait=False, cancel_futures=True)
        for p in procs:
            if p.is_alive():
                p.terminate()
        for p in procs:
            p.join(timeout=5)

    def close(self):
        self.executor.shutdown(wait=True)


class _DaskPool:
    """Runs submitted to a Dask distributed scheduler at `address` (optional dependency)."""

    def __init__(self, address):
        try:
            import distributed
        except ImportError:
            raise InputError("--scheduler needs the optional dependency dask.distributed: "
                             "pip install 'rollcontact[dask]'") from None
        self._distributed = distributed
        try:
            self.client = distributed.Client(address, timeout=30)
        except (OSError, TimeoutError) as exc:
            raise InputError(f"--scheduler {address!r}: cannot connect to the Dask scheduler ({exc})") from None

    def submit(self, fn, *args):
        return self.client.submit(fn, *args, pure=False)

    def as_completed(self, futures):
        return self._distributed.as_completed(futures)

    def stop(self):
        self.client.close()

    def close(self):
        self.client.close()


class _SerialPool:
    """In-process execution (jobs = 1): futures that have already run."""

    class _Done:
        def __init__(self, fn, args):
            self._fn, self._args = fn, args

        def result(self):
            return self._fn(*self._args)

    def submit(self, fn, *args):
        return self._Done(fn, args)

    def as_completed(self, futures):
        return iter(futures)

    def stop(self):
        pass

    def close(self):
        pass


def _make_pool(jobs, scheduler):
    if scheduler:
        return _DaskPool(scheduler)
    if jobs == 1:
        return _SerialPool()
    return _LocalPool(jobs)


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
              f"{_describe({k: row[k] for k in row if '.' in k})}: {what}", file=self.stream, flush=True)


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


def default_jobs() -> int:
    """Number of usable cores (the default of --jobs)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:                  # pragma: no cover - not on Linux
        return os.cpu_count() or 1


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
    plan = plan_sweep(base, axes, outdir, overrides)
    keys = [a.key for a in axes]
    outdir.mkdir(parents=True, exist_ok=True)
    _remove_stale_temporaries(outdir, plan)
    rows, todo = {}, []
    for run in plan:
        if is_done(run):
            rows[run.index] = _stored_row(run, outdir)
        else:
            todo.append(run)
    skipped = len(plan) - len(todo)
    attrs = {"base_scene": base.to_toml(), "overrides": list(overrides) or [""],
             "rollcontact_sweep": "one row per finished run; see cases.sweep.SUMMARY_COLUMNS"}
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
    pool = _make_pool(jobs, scheduler) if todo else None
    try:
        if todo:
            futures = {}
            for run in todo:
                f = pool.submit(execute_run, run.scene_toml, run.scene_name, str(run.path))
                futures[f] = run
            for f in pool.as_completed(list(futures)):
                run = futures[f]
                try:
                    result = f.result()
                except KeyboardInterrupt:
                    raise
                except Exception as exc:     # a worker that died (BrokenProcessPool) or a non-rollcontact bug
                    result = {"status": "failed", "error": f"{type(exc).__name__}: {exc}", "summary": {}}
                row = _row(run, result, outdir)
                rows[run.index] = row
                report.ran += 1
                report.failed += row["status"] != "complete"
                bar.update(row)
                write_summary(outdir, keys, rows.values(), attrs=attrs)
                _raise_if_interrupted()
            pool.close()
        _raise_if_interrupted()
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
    """Delete temporary files a killed run left behind (`.<name>.<pid>.tmp`, see cases.hdf5.write_run)."""
    names = {r.name for r in plan}
    for tmp in outdir.glob(".*.tmp"):
        parts = tmp.name[1:].rsplit(".", 2)
        if len(parts) == 3 and parts[0] in names:
            pid = parts[1]
            if pid.isdigit() and _pid_alive(int(pid)):
                continue
            tmp.unlink(missing_ok=True)


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:                 # pragma: no cover
        return True
    return True


# ------------------------------------------------------------------------------------ limit search
LIMIT_KAPPAS = (1.0, 1.1, 1.5)
"""Closed-form MDR limits reported beside each 3D bracket: seed fits parallel (1) and perpendicular (1.1),
pure MDR (1.5); seed Eqs. 18-19 and theory.md §8.4."""

LIMIT_COLUMNS = ("index", "searched", "lower", "upper", "midpoint", "width", "status", "probes",
                 "undecided", "mdr_kappa=1", "mdr_kappa=1.1", "mdr_kappa=1.5", "f_t", "w", "error")
"""Columns of limits.csv / limits.h5 after the varied keys.

searched: 'f_t' (limit f_t,lim(w), when w is varied) or 'w' (limit w_lim(f_t), when f_t is varied);
lower: largest searched value found to shake down; upper: smallest found to ratchet (or slide);
midpoint, width = upper - lower; status: 'ok' (width <= tol), 'widened' (a probe stayed undecided after
two doublings of the periods: the bracket is the neighbourhood around it), 'failed' (error says why);
probes: runs made (or reused); undecided: searched values that stayed undecided (';'-separated);
mdr_kappa=K: closed-form limit for kappa = K (seed Eqs. 18-19, or its inverse w_lim); f_t, w: the other,
fixed, normalised coordinate of the search (f_t = Ft/(mu Fn), w = W/a)."""

_FT_KEYS = ("load.ft", "load.Ft")
_W_KEYS = ("motion.w", "motion.W")
_SEARCH_RANGE = {"load.ft": (0.01, 0.99), "motion.w": (0.02, 0.98)}
_BRACKET_MARGIN = 0.05          # the first bracket is the closed forms' [kappa = 1.5, kappa = 1] range +- this
_UNDECIDED_RETRIES = 2          # an undecided probe is rerun with 2x, then 4x the periods


def _side(state: str) -> int:
    """-1 below the limit (shakedown/static), +1 above (ratcheting/gross sliding), 0 undecided."""
    return {"shakedown": -1, "static": -1, "ratcheting": 1, "gross_sliding": 1}.get(state, 0)


class _LimitSearch:
    """Bisection of one combination: probes are ordinary run files in `runs_dir` (so a rerun resumes)."""

    def __init__(self, base, overrides, values, searched, tol, runs_dir, outdir, log):
        self.base, self.overrides, self.values = base, list(overrides), dict(values)
        self.searched, self.tol, self.runs_dir, self.outdir, self.log = searched, tol, runs_dir, outdir, log
        self.periods = build_scene(base, overrides, values).motion.periods
        self.probes, self.undecided = 0, []

    def run(self, x, periods) -> str:
        values = dict(self.values)
        values[self.searched] = float(f"{x:.{_RANGE_DIGITS}g}")
        extra = [] if periods == self.periods else [f"motion.periods={periods}"]
        name_values = dict(values, **({"motion.periods": periods} if extra else {}))
        scene = build_scene(self.base, self.overrides + extra, values)
        toml = scene.to_toml()
        run = PlannedRun(self.probes, name_values, toml, self.runs_dir / run_file_name(name_values, toml),
                         scene.name)
        self.probes += 1
        if is_done(run):
            summary = stored_summary(run.path)["summary"]
        else:
            result = execute_run(toml, scene.name, str(run.path))
            if result["status"] != "complete":
                raise RollcontactError(f"probe {_describe(name_values)} failed: {result['error']}")
            summary = result["summary"]
        state = summary.get("state") or ""
        if self.log:
            print(f"limit-search {_describe(self.values)}: {self.searched}={x:.6g} periods={periods} -> {state}",
                  file=sys.stderr, flush=True)
        return state

    def classify(self, x) -> int:
        periods = self.periods
        for _ in range(_UNDECIDED_RETRIES + 1):
            side = _side(self.run(x, periods))
            if side != 0:
                return side
            periods *= 2
        self.undecided.append(x)
        return 0

    def bracket(self, guess_lo, guess_hi):
        """Find lo (below the limit) and hi (above it), starting from the closed-form guesses."""
        xmin, xmax = _SEARCH_RANGE[self.searched]
        lo, hi = max(xmin, guess_lo), min(xmax, guess_hi)
        step = _BRACKET_MARGIN
        while True:
            s = self.classify(lo)
            if s == -1:
                break
            if s == 1:
                hi = min(hi, lo)
            if lo <= xmin:
                raise RollcontactError(f"{self.searched} = {xmin}: still no shakedown at the lower end of the "
                                       f"search range [{xmin}, {xmax}]")
            lo, step = max(xmin, lo - step), 2 * step
        step = _BRACKET_MARGIN
        while hi <= lo:
            hi = min(xmax, lo + step)
        while True:
            s = self.classify(hi)
            if s == 1:
                break
            if s == -1:
                lo = max(lo, hi)
            if hi >= xmax:
                raise RollcontactError(f"{self.searched} = {xmax}: still no ratcheting at the upper end of the "
                                       f"search range [{xmin}, {xmax}]")
            hi, step = min(xmax, hi + step), 2 * step
        return lo, hi

    def bisect(self, lo, hi):
        """Halve [lo, hi] until hi - lo <= tol; an undecided midpoint ends it with a widened bracket."""
        while hi - lo > self.tol * (1 + 1e-9):
            m = 0.5 * (lo + hi)
            s = self.classify(m)
            if s == -1:
                lo = m
            elif s == 1:
                hi = m
            else:
                return self.widen(m, lo, hi) + ("widened",)
        return lo, hi, "ok"

    def widen(self, m, lo, hi):
        """Around an undecided m: step outwards by tol/2, tol, 2 tol, ... until each side is decided."""
        h, lo_found, hi_found = 0.5 * self.tol, False, False
        while not (lo_found and hi_found):
            if not lo_found:
                a = m - h
                if a <= lo:
                    lo_found = True
                elif self.classify(a) == -1:
                    lo, lo_found = a, True
            if not hi_found:
                b = m + h
                if b >= hi:
                    hi_found = True
                elif self.classify(b) == 1:
                    hi, hi_found = b, True
            h *= 2
        return lo, hi


def _limit_task(base_toml, base_name, overrides, values, searched, tol, runs_dir, outdir, log) -> dict:
    """Worker entry of one limit search (picklable in and out); never raises a RollcontactError."""
    from solver import mdr_limits as lim
    base = Scene.from_toml_text(base_toml, name=base_name)
    search = _LimitSearch(base, overrides, values, searched, tol, Path(runs_dir), Path(outdir), log)
    scene = build_scene(base, overrides, values)
    row = dict(values)
    kappas = {k: f"mdr_kappa={k:g}" for k in LIMIT_KAPPAS}
    if searched == "load.ft":
        w = scene.amplitude / scene.contact_radius
        row.update(searched="f_t", w=w, f_t=None)
        closed = {k: lim.f_t_lim(min(w, 1.0), k) for k in LIMIT_KAPPAS}
    else:
        f = scene.f_t
        row.update(searched="w", f_t=f, w=None)
        closed = {k: lim.w_lim(f, k) for k in LIMIT_KAPPAS}
    for k, label in kappas.items():
        row[label] = closed[k]
    lo_guess, hi_guess = min(closed.values()) - _BRACKET_MARGIN, max(closed.values()) + _BRACKET_MARGIN
    try:
        lo, hi = search.bracket(lo_guess, hi_guess)
        lo, hi, status = search.bisect(lo, hi)
        row.update(lower=lo, upper=hi, midpoint=0.5 * (lo + hi), width=hi - lo, status=status, error="")
    except RollcontactError as exc:
        row.update(status="failed", error=f"{type(exc).__name__}: {exc}")
    row.update(probes=search.probes, undecided=";".join(f"{x:.6g}" for x in search.undecided))
    return row


@dataclass
class LimitReport:
    """Rows of limits.csv (one per combination of the varied keys) and where they were written."""

    outdir: Path
    keys: list
    searched: str
    rows: list = field(default_factory=list)
    wall_time: float = 0.0

    @property
    def limits_csv(self) -> Path:
        return self.outdir / "limits.csv"


def search_limits(base: Scene, axes, outdir, *, overrides=(), tol=0.01, jobs=None, scheduler=None,
                  progress=sys.stderr) -> LimitReport:
    """Shakedown limit of the 3D model for every combination of the axes, by bisection on the run state.

    Varying motion.w (or motion.W) searches f_t,lim(w); varying load.ft (or load.Ft) searches w_lim(f_t);
    other varied keys (e.g. motion.angle) are carried along. Bisection to `tol` (in f_t or w units) from a
    bracket around the closed-form limits for kappa = 1 ... 1.5; an undecided probe is rerun with doubled
    periods at most twice, else the bracket is widened around it (status 'widened'). Probe runs are files
    in OUTDIR/runs (named like sweep runs, so a rerun reuses them); results in OUTDIR/limits.{csv,h5}
    (columns: LIMIT_COLUMNS), rewritten after each finished combination. Combinations run in parallel.
    """
    t0 = time.perf_counter()
    axes = [parse_vary(a) if isinstance(a, str) else a for a in axes]
    keys = [a.key for a in axes]
    has_ft = [k for k in keys if k in _FT_KEYS]
    has_w = [k for k in keys if k in _W_KEYS]
    if has_ft and has_w:
        raise SceneError(f"limit-search: vary either the amplitude (motion.w) or the load (load.ft), not both "
                         f"(got {has_w + has_ft}); the other one is searched")
    if not (has_ft or has_w):
        raise SceneError("limit-search: vary motion.w (to find f_t,lim(w)) or load.ft (to find w_lim(f_t)), "
                         "e.g. --vary motion.w=0.1,0.23,0.4")
    if not tol > 0 or not tol < 0.5:
        raise InputError(f"--tol = {tol!r}: allowed range is 0 < tol < 0.5 (in units of f_t or w)")
    searched = "motion.w" if has_ft else "load.ft"
    lo_x = _SEARCH_RANGE[searched][0]
    plan = plan_sweep(base, axes, outdir, list(overrides) + [f"{searched}={lo_x}"])
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    runs_dir = outdir / "runs"
    jobs = default_jobs() if jobs is None else int(jobs)
    if jobs < 1:
        raise InputError(f"--jobs = {jobs!r}: allowed range is jobs >= 1")
    attrs = {"base_scene": base.to_toml(), "overrides": list(overrides) or [""], "tol": float(tol),
             "searched": searched}
    if progress is not None:
        print(f"limit-search: {len(plan)} combination(s), searching {searched} to tol = {tol:g}; probe runs in "
              f"{runs_dir}", file=progress, flush=True)
    pool = _make_pool(min(jobs, len(plan)), scheduler)
    rows = {}
    try:
        futures = {}
        for run in plan:
            f = pool.submit(_limit_task, base.to_toml(), base.name, list(overrides), run.values, searched,
                            float(tol), str(runs_dir), str(outdir), progress is not None)
            futures[f] = run
        for f in pool.as_completed(list(futures)):
            run = futures[f]
            try:
                row = f.result()
            except KeyboardInterrupt:
                raise
            except Exception as exc:
                row = dict(run.values, status="failed", error=f"{type(exc).__name__}: {exc}")
            row["index"] = run.index
            rows[run.index] = row
            write_summary(outdir, keys, rows.values(), stem="limits", columns=LIMIT_COLUMNS, attrs=attrs)
            if progress is not None:
                what = (f"{row['searched']} in [{row['lower']:.4f}, {row['upper']:.4f}] ({row['status']})"
                        if row["status"] != "failed" else f"FAILED ({row['error']})")
                print(f"limit-search [{len(rows)}/{len(plan)}] {_describe(run.values)}: {what}",
                      file=progress, flush=True)
            _raise_if_interrupted()
        pool.close()
        _raise_if_interrupted()
    except KeyboardInterrupt:
        pool.stop()
        write_summary(outdir, keys, rows.values(), stem="limits", columns=LIMIT_COLUMNS, attrs=attrs)
        raise
    return LimitReport(outdir, keys, searched, [rows[i] for i in sorted(rows)], time.perf_counter() - t0)

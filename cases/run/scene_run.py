"""Run one scene: the single entry point of the CLI, the sweeps and the Python API (`rollcontact.run`).

`run_scene` runs the scene's model ([solver] fidelity: the BEM model, cases.run.bem_run, or the 1-D MDR model,
cases.run.mdr_run; 'auto' chooses between them by the measured MDR map and says so on stderr, cases.run.fidelity;
[rolling] scenes: cases.run.creep_run) and, given a file, writes the result to HDF5. No result is lost and none is replaced unasked:

* one writer per file: the run holds the output's lock (cases.results.lock) from start to end; a second writer is
  refused at once, naming the holder;
* an existing file is not replaced unless `overwrite` (the CLI's --overwrite), or when a restart continues an
  incomplete run in its own file;
* a BEM run writes checkpoints as it goes (cases.run.checkpoint): after kill -9 the file holds every finished
  period with status 'incomplete';
* a run that fails still writes the steps it completed (status 'failed'), and an interrupted one (Ctrl-C,
  SIGTERM through the CLI) writes them before RunInterrupted is raised; neither is written over a complete run
  file: they, and the checkpoints of a run that replaces one, go to <name>.partial.h5 beside it;
* with `stresses`, the subsurface stresses of each stored step are computed when it is stored and kept in a file of
  their own until the final write puts them in the run's file (cases.run.step_stresses): a killed run keeps them,
  and its restart computes only the others.

Units: mm, N, MPa.
"""
from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path
import signal
import sys
import threading

import h5py

from rollcontact.bem.errors import (InputError, OutputExistsError, OutputInUseError, OutputWriteError,
                                    RollcontactError)
from rollcontact.bem.wisdom import process_exists
from rollcontact.cases.arguments import arg, flag, on_command_line, restart_hint
from rollcontact.cases.results.hdf5 import is_complete, stored_history, stored_summary, wait_for_replaced, write_run
from rollcontact.cases.results.lock import OutputLock, lock_path
from rollcontact.cases.results.outputs import free_name
from rollcontact.cases.results.run_result import RunInterrupted, RunResult
from rollcontact.cases.results.subsurface import Subsurface
from rollcontact.cases.run.checkpoint import Checkpoints
from rollcontact.cases.run.fidelity import choose_fidelity
from rollcontact.cases.scene.scene import Scene, stored_name


def run_scene(scene: Scene, out=None, *, overwrite=False, progress=None, restart=None,
              attrs: dict | None = None, label: str | None = None, lock: OutputLock | None = None,
              stresses: bool = False, depths=None, new_name: bool = False) -> RunResult:
    """Run `scene`; write the result to `out` (HDF5) unless it is None. Returns the result (also on failure), its
    `path` the file written.

    overwrite: replace an existing `out` (else OutputExistsError, before any work). progress: callable(message)
    for progress lines (None: silent); restart: a cases.run.restart.RestartSource to continue from (BEM runs);
    attrs: further root attributes of the file (a restart's source and step); label: how messages name `out`
    (default '-o OUT'); lock: the output's lock when the caller holds it already (a sweep, which claims its runs);
    stresses: add the subsurface stresses of every stored step to the file, computed as the run goes, at `depths`
    (mm; None: the default depths), as `rollcontact stresses RUN.h5 --all-steps` would (the result's `subsurface`).
    new_name: when `out` exists (or another process is writing it), write to the first of <stem>-2.h5, -3, ...
    that is free, claimed through its lock so that runs started together take different names (the result's `path`
    says which; `progress` is told), unless the run continues an incomplete `out` in place.
    OutputInUseError when another process writes `out` (or the partial file beside it). A symbolic link is
    followed: the file it points to is the output.
    """
    if stresses and scene.wheelrail_on:
        raise InputError(f"{flag('stresses')}: a [wheelrail] run stores its patches in /patches, each in its own "
                         "tangent plane; the subsurface stresses of its patches are not computed")
    if out is None:
        if stresses:
            raise InputError(f"{flag('stresses')}: the stresses go into the run's file; give an output file "
                             f"({arg('output')})")
        return _run_model(scene, progress, restart, None, None)
    out = Path(out).resolve() if Path(out).is_symlink() else Path(out)
    if lock is None and new_name and not _resuming(out, restart):
        lock = _claim_free_name(out, progress)
        out, label, locks = lock.output, lock.label, [lock]
    else:
        label = label or f"{arg('output')} {out}"
        locks = [] if lock is not None else [OutputLock(out, label=label).acquire()]
    try:
        target = _target(out, overwrite, restart, label, scene)
        if target != out:
            locks.append(OutputLock(target, label=f"{label} (its partial file {target.name})").acquire())
        for path in (out, target):
            remove_stale_temporaries(path)
        shakedown = not (scene.rolling_on or scene.wheelrail_on)
        stepped = shakedown and (scene.solver.fidelity == "bem" or (scene.solver.fidelity == "auto"
                                                                    and choose_fidelity(scene).model == "bem"))
        checkpoints = Checkpoints(target, attrs) if stepped else None
        stepwise = None
        if stresses:
            from rollcontact.cases.run.step_stresses import StepStresses
            stepwise = StepStresses(scene, target, depths, restart, progress)
        try:
            result = _run_model(scene, progress, restart, checkpoints, stepwise)
        except RunInterrupted as exc:
            try:
                _finish(exc.result, out, target, attrs, stepwise)
            except OutputWriteError as failed:
                raise stopped_writing(failed, target, stepwise, exc.result) from None
            raise
        except OutputWriteError as exc:
            raise stopped_writing(exc, target, stepwise) from None
        finally:
            if checkpoints is not None:
                checkpoints.close()
        try:
            cut = stepwise is not None and not _complete_stresses(stepwise, result, progress)
            _finish(result, out, target, attrs, stepwise)
        except OutputWriteError as exc:
            raise stopped_writing(exc, target, stepwise, result) from None
        if cut:
            raise KeyboardInterrupt     # after the run's file is written, with the stresses computed until then
    finally:
        for held in reversed(locks):
            held.release()
    return result


def _run_model(scene, progress, restart, checkpoints, stresses) -> RunResult:
    """The scene's model; each imported when it runs (a process loads only the model it uses)."""
    if scene.wheelrail_on:
        if restart is not None:
            raise InputError(f"{arg('restart')}: a [wheelrail] scene is solved in one run; there is nothing to "
                             "restart")
        from rollcontact.cases.run.wheelrail_run import run_wheelrail
        return run_wheelrail(scene, progress=progress)
    if scene.rolling_on:
        if restart is not None:
            raise InputError(f"{arg('restart')}: a [rolling] scene is solved in one run; there is nothing to restart")
        from rollcontact.cases.run.creep_run import run_creep
        return run_creep(scene, progress=progress)
    choice = choose_fidelity(scene)
    choice.announce()
    if choice.model == "mdr":
        from rollcontact.cases.run.mdr_run import run_mdr
        result = run_mdr(scene, progress=progress)
    else:
        from rollcontact.cases.run.bem_run import run_bem
        result = run_bem(scene, progress=progress, restart=restart, checkpoint=checkpoints, stresses=stresses)
    if choice.automatic:
        result.summary.update(choice.summary())
    return result


def _complete_stresses(stresses, result: RunResult, progress):
    """The stresses of the stored steps still without them: the last step of a run that failed (its fields are
    stored when it stops), every step of a model that does not compute them as it goes ([rolling] scenes). An error
    here, or an interrupt (then False is returned), is reported and leaves the run's own results to be written."""
    if not len(result.field_steps):
        return True
    stresses.start(result.x, result.y, result.summary.get("a"))
    try:
        for i, step in enumerate(result.field_steps):
            stresses.ensure(step, *(result.fields[n][i] for n in ("p", "tau_x", "tau_y")))
    except OutputWriteError:
        raise
    except (RollcontactError, KeyboardInterrupt) as exc:
        if progress:
            why = "interrupted" if isinstance(exc, KeyboardInterrupt) else f"{type(exc).__name__}: {exc}"
            progress(f"{flag('stresses')}: stopped at step {step} ({why}); the run is written with the stresses computed")
        return not isinstance(exc, KeyboardInterrupt)
    return True


def stopped_writing(exc: OutputWriteError, target: Path, stresses=None, result=None) -> OutputWriteError:
    """The error of a run that could not write its file (a checkpoint, a step's stresses, the final write): `exc`'s
    message, then what is kept on disk and how to continue. Nothing more is written: the last good checkpoint in
    `target` (the file the run wrote as it went) is kept as it was, with every step file of `run --stresses`.
    `result`: the run as far as it went, still in memory (then the error's `result`)."""
    parts = [str(exc), "the run stopped"]
    kept = kept_checkpoint(target)
    if kept:
        depths = None if stresses is None or stresses.default else stresses.z
        parts.append(f"its last checkpoint is kept in {target} ({kept}); continue with: "
                     f"{restart_hint(target, stresses is not None, depths)}")
    elif target.exists():
        parts.append(f"{target} is left as it was")
    else:
        parts.append("no checkpoint of it was written, so nothing of it is on disk")
    if stresses is not None:
        steps = sorted(stresses.folder.glob("step_*.h5")) if stresses.folder.is_dir() else []
        if not steps and stresses.folder.is_dir():
            try:
                stresses.folder.rmdir()          # made by this run, empty: a step file could not be written
            except OSError:
                pass
        if steps:
            parts.append(f"the subsurface stresses of {len(steps)} stored step(s) are kept in {stresses.folder}")
    error = OutputWriteError("; ".join(parts), path=exc.path, errno=exc.errno)
    error.result, error.restart = result, (target if kept else None)
    return error


def kept_checkpoint(path: Path) -> str | None:
    """'N steps, up to period P' of the run file `path` when it is a checkpoint a restart continues from (status
    'incomplete' or 'failed', with the fields of a stored step), else None."""
    stored = stored_summary(path) if path.is_file() else None
    if stored is None or stored["status"] == "complete":
        return None
    try:
        h = stored_history(path, ("step", "period"))
        with h5py.File(path, "r") as h5:
            snapshots = len(h5["fields/step"])
    except (OSError, KeyError):
        return None
    if not snapshots or not len(h["step"]):
        return None
    return f"status '{stored['status']}', {len(h['step'])} steps, up to period {int(h['period'][-1])}"


def _resuming(out: Path, restart) -> bool:
    """True when the run continues the incomplete run stored in `out` itself."""
    return (restart is not None and out.exists() and Path(restart.path).resolve() == out.resolve()
            and restart.data.status != "complete")


def _claim_free_name(base: Path, progress) -> OutputLock:
    """The lock of the first of `base`, <stem>-2<suffix>, -3, ... that exists neither as a file nor as a lock file
    and whose lock this process takes (another run started at the same moment takes the next one)."""
    n, candidate = 1, base
    while True:
        if not candidate.exists() and not lock_path(candidate).exists():
            lock = OutputLock(candidate, label=f"{arg('output')} {candidate}")
            try:
                lock.acquire()
            except OutputInUseError:
                lock = None
            if lock is not None:
                if not candidate.exists():
                    break
                lock.release()
        n += 1
        candidate = base.with_name(f"{base.stem}-{n}{base.suffix}")
    if candidate != base and progress:
        progress(f"{base} exists: writing to {candidate} (no file is replaced without {arg('output')} ... "
                 f"{flag('overwrite')})")
    return lock


def _target(out: Path, overwrite: bool, restart, label: str, scene: Scene | None = None) -> Path:
    """Where the run writes until it completes: `out`, or, beside a complete run file that it is allowed to
    replace, <name>.partial.h5 (or <name>.partial-2.h5, ... when that holds the result of another run).
    OutputExistsError when `out` exists and may not be replaced."""
    if not out.exists():
        return out
    resuming = (restart is not None and Path(restart.path).resolve() == out.resolve()
                and restart.data.status != "complete")
    if not (overwrite or resuming):
        raise OutputExistsError(f"{label}: {describe_file(out, scene)} exists; rollcontact does not replace a file unless "
                                f"asked: {'add' if on_command_line() else 'pass'} {flag('overwrite')}, or choose "
                                "another name")
    return free_name(out.with_name(out.stem + ".partial" + out.suffix)) if is_complete(out) else out


def describe_file(path: Path, scene: Scene | None = None) -> str:
    """What an existing output is, for messages: 'the complete run file X (scene S; the same scene as this run's)', 'the
    file X (not a run file)', ...; with `scene` (the run about to be written), whether the stored scene is the same
    or in which keys it differs."""
    if path.is_dir():
        return f"the folder {path}"
    stored = stored_summary(path)
    if stored is None:
        return f"the file {path} (not a run file)"
    what = f"scene '{stored_name(stored['scene']) or '?'}'"
    if scene is not None:
        try:
            other = Scene.from_toml_text(stored["scene"], run_limits=False).to_dict(include_none=True)
        except RollcontactError:
            other = None
        mine = scene.to_dict(include_none=True)
        if other is not None:
            differ = [f"{sec}.{key}" for sec in sorted(set(mine) | set(other))
                      for key in sorted(set(mine.get(sec, {})) | set(other.get(sec, {})))
                      if mine.get(sec, {}).get(key) != other.get(sec, {}).get(key)]
            what += ("; the same scene as this run's" if not differ else
                     f"; it differs from this run's in {', '.join(differ[:4])}{', ...' if len(differ) > 4 else ''}")
    return f"the {stored['status'] or 'unfinished'} run file {path} ({what})"


def _finish(result: RunResult, out: Path, target: Path, attrs, stresses=None):
    """The final write: to `out` when the run completed (then the partial file this run wrote beside a complete one
    goes), else to `target`, with the stresses computed as the run went (then their folder goes). A second Ctrl-C or
    SIGTERM during it waits until it is done."""
    result.attrs.update(attrs or {})
    path = out if result.status == "complete" else target
    filled = []
    extend = None if stresses is None else (lambda h5: filled.extend(stresses.fill(h5, result.field_steps, result.fields)))
    with _deferred_interrupts():
        try:
            write_run(path, result, result.snapshot_chunks, extend=extend)
            result.path = path
            if path == out and target != out:
                target.unlink(missing_ok=True)      # this run's checkpoints (the name was free when it started)
            if stresses is not None:
                stresses.discard()
                result.subsurface = Subsurface.of_file(path, seconds=stresses.seconds,
                                                       computed=list(stresses.computed), reused=list(stresses.reused))
        finally:
            wait_for_replaced()


@contextmanager
def _deferred_interrupts():
    """SIGINT and SIGTERM held back (delivered on exit) around a write that must not be cut short; a no-op outside
    the main thread of the main interpreter, where signals are not delivered anyway."""
    signals = {signal.SIGINT, signal.SIGTERM}
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, signals)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def remove_stale_temporaries(out: Path):
    """Delete the temporary files (.<name>.<pid>.tmp and .<name>.<pid>.old, cases.results.hdf5) that processes
    writing `out` left behind when they were killed; those of live processes are kept."""
    prefix = f".{out.name}."
    for tmp in out.parent.glob(f".{out.name}.*"):
        pid, _, suffix = tmp.name[len(prefix):].partition(".")
        if suffix in ("tmp", "old") and pid.isdigit() and not process_exists(int(pid)):
            tmp.unlink(missing_ok=True)


def print_progress(message: str):
    """The progress callable of the CLI: one line on stderr."""
    print(message, file=sys.stderr, flush=True)

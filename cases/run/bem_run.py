"""One BEM run of a scene: scene -> grid and operator (rollcontact.bem) -> stepping solver (rollcontact.solver)
-> a RunResult (written to HDF5 by cases.run.scene_run). Units: mm, N, MPa.

A run that fails (no convergence, contact at the grid edge) still returns the steps it finished, with status
'failed' and the error; an interrupt (Ctrl-C) raises RunInterrupted carrying them. Gross sliding is a result
(state 'gross_sliding'), not a failure.
"""
from __future__ import annotations

import time

from rollcontact.bem.errors import GrossSlidingError, OutputWriteError, RollcontactError
from rollcontact.cases.results.hdf5 import version
from rollcontact.cases.results.run_result import RunInterrupted, RunResult
from rollcontact.cases.run.discretise import field_steps, scene_grid, scene_operator, scene_path
from rollcontact.cases.run.recorder import StepRecorder
from rollcontact.cases.run.summary import summarise
from rollcontact.cases.run.viscoelastic import scene_memory
from rollcontact.cases.scene.friction import local_friction
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.normal import NormalParams
from rollcontact.solver.rolling import StepParams, run_path
from rollcontact.solver.tangential import TangentialParams, kernels_cached

#: Seconds between two progress lines.
PROGRESS_INTERVAL = 2.0


def run_bem(scene: Scene, *, progress=None, restart=None, checkpoint=None, stresses=None) -> RunResult:
    """Run `scene` on the boundary-element model and return the result (written by the caller).

    progress: callable(message) for progress lines (None: silent). restart: a cases.run.restart.RestartSource to
    continue from (its history and snapshots up to the restart step are part of the result). checkpoint: a
    cases.run.checkpoint.Checkpoints that writes the finished steps as the run goes (at every period end and
    every few seconds). stresses: a cases.run.step_stresses.StepStresses that computes the subsurface stresses of each
    stored step when it is stored (those a restart inherits first). A scene whose grid would exceed the element limit
    raises SceneError before any work.
    """
    t_start = time.perf_counter()
    scene_grid(scene)          # refuses a scene whose grid would exceed the element limit, before any work
    path = scene_path(scene)
    grid = scene_grid(scene, path)
    op = scene_operator(scene, grid)
    tol, max_iter = scene.solver.tol, scene.solver.max_iter
    params = StepParams(NormalParams(tol=tol, max_iter=max_iter), TangentialParams(tol=tol, max_iter=max_iter),
                        coupling_tol=max(tol, 1e-10))
    friction = local_friction(scene)
    memory = scene_memory(scene, op)      # viscoelastic bodies: their element states (None for elastic ones)
    if memory is not None and restart is not None:
        restart.restore(memory)
    recorder = StepRecorder(grid, path, field_steps(scene, path), restart, compress=checkpoint is not None,
                            transverse=scene.transverse_direction,
                            states=() if memory is None else tuple(memory.states()), rolling=scene.rolling_direction,
                            friction=friction is not None)
    result = partial(scene, path, grid, recorder, t_start)
    ends = set(path.period_ends().tolist())
    if progress:
        _announce(progress, grid, path, op, scene)
    status, error, state_label, interrupted = "complete", "", None, None
    last_report = time.perf_counter()
    if stresses is not None:
        stresses.start(grid.x, grid.y, scene.normal_reference.a)       # the summary's a (cases.run.summary)
    try:
        if stresses is not None:
            stresses.catch_up(recorder)          # the snapshots a restart inherits
        for rec in run_path(op, scene.profile, path, Fn=scene.load.Fn, mu=scene.load.mu,
                            params=params, state=None if restart is None else restart.state, memory=memory,
                            friction=friction):
            row = recorder.add(rec)
            if stresses is not None:
                stresses.catch_up(recorder)
            if checkpoint is not None:
                checkpoint.after_step(rec.step in ends, result, len(recorder.stored))
            if progress and (time.perf_counter() - last_report > PROGRESS_INTERVAL or rec.step == path.n_steps - 1):
                last_report = time.perf_counter()
                progress(f"step {rec.step + 1}/{path.n_steps}  period {row['period']}/{scene.motion.periods}  "
                         f"U_x = {row['U_x']:.6f} mm  iterations {row['normal_iterations']}+"
                         f"{row['tangential_iterations']}")
    except GrossSlidingError as exc:
        state_label, error = "gross_sliding", str(exc)
    except OutputWriteError:
        raise               # a checkpoint or a step's stresses could not be written: the run stops (cases.run.scene_run)
    except (RollcontactError, KeyboardInterrupt) as exc:
        status, interrupted = "failed", exc if isinstance(exc, KeyboardInterrupt) else None
        error = "interrupted by the user" if interrupted else f"{type(exc).__name__}: {exc}"
        if interrupted:
            recorder.trim_to_whole_steps()
    if scene.output.fields in ("reversals", "last") or status != "complete":
        recorder.keep_last_step_fields()      # what 'reversals' and 'last' promise, and what --restart needs
    final = result(status=status, error=error, state_label=state_label)
    if checkpoint is not None:
        final.summary.update(checkpoints=checkpoint.written, checkpoint_time=checkpoint.seconds)
    if interrupted:
        raise RunInterrupted(final) from interrupted
    return final


def partial(scene, path, grid, recorder, t_start):
    """result(status, error, state_label, extra_snapshot=False) -> the RunResult of the steps recorded so far
    (with extra_snapshot, also the fields of the last step when they are not stored: a checkpoint's restart
    point), with the compressed snapshots for the writer in `snapshot_chunks`."""
    def result(status, error="", state_label=None, extra_snapshot=False) -> RunResult:
        summary = summarise(scene, path, recorder.history, state_label, grid, time.perf_counter() - t_start)
        if state_label == "gross_sliding":   # the step that found no equilibrium; the solver's message
            summary.update(stopped_at_step=recorder.n_steps, state_message=error)
        history, fields, stored, chunks = recorder.arrays(extra_snapshot=extra_snapshot)
        return RunResult(scene_toml=scene.to_toml(), status=status, error=error, x=grid.x, y=grid.y,
                         history=history, fields=fields, field_steps=stored, summary=summary, version=version(),
                         snapshot_chunks=chunks)
    return result


def _announce(progress, grid, path, op, scene):
    progress(f"grid {grid.nx} x {grid.ny} = {grid.size} elements (dx = {grid.dx}, dy = {grid.dy} mm), "
             f"{path.n_steps} steps, coupling {'on' if op.coupled else 'off'} (beta = {scene.material_pair.beta:.2e})")
    if not kernels_cached():
        progress("compiling the numerical kernels (first run after an install: about half a minute on 2 cores, "
                 "kept for later runs)")

"""Run one scene: the single entry point of the CLI, the sweeps and the Python API (`rollcontact.run`).

`run_scene` runs the scene's model ([solver] fidelity: the BEM model, cases.run.bem_run, or the 1-D MDR model,
cases.run.mdr_run) and writes the result to HDF5 when given a file. It never loses finished work: a run that
fails still writes the steps it completed, with status 'failed' and the error, and an interrupted one
(Ctrl-C, SIGTERM through the CLI) writes them before RunInterrupted is raised; neither is written over a
complete run file (it goes to <name>.partial.h5 beside it). Units: mm, N, MPa.
"""
from __future__ import annotations

from pathlib import Path
import sys

from rollcontact.cases.results.hdf5 import is_complete, write_run
from rollcontact.cases.results.run_result import RunInterrupted, RunResult
from rollcontact.cases.run.bem_run import run_bem
from rollcontact.cases.run.mdr_run import run_mdr
from rollcontact.cases.scene.scene import Scene


def run_scene(scene: Scene, out=None, *, progress=None, restart=None, attrs: dict | None = None) -> RunResult:
    """Run `scene`; write the result to `out` (HDF5) unless it is None. Returns the result (also on failure), its
    `path` the file written.

    progress: callable(message) for progress lines (None: silent); restart: a cases.run.restart.RestartSource to
    continue from (BEM runs); attrs: further root attributes of the file (a restart's source and step).
    """
    try:
        if scene.solver.fidelity == "mdr":
            result = run_mdr(scene, progress=progress)
        else:
            result = run_bem(scene, progress=progress, restart=restart)
    except RunInterrupted as exc:
        _write(exc.result, out, attrs)
        raise
    _write(result, out, attrs)
    return result


def _write(result: RunResult, out, attrs):
    result.attrs.update(attrs or {})
    if out is None:
        return
    out = Path(out)
    if result.status != "complete" and out.exists() and is_complete(out):
        # a run that did not complete is not written over a complete run file (an interrupted rerun would
        # otherwise replace a finished result with a part of one)
        out = out.with_name(out.stem + ".partial" + out.suffix)
    write_run(out, result)
    result.path = out


def print_progress(message: str):
    """The progress callable of the CLI: one line on stderr."""
    print(message, file=sys.stderr, flush=True)

"""The Python API of rollcontact, exposed as `import rollcontact` (the `rollcontact` command is a thin layer over it).

    scene = rollcontact.load_scene(overrides={"load.ft": 0.6, "motion.periods": 4})   # the paper scene, changed
    result = rollcontact.run(scene)                         # in memory; run(scene, "out.h5") also writes HDF5
    result.summary["u_sd"], result.history["U_x"], result.field("p")
    same = rollcontact.read_run("out.h5")                   # a stored run as the same RunResult
    rollcontact.sweep(scene, {"load.ft": [0.2, 0.4], "motion.angle": [0, 90]}, "results/sweep")
    rollcontact.limit_search(scene, {"motion.w": [0.23]}, "results/limits")
    rollcontact.creep_curve(scene, "xi", fidelity=["bem", "fastsim"], output="creep")   # a [rolling] scene

Units: mm, N, MPa, degrees; dimensionless f_t = Ft/(mu Fn), w = W/a, u = U/U0 (seed Eq. 9). Errors are the
CLI's: SceneError (a scene key out of range, naming the key and the range), InputError (a bad argument, naming
it), ConvergenceError; all are RollcontactError. A run that fails still returns its finished steps with
status 'failed'; Ctrl-C raises RunInterrupted, whose `result` holds them.
"""
from __future__ import annotations

from pathlib import Path

from rollcontact.bem.errors import ConvergenceError, InputError, RollcontactError, SceneError
from rollcontact.cases.results.hdf5 import read_run_file
from rollcontact.cases.results.outputs import check_output
from rollcontact.cases.results.run_result import RunInterrupted, RunResult
from rollcontact.cases.scene.scene import Scene, default_scene

__all__ = ["load_scene", "run", "restart", "read_run", "stresses", "sweep", "limit_search", "creep_curve", "RunResult",
           "Scene", "RollcontactError", "InputError", "SceneError", "ConvergenceError", "RunInterrupted"]


def load_scene(path=None, overrides=None) -> Scene:
    """A validated scene: the TOML file `path` (str or Path), or the embedded default (the seed paper's Table 1,
    perpendicular setting, f_t = 0.46, w = 0.23) when `path` is None.

    overrides: {"section.key": value} (e.g. {"load.ft": 0.77, "motion.angle": 0}), or a list of
    "section.key=value" strings as `--set` takes them. SceneError names a key that is unknown or out of range.
    """
    scene = Scene.from_toml(path) if path is not None else default_scene()
    return scene.with_overrides(overrides) if overrides else scene


def run(scene: Scene, output=None, *, overwrite=False, progress=False, stresses=False, depths=None) -> RunResult:
    """Run `scene` on its model ([solver] fidelity: "bem", or "mdr" for the 1-D MDR model) and return the result.

    output: an HDF5 file to write (str or Path; the result's `path`), or None to keep the result in memory only.
    A BEM run writes it as it goes (checkpoints with status 'incomplete'; `restart` continues a killed run).
    overwrite: replace an existing file (else OutputExistsError, before any work); OutputInUseError when another
    process is writing it. progress: True for progress lines on stderr, a callable(message), or False for none.
    stresses: also compute the subsurface stresses of every stored step as the run goes, at `depths` (mm; None: 30
    depths down to 2a), and add them to the file as `stresses(output, steps="all")` would (README, "Stresses below
    the contact"); `result.subsurface` says which.
    """
    from rollcontact.cases.run.scene_run import run_scene
    out = check_output(output) if output is not None else None
    return run_scene(_as_scene(scene), out, overwrite=overwrite, progress=_progress(progress),
                     **_stress_options(stresses, depths))


def restart(path, *, step=None, overrides=None, output=None, overwrite=False, progress=False, stresses=False,
            depths=None) -> RunResult:
    """Continue the stored run `path` from a stored step (default: the last) and return the whole run (the source's
    history and snapshots up to that step, then the continuation).

    overrides: only the keys a restart may change (cases.run.restart.RESTART_SAFE_KEYS, e.g. {"motion.periods": 20}).
    output: the HDF5 file to write, or None to keep the result in memory. It may be `path` itself when that run is
    not complete (a checkpoint of a killed run, or a failed run): the run then continues in its own file.
    overwrite: replace another existing file. stresses, depths: as in `run`; the stresses the source (its file, or
    the folder a killed run left) holds already at the same depths are taken, not computed again.
    """
    from rollcontact.cases.run.restart import continued_scene, load_restart
    from rollcontact.cases.run.scene_run import run_scene
    source = load_restart(path, step)
    items = Scene.assignments(overrides) if overrides else []
    scene = continued_scene(source, items)
    out = check_output(output) if output is not None else None
    if out is not None and out.resolve() == source.path.resolve():
        last = int(source.data.history["step"][-1])
        if source.data.status == "complete" or source.step != last:
            why = ("a complete run" if source.data.status == "complete"
                   else f"whose steps after {source.step} (up to {last}) it would replace")
            raise InputError(f"-o {out}: is the --restart file itself, {why}; write the continuation to another file")
    attrs = dict(restarted_from=str(source.path.resolve()), restart_step=source.step,
                 restart_overrides=items or [""])
    progress = _progress(progress)
    if progress:
        progress(f"continuing {source.path} from step {source.step} (period {source.period})")
    return run_scene(scene, out, overwrite=overwrite, progress=progress, restart=source, attrs=attrs,
                     **_stress_options(stresses, depths))


def _stress_options(stresses, depths) -> dict:
    if depths is not None and not stresses:
        raise InputError(f"depths={depths!r}: applies only with stresses=True (--depths only with --stresses)")
    return dict(stresses=bool(stresses), depths=depths)


def read_run(path) -> RunResult:
    """The run stored in the HDF5 file `path` (written by `run` or `rollcontact run`) as a RunResult. InputError
    when the file is missing or is not a run file."""
    return read_run_file(path, InputError, str(path))


def stresses(path, *, steps=None, depths=None, progress=False) -> dict:
    """Add the subsurface stresses of the run file `path` to it (as `rollcontact stresses`): the stress tensor, von
    Mises, Tresca and the first principal stress at `depths` (mm; default: 30 depths from 0 to 2 a, finer near the
    surface) for `steps` (stored steps, 'all', or None for the last stored one), stored as /subsurface (README, "HDF5
    layout"). Returns {'steps', 'z', 'seconds'}; read them back with h5py or `rollcontact plot`."""
    from rollcontact.cases.run.stresses import add_subsurface
    return add_subsurface(path, steps=steps, depths=depths, progress=_progress(progress))


def sweep(scene: Scene, vary, output, *, overrides=None, jobs=None, scheduler=None, overwrite=False,
          progress=False):
    """Run every combination of the varied keys (as `rollcontact sweep`): one HDF5 file per run in the folder
    `output`, with output/summary.csv and summary.h5; a rerun resumes. Returns a SweepReport (planned, ran,
    skipped, failed, rows: one dict per finished run).

    vary: {"section.key": values}, values a list ([0.2, 0.4]) or a range string "start:stop:count"; or a list
    of `--vary` strings. overrides: as in `load_scene`, applied to every run before the varied values.
    jobs: local worker processes (default: the number of cores; 1 = this process); scheduler: a Dask scheduler
    address (the `dask` extra). overwrite: replace the summary of another sweep in `output` (else
    OutputExistsError). Sweeps started on one folder share the work. progress: True for progress lines on stderr.
    """
    from rollcontact.cases.sweep.runner import run_sweep
    return run_sweep(_as_scene(scene), vary_specs(vary), output, overrides=Scene.assignments(overrides or []),
                     jobs=jobs, scheduler=scheduler, overwrite=overwrite, progress=_stream(progress))


def limit_search(scene: Scene, vary, output, *, overrides=None, tol=0.01, jobs=None, scheduler=None,
                 overwrite=False, progress=False):
    """The 3D shakedown limit by bisection on the run state (as `rollcontact limit-search`): varying motion.w
    searches f_t,lim(w), varying load.ft searches w_lim(f_t), other varied keys are carried along; to `tol` (in f_t
    or w). Results in output/limits.csv and limits.h5, probe runs in output/runs. Returns a LimitReport (rows:
    one dict per combination with lower, upper, midpoint, status and the MDR closed forms).

    vary, overrides, jobs, scheduler, overwrite, progress: as in `sweep` (overwrite: of another search's limits).
    """
    from rollcontact.cases.sweep.limit_search import search_limits
    return search_limits(_as_scene(scene), vary_specs(vary), output, overrides=Scene.assignments(overrides or []),
                         tol=tol, jobs=jobs, scheduler=scheduler, overwrite=overwrite, progress=_stream(progress))


def creep_curve(scene: Scene, of: str = "xi", *, points: int = 20, max: float = 4.0, fidelity=None, output=None,
                overwrite=False) -> dict:
    """Creep-force curves of a [rolling] scene (as `rollcontact creep-curve`): `points` creepages of `of` ("xi",
    "eta", "phi"; the others zero) geometrically from 0.02 to `max` times its saturation creepage, each model of
    `fidelity` ("bem", "fastsim", "fastrip", or a list of them drawn side by side; default the scene's [solver]
    fidelity when it is one of these, else "bem") on the same grid and pressure.

    output: a folder for <scene>_creep_<of>.csv (the exact theory; <..>_<model>.csv for a fast model) and the figure
    <scene>_creep_<of>.png/.pdf, or None for the tables alone. overwrite: replace existing files (else
    OutputExistsError before any work). Returns {"tables": [CurveTable, ...], "paths": [...], "seconds": wall s}.
    Units: mm, N, MPa; phi in 1/mm; forces on the rolling sphere (Kalker's convention).
    """
    import time
    import numpy as np
    from rollcontact.bem.errors import OutputExistsError
    from rollcontact.cases.run.creep_curve import CURVE_FIDELITIES, compute_curves, write_csv
    scene = _as_scene(scene)
    if not scene.rolling_on:
        raise InputError(f"creep-curve: scene {scene.name}: no [rolling] section (mode = \"steady\"); add one, or "
                         "set rolling.mode = \"steady\"")
    if not (int(points) == points and points >= 2 and 0 < max <= 100):
        raise InputError(f"creep-curve: points = {points!r}, max = {max!r}: allowed ranges are points >= 2 (an integer) "
                         "and 0 < max <= 100")
    if fidelity is None:
        fidelity = [scene.solver.fidelity if scene.solver.fidelity in CURVE_FIDELITIES else "bem"]
    fidelity = [fidelity] if isinstance(fidelity, str) else list(dict.fromkeys(fidelity))
    for f in fidelity:
        if f not in CURVE_FIDELITIES:
            raise InputError(f"creep-curve: fidelity = {f!r}: allowed values are {list(CURVE_FIDELITIES)}")
    stem = f"{scene.name}_creep_{of}"
    targets = []
    if output is not None:
        out = Path(output)
        targets = [out / (f"{stem}.csv" if f == "bem" else f"{stem}_{f}.csv") for f in fidelity]
        existing = [t for t in targets + [out / f"{stem}{e}" for e in (".png", ".pdf")] if t.exists()]
        if existing and not overwrite:
            raise OutputExistsError(f"{existing[0]}: exists; rollcontact does not replace a file unless asked: add "
                                    "--overwrite (overwrite=True), or give another folder")
    t0 = time.perf_counter()
    tables = compute_curves(scene, of, np.geomspace(0.02, max, int(points)), fidelity)
    seconds = time.perf_counter() - t0
    paths = []
    if output is not None:
        from rollcontact.cases.plots.creep_figures import plot_curve
        paths = [write_csv(t, path, overwrite=overwrite) for t, path in zip(tables, targets)]
        paths += plot_curve(tables, Path(output), stem, overwrite=overwrite)
    return {"tables": tables, "paths": paths, "seconds": seconds}


def vary_specs(vary) -> list[str]:
    """`--vary` strings from {"section.key": values or "start:stop:count"} (a list of strings passes through)."""
    from rollcontact.cases.sweep.plan import vary_spec
    if isinstance(vary, dict):
        return [vary_spec(key, values) for key, values in vary.items()]
    if isinstance(vary, str):
        return [vary]
    return list(vary)


def _as_scene(scene) -> Scene:
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, (str, Path)):
        return load_scene(scene)
    raise InputError(f"scene: expected a Scene (rollcontact.load_scene) or a TOML file path, got "
                     f"{type(scene).__name__}")


def _progress(progress):
    from rollcontact.cases.run.scene_run import print_progress
    if callable(progress):
        return progress
    return print_progress if progress else None


def _stream(progress):
    import sys
    return sys.stderr if progress else None

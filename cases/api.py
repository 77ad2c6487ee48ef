"""The Python API of rollcontact, exposed as `import rollcontact`; every `rollcontact` command is a thin layer over one
function here (cases.cli.main says how a command is added).

    scene = rollcontact.load_scene(overrides={"load.ft": 0.6, "motion.periods": 4})   # the paper scene, changed
    result = rollcontact.run(scene)                         # in memory; run(scene, "out.h5") also writes HDF5
    result.summary["u_sd"], result.history["U_x"], result.field("p"), result.units["U_x"]
    same = rollcontact.read_run("out.h5")                   # a stored run as the same RunResult (== compares values)
    rollcontact.stresses("out.h5")                          # the subsurface stresses, added to the file
    rollcontact.plot("out.h5"); rollcontact.compare("a.h5", "b.h5")
    rollcontact.sweep(scene, {"load.ft": [0.2, 0.4], "motion.angle": [0, 90]}, "results/sweep")
    rollcontact.limit_search(scene, {"motion.w": [0.23]}, "results/limits")
    rollcontact.limits(w=0.23, ft=0.46)                     # the closed forms (seed Eqs. 12-21)
    rollcontact.creep_curve("cases/creep_steady.toml", of="xi", fidelity=["bem", "fastsim"])   # models side by side
    rollcontact.import_contact("cattaneo.inp", "imported")   # a CONTACT deck as scenes and a report

    command                 function
    run [SCENE]             load_scene + run (default_output without -o)
    run --restart RUN.h5    restart
    limits                  limits
    sweep, limit-search     sweep, limit_search
    plot, compare           plot, compare
    stresses                stresses
    creep-curve             creep_curve
    import-contact          import_contact

Units: mm, N, MPa, degrees; dimensionless f_t = Ft/(mu Fn), w = W/a, u = U/U0 (seed Eq. 9). Errors are the
commands' own messages, naming these functions' arguments (`output`, `overrides`, `overwrite=True`) where a command
names its options (-o, --set, --overwrite): SceneError (a scene key out of range, naming the key and the range),
InputError (a bad argument, naming it), OutputExistsError, OutputInUseError, OutputWriteError (a file that could not
be written: a full disk, a vanished folder, a read-only file system; the run's last checkpoint is kept and the message
says how to continue), ConvergenceError; all are RollcontactError. A run that fails still returns its finished steps
with status 'failed'; Ctrl-C raises RunInterrupted, whose `result` holds them.
"""
from __future__ import annotations

from pathlib import Path

from rollcontact.bem.errors import (ConvergenceError, InputError, OutputExistsError, OutputInUseError,
                                    OutputWriteError, RollcontactError, SceneError)
from rollcontact.cases.results.hdf5 import read_run_file
from rollcontact.cases.results.outputs import check_output
from rollcontact.cases.results.run_result import RunInterrupted, RunResult
from rollcontact.cases.scene.scene import Scene, default_scene

__all__ = ["load_scene", "run", "restart", "read_run", "stresses", "sweep", "limit_search", "import_contact", "limits",
           "plot", "compare", "creep_curve", "default_output", "RunResult", "Scene", "RollcontactError", "InputError",
           "SceneError", "ConvergenceError", "OutputExistsError", "OutputInUseError", "OutputWriteError",
           "RunInterrupted"]


def load_scene(path=None, overrides=None) -> Scene:
    """A validated scene: the TOML file `path` (str or Path), or the embedded default (the seed paper's Table 1,
    perpendicular setting, f_t = 0.46, w = 0.23) when `path` is None.

    overrides: {"section.key": value} (e.g. {"load.ft": 0.77, "motion.angle": 0}; a text value is read as `--set`
    reads it: {"load.ft": "0.77"}), or a list of "section.key=value" strings. SceneError names a key that is
    unknown or out of range, and an override in the other spelling of a quantity the scene gives (load.Ft where it
    gives load.ft)."""
    scene = Scene.from_toml(path) if path is not None else default_scene()
    return scene.with_overrides(overrides) if overrides else scene


def run(scene, output=None, *, overwrite=False, new_name=False, progress=False, stresses=False,
        depths=None) -> RunResult:
    """Run `scene` (a Scene, or a TOML file path) on its model ([solver] fidelity: "bem", or "mdr" for the 1-D MDR
    model) and return the result.

    output: an HDF5 file to write (str or Path; the result's `path`), or None to keep the result in memory only.
    A BEM run writes it as it goes (checkpoints with status 'incomplete'; `restart` continues a killed run).
    overwrite: replace an existing file (else OutputExistsError, before any work); new_name: write to <stem>-2.h5,
    -3, ... when the file exists (the first free name, claimed so that runs started together take different ones;
    `result.path` says which). OutputInUseError when another process is writing it. progress: True for progress
    lines on stderr, a callable(message), or False for none. stresses: also compute the subsurface stresses of every
    stored step as the run goes, at `depths` (mm, increasing; None: 30 depths down to 2a), added to the file as
    `stresses(output, steps="all")` would (`result.subsurface`).
    """
    from rollcontact.cases.run.scene_run import run_scene
    out = check_output(output) if output is not None else None
    return _interrupts_named(out, lambda: run_scene(
        _as_scene(scene), out, overwrite=overwrite, new_name=new_name, progress=_progress(progress),
        **_stress_options(stresses, depths)))


def restart(path, *, step=None, overrides=None, output=None, overwrite=False, new_name=False, progress=False,
            stresses=False, depths=None) -> RunResult:
    """Continue the stored run `path` from a stored step (default: the last) and return the whole run (the source's
    history and snapshots up to that step, then the continuation).

    overrides: only the keys a restart may change (cases.run.restart.RESTART_SAFE_KEYS, e.g. {"motion.periods": 20}).
    output: the HDF5 file to write, or None to keep the result in memory. It may be `path` itself when that run is
    not complete (a checkpoint of a killed run, or a failed run): the run then continues in its own file.
    overwrite, new_name: as in `run`. stresses, depths: as in `run`; the stresses the source (its file, or the
    folder a killed run left) holds already at the same depths are taken, not computed again.
    """
    from rollcontact.cases.run.restart import continued_scene, load_restart
    from rollcontact.cases.run.scene_run import run_scene
    from rollcontact.cases.arguments import arg
    source = load_restart(path, step)
    items = Scene.assignments(overrides) if overrides else []
    scene = continued_scene(source, items)
    out = check_output(output) if output is not None else None
    if out is not None and out.resolve() == source.path.resolve():
        last = int(source.data.history["step"][-1])
        if source.data.status == "complete" or source.step != last:
            why = ("a complete run" if source.data.status == "complete"
                   else f"whose steps after {source.step} (up to {last}) it would replace")
            raise InputError(f"{arg('output')} {out}: is the {arg('restart')} file itself, {why}; write the "
                             "continuation to another file")
    attrs = dict(restarted_from=str(source.path.resolve()), restart_step=source.step, restart_overrides=items)
    progress = _progress(progress)
    if progress:
        progress(f"continuing {source.path} from step {source.step} (period {source.period})")
    return _interrupts_named(out, lambda: run_scene(
        scene, out, overwrite=overwrite, new_name=new_name, progress=progress, restart=source, attrs=attrs,
        **_stress_options(stresses, depths)))


def default_output(scene=None, *, overrides=None, restart=None, step=None) -> Path:
    """Where `rollcontact run` writes without -o: results/<scene name>.h5, or for a variant a name that says what
    differs (results/<scene>__<key=value>....h5 with the overrides), so that no variant overwrites the plain scene's
    file; for a restart results/<run file's name>__from_step<N>[__<key=value>...].h5, or, for a run that did not
    complete (a checkpoint, a failed run) continued from its last step, that run's own file (it continues there). Give `scene` (a Scene or a name) or `restart` (a run
    file, with `step`: default its last stored step). Used with `run(..., new_name=True)`, which adds -2, -3, ...
    to a name that exists."""
    from rollcontact.cases.results.outputs import default_output as named
    items = Scene.assignments(overrides) if overrides else []
    if restart is not None:
        from rollcontact.cases.run.restart import load_restart
        source = load_restart(restart, step)
        if source.data.status != "complete" and source.step == int(source.data.history["step"][-1]):
            return Path(restart)
        return named(Path(restart).stem, items, source.step)      # named after the file it continues
    name = scene.name if isinstance(scene, Scene) else str(scene if scene is not None else default_scene().name)
    return named(name, items, None)


def _stress_options(stresses, depths) -> dict:
    from rollcontact.cases.arguments import arg, flag
    if depths is not None and not stresses:
        raise InputError(f"{arg('depths')} {depths!r}: applies only with {flag('stresses')} (the subsurface stresses "
                         "of the stored steps)")
    if depths is not None:
        from rollcontact.cases.run.stresses import check_depths
        depths = check_depths(depths)
    return dict(stresses=bool(stresses), depths=depths)


def _interrupts_named(out, call):
    """call(), with an interrupt before the run's first step, or while its file is written, raised as RunInterrupted
    naming `out` (its str says what is kept)."""
    try:
        return call()
    except RunInterrupted:
        raise
    except KeyboardInterrupt:
        raise RunInterrupted(None, out) from None


def read_run(path) -> RunResult:
    """The run stored in the HDF5 file `path` (written by `run` or `rollcontact run`) as a RunResult, with its
    subsurface stresses when the file holds them (read on first use). InputError when the file is missing or is not
    a run file (a truncated or damaged one included)."""
    return read_run_file(path, InputError, str(path))


def stresses(run, *, steps=None, depths=None, progress=False):
    """The subsurface stresses of a run (as `rollcontact stresses`): the stress tensor, von Mises, Tresca and the
    first principal stress at `depths` (mm, increasing; default: 30 depths from 0 to 2 a, finer near the surface) for
    `steps` (stored steps, 'all', or None for the last stored one).

    run: a run file (path), whose /subsurface they become (docs/hdf5_schema.md; docs/user_guide.md, "HDF5 layout"; an earlier one is replaced), or a
    RunResult: of a file, added to that file (and its `subsurface` updated), or held in memory only, computed and
    kept in memory. Returns them (cases.results.subsurface.Subsurface: name -> (steps, nz, ny, nx) MPa arrays, with
    `z`, `steps`, `units`; `report()` is the line the command prints)."""
    from rollcontact.cases.results.subsurface import Subsurface
    from rollcontact.cases.run.stresses import add_subsurface, subsurface_in_memory
    progress = _progress(progress)
    if isinstance(run, RunResult) and run.path is None:
        run.subsurface = subsurface_in_memory(run, steps=steps, depths=depths, progress=progress)
        return run.subsurface
    path = run.path if isinstance(run, RunResult) else run
    if not isinstance(path, (str, Path)):
        raise InputError(f"run: expected a run file (a path) or a RunResult, got {type(run).__name__}")
    done = add_subsurface(path, steps=steps, depths=depths, progress=progress)
    found = Subsurface.of_file(path, seconds=done["seconds"], computed=done["steps"])
    if isinstance(run, RunResult):
        run.subsurface = found
    return found


def sweep(scene, vary, output, *, overrides=None, jobs=None, scheduler=None, overwrite=False, progress=False):
    """Run every combination of the varied keys (as `rollcontact sweep`): one HDF5 file per run in the folder
    `output`, with output/summary.csv and summary.h5; a rerun resumes (a run killed part-way continues from its last
    checkpoint). Returns a SweepReport (planned, ran, skipped, failed, rows: one dict per finished run; `report()`).

    vary: {"section.key": values}, values a list ([0.2, 0.4]) or a range string "start:stop:count"; or a list
    of `--vary` strings. overrides: as in `load_scene`, applied to every run (a key also varied is refused).
    jobs: local worker processes (default: the number of cores; 1 = this process); scheduler: a Dask scheduler
    address (the `dask` extra). overwrite: replace the summary of another sweep in `output` (else
    OutputExistsError). Sweeps started on one folder share the work. progress: True for progress lines on stderr.
    """
    from rollcontact.cases.sweep.runner import run_sweep
    return run_sweep(_as_scene(scene), vary_specs(vary), output, overrides=Scene.assignments(overrides or []),
                     jobs=jobs, scheduler=scheduler, overwrite=overwrite, progress=_stream(progress))


def limit_search(scene, vary, output, *, overrides=None, tol=0.01, jobs=None, scheduler=None,
                 overwrite=False, progress=False):
    """The 3D shakedown limit by bisection on the run state (as `rollcontact limit-search`): varying motion.w
    searches f_t,lim(w), varying load.ft searches w_lim(f_t), other varied keys are carried along; to `tol` (in f_t
    or w). Results in output/limits.csv and limits.h5, probe runs in output/runs. Returns a LimitReport (rows:
    one dict per combination with lower, upper, midpoint, status and the MDR closed forms; `report()`). Varied values
    outside the range a search can bracket (cases.sweep.limit_search.fixed_range) are refused before any probe.

    vary, overrides, jobs, scheduler, overwrite, progress: as in `sweep` (overwrite: of another search's limits).
    """
    from rollcontact.cases.sweep.limit_search import search_limits
    return search_limits(_as_scene(scene), vary_specs(vary), output, overrides=Scene.assignments(overrides or []),
                         tol=tol, jobs=jobs, scheduler=scheduler, overwrite=overwrite, progress=_stream(progress))


def limits(w=None, ft=None, *, angle=None, kappa=None):
    """The closed-form shakedown limits of oscillating rolling (as `rollcontact limits`; seed Eqs. 12-21): at the
    amplitude `w` = W/a and/or the load `ft` = Ft/(mu Fn), for the rolling `angle` to Ft (deg, 0-180) or a given
    `kappa` (0 < kappa <= 1.5), else for the three reference kappas. Returns a cases.closed_forms.Limits (`values`:
    u_lim, f_t_lim, u_stat, w_lim, state; `report()`: the command's text). InputError naming an argument out of
    range."""
    from rollcontact.cases.closed_forms import closed_form_limits
    return closed_form_limits(w=w, ft=ft, angle=angle, kappa=kappa)


def plot(target, *, step=None, output=None, overwrite=False):
    """The figures of a run (a run file or a RunResult) or of a sweep folder, PNG and PDF (as `rollcontact plot`):
    history, maps and centre lines at a stored `step` (default: the last), the loads of an oscillating run, the
    subsurface stresses a file holds; for a folder u_sd(f_t), the limits, the ratcheting increment. output: the
    folder (default: plots/ next to the file or in the sweep folder); overwrite: replace figures that exist (else
    OutputExistsError, and nothing is written). All figures or none are written. Returns a
    cases.plots.figures.Figures (paths, notes, lines; `report()`)."""
    from rollcontact.cases.plots.figures import plot_target
    return plot_target(target, step=step, output=output, overwrite=overwrite)


def compare(a, b, *, step=None, output=None, overwrite=False):
    """Two runs (files or RunResults) on shared colour scales, with B - A and the histories overlaid (as `rollcontact
    compare`); step: a stored step of both (default: the last of each); output, overwrite: as in `plot`. Returns a
    cases.plots.figures.Figures."""
    from rollcontact.cases.plots.figures import compare_targets
    return compare_targets(a, b, step=step, output=output, overwrite=overwrite)


def creep_curve(scene, *, of="xi", points=20, max_ratio=4.0, fidelity=None, overrides=None, output="results/creep",
                overwrite=False):
    """The creep-force curve of a steady [rolling] scene (a Scene or a TOML file path; as `rollcontact creep-curve`):
    `points` creepages of `of` ('xi', 'eta' or 'phi') geometrically from 0.02 to `max_ratio` times the saturation
    creepage, on each model of `fidelity` ('bem', 'fastsim', 'fastrip', or a list drawn side by side; default the
    scene's [solver] fidelity when it is one of them, else 'bem'; docs/creep_fidelity.md), written to
    output/<scene>_creep_<of>.csv (<scene>_creep_<of>_<model>.csv for a fast model), .png and .pdf (all or none;
    overwrite: replace them; output None: no files). overrides: as in `load_scene`. Returns a
    cases.run.creep_curve.CreepCurve (tables, table, paths, seconds; `report()`)."""
    from rollcontact.cases.run.creep_curve import creep_curve_files
    scene = _as_scene(scene)
    if overrides:
        scene = scene.with_overrides(overrides)
    return creep_curve_files(scene, of=of, points=points, max_ratio=max_ratio, output=output, overwrite=overwrite,
                             fidelity=fidelity)


def import_contact(deck, output=None, *, overwrite=False):
    """Import a CONTACT input deck (`<experim>.inp`, or `.inp.gz`) as `rollcontact import-contact` does: every case
    rollcontact can pose becomes a scene (a history of cases one scene run as one), the others are reported with
    each digit or value rollcontact cannot pose (docs/contact_decks.md). Returns a DeckImport (`problems`, `status`
    'yes' / 'partly' / 'no', `summary()`, `report()`, `scene_text(problem)`).

    output: a folder for the scene files `<deck>_case<N>.toml`, the profiles they name, the report
    `<deck>_import.md` and `<deck>_import.json`; None writes nothing. overwrite: replace files that exist (else
    OutputExistsError, before anything is written). DeckError (an InputError) names the line and the field of a deck
    that cannot be read.
    """
    from rollcontact.cases.decks.importer import import_contact as _import
    return _import(deck, output, overwrite=overwrite)


# ---------------------------------------------------------------------------- what the commands add to the API
def stop_on_sigterm(sweep: bool = False):
    """Make SIGTERM (and Ctrl-C) stop a run or a sweep as Ctrl-C does: a run writes its finished steps, a sweep stops
    its workers and writes its summary (cases.sweep.workers.sigterm_as_interrupt; `sweep`: also re-raise an
    interrupt that Python swallowed in a finaliser). Call it in the main thread."""
    from rollcontact.cases.sweep.workers import sigterm_as_interrupt
    sigterm_as_interrupt(flag=sweep)


def unused_stresses_note(*run_files) -> str | None:
    """The note `run` prints when a run file has beside it the step files of an earlier `run --stresses` that
    stopped, which a run without stresses does not use (None when there are none)."""
    from rollcontact.cases.run.step_stresses import folder_of
    for run_file in {Path(f) for f in run_files if f}:
        folder = folder_of(run_file)
        steps = list(folder.glob("step_*.h5")) if folder.is_dir() else []
        if steps:
            return (f"note: {folder} holds the subsurface stresses of {len(steps)} stored step(s) of an earlier "
                    "`run --stresses` that stopped; this run (without --stresses) did not use them: restart with "
                    "--stresses to take them, or remove the folder")
    return None


def parse_depths(text: str):
    """'z1,z2,...' (mm) as the depths `run` and `stresses` take; InputError for anything but finite values >= 0 in
    increasing order."""
    from rollcontact.cases.run.stresses import parse_depths as parse
    return parse(text)


def vary_specs(vary) -> list[str]:
    """`--vary` strings from {"section.key": values or "start:stop:count"} (a list of strings passes through)."""
    from rollcontact.cases.arguments import arg
    from rollcontact.cases.sweep.plan import vary_spec
    if isinstance(vary, dict):
        return [vary_spec(key, values) for key, values in vary.items()]
    if isinstance(vary, str):
        return [vary]
    try:
        specs = list(vary)
    except TypeError:
        specs = None
    if specs is None or not all(isinstance(v, str) for v in specs):
        raise InputError(f"{arg('vary')} = {vary!r}: expected {{'section.key': [values]}} or a list of "
                         "'section.key=values' strings")
    return specs


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

"""The figures of `rollcontact plot` and `rollcontact compare` (and `rollcontact.plot`, `rollcontact.compare`): of one
run file, of a sweep folder, of two runs side by side, as PNG and PDF. Every figure of one call is written together
or none is (cases.plots.common.all_or_none): a step that was not stored, a figure that exists or a full disk leaves
no figure of the call behind.

Default output folder: `plots/` next to a run file, `OUTDIR/plots/` for a sweep folder OUTDIR, `plots/` in the
current folder for a result held in memory only.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from rollcontact.cases.plots.common import PlotError, RunView, all_or_none, open_run
from rollcontact.cases.results.run_result import RunResult


@dataclass
class Figures:
    """What `plot` or `compare` wrote: `paths` (PNG and PDF files), `notes` (what was not drawn, and why) and `lines`
    (text the figures come with: the kappa fitted to a sweep, the table of a phase sweep)."""
    paths: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    lines: list = field(default_factory=list)

    def report(self) -> str:
        """The lines the command prints: the text, the notes, then every written file (absolute path)."""
        return "\n".join(self.lines + [f"note: {n}" for n in self.notes]
                         + [str(Path(p).resolve()) for p in self.paths])

    def __repr__(self) -> str:
        return f"Figures({len(self.paths)} file(s), {len(self.notes)} note(s))"


def _default_dir(target: Path) -> Path:
    return (target if target.is_dir() else target.parent) / "plots"


def _view(run) -> RunView:
    """A run file (path) or a RunResult (its file, or, held in memory only, itself, named after its scene)."""
    if isinstance(run, RunResult):
        if run.path is not None:
            return open_run(run.path)
        scene = run.scene
        view = RunView(Path(f"{scene.name}.h5"), run, scene)
        if "U0" not in run.summary or len(run.history.get("step", [])) == 0:
            raise PlotError(f"result of scene {scene.name!r}: no summary or no steps (status '{run.status}')")
        return view
    if not isinstance(run, (str, Path)):
        raise PlotError(f"expected a run file (a path) or a RunResult, got {type(run).__name__}")
    return open_run(run)


def _creep_result(run):
    """The result of a [rolling] run (its maps are drawn by cases.plots.creep_figures), else None."""
    from rollcontact.cases.plots.creep_figures import is_creep_run
    from rollcontact.cases.results.hdf5 import read_run_file
    if isinstance(run, RunResult):
        return run if is_creep_run(run) else None
    target = Path(run)
    if not target.is_file():
        return None
    data = read_run_file(target, PlotError, str(target))
    return data if is_creep_run(data) else None


def _wheelrail_result(run):
    """The result of a [wheelrail] run (cases.plots.wheelrail_figures, recognised from its summary), else None."""
    from rollcontact.cases.results.hdf5 import read_run_file, stored_summary
    if isinstance(run, RunResult):
        return run if "n_patches" in run.summary else None
    target = Path(run)
    stored = stored_summary(target) if target.is_file() else None
    if stored is None or "n_patches" not in stored["summary"]:
        return None
    return read_run_file(target, PlotError, str(target))


def plot_target(target, step=None, output=None, overwrite=False) -> Figures:
    """The figures of one run (a run file or a RunResult) or of a sweep folder (cases.plots.run_figures, sweep_figures,
    creep_figures, wheelrail_figures) into `output` (default: `_default_dir`). PlotError (InputError) for a missing file, a file that is
    not a run file, a step that was not stored, a `step` with a folder."""
    from rollcontact.cases.plots.run_figures import plot_run
    from rollcontact.cases.plots.sweep_figures import plot_folder
    figures = Figures()
    in_memory = isinstance(target, RunResult)
    path = target.path if in_memory else Path(target)
    out_dir = Path(output) if output is not None else (Path("plots") if path is None else _default_dir(Path(path)))
    with all_or_none():
        if not in_memory and path.is_dir():
            if step is not None:
                from rollcontact.cases.arguments import arg
                raise PlotError(f"{arg('step')} applies to a run file, not to a sweep folder")
            figures.paths = plot_folder(path, out_dir, figures.notes, out=figures.lines.append, overwrite=overwrite)
            return figures
        wheelrail = _wheelrail_result(target)
        creep = _creep_result(target) if wheelrail is None else None
        if wheelrail is not None:
            from rollcontact.cases.plots.wheelrail_figures import plot_wheelrail_run
            stem = Path(path).stem if path is not None else wheelrail.scene.name
            figures.paths = plot_wheelrail_run(wheelrail, out_dir, stem, overwrite=overwrite, notes=figures.notes)
        elif creep is not None:
            from rollcontact.cases.plots.creep_figures import plot_creep_run
            stem = Path(path).stem if path is not None else creep.scene.name
            figures.paths = plot_creep_run(creep, out_dir, stem, overwrite=overwrite)
        else:
            figures.paths = plot_run(_view(target), out_dir, step, figures.notes, overwrite=overwrite)
    return figures


def compare_targets(a, b, step=None, output=None, overwrite=False) -> Figures:
    """Two runs (run files or RunResults) on shared scales, B - A, overlaid histories (cases.plots.run_figures
    .compare_runs) into `output` (default: plots/ next to A)."""
    from rollcontact.cases.plots.run_figures import compare_runs
    figures = Figures()
    va, vb = _view(a), _view(b)
    a_path = a.path if isinstance(a, RunResult) else Path(a)
    out_dir = Path(output) if output is not None else (Path("plots") if a_path is None else _default_dir(Path(a_path)))
    with all_or_none():
        figures.paths = compare_runs(va, vb, out_dir, step, figures.notes, overwrite=overwrite)
    return figures

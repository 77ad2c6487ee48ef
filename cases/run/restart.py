"""Continuing a stored run (`rollcontact run --restart RUN.h5 [--step N]`).

The state a run continues from is the stored field snapshot of one step (pressure, traction; with a friction law
its local coefficient /fields/mu, the memory state) with the history up to it (rigid shift U, approach). Units mm,
N, MPa.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rollcontact.bem.errors import InputError, SceneError
from rollcontact.cases.arguments import arg
from rollcontact.solver.rolling.stepping import StepState

from rollcontact.cases.results.hdf5 import read_run_file
from rollcontact.cases.results.run_result import RunResult
from rollcontact.cases.run.discretise import scene_grid, scene_path
from rollcontact.cases.scene.scene import Scene

#: The keys a restart may change (--set): none of them enters the stored state (grid, pressure, traction,
#: rigid shift) or the path already travelled. motion.periods extends or shortens the oscillation after the
#: restart step (the path of P periods is the start of the path of P + 1; `continued_scene` checks that the
#: restart step stays on it and that the grid is the same); output.fields chooses the snapshots of the steps
#: still to come; solver.max_iter, solver.tol and solver.threads govern only the solves still to come (the
#: file records the restart: attributes restarted_from, restart_step, restart_overrides); solver.shakedown_tol
#: only classifies the history. Everything else (materials, geometry, load, the other motion keys, grid,
#: solver.fidelity and solver.coupling) changes what the stored state is the state of.
RESTART_SAFE_KEYS = ("motion.periods", "output.fields", "solver.max_iter", "solver.tol", "solver.threads",
                     "solver.shakedown_tol")


@dataclass
class RestartSource:
    """A stored run and the step it is continued from."""

    path: Path
    scene: Scene
    data: RunResult
    state: StepState

    @property
    def step(self) -> int:
        return self.state.step

    def restore(self, memory):
        """Set the element states of viscoelastic bodies (a solver.visco.ViscoMemory) to the restart step's, from its
        stored snapshot (the states q and the total displacement u_x, u_y); InputError when they were not stored."""
        steps = [int(s) for s in np.asarray(self.data.field_steps)]
        i = steps.index(self.step)
        fields = self.data.fields
        missing = [name for name in memory.states() if name not in fields]
        if missing:
            raise InputError(f"--restart {self.path}: the viscoelastic element states {missing} were not stored, so "
                             "the run cannot continue from them; run the scene anew")
        states = {name: np.asarray(fields[name][i]) for name in memory.states()}
        displacement = np.stack([fields["u_x"][i], fields["u_y"][i]])
        memory.restore(states, self.state.pressure, self.state.traction, displacement)

    @property
    def period(self) -> int:
        """Oscillation period of the restart step (0: the loading phase)."""
        h = self.data.history
        return int(np.asarray(h["period"])[np.flatnonzero(np.asarray(h["step"]) == self.step)[0]])

    def snapshots(self) -> tuple[list, dict]:
        """The stored field steps up to the restart step and their fields (copied into the new file)."""
        steps = [int(s) for s in np.asarray(self.data.field_steps)]
        n = steps.index(self.step) + 1
        return steps[:n], {k: np.asarray(v)[:n] for k, v in self.data.fields.items()}


def read_source(path) -> RunResult:
    """The run file given to --restart; InputError naming the option if it is missing or not a run file."""
    return read_run_file(path, InputError, f"{arg('restart')} {path}")


def load_restart(path, step: int | None = None) -> RestartSource:
    """The stored run at `step` (default: the last stored field step)."""
    data = read_source(path)
    scene = Scene.from_toml_text(data.scene_toml)          # with the name it was run under
    steps = [int(s) for s in np.asarray(data.field_steps)]
    if not steps:
        raise InputError(f"{arg('restart')} {path}: stores no fields, so no step can be continued from")
    step = steps[-1] if step is None else int(step)
    if step not in steps:
        raise InputError(f"{arg('step')} {step}: the fields of that step were not stored in {path}; "
                         f"stored steps: {steps}")
    i = steps.index(step)
    h = data.history
    k = int(np.flatnonzero(np.asarray(h["step"]) == step)[0])
    state = StepState(step, data.fields["p"][i].copy(),
                      np.stack([data.fields["tau_x"][i], data.fields["tau_y"][i]]).copy(),
                      np.array([h["U_x"][k], h["U_y"][k]], dtype=float), float(h["approach"][k]),
                      data.fields["mu"][i].copy() if "mu" in data.fields else None)
    return RestartSource(Path(path), scene, data, state)


def _key(item: str) -> str:
    return item.split("=", 1)[0].strip()


def _state_part(scene: Scene) -> dict:
    """The scene without RESTART_SAFE_KEYS: what the stored state and the travelled path depend on."""
    d = scene.to_dict(include_none=True)
    for key in RESTART_SAFE_KEYS:
        sec, name = key.split(".")
        d[sec].pop(name, None)
    return d


def continued_scene(source: RestartSource, overrides) -> Scene:
    """The source's scene with the --set overrides a restart allows; SceneError (naming the key) otherwise.

    An override of any other key is refused unless it leaves the stored value unchanged. motion.periods must
    keep the restart step on the path and the grid unchanged.
    """
    overrides = list(overrides)
    if not overrides:
        return source.scene
    unsafe = [item for item in overrides if _key(item) not in RESTART_SAFE_KEYS]
    if unsafe:
        try:
            same = _state_part(source.scene.with_overrides(unsafe)) == _state_part(source.scene)
        except SceneError:
            same = False
        if not same:
            raise SceneError(
                f"{arg('overrides')} {unsafe[0]}: cannot change on {arg('restart')}: the stored state (grid, fields, "
                "rigid shift) "
                f"and the path it has travelled depend on it; keys that may change on a restart: "
                f"{', '.join(RESTART_SAFE_KEYS)}; to change {_key(unsafe[0])}, run the scene anew without "
                f"{arg('restart')}")
    scene = source.scene.with_overrides(overrides)
    _check_path(source, scene)
    return scene


def extension_source(path, scene: Scene) -> RestartSource | None:
    """The complete run stored in `path`, as the start of `scene`, when `scene` is that run with more periods
    (and nothing else changed but RESTART_SAFE_KEYS): continuing it gives `scene`'s run without redoing the
    periods already run (a limit search extends a probe that is still undecided). None when it cannot: the file
    is missing, not complete, stores no fields of its last step, or holds another scene."""
    try:
        source = load_restart(path)
    except (InputError, OSError):
        return None
    if source.data.status != "complete" or source.step != int(np.asarray(source.data.history["step"])[-1]):
        return None
    if _state_part(source.scene) != _state_part(scene) or scene.motion.periods <= source.scene.motion.periods:
        return None
    try:
        _check_path(source, scene)
    except SceneError:
        return None
    return source


def _check_path(source: RestartSource, scene: Scene):
    """The continued path passes through the restart step the same way, on the stored grid."""
    periods = scene.motion.periods
    rolls = source.scene.amplitude > 0 and source.scene.motion.periods > 0
    least = max(source.period, 1) if rolls else source.scene.motion.periods
    if rolls and periods < least or not rolls and periods != least and scene.amplitude > 0:
        allowed = f"periods >= {least}" if rolls else f"periods = {least} (the stored run does not roll)"
        raise SceneError(f"{arg('overrides')} motion.periods = {periods}: the restart step {source.step} lies in period "
                         f"{source.period} of the stored run; allowed range is {allowed}")
    path = scene_path(scene)
    grid = scene_grid(scene, path)
    h, n = source.data.history, source.step + 1
    stored = np.stack([np.asarray(h["W_x"])[:n], np.asarray(h["W_y"])[:n]], axis=1)
    same_grid = (grid.nx, grid.ny) == (len(source.data.x), len(source.data.y)) and \
        np.allclose(grid.x, source.data.x) and np.allclose(grid.y, source.data.y)
    if n > path.n_steps or not same_grid or not np.allclose(path.centres[:n], stored, atol=1e-9):
        raise SceneError(f"{arg('restart')}: the continued scene does not pass through step {source.step} of "
                         f"{source.path} on its grid; leave the {arg('overrides')} out or run the scene anew")

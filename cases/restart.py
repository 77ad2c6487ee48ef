"""Continuing a stored run (`rollcontact run --restart RUN.h5 [--step N]`).

The state a run continues from is the stored field snapshot of one step (pressure, traction) with the
history up to it (rigid shift U, approach). Units mm, N, MPa.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from bem.errors import InputError
from solver.stepping import StepState

from .hdf5 import RunData, read_run
from .scene import Scene


@dataclass
class RestartSource:
    """A stored run and the step it is continued from."""

    path: Path
    scene: Scene
    data: RunData
    state: StepState

    @property
    def step(self) -> int:
        return self.state.step


def read_source(path) -> RunData:
    """The run file given to --restart; InputError naming the option if it is missing or not a run file."""
    p = Path(path)
    if not p.exists():
        raise InputError(f"--restart {path}: no such file")
    if p.is_dir():
        raise InputError(f"--restart {path}: is a directory; expected a run file (.h5) written by rollcontact run")
    try:
        return read_run(p)
    except (OSError, KeyError, ValueError, TypeError) as exc:
        why = "not an HDF5 file" if isinstance(exc, OSError) else "HDF5, but without the run file layout"
        raise InputError(f"--restart {path}: not a run file written by rollcontact run ({why})") from None


def load_restart(path, step: int | None = None) -> RestartSource:
    """The stored run at `step` (default: the last stored field step)."""
    data = read_source(path)
    scene = Scene.from_toml_text(data.scene_toml, name=Path(path).stem)
    steps = [int(s) for s in np.asarray(data.field_steps)]
    if not steps:
        raise InputError(f"--restart {path}: stores no fields, so no step can be continued from")
    step = steps[-1] if step is None else int(step)
    if step not in steps:
        raise InputError(f"--step {step}: the fields of that step were not stored in {path}; "
                         f"stored steps: {steps}")
    i = steps.index(step)
    h = data.history
    k = int(np.flatnonzero(np.asarray(h["step"]) == step)[0])
    state = StepState(step, data.fields["p"][i].copy(),
                      np.stack([data.fields["tau_x"][i], data.fields["tau_y"][i]]).copy(),
                      np.array([h["U_x"][k], h["U_y"][k]], dtype=float), float(h["approach"][k]))
    return RestartSource(Path(path), scene, data, state)

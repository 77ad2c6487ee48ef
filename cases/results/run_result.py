"""The result of one run, `RunResult`: what `rollcontact.run` returns, what a run file holds and what
`rollcontact.read_run` reads back, as numpy arrays and plain Python values. Units: mm, N, MPa, s.

The names below are the public contract of the HDF5 layout too (cases.results.hdf5; README, "HDF5 layout"):
later versions add names, never rename them.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

#: /history: one value per step, name -> unit. W_x, W_y: sphere centre; U_x, U_y: rigid shift of the sphere
#: relative to the substrate far field; U_perp: its component across Ft (along Ft turned by +90 deg), the
#: sideways walk of oblique rolling; F_x, F_y: tangential force; the iteration counts are FFT-convolution
#: products of the step (all outer iterations of a coupled step summed).
HISTORY_UNITS = {
    "step": "-", "period": "-", "W_x": "mm", "W_y": "mm", "approach": "mm", "Fn": "N", "contact_area": "mm^2",
    "stick_area": "mm^2", "U_x": "mm", "U_y": "mm", "U_perp": "mm", "F_x": "N", "F_y": "N", "iterations": "-",
    "normal_iterations": "-", "tangential_iterations": "-", "outer_iterations": "-", "residual": "-",
    "wall_time": "s", "dissipation": "N mm",
}
#: dissipation: the frictional work of the step, -sum tau . s dA with the end-of-step traction tau and the step's
#: slip s (solver.rolling.energy; theory.md §11.2).
HISTORY_NAMES = tuple(HISTORY_UNITS)
#: /history of a [rolling] transient run (cases.run.creep_transient) adds: M_z the moment on the rolling sphere
#: about the contact centre (Kalker's convention), xi, eta the creepages of the step, cpu_time its process CPU time.
CREEP_HISTORY_UNITS = {"M_z": "N mm", "xi": "-", "eta": "-", "cpu_time": "s"}
#: /history of a scene with a speed adds `time`, the end of each step (s; step n at n step_time); with a [friction] law
#: `friction_iterations` (the solves of the step's slip-velocity iteration), `frictional_power` (W, sum tau . s dA
#: with s the slip velocity) and `friction_feedback` (the step's uniqueness indicator, solver.friction.FrictionState); with [thermal] (transient [rolling]) T1_max, T2_max, the largest surface temperatures.
FRICTION_HISTORY_UNITS = {"time": "s", "friction_iterations": "-", "frictional_power": "W", "friction_feedback": "-",
                          "T1_max": "degC", "T2_max": "degC"}
FRICTION_HISTORY = ("friction_iterations", "frictional_power", "friction_feedback")

#: /fields: snapshots of shape (stored steps, ny, nx), name -> unit. p, tau: pressure and traction exerted by the
#: sphere on the substrate; u: displacements of the substrate surface relative to the sphere; slip: of that step.
FIELD_UNITS = {
    "p": "MPa", "u_z": "mm", "tau_x": "MPa", "tau_y": "MPa", "slip_x": "mm", "slip_y": "mm", "u_x": "mm",
    "u_y": "mm", "region": "0 exterior, 1 stick, 2 slip",
}
FIELD_NAMES = tuple(FIELD_UNITS)
#: /fields of a run with a [friction] law add mu, the local coefficient of friction that bounds the step's traction (the
#: memory state at its end), and slip_velocity, the magnitude of the slip velocity (slip of the step over its time, or
#: the speed times the slip per unit rolled distance in steady rolling); with [thermal] T1, T2, the surface temperatures
#: of body 1 (the sphere) and body 2 (the substrate).
FRICTION_FIELD_UNITS = {"mu": "-", "slip_velocity": "mm/s", "T1": "degC", "T2": "degC"}
FRICTION_FIELDS = ("mu", "slip_velocity")

#: /summary: name -> unit ('-': dimensionless, a count or text). Normalised values follow seed Eq. 9:
#: f_t = Ft/(mu Fn), w = W/a, u = U/U0 with U0 = mu E* d/G*. U_perp: the final shift across Ft,
#: dU_perp_per_period: its change over the last period. Values that do not apply are None.
SUMMARY_UNITS = {
    "state": "-", "periods_to_shakedown": "-", "U_sd": "mm", "u_sd": "-", "dU_per_period": "mm", "du": "-",
    "U_perp": "mm", "dU_perp_per_period": "mm",
    "U_stat": "mm", "u_stat": "-", "U0": "mm", "a": "mm", "d": "mm", "p0": "MPa", "f_t": "-", "w": "-",
    "W": "mm", "dW_used": "mm", "nx": "-", "ny": "-", "elements": "-", "steps": "-", "steps_planned": "-",
    "iterations": "-", "wall_time": "s", "stopped_at_step": "-", "state_message": "-", "fidelity": "-",
    "springs": "-", "ds": "mm", "checkpoints": "-", "checkpoint_time": "s", "dissipation_per_period": "N mm",
    "speed": "mm/s", "step_time": "s", "mu_static": "-", "friction_law": "-", "frictional_power": "W",
    "T1_max": "degC", "T2_max": "degC", "friction_feedback": "-",
}
#: dissipation_per_period: the frictional work of the last complete period (sum of /history/dissipation over it).
#: speed: the scene's rolling speed (motion.speed or rolling.speed), step_time: the duration of every step (its
#: displacement over the speed; Scene.step_time); both only in a scene with a speed. With a [friction] law: mu_static
#: (its mu(0), the mu of f_t = Ft/(mu Fn) and U0), friction_law (the law in words), frictional_power (W, of the last
#: step or of the steady state), friction_feedback (the largest J of the slip-velocity iteration: >= 1 where falling
#: friction may give the quasi-static problem several solutions, docs/friction.md); with [thermal] T1_max, T2_max
#: (degC), the largest surface temperatures of the last step or the steady state.

#: /subsurface: z (depths below the surface, mm), step (the stored steps), and per name a dataset of shape
#: (snapshots, nz, ny, nx): the stress components in the frame (x, y, z = depth into the substrate), tension
#: positive; tresca is the maximum shear stress (sigma_1 - sigma_3)/2, principal_1 the largest principal stress.
SUBSURFACE_UNITS = {
    "s_xx": "MPa", "s_yy": "MPa", "s_zz": "MPa", "s_yz": "MPa", "s_xz": "MPa", "s_xy": "MPa", "von_mises": "MPa",
    "tresca": "MPa", "principal_1": "MPa",
}
SUBSURFACE_NAMES = tuple(SUBSURFACE_UNITS)

#: Units of every stored dataset (its 'units' attribute in HDF5).
UNITS = {**HISTORY_UNITS, **CREEP_HISTORY_UNITS, **FRICTION_HISTORY_UNITS, **FIELD_UNITS, **FRICTION_FIELD_UNITS,
         **SUBSURFACE_UNITS, "x": "mm", "y": "mm", "z": "mm"}


@dataclass
class RunResult:
    """One run: the scene it ran, its per-step history, the stored field snapshots and the summary.

    * `history[name]`: 1-D arrays, one value per finished step (names and units: HISTORY_UNITS), e.g.
      `history["U_x"]` (mm), `history["F_x"]` (N), `history["period"]` (0 = loading phase).
    * `fields[name]`: arrays of shape (len(field_steps), ny, nx) on the world-fixed grid `x` (nx,), `y` (ny,) in mm
      (names and units: FIELD_UNITS); `field_steps` lists the stored steps (0-based). `field(name, step)` picks one.
      A run of the 1-D MDR model stores no fields; its `x` holds the spring positions.
    * `summary`: plain values (names and units: SUMMARY_UNITS), e.g. `summary["state"]` ('static', 'shakedown',
      'ratcheting', 'undecided', 'gross_sliding', 'incomplete'), `summary["u_sd"]`, `summary["U_sd"]` (mm);
      None where a value does not apply (u_sd of a ratcheting run).
    * `status`: 'complete', 'failed' (then `error` says why) or 'incomplete' (a checkpoint of a run still going,
      or killed); `path`: the HDF5 file, None if not written.
    """

    scene_toml: str
    status: str
    x: np.ndarray
    y: np.ndarray
    history: dict = field(default_factory=dict)
    fields: dict = field(default_factory=dict)
    field_steps: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    summary: dict = field(default_factory=dict)
    error: str = ""
    version: str = ""
    attrs: dict = field(default_factory=dict)   # further root attributes (restarted_from, restart_step, ...)
    path: Path | None = None
    #: the gzip chunks of the snapshots as a run compressed them for its file (empty when read back)
    snapshot_chunks: dict = field(default_factory=dict, repr=False, compare=False)
    #: what a run with stresses=True (`run --stresses`) wrote to /subsurface: 'steps', 'z' (mm), 'seconds' (computing),
    #: 'computed' and 'reused' (the steps this run computed, and those computed before a restart); empty otherwise
    subsurface: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def scene(self):
        """The scene of the run as a `Scene` (parsed from `scene_toml`)."""
        from rollcontact.cases.scene.scene import Scene
        name = Path(self.path).stem if self.path else "scene"
        return Scene.from_toml_text(self.scene_toml, name=name, run_limits=False)

    @property
    def state(self) -> str | None:
        """summary['state']: 'static', 'shakedown', 'ratcheting', 'undecided', 'gross_sliding' or 'incomplete'."""
        return self.summary.get("state")

    @property
    def wall_time(self) -> float:
        """Wall time of the run (s), from the start of the run to its summary."""
        return float(self.summary.get("wall_time", float("nan")))

    def field(self, name: str, step: int | None = None) -> np.ndarray:
        """The (ny, nx) snapshot of field `name` at a stored `step` (default: the last stored one); units in
        FIELD_UNITS. KeyError names the stored steps when `step` was not stored."""
        steps = [int(s) for s in np.asarray(self.field_steps)]
        if name not in self.fields:
            raise KeyError(f"field {name!r}: not stored; stored fields: {sorted(self.fields)}")
        if not steps:
            raise KeyError(f"field {name!r}: this run stored no snapshots (output.fields = 'none', or the MDR model)")
        step = steps[-1] if step is None else int(step)
        if step not in steps:
            raise KeyError(f"step {step}: its fields were not stored; stored steps: {steps}")
        return np.asarray(self.fields[name])[steps.index(step)]


class RunInterrupted(KeyboardInterrupt):
    """Ctrl-C (or SIGTERM through the CLI) during a run: `result` holds the finished steps (status 'failed'), and its
    `path` the file they were written to (None when the run writes no file)."""

    def __init__(self, result: RunResult):
        super().__init__(f"interrupted; {len(result.history.get('step', []))} step(s) finished"
                         + (f", written to {result.path}" if result.path else ""))
        self.result = result

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

#: /fields: snapshots of shape (stored steps, ny, nx), name -> unit. p, tau: pressure and traction exerted by the
#: sphere on the substrate; u: displacements of the substrate surface relative to the sphere; slip: of that step.
FIELD_UNITS = {
    "p": "MPa", "u_z": "mm", "tau_x": "MPa", "tau_y": "MPa", "slip_x": "mm", "slip_y": "mm", "u_x": "mm",
    "u_y": "mm", "region": "0 exterior, 1 stick, 2 slip",
}
FIELD_NAMES = tuple(FIELD_UNITS)

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
    "speed": "mm/s", "step_time": "s",
}
#: dissipation_per_period: the frictional work of the last complete period (sum of /history/dissipation over it).
#: speed: the scene's rolling speed (motion.speed or rolling.speed), step_time: the duration of every step (its
#: displacement over the speed; Scene.step_time); both only in a scene with a speed.

#: /subsurface: z (depths below the surface, mm), step (the stored steps), and per name a dataset of shape
#: (snapshots, nz, ny, nx): the stress components in the frame (x, y, z = depth into the substrate), tension
#: positive; tresca is the maximum shear stress (sigma_1 - sigma_3)/2, principal_1 the largest principal stress.
SUBSURFACE_UNITS = {
    "s_xx": "MPa", "s_yy": "MPa", "s_zz": "MPa", "s_yz": "MPa", "s_xz": "MPa", "s_xy": "MPa", "von_mises": "MPa",
    "tresca": "MPa", "principal_1": "MPa",
}
SUBSURFACE_NAMES = tuple(SUBSURFACE_UNITS)

#: /summary of a [wheelrail] run (cases.run.wheelrail_run; docs/wheelrail.md): arrays over the patches (in increasing
#: y of the side frame, i.e. from the track centre towards the field side) and the totals. Track frame: x along the
#: direction of travel, y to the left, z up; each patch in its own axes (x along the track, n the rail's normal into
#: the wheel, s = n x x). Forces and moments are those on the wheel (Kalker's body 1).
#: patch_y_rail, patch_y_wheel: the patch's reference point in the rail's and the wheel's profile coordinates (y to the
#: field side); patch_x: its x in the track frame (ahead of the wheelset centre > 0); patch_contact_angle: the
#: rotation about x from the track's z to n (negative on the right rail's gauge side, positive on the left's);
#: patch_rolling_radius: the wheel's radius at the reference; patch_Fn, patch_Fx, patch_Fy: normal force and the
#: tangential forces along x and s; patch_Mz: moment about n at the reference; patch_xi, patch_eta, patch_phi: the
#: creepages and spin there (Kalker's convention); patch_pmax: peak pressure; patch_length, patch_width: the contact's
#: extent along x and s; patch_penetration: the largest interpenetration of the undeformed surfaces along n;
#: patch_angle_spread: the range of the rail's surface angle across the contact (the planar patch takes one angle).
#: F_track_x, F_track_y, F_track_z: the total force on the wheel in the track frame (F_track_z = Fz in balance);
#: z_ws: the wheelset centre's height above its nominal position (the axle wheel_radius above the rail's top);
#: lowering: how far the wheel is lowered beyond its first touch of the rail; xi_nominal: the longitudinal creepage at
#: the nominal rolling radius; omega: the wheelset's rotation (with a speed); outer_iterations: normal / tangential
#: alternations of the vertical balance.
WHEELRAIL_SUMMARY_UNITS = {
    "n_patches": "-", "patch_y_rail": "mm", "patch_y_wheel": "mm", "patch_x": "mm", "patch_contact_angle": "rad",
    "patch_rolling_radius": "mm", "patch_Fn": "N", "patch_Fx": "N", "patch_Fy": "N", "patch_Mz": "N mm",
    "patch_xi": "-", "patch_eta": "-", "patch_phi": "1/mm", "patch_pmax": "MPa", "patch_length": "mm",
    "patch_width": "mm", "patch_penetration": "mm", "patch_angle_spread": "rad", "F_track_x": "N", "F_track_y": "N", "F_track_z": "N",
    "z_ws": "mm", "lowering": "mm", "xi_nominal": "-", "omega": "rad/s", "side": "-", "outer_iterations": "-",
    "cpu_time": "s",
}
SUMMARY_UNITS.update(WHEELRAIL_SUMMARY_UNITS)

#: /patches/<k>/ of a [wheelrail] run: the layout of the file's root for one patch (grid/x, grid/y in the patch's
#: tangent plane: x along the track, y along s; fields/<name> of shape (1, ny, nx) with FIELD_UNITS, the wheel taking
#: the sphere's part and the rail the substrate's, and gap, the undeformed distance h(x, s) of wheel and rail along n;
#: fields/step = [0]; a transient run: the last step on the world-fixed grid, its history/<name> per step: step, W_x
#: the contact centre, Fn, F_x, F_y the force on the rail, M_z on the wheel, stick_area, iterations, cpu_time); its
#: attributes are the patch's values (PATCH_UNITS).
PATCH_FIELD_UNITS = {"gap": "mm"}
PATCH_UNITS = {"y_rail": "mm", "y_wheel": "mm", "x_track": "mm", "contact_angle": "rad", "rolling_radius": "mm",
               "Fn": "N", "Fx": "N", "Fy": "N", "Mz": "N mm", "xi": "-", "eta": "-", "phi": "1/mm", "pmax": "MPa",
               "length": "mm", "width": "mm", "penetration": "mm", "angle_spread": "rad", "dx": "mm", "dy": "mm",
               "normal_iterations": "-", "sweeps": "-", "contact_elements": "-", "stick_elements": "-",
               "Fx_steady": "N", "Fy_steady": "N", "Mz_steady": "N mm", "distance": "mm", "step": "mm", "steps": "-"}
#: A transient [wheelrail] run ([rolling] mode = "transient") reports the patches' forces after rolling; the steady
#: state's are PATCH_UNITS' Fx_steady, Fy_steady, Mz_steady and the summary's patch_Fx_steady, ... below.
SUMMARY_UNITS.update({"patch_Fx_steady": "N", "patch_Fy_steady": "N", "patch_Mz_steady": "N mm", "mode": "-",
                      "distance": "mm", "step": "mm"})

#: Units of every stored dataset (its 'units' attribute in HDF5).
UNITS = {**HISTORY_UNITS, **CREEP_HISTORY_UNITS, **FIELD_UNITS, **PATCH_FIELD_UNITS, **SUBSURFACE_UNITS, "x": "mm",
         "y": "mm", "z": "mm"}


@dataclass
class PatchData:
    """One contact patch of a [wheelrail] run: its grid `x` (nx,), `y` (ny,) (mm, in its tangent plane), `fields`
    {name: (ny, nx)} (FIELD_UNITS, PATCH_FIELD_UNITS), `values` {name: value} (PATCH_UNITS) and, rolled transiently,
    its `history` {name: one value per step} (HISTORY_UNITS, CREEP_HISTORY_UNITS)."""

    x: np.ndarray
    y: np.ndarray
    fields: dict = field(default_factory=dict)
    values: dict = field(default_factory=dict)
    history: dict = field(default_factory=dict)


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
    * `patches`: the contact patches of a [wheelrail] run (PatchData), empty for the others.
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
    patches: list = field(default_factory=list)

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

"""The result of one run, `RunResult`: what `rollcontact.run` returns, what a run file holds and what
`rollcontact.read_run` reads back, as numpy arrays and plain Python values. Units: mm, N, MPa, s.

The names below are the public contract of the HDF5 layout too (cases.results.hdf5; docs/hdf5_schema.md):
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
#: slip s (solver.rolling.energy; docs/theory.md §11.2).
HISTORY_NAMES = tuple(HISTORY_UNITS)
#: /history of a [rolling] transient run (cases.run.creep_transient) adds: M_z the moment on the rolling sphere
#: about the contact centre (Kalker's convention), xi, eta the creepages of the step, cpu_time its process CPU time.
CREEP_HISTORY_UNITS = {"M_z": "N mm", "xi": "-", "eta": "-", "cpu_time": "s"}
#: /history of a run with a [friction] law adds `friction_iterations` (the solves of the step's slip-velocity
#: iteration), `frictional_power` (W, sum tau . s dA with s the slip velocity) and `friction_feedback` (the step's
#: uniqueness indicator, solver.friction.FrictionState); with [thermal] (transient [rolling]) T1_max, T2_max, the
#: largest surface temperatures.
FRICTION_HISTORY_UNITS = {"friction_iterations": "-", "frictional_power": "W", "friction_feedback": "-",
                          "T1_max": "degC", "T2_max": "degC"}
FRICTION_HISTORY = ("friction_iterations", "frictional_power", "friction_feedback")

#: /history of a scene with a speed adds time, the end of the step (s; step n ends at n step_time, step 0 at 0); of a
#: scene with viscoelastic bodies (docs/viscoelastic.md; cases.run.viscoelastic) pressure_centroid_x, int x p dA / Fn
#: along the rolling direction from the rolling body's lowest point, and viscous_dissipation, the work of the bodies'
#: viscous dashpots in the step.
TIME_HISTORY_UNITS = {"time": "s"}
VISCO_HISTORY_UNITS = {"pressure_centroid_x": "mm", "viscous_dissipation": "N mm"}

#: /fields: snapshots of shape (stored steps, ny, nx), name -> unit. p, tau: pressure and traction exerted by the
#: sphere on the substrate; u: displacements of the substrate surface relative to the sphere; slip: of that step.
FIELD_UNITS = {
    "p": "MPa", "u_z": "mm", "tau_x": "MPa", "tau_y": "MPa", "slip_x": "mm", "slip_y": "mm", "u_x": "mm",
    "u_y": "mm", "region": "0 exterior, 1 stick, 2 slip",
}
FIELD_NAMES = tuple(FIELD_UNITS)
#: /fields of a stepped run with viscoelastic bodies add the element states q of each such body i (MPa; the tractions
#: p, tau_x, tau_y filtered by the body's exponential memory, solver.visco.memory), from which a restart continues.
VISCO_FIELD_UNITS = {f"q_{c}{i}": "MPa" for i in (1, 2) for c in "pxy"}
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
    "fidelity_used": "-", "accuracy": "-", "predicted_error": "-", "fidelity_reason": "-", "traction_bound": "-",
    "flexibility": "mm/MPa", "ellipse_a": "mm", "ellipse_b": "mm", "model_cpu_time": "s",
}
#: fidelity: the model that ran, fidelity_used the same (docs/creep_fidelity.md); with [solver] fidelity = "auto" also
#: accuracy (requested), predicted_error (of the chosen model, by the measured map; 0 for the 3-D reference) and
#: fidelity_reason. A fast model's run ([rolling], fastsim / fastrip): traction_bound, flexibility (Kalker's weighted
#: L), ellipse_a, ellipse_b (the ellipse of its flexibilities) and model_cpu_time (the tangential model alone).

#: Summary values of a scene with viscoelastic bodies (docs/viscoelastic.md): pressure_centroid_x (mm, at the last
#: step, or the steady state's), rolling_resistance_moment = Fn pressure_centroid_x (N mm), the viscous work of the last
#: complete period (oscillating scenes, N mm) or the power dissipated (steady rolling, and a transient's last step, W);
#: a [rolling] transient gives the steady state's beside its own (the names with _steady).
VISCO_SUMMARY_UNITS = {"pressure_centroid_x": "mm", "rolling_resistance_moment": "N mm",
                       "viscous_dissipation_per_period": "N mm", "viscous_power": "W",
                       "pressure_centroid_x_steady": "mm", "rolling_resistance_moment_steady": "N mm",
                       "viscous_power_steady": "W"}
SUMMARY_UNITS.update(VISCO_SUMMARY_UNITS)
#: dissipation_per_period: the frictional work of the last complete period (sum of /history/dissipation over it).
#: speed: the scene's rolling speed (motion.speed or rolling.speed), step_time: the duration of every step (its
#: displacement over the speed; Scene.step_time); both only in a scene with a speed. With a [friction] law: mu_static
#: (its mu(0), the mu of f_t = Ft/(mu Fn) and U0), friction_law (the law in words), frictional_power (W, of the last
#: step or of the steady state), friction_feedback (the largest J of the slip-velocity iteration: >= 1 where falling
#: friction may give the quasi-static problem several solutions, docs/friction.md); with [thermal] T1_max, T2_max
#: (degC), the largest surface temperatures of the last step or the steady state.

#: /summary of a [rolling] run (cases.run.creep_run, cases.run.creep_transient), beside SUMMARY_UNITS: the creepages
#: xi, eta (dimensionless) and the spin phi (1/mm) of the steady state or of the last step, the rolling direction
#: (deg), the forces F_x, F_y (N) and the moment M_z (N mm) on the sphere (Kalker's convention), Kalker's linear
#: forces, mu Fn, the stick fraction, the contact semi-axes a, b (mm), the peak pressure p0 (MPa); a transient also
#: the distance rolled and its step (mm), the steady state beside it (_steady), its grid (rolling_grid: 'contact',
#: moving with the contact, or 'world', fixed to the substrate; grid_extent: its elements and extent in the rolling
#: frame, text), CPU and step times.
CREEP_SUMMARY_UNITS = {
    "mode": "-", "xi": "-", "eta": "-", "phi": "1/mm", "direction": "deg", "forces_prescribed": "-", "F_x": "N",
    "F_y": "N", "M_z": "N mm", "F_x_linear": "N", "F_y_linear": "N", "mu_Fn": "N", "stick_fraction": "-", "b": "mm",
    "initial": "-", "distance": "mm", "step": "mm", "F_x_steady": "N", "F_y_steady": "N", "M_z_steady": "N mm",
    "xi_steady": "-", "eta_steady": "-", "p0_steady": "MPa", "rolling_grid": "-", "grid_extent": "-", "cpu_time": "s",
    "time_per_step": "s",
}

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
UNITS = {**HISTORY_UNITS, **CREEP_HISTORY_UNITS, **TIME_HISTORY_UNITS, **FRICTION_HISTORY_UNITS, **VISCO_HISTORY_UNITS,
         **FIELD_UNITS, **FRICTION_FIELD_UNITS, **VISCO_FIELD_UNITS, **PATCH_FIELD_UNITS, **SUBSURFACE_UNITS,
         "x": "mm", "y": "mm", "z": "mm"}


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


#: history and summary names whose values the clock decides, not the computation (RunResult.equals(times=False))
TIME_NAMES = ("wall_time", "cpu_time", "time_per_step", "checkpoints", "checkpoint_time")


@dataclass(eq=False, repr=False)
class RunResult:
    """One run: the scene it ran, its per-step history, the stored field snapshots and the summary.

    * `history[name]`: 1-D arrays, one value per finished step (names and units: HISTORY_UNITS), e.g.
      `history["U_x"]` (mm), `history["F_x"]` (N), `history["period"]` (0 = loading phase).
    * `fields[name]`: arrays of shape (len(field_steps), ny, nx) on the grid `x` (nx,), `y` (ny,) in mm (world-fixed;
      in a [rolling] transient with summary rolling_grid 'contact' the grid moving with the contact, x from its centre)
      (names and units: FIELD_UNITS); `field_steps` lists the stored steps (0-based). `field(name, step)` picks one.
      A run of the 1-D MDR model stores no fields; its `x` holds the spring positions.
    * `summary`: plain values (names and units: SUMMARY_UNITS), e.g. `summary["state"]` (see `state`),
      `summary["u_sd"]`, `summary["U_sd"]` (mm); None where a value does not apply (u_sd of a ratcheting run).
    * `subsurface`: the stresses below the contact when the run file holds them (`rollcontact.stresses`, `run(...,
      stresses=True)`): a mapping name -> (snapshots, nz, ny, nx) array (MPa) with its depths `z` (mm), `steps` and
      `units` (cases.results.subsurface.Subsurface); empty otherwise.
    * `units[name]`: the unit of every history, field, summary and subsurface name the result holds ('-' for counts,
      flags, text and dimensionless values).
    * `status`: 'complete', 'failed' (then `error` says why) or 'incomplete' (a checkpoint of a run still going,
      or killed); `path`: the HDF5 file, None if not written.
    * `patches`: the contact patches of a [wheelrail] run (PatchData), empty for the others.

    Two results are equal (`==`, `equals`) when they hold the same run, value by value (the file they came from is
    not compared): `rollcontact.run(scene, path) == rollcontact.read_run(path)`. `repr` is one short line.
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
    snapshot_chunks: dict = field(default_factory=dict)
    #: the subsurface stresses (cases.results.subsurface.Subsurface; empty when the file holds none)
    subsurface: object = field(default_factory=lambda: _no_subsurface())
    patches: list = field(default_factory=list)

    @property
    def scene(self):
        """The scene of the run as a `Scene` (parsed from `scene_toml`, with the name it was run under)."""
        from rollcontact.cases.scene.scene import Scene
        return Scene.from_toml_text(self.scene_toml, run_limits=False)

    @property
    def state(self) -> str | None:
        """summary['state']: 'static' (no motion), 'shakedown' (the slip stopped: U settled and the frictional work
        per period going to zero), 'cyclic_slip' (loads varying within the period: U settled but the contact slips
        to and fro every period), 'ratcheting' (U grows by dU_per_period every period), 'undecided' (not settled
        within the periods run), 'gross_sliding' (the tangential load reached mu Fn), 'incomplete' (a run that
        stopped early), 'steady' (a [rolling] scene solved in its steady state) or 'transient' (a [rolling] scene
        rolled on the world-fixed grid); None before a summary exists."""
        return self.summary.get("state")

    @property
    def wall_time(self) -> float:
        """Wall time of the run (s), from the start of the run to its summary."""
        return float(self.summary.get("wall_time", float("nan")))

    @property
    def units(self) -> dict:
        """name -> unit of every name this result holds: history, fields, summary, subsurface, and the grid x, y
        (and z of the subsurface), as in the HDF5 `units` attributes ('-': a count, a flag, text or dimensionless).
        One name means two things: `step` is the step number in the history ('-') and the rolling step of a
        transient [rolling] run in its summary (mm); `units` gives the history's, `summary_units` the summary's."""
        known = {**SUMMARY_UNITS, **CREEP_SUMMARY_UNITS, **UNITS}
        names = ["x", "y", *self.summary, *self.history, *self.fields]
        out = {name: known[name] for name in names if name in known}
        out.update({name: UNITS[name] for name in ("step",) if name in self.history})
        out.update(self.subsurface.units)
        return out

    @property
    def summary_units(self) -> dict:
        """name -> unit of every summary value (SUMMARY_UNITS, and CREEP_SUMMARY_UNITS of a [rolling] run)."""
        known = {**SUMMARY_UNITS, **CREEP_SUMMARY_UNITS}
        return {name: known[name] for name in self.summary if name in known}

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

    def report(self) -> str:
        """The summary `rollcontact run` prints: contact, iterations, time, state (u_sd or du), the output file."""
        from rollcontact.cases.run.summary import format_summary
        return format_summary(self)

    def equals(self, other, times: bool = True) -> bool:
        """True when `other` holds the same run as this one: the scene, status, error, version and root attributes,
        the grid, every history and field array (NaN equal to NaN), the stored steps, the summary (a value that does
        not apply equal whether None or NaN) and the subsurface stresses. Not compared: the file (`path`) and the
        compressed snapshots a run keeps for its writer. times=False leaves out what the clock decides (TIME_NAMES:
        wall and CPU times, and the checkpoints, written every few seconds), so that two runs of one scene compare
        equal when they computed the same."""
        if not isinstance(other, RunResult):
            return False
        skip = () if times else TIME_NAMES
        history, summary = ({k: v for k, v in d.items() if k not in skip} for d in (self.history, self.summary))
        o_history, o_summary = ({k: v for k, v in d.items() if k not in skip} for d in (other.history, other.summary))
        return (self.scene_toml == other.scene_toml and self.status == other.status and self.error == other.error
                and self.version == other.version and _same_dict(self.attrs, other.attrs)
                and same_value(self.x, other.x) and same_value(self.y, other.y)
                and _same_dict(history, o_history) and _same_dict(self.fields, other.fields)
                and same_value(self.field_steps, other.field_steps) and _same_dict(summary, o_summary)
                and self.subsurface == other.subsurface and _same_patches(self.patches, other.patches, skip))

    def __eq__(self, other):
        if not isinstance(other, RunResult):
            return NotImplemented
        return self.equals(other)

    __hash__ = None

    def __repr__(self) -> str:
        name = _scene_name(self.scene_toml)
        steps = len(np.asarray(self.history.get("step", ())))
        parts = [f"scene={name!r}", f"status={self.status!r}", f"state={self.state!r}", f"steps={steps}",
                 f"snapshots={len(np.asarray(self.field_steps))}"]
        if np.ndim(self.x) == 1 and np.ndim(self.y) == 1 and len(self.y) > 1:
            parts.append(f"grid={len(self.x)}x{len(self.y)}")
        if self.subsurface:
            parts.append(f"subsurface={len(self.subsurface.steps)} step(s)")
        parts.append(f"path={str(self.path) if self.path is not None else None!r}")
        return f"RunResult({', '.join(parts)})"


def same_value(a, b) -> bool:
    """True when two stored values are equal: arrays element by element (NaN equal to NaN), None equal to NaN (a
    value that does not apply, in memory and read back), else ==."""
    if a is None or b is None:
        return (a is None or _is_nan(a)) and (b is None or _is_nan(b))
    if isinstance(a, str) or isinstance(b, str):
        return isinstance(a, str) and isinstance(b, str) and a == b
    if isinstance(a, dict) or isinstance(b, dict):
        return isinstance(a, dict) and isinstance(b, dict) and _same_dict(a, b)
    try:
        x, y = np.asarray(a), np.asarray(b)
    except (TypeError, ValueError):
        return a == b
    if x.shape != y.shape:
        return False
    if x.dtype.kind in "fc" or y.dtype.kind in "fc":
        try:
            return bool(np.array_equal(x, y, equal_nan=True))
        except TypeError:
            pass
    return bool(np.array_equal(x, y))


def _same_patches(a: list, b: list, skip=()) -> bool:
    """The patches of two [wheelrail] runs hold the same values (the names in `skip` left out)."""
    return len(a) == len(b) and all(
        same_value(p.x, q.x) and same_value(p.y, q.y) and _same_dict(p.fields, q.fields)
        and _same_dict({k: v for k, v in p.values.items() if k not in skip},
                       {k: v for k, v in q.values.items() if k not in skip})
        and _same_dict({k: v for k, v in p.history.items() if k not in skip},
                       {k: v for k, v in q.history.items() if k not in skip})
        for p, q in zip(a, b))


def _same_dict(a: dict, b: dict) -> bool:
    keys = set(a) | set(b)
    return all(same_value(a.get(k), b.get(k)) for k in keys)


def _is_nan(v) -> bool:
    try:
        return bool(np.isnan(v))
    except (TypeError, ValueError):
        return False


def _scene_name(scene_toml: str) -> str:
    from rollcontact.cases.scene.scene import stored_name
    return stored_name(scene_toml) or "scene"


def _no_subsurface():
    from rollcontact.cases.results.subsurface import Subsurface
    return Subsurface()


class RunInterrupted(KeyboardInterrupt):
    """Ctrl-C (or SIGTERM through the CLI) during a run. `result` holds the finished steps (status 'failed'), its
    `path` the file they were written to (None when the run writes no file); `result` is None when the run was stopped
    before its first step, or while its file was being written: then `path` names the output. `str()` says what is
    kept and how to continue (the line `rollcontact run` prints)."""

    def __init__(self, result: RunResult | None = None, path=None):
        super().__init__()
        self.result = result
        self.path = result.path if result is not None else (None if path is None else Path(path))

    def __str__(self) -> str:
        from rollcontact.cases.arguments import restart_hint, restart_step_hint
        if self.result is None:
            from rollcontact.cases.results.hdf5 import stored_summary
            stored = stored_summary(self.path) if self.path is not None and Path(self.path).is_file() else None
            if stored is None:
                return "interrupted before the first step; nothing written"
            more = "" if stored["status"] == "complete" else f"; continue with: {restart_hint(self.path)}"
            return f"interrupted; {self.path} is left with status '{stored['status']}'{more}"
        n = len(self.result.history.get("step", []))
        if self.result.path is None:
            return f"interrupted after {n} step(s); the result held in memory has them (status 'failed')"
        text = f"interrupted after {n} step(s); they are in {self.result.path} (status 'failed')"
        if len(self.result.field_steps):
            step = int(self.result.field_steps[-1])
            text += f"; continue with: {restart_step_hint(self.result.path, step)}"
        return text

"""The layout of a run file described name by name: every group, dataset and attribute with its unit (from the unit
tables of `cases.results.run_result`) and its meaning, for docs/hdf5_schema.md (docs/scripts/reference.py).

Units: mm, N, MPa, s, degrees; '-' for counts, flags, text and dimensionless values. Signs as in docs/theory.md §0:
p and tau act on the substrate, u is the substrate relative to the sphere, U the sphere's rigid shift.
"""
from __future__ import annotations

from rollcontact.cases.results.run_result import (CREEP_HISTORY_UNITS, CREEP_SUMMARY_UNITS, FIELD_UNITS,
                                                   FRICTION_FIELD_UNITS, FRICTION_HISTORY_UNITS,
                                                   HISTORY_UNITS, PATCH_FIELD_UNITS, PATCH_UNITS, SUBSURFACE_UNITS,
                                                   SUMMARY_UNITS, TIME_HISTORY_UNITS, VISCO_FIELD_UNITS,
                                                   VISCO_HISTORY_UNITS)

#: / attributes: name -> (unit, meaning)
ROOT_ATTRIBUTES = {
    "rollcontact_version": ("-", "version of rollcontact that wrote the file"),
    "scene": ("-", "the full scene as TOML text, every key with its value (for shape = \"file\" with the profile "
                   "file's absolute path and SHA-256)"),
    "status": ("-", "'complete', 'failed', or 'incomplete' (a checkpoint of a run still going, or killed)"),
    "error": ("-", "the error of a failed run (empty otherwise)"),
    "restarted_from": ("-", "a restarted run: the source file"),
    "restart_step": ("-", "a restarted run: the stored step it continued from"),
    "restart_overrides": ("-", "a restarted run: its --set items"),
}

GRID = {"x": "cell-centre coordinates along x (world-fixed; integer multiples of dx)",
        "y": "cell-centre coordinates along y"}

HISTORY = {
    "step": "step number (0: the normal load alone from the unloaded state)",
    "period": "period of the step (0: the loading phase)",
    "W_x": "position of the sphere's centre, x", "W_y": "position of the sphere's centre, y",
    "approach": "approach d of the step", "Fn": "normal force of the step",
    "contact_area": "area of the elements in contact", "stick_area": "area of the sticking elements",
    "U_x": "rigid shift of the sphere relative to the substrate far field, x",
    "U_y": "rigid shift of the sphere relative to the substrate far field, y",
    "U_perp": "the shift across Ft (along Ft turned by +90°): the sideways walk of oblique rolling; 0 for the MDR",
    "F_x": "tangential force of the step on the substrate, x", "F_y": "tangential force of the step on the substrate, y",
    "iterations": "FFT-convolution products of the step, normal and tangential (all outer iterations summed)",
    "normal_iterations": "normal-solver products of the step", "tangential_iterations": "tangential-solver products",
    "outer_iterations": "outer (normal-tangential) iterations of a coupled step; 1 when uncoupled",
    "residual": "the largest solver residual of the step", "wall_time": "wall time of the step",
    "dissipation": "frictional work of the step, −Σ τ·s dA with the end-of-step traction (docs/theory.md §11.2)",
    "M_z": "[rolling] transient: moment on the rolling sphere about the contact centre (Kalker's convention)",
    "xi": "[rolling] transient: longitudinal creepage of the step", "eta": "[rolling] transient: lateral creepage",
    "cpu_time": "[rolling] transient: process CPU time of the step",
    "time": "a scene with a speed: the end of the step (step n ends at n step_time)",
    "pressure_centroid_x": "viscoelastic bodies: ∫ x p dA / Fn along the rolling direction from the body's lowest point",
    "viscous_dissipation": "viscoelastic bodies: the work of the viscous dashpots in the step",
    "friction_iterations": "[friction] law: the solves of the step's slip-velocity iteration (docs/friction.md)",
    "frictional_power": "[friction] law or [thermal]: the step's frictional power, sum of tau . slip velocity dA",
    "friction_feedback": "[friction] law: the step's uniqueness indicator (1 and above: several solutions possible)",
    "T1_max": "[thermal] transient: the largest surface temperature of body 1 (the sphere)",
    "T2_max": "[thermal] transient: the largest surface temperature of body 2 (the substrate)",
}

FIELDS = {
    "step": "the stored steps (index into /history)",
    "p": "pressure on the substrate", "u_z": "normal displacement (into the bodies: the loss of separation)",
    "tau_x": "traction of the sphere on the substrate, x", "tau_y": "traction of the sphere on the substrate, y",
    "slip_x": "slip of the step, substrate relative to the sphere, x", "slip_y": "slip of the step, y",
    "u_x": "tangential displacement of the substrate relative to the sphere, x", "u_y": "the same, y",
    "region": "int8: 0 exterior, 1 stick, 2 slip",
    **{f"q_{c}{i}": f"viscoelastic body {i}: the memory state of {name} (the traction filtered by the body's "
                    "exponential memory; a restart continues from it)"
       for i in (1, 2) for c, name in (("p", "p"), ("x", "tau_x"), ("y", "tau_y"))},
    "mu": "[friction] law: the local coefficient of friction bounding the step's traction (with memory its state at "
          "the step's end)",
    "slip_velocity": "[friction] law or [thermal]: magnitude of the slip velocity (slip over the step time; steady: "
                     "speed x slip per unit rolled distance)",
    "T1": "[thermal]: surface temperature of body 1 (the sphere)", "T2": "[thermal]: surface temperature of body 2",
    "gap": "[wheelrail] patch: the undeformed distance h(x, s) of wheel and rail along the normal",
}

SUBSURFACE = {
    "z": "depths below the surface", "step": "the steps computed (each a stored step of /fields)",
    "s_xx": "stress σxx (frame x, y, z = depth into the substrate; tension positive)", "s_yy": "stress σyy",
    "s_zz": "stress σzz (−p at the surface)", "s_yz": "stress σyz (−τy at the surface)",
    "s_xz": "stress σxz (−τx at the surface)", "s_xy": "stress σxy", "von_mises": "von Mises equivalent stress",
    "tresca": "maximum shear stress (σ1 − σ3)/2", "principal_1": "the largest principal stress",
}
SUBSURFACE_ATTRIBUTES = {"nu": ("-", "the substrate's ν2 used (the stresses depend on it alone)"),
                         "depths": ("-", "'default' (30 depths from 0 to 2a, finer near the surface) or 'given'")}

SUMMARY = {
    "state": "'static', 'shakedown', 'cyclic_slip', 'ratcheting', 'undecided', 'gross_sliding', 'incomplete'; "
             "'steady' or 'transient' for a [rolling] run (docs/theory.md §6.2)",
    "periods_to_shakedown": "periods after which every increment stayed below solver.shakedown_tol",
    "U_sd": "shakedown shift along Ft", "u_sd": "U_sd/U0", "dU_per_period": "ratcheting increment per period",
    "du": "dU_per_period/U0", "U_perp": "the final shift across Ft", "dU_perp_per_period": "its change over the last period",
    "U_stat": "shift along Ft at the end of the ramp to f_t", "u_stat": "U_stat/U0",
    "U0": "μE*d/G*, the unit of u (docs/theory.md §0)", "a": "contact radius (closed form of the shape; [rolling]: "
    "semi-axis along the rolling direction)", "d": "approach (closed form; solved for the cylinder and a file profile)",
    "p0": "peak pressure of Hertz or the line contact, else the scale 3Fn/(2πa²)", "f_t": "Ft/(μFn)", "w": "W/a",
    "W": "rolling amplitude", "dW_used": "rolling step used, W/ceil(W/dW)", "nx": "grid elements along x",
    "ny": "grid elements along y", "elements": "grid elements", "steps": "steps computed",
    "steps_planned": "steps of the load path", "iterations": "FFT-convolution products of the run",
    "wall_time": "wall time of the run", "stopped_at_step": "gross sliding: the step without equilibrium",
    "state_message": "gross sliding: the solver's message", "fidelity": "'bem' or 'mdr'",
    "springs": "MDR: springs of the 1-D model", "ds": "MDR: spring spacing",
    "checkpoints": "checkpoints written during the run", "checkpoint_time": "time spent writing them",
    "dissipation_per_period": "frictional work of the last complete period (None without one)",
    "speed": "the scene's speed (motion.speed or rolling.speed), only with one",
    "step_time": "duration of every step (docs/theory.md §6.3), only with a speed",
    "mode": "[rolling] mode", "xi": "longitudinal creepage (found, with prescribed forces)",
    "eta": "lateral creepage", "phi": "spin creepage", "direction": "rolling direction from the x axis",
    "forces_prescribed": "true when Fx, Fy were given instead of the creepages",
    "F_x": "force on the rolling sphere along the rolling direction (Kalker's convention: −/history/F_x)",
    "F_y": "lateral force on the rolling sphere", "M_z": "moment on the rolling sphere about the contact centre",
    "F_x_linear": "Kalker's linear theory, F_x", "F_y_linear": "Kalker's linear theory, F_y", "mu_Fn": "μFn",
    "stick_fraction": "sticking elements / elements in contact", "b": "semi-axis across the rolling direction",
    "initial": "transient: initial state ('rest' or 'cattaneo')", "distance": "transient: distance rolled",
    "step": "transient: rolling step", "F_x_steady": "transient: the steady state's F_x beside it",
    "F_y_steady": "transient: the steady F_y", "M_z_steady": "transient: the steady M_z",
    "xi_steady": "transient: the steady state's xi (prescribed forces)", "eta_steady": "transient: the steady eta",
    "p0_steady": "transient: the steady state's peak pressure",
    "rolling_grid": "transient: the grid of the steps, 'contact' (moving with the contact) or 'world' (fixed to the "
                    "substrate)",
    "grid_extent": "transient: that grid's elements and extent in the rolling frame",
    "time_per_step": "transient: mean wall time per rolling step", "cpu_time": "transient: process CPU time",
    "pressure_centroid_x": "viscoelastic bodies: the pressure centroid along the rolling direction (last step, or the "
                           "steady state's)",
    "rolling_resistance_moment": "viscoelastic bodies: Fn pressure_centroid_x",
    "viscous_dissipation_per_period": "viscoelastic bodies: the viscous work of the last complete period",
    "viscous_power": "viscoelastic bodies: the power dissipated (steady rolling, a transient's last step)",
    "pressure_centroid_x_steady": "viscoelastic transient: the steady state's pressure_centroid_x",
    "rolling_resistance_moment_steady": "viscoelastic transient: the steady state's moment",
    "viscous_power_steady": "viscoelastic transient: the steady state's power",
    "mu_static": "[friction]: the law's static coefficient mu(0), used in f_t = Ft/(mu Fn) and u = U/U0",
    "friction_law": "[friction]: the law's name", "frictional_power": "[friction] or [thermal]: frictional power "
    "(steady rolling, a transient's last step)", "friction_feedback": "[friction]: the largest uniqueness indicator",
    "T1_max": "[thermal]: the largest surface temperature of body 1", "T2_max": "[thermal]: the same of body 2",
    "n_patches": "[wheelrail]: contact patches found", "patch_y_rail": "[wheelrail] per patch: reference point, rail "
    "profile coordinate", "patch_y_wheel": "per patch: reference point, wheel profile coordinate",
    "patch_x": "per patch: x in the track frame", "patch_contact_angle": "per patch: contact angle",
    "patch_rolling_radius": "per patch: the wheel's rolling radius", "patch_Fn": "per patch: normal force on the wheel",
    "patch_Fx": "per patch: tangential force along x", "patch_Fy": "per patch: tangential force along s",
    "patch_Mz": "per patch: moment about the normal", "patch_xi": "per patch: longitudinal creepage",
    "patch_eta": "per patch: lateral creepage", "patch_phi": "per patch: spin", "patch_pmax": "per patch: peak pressure",
    "patch_length": "per patch: extent along x", "patch_width": "per patch: extent along s",
    "patch_penetration": "per patch: largest interpenetration of the undeformed surfaces",
    "patch_angle_spread": "per patch: range of the rail's surface angle across the contact",
    "F_track_x": "[wheelrail]: total force on the wheel, track frame x", "F_track_y": "the same, y",
    "F_track_z": "the same, z (= Fz in balance)", "z_ws": "[wheelrail]: wheelset centre above its nominal height",
    "lowering": "[wheelrail]: lowering beyond the first touch", "xi_nominal": "[wheelrail]: creepage at the nominal "
    "rolling radius", "omega": "[wheelrail]: the wheelset's rotation (with a speed)", "side": "[wheelrail]: the rail",
    "outer_iterations": "[wheelrail]: normal / tangential alternations of the vertical balance",
    "patch_Fx_steady": "[wheelrail] transient: the steady patch_Fx", "patch_Fy_steady": "the steady patch_Fy",
    "patch_Mz_steady": "the steady patch_Mz",
}
#: /patches/<k> attributes of a [wheelrail] run (docs/wheelrail.md): the patch's values
PATCH = {"y_rail": "reference point, rail profile coordinate", "y_wheel": "reference point, wheel profile coordinate",
         "x_track": "x in the track frame", "contact_angle": "contact angle", "rolling_radius": "the wheel's radius",
         "Fn": "normal force", "Fx": "tangential force along x", "Fy": "tangential force along s",
         "Mz": "moment about the normal", "xi": "longitudinal creepage", "eta": "lateral creepage", "phi": "spin",
         "pmax": "peak pressure", "length": "extent along x", "width": "extent along s",
         "penetration": "largest interpenetration", "angle_spread": "range of the surface angle", "dx": "element size x",
         "dy": "element size s", "normal_iterations": "normal-solver products", "sweeps": "steady-solver sweeps",
         "contact_elements": "elements in contact", "stick_elements": "sticking elements",
         "Fx_steady": "transient: steady Fx", "Fy_steady": "transient: steady Fy", "Mz_steady": "transient: steady Mz",
         "distance": "transient: distance rolled", "step": "transient: rolling step", "steps": "transient: steps"}


def groups() -> list:
    """The layout as (path, kind, [(name, unit, meaning)]) in the order of the file; kind 'attributes' or
    'datasets'. Units from the tables of cases.results.run_result; a name without a meaning here reads '-'."""
    def rows(units, docs):
        return [(name, unit, docs.get(name, "-")) for name, unit in units.items()]

    return [
        ("/", "attributes", [(k, u, d) for k, (u, d) in ROOT_ATTRIBUTES.items()]),
        ("/grid", "datasets", [(k, "mm", d) for k, d in GRID.items()]),
        ("/history", "datasets", rows({**HISTORY_UNITS, **CREEP_HISTORY_UNITS, **TIME_HISTORY_UNITS,
                                       **FRICTION_HISTORY_UNITS, **VISCO_HISTORY_UNITS}, HISTORY)),
        ("/fields", "datasets", rows({"step": "-", **FIELD_UNITS, **FRICTION_FIELD_UNITS, **VISCO_FIELD_UNITS},
                                      FIELDS)),
        ("/subsurface", "datasets", rows({"z": "mm", "step": "-", **SUBSURFACE_UNITS}, SUBSURFACE)),
        ("/subsurface", "attributes", [(k, u, d) for k, (u, d) in SUBSURFACE_ATTRIBUTES.items()]),
        ("/summary", "attributes", rows({**SUMMARY_UNITS, **CREEP_SUMMARY_UNITS}, SUMMARY)),
        ("/patches/<k>", "attributes", rows(PATCH_UNITS, PATCH)),
        ("/patches/<k>/fields", "datasets", rows({**FIELD_UNITS, **PATCH_FIELD_UNITS}, FIELDS)),
    ]

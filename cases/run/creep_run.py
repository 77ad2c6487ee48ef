"""One run of a [rolling] scene: steady rolling with creepage and spin (solver.creep; docs/theory.md §7.3, §11.5).

The scene's profile is turned into the rolling frame (x along [rolling] direction, y to its left), the normal
problem is solved on a contact-fixed grid over the Hertz contact plus the scene's margin (NormCG), and the steady
tangential problem on the same grid (Kalker's Gauss-Seidel in traction differences, solver.creep.steady). For
coupled materials (Kalker's K != 0, [solver] coupling) the two are alternated until neither the pressure
(relative to its maximum) nor the traction (relative to mu p_max) changes by more than the solver tolerance (the
tangential traction's normal displacement enters the normal problem, the pressure's tangential displacement the
slip).

What is stored: one step (step 0) in /history and /fields (output.fields = "none" stores no fields), on the
contact-fixed grid of the rolling frame (a transient run: cases.run.creep_transient, on the world-fixed grid).
The fields keep the meaning they have in every run file (docs/hdf5_schema.md): tau_x, tau_y the traction the
sphere exerts on the substrate, u_x, u_y the substrate's displacement relative to the sphere, slip_x, slip_y the
slip of the substrate relative to the sphere over a rolling step of one element (dx, in mm: the steady state
seen as one step of the transient), region 0 / 1 / 2; history F_x, F_y is sum(tau) dA, the force on the
substrate. The summary states the forces in Kalker's convention instead, on the rolling sphere (body 1):
F_x = -history F_x, opposing the creepages (F_x = -G c^2 C11 xi in the linear range), M_z the moment about the
grid origin (the sphere's centre, N mm), with xi, eta, phi and the linear theory's forces beside them.

On a fast model ([solver] fidelity 'fastsim', 'fastrip', or chosen by 'auto': cases.run.fidelity) the normal
problem is solved the same way (without coupling) and the tangential state by the model (cases.run.creep_fast), with
the same layout: u_x, u_y are then the simplified theory's L tau, the history's tangential iterations 1 (one pass
over the strips); the summary adds traction_bound, flexibility (L, mm/MPa), ellipse_a, ellipse_b (the ellipse of
the flexibilities) and model_cpu_time. Every summary states fidelity and fidelity_used (the model run); 'auto' adds
accuracy, predicted_error and fidelity_reason. Units: mm, N, MPa.
"""
from __future__ import annotations

import math
import time

import numpy as np

from rollcontact.bem.errors import RollcontactError
from rollcontact.cases.results.hdf5 import version
from rollcontact.cases.results.run_result import RunResult
from rollcontact.cases.run.creep_fast import fast_steady
from rollcontact.cases.run.creep_steady import solve_scene
from rollcontact.cases.run.discretise import scene_operator
from rollcontact.cases.run.friction_outputs import friction_fields, friction_summary
from rollcontact.cases.run.creep_transient import run_transient
from rollcontact.cases.run.fidelity import NAMES, choose_fidelity
from rollcontact.cases.run.rolling_frame import creep_grid, linear_forces
from rollcontact.cases.run.viscoelastic import steady_outputs, steady_visco
from rollcontact.cases.scene.keys import FAST_FIDELITIES
from rollcontact.cases.scene.scene import Scene


def run_creep(scene: Scene, *, progress=None) -> RunResult:
    """Run a [rolling] scene (mode 'steady', or 'transient': cases.run.creep_transient) on its model ([solver]
    fidelity; 'auto' chooses one and says so on stderr: cases.run.fidelity) and return its result (written by the
    caller). A solver that does not converge gives status 'failed' with the error; nothing is stored then but the
    scene."""
    t_start = time.perf_counter()
    choice = choose_fidelity(scene)
    choice.announce()
    grid = creep_grid(scene)
    try:
        if scene.rolling.mode == "transient":
            return run_transient(scene, t_start, progress=progress, choice=choice)
        if choice.model in FAST_FIDELITIES:
            return _fast_steady(scene, grid, choice, t_start, progress)
        pair = scene.material_pair
        visco = steady_visco(scene, grid) if scene.viscoelastic else None
        op = scene_operator(scene, grid) if visco is None else visco.operator
        if progress:
            progress(f"steady rolling: grid {grid.nx} x {grid.ny} = {grid.size} elements (dx = {grid.dx}, dy = "
                     f"{grid.dy} mm, contact-fixed, x along the rolling direction {scene.rolling.direction} deg), "
                     f"coupling {'on' if op.coupled else 'off'}")
        state = solve_scene(scene, grid, op, pair, visco)
    except RollcontactError as exc:
        return RunResult(scene_toml=scene.to_toml(), status="failed", error=f"{type(exc).__name__}: {exc}",
                         x=grid.x, y=grid.y, summary={"state": "failed", "wall_time": time.perf_counter() - t_start,
                                                      **choice.summary()},
                         version=version())
    normal, steady, outer, creep = state
    tau_sub = -steady.traction                       # the sphere's traction on the substrate (run-file meaning)
    u = op.tangential(tau_sub[0], tau_sub[1])
    if op.coupled:
        u += op.tangential_from_pressure(normal.pressure)
    counts = dict(tangential=steady.sweeps, outer=outer, residual=max(normal.residual, steady.change))
    extra = choice.summary()
    if visco is not None:                 # docs/viscoelastic.md: the forward lean of the pressure and its cost
        extra.update(steady_outputs(visco, grid, normal.pressure, tau_sub, normal.force))
    return _result(scene, grid, normal, steady, u, counts, creep, extra, time.perf_counter() - t_start)


def _fast_steady(scene, grid, choice, t_start, progress):
    """The steady state on a fast model (cases.run.creep_fast) as a run result."""
    if progress:
        progress(f"steady rolling on {NAMES[choice.model]} ('{choice.model}'): grid {grid.nx} x {grid.ny} = "
                 f"{grid.size} elements (dx = {grid.dx}, dy = {grid.dy} mm, contact-fixed, x along the rolling "
                 f"direction {scene.rolling.direction} deg), traction bound '{scene.traction_bound}', no coupling")
    fast = fast_steady(scene, choice.model, grid)
    state, normal = fast.state, fast.normal
    tau_sub = -state.traction
    u = tau_sub * state.flexibility                  # the simplified theory's u = L tau (substrate relative to sphere)
    counts = dict(tangential=1, outer=1, residual=normal.residual)
    extra = dict(choice.summary(), traction_bound=fast.bound, flexibility=float(state.flexibility),
                 ellipse_a=fast.ellipse[0], ellipse_b=fast.ellipse[1], model_cpu_time=fast.model_cpu_time)
    return _result(scene, grid, normal, state, u, counts, state.creepages, extra, time.perf_counter() - t_start)


def _result(scene, grid, normal, steady, u, counts, creep, extra, wall):
    """The steady state as a run result (module docstring): `steady` has traction, slip (per unit rolling distance),
    stick, contact, force and moment in Kalker's convention; u the substrate's tangential displacement (mm)."""
    xi, eta, phi = creep
    dA = grid.cell_area
    tau_sub = -steady.traction
    region = np.where(steady.stick, 1, np.where(steady.contact, 2, 0)).astype(np.int8)
    F_sub = (float(tau_sub[0].sum() * dA), float(tau_sub[1].sum() * dA))
    history = dict(step=[0], period=[0], W_x=[0.0], W_y=[0.0], approach=[normal.approach], Fn=[normal.force],
                   contact_area=[float(steady.contact.sum() * dA)], stick_area=[float(steady.stick.sum() * dA)],
                   U_x=[math.nan], U_y=[math.nan], F_x=[F_sub[0]], F_y=[F_sub[1]],
                   iterations=[normal.iterations + counts["tangential"]], normal_iterations=[normal.iterations],
                   tangential_iterations=[counts["tangential"]], outer_iterations=[counts["outer"]],
                   residual=[counts["residual"]], wall_time=[wall])
    friction = getattr(steady, "friction", None)     # a friction law or [thermal] (the exact steady solver's)
    if scene.speed is not None:
        history["time"] = [0.0]        # the steady state: one row, at t = 0
    if friction is not None:
        history.update(friction_iterations=[friction.iterations], frictional_power=[friction.power],
                       friction_feedback=[friction.feedback])
    history = {k: np.asarray(v) for k, v in history.items()}
    fields = {"p": normal.pressure, "u_z": normal.displacement, "tau_x": tau_sub[0], "tau_y": tau_sub[1],
              "slip_x": -steady.slip[0] * grid.dx, "slip_y": -steady.slip[1] * grid.dx, "u_x": u[0], "u_y": u[1],
              "region": region, **friction_fields(friction)}
    fields, stored = _stored(scene, fields, 0)
    ro = scene.rolling
    a, b = scene.semi_axes
    linear = linear_forces(scene, xi, eta, phi)
    summary = dict(state="steady", mode=ro.mode, xi=xi, eta=eta, phi=phi, direction=ro.direction,
                   forces_prescribed=scene.prescribed_forces is not None,
                   F_x=steady.force[0], F_y=steady.force[1], M_z=steady.moment,
                   F_x_linear=linear[0], F_y_linear=linear[1], mu_Fn=scene.load.mu * normal.force,
                   stick_fraction=float(steady.stick.sum() / steady.contact.sum()), a=a, b=b,
                   p0=float(np.max(normal.pressure)), nx=grid.nx, ny=grid.ny, elements=grid.size, steps=1,
                   steps_planned=1, iterations=int(history["iterations"][0]), wall_time=wall)
    if scene.speed is not None:
        summary["speed"] = scene.speed
    if friction is not None:
        summary.update(friction_summary(scene, history, friction))
    summary.update(extra)
    return RunResult(scene_toml=scene.to_toml(), status="complete", x=grid.x, y=grid.y, history=history,
                     fields=fields, field_steps=stored, summary=summary, version=version())


def _stored(scene, fields, step):
    """The snapshot of `step` as stored fields, or none with output.fields = 'none' (any other choice stores the
    one snapshot a steady run keeps: its state)."""
    if scene.output.fields == "none":
        return {}, np.zeros(0, dtype=np.int64)
    return {k: np.asarray(v)[None] for k, v in fields.items()}, np.array([step], dtype=np.int64)

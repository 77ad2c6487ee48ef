"""One run of a [rolling] mode = "transient" scene: rolled from an initial state on the grid of [rolling] grid
(Scene.transient_grid; FASTSIM always on the world-fixed grid), with the steady state of the same scene solved beside
it (docs/theory.md §6, §11.5).

Both grids have their x axis along [rolling] direction (the frame of the steady run), y over +-(b_r + margin), with
a_r, b_r the Hertz contact's half-extents in the rolling frame (10 % allowance for an ellipse) and the scene's margin
(at least one element); the summary's `rolling_grid` names the grid and `grid_extent` states it, as the progress log.
* 'contact' (solver.creep.moving): the grid moves with the contact, x from the contact centre, from -(a_r + margin,
  at least a step) to a_r + margin; its cost per step does not grow with the distance rolled.
* 'world' (solver.creep.world): the grid is fixed to the substrate and just long enough for the rolled distance plus
  the contact: x from -(a_r + margin) to distance + a_r + margin; the contact centre starts at x = 0.
The contact centre moves by [rolling] step (default dx) per step.

What is stored: /history one row per step, step 0 the initial state (at rest), with the usual names (W_x, W_y the
contact centre's travel from its start, along the rolling direction and across it, mm; U_x, U_y the accumulated rigid
slip of the sphere relative to the substrate, sum of step (xi, eta), mm; F_x, F_y the force on the substrate, N;
stick_area; iterations: FFT products of the step) and M_z (N mm, on the sphere, about the contact centre), xi, eta (the creepages of the step: prescribed, or found
for prescribed forces); /fields the snapshots of the stored steps on the run's grid (output.fields: 'reversals',
the default, stores the initial state, each further contact length 2a rolled and the last step; 'all', 'last',
'none'), with their usual meaning (tau on the substrate, slip of the substrate relative to the sphere over the step,
mm). The summary gives the last step in Kalker's convention (F_x, F_y, M_z on the sphere; xi, eta, phi) beside the
steady state's (F_x_steady, ..., and xi_steady, eta_steady for prescribed forces). On FASTSIM ([solver] fidelity
'fastsim', or chosen by 'auto') the same grid and records come from cases.run.creep_fast.roll_fast (the normal
problem at every step, FASTSIM's transient step), the steady state beside it from FASTSIM too. Units: mm, N, MPa.
"""
from __future__ import annotations

import math
import time

import numpy as np

from rollcontact.cases.results.hdf5 import version
from rollcontact.cases.results.run_result import RunResult
from rollcontact.cases.run.creep_fast import fast_operator, fast_steady, roll_fast
from rollcontact.cases.run.creep_steady import steady_state
from rollcontact.cases.run.discretise import scene_operator
from rollcontact.cases.run.friction_outputs import friction_fields, friction_summary, temperature_summary
from rollcontact.cases.scene.friction import local_friction
from rollcontact.cases.run.rolling_frame import creep_grid, linear_forces, rolling_frame_gap
from rollcontact.cases.run.viscoelastic import MILLI, pressure_centroid, scene_memory, steady_outputs, steady_visco
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.creep.moving import roll_moving
from rollcontact.solver.creep.world import roll_world, rolling_steps
from rollcontact.solver.normal import NormalParams
from rollcontact.solver.rolling import FunctionProfile, StepParams
from rollcontact.solver.rolling.energy import frictional_work
from rollcontact.solver.tangential import TangentialParams

FIELDS = ("p", "u_z", "tau_x", "tau_y", "slip_x", "slip_y", "u_x", "u_y", "region")


def run_transient(scene: Scene, t_start: float, *, progress=None, choice=None) -> RunResult:
    """Roll the scene's [rolling] transient on its model (choice: cases.run.fidelity.FidelityChoice, default the
    scene's fidelity; 'bem' or 'fastsim') and return its RunResult (t_start: the run's perf_counter start); solver
    errors propagate to the caller (cases.run.creep_run.run_creep)."""
    from rollcontact.cases.run.fidelity import choose_fidelity
    choice = choose_fidelity(scene) if choice is None else choice
    fast = choice.model == "fastsim"
    c_start = time.process_time()
    ro, tol = scene.rolling, scene.solver.tol
    a, b = scene.semi_axes
    step = ro.step if ro.step is not None else scene.spacing[0]
    distance = ro.distance if ro.distance is not None else 8.0 * scene.rolling_half_length
    n = rolling_steps(distance, step)
    frame = "world" if fast else scene.transient_grid       # FASTSIM's transient steps the world-fixed grid
    grid = creep_grid(scene, travel=n * step) if frame == "world" else creep_grid(scene, trail=step)
    op = fast_operator(scene, grid) if fast else scene_operator(scene, grid)
    x0, x1 = grid.x[0] - grid.dx / 2, grid.x[-1] + grid.dx / 2
    y0, y1 = grid.y[0] - grid.dy / 2, grid.y[-1] + grid.dy / 2
    world = f"{grid.nx} x {grid.ny} = {grid.size} elements over x = [{x0:.6g}, {x1:.6g}] x y = [{y0:.6g}, {y1:.6g}] mm"
    if progress:
        model = "FASTSIM ('fastsim', no coupling)" if fast else f"coupling {'on' if op.coupled else 'off'}"
        progress(f"transient rolling on the {frame}-fixed grid {world} (x along the rolling direction "
                 f"{ro.direction} deg), {n} steps of {step:.6g} mm from the {ro.initial or 'rest'} state, {model}")
    xi, eta, phi = scene.creepages
    forces = scene.prescribed_forces
    visco, memory = None, None
    if fast:
        steady_fast = fast_steady(scene, "fastsim")
        steady_normal, steady, steady_creep = steady_fast.normal, steady_fast.state, steady_fast.creepages
        records = roll_fast(scene, op, distance=distance, step=step, initial=ro.initial or "rest")
    else:
        visco = steady_visco(scene, creep_grid(scene)) if scene.viscoelastic else None
        steady_normal, steady, _, steady_creep = steady_state(scene, visco)
        memory = scene_memory(scene, op)
        params = StepParams(normal=NormalParams(tol=tol, max_iter=scene.solver.max_iter),
                            tangential=TangentialParams(tol=tol, max_iter=scene.solver.max_iter),
                            coupling_tol=max(tol, 1e-10))
        roll = roll_world if frame == "world" else roll_moving
        held = dict(memory=memory, friction=local_friction(scene, grid)) if frame == "world" else {}
        records = roll(op, FunctionProfile(rolling_frame_gap(scene)), Fn=scene.load.Fn, mu=scene.load.mu,
                       distance=distance, step=step, xi=0.0 if forces else xi, eta=0.0 if forces else eta,
                       phi=phi, forces=forces, initial=ro.initial or "rest", params=params, **held)
    keep = _stored_steps(scene.output.fields, n, math.ceil(2.0 * scene.rolling_half_length / step - 1e-9))
    rows, fields, stored = [], {k: [] for k in FIELDS}, []
    for rec in records:
        rows.append(_row(rec, grid))            # with a friction law its columns
        if memory is not None:          # docs/viscoelastic.md; time: with cattaneo, its load at rest takes a step
            rows[-1].update(time=(rec.step + (ro.initial == "cattaneo")) * scene.step_time,
                            pressure_centroid_x=pressure_centroid(grid, rec.normal.pressure, (rec.centre, 0.0)),
                            viscous_dissipation=rec.viscous_dissipation)
        elif scene.step_time is not None:
            rows[-1]["time"] = (rec.step + (ro.initial == "cattaneo")) * scene.step_time
        if rec.step in keep:
            stored.append(rec.step)
            for k, v in _fields(rec).items():
                fields.setdefault(k, []).append(v)
        last = rec
    wall, cpu = time.perf_counter() - t_start, time.process_time() - c_start
    history = {k: np.asarray([r[k] for r in rows]) for k in rows[0]}
    linear = linear_forces(scene, *last.creepages)
    contact = last.normal.contact
    summary = dict(state="transient", mode=ro.mode, xi=last.creepages[0], eta=last.creepages[1], phi=phi,
                   direction=ro.direction, forces_prescribed=forces is not None, initial=ro.initial or "rest",
                   distance=float(last.centre), step=step, F_x=float(last.force[0]), F_y=float(last.force[1]),
                   M_z=last.moment, F_x_steady=steady.force[0], F_y_steady=steady.force[1], M_z_steady=steady.moment,
                   xi_steady=steady_creep[0], eta_steady=steady_creep[1],
                   F_x_linear=linear[0], F_y_linear=linear[1], mu_Fn=scene.load.mu * last.normal.force,
                   stick_fraction=float(last.stick_cells / contact.sum()), a=a, b=b,
                   p0=float(np.max(last.normal.pressure)), p0_steady=float(np.max(steady_normal.pressure)),
                   rolling_grid=frame, grid_extent=world, nx=grid.nx, ny=grid.ny, elements=grid.size, steps=n + 1,
                   steps_planned=n + 1,
                   iterations=int(history["iterations"].sum()), wall_time=wall, cpu_time=cpu,
                   time_per_step=float(history["wall_time"][1:].mean()), **choice.summary())
    if fast:
        summary.update(traction_bound=steady_fast.bound, flexibility=float(last.tangential.flexibility),
                       ellipse_a=steady_fast.ellipse[0], ellipse_b=steady_fast.ellipse[1])
    if scene.speed is not None:
        summary.update(speed=scene.speed, step_time=scene.step_time)
    friction = getattr(last, "friction", None)
    if friction is not None:
        summary.update(friction_summary(scene, history, friction))
        summary.update({f"{k}_steady": v for k, v in temperature_summary(steady.friction).items()})
    if visco is not None:
        xc = float(history["pressure_centroid_x"][-1])
        steady_out = steady_outputs(visco, visco.grid, steady_normal.pressure, -steady.traction, steady_normal.force)
        summary.update(pressure_centroid_x=xc, rolling_resistance_moment=last.normal.force * xc,
                       viscous_power=last.viscous_dissipation / scene.step_time * MILLI,
                       **{f"{k}_steady": v for k, v in steady_out.items()})
    out = {k: np.asarray(v) for k, v in fields.items()} if stored else {}
    return RunResult(scene_toml=scene.to_toml(), status="complete", x=grid.x, y=grid.y, history=history,
                     fields=out, field_steps=np.asarray(stored, dtype=np.int64), summary=summary, version=version())


def _stored_steps(choice: str, n: int, per_length: int) -> set:
    """The steps whose fields are stored (output.fields): 'reversals' the initial state, each contact length and
    the last step; 'all'; 'last'; 'none'."""
    if choice == "none":
        return set()
    if choice == "all":
        return set(range(n + 1))
    if choice == "last":
        return {n}
    return set(range(0, n + 1, max(per_length, 1))) | {n}


def _row(rec, grid) -> dict:
    """The history row of one step (run-file meaning: the force on the substrate; M_z, xi, eta in Kalker's); with a
    friction law its iterations and frictional power, with temperatures their largest values."""
    nr, tr = rec.normal, rec.tangential
    dA = grid.cell_area
    extra = {}
    if getattr(rec, "friction", None) is not None:
        extra.update(friction_iterations=rec.friction.iterations, frictional_power=rec.friction.power,
                     friction_feedback=rec.friction.feedback)
        extra.update({f"{k}": v for k, v in temperature_summary(rec.friction).items()})
    return dict(step=rec.step, period=0, W_x=rec.centre, W_y=0.0, approach=nr.approach, Fn=nr.force,
                contact_area=float(nr.contact.sum()) * dA, stick_area=rec.stick_cells * dA,
                U_x=float(rec.rigid_shift[0]), U_y=float(rec.rigid_shift[1]), F_x=float(tr.force[0]),
                F_y=float(tr.force[1]), M_z=rec.moment, xi=rec.creepages[0], eta=rec.creepages[1],
                iterations=nr.iterations + tr.iterations, normal_iterations=nr.iterations,
                tangential_iterations=tr.iterations, outer_iterations=rec.outer_iterations,
                residual=max(nr.residual, tr.residual), wall_time=rec.wall_time, cpu_time=rec.cpu_time,
                dissipation=frictional_work(tr.traction, tr.slip, dA), **extra)


def _fields(rec) -> dict:
    """The snapshot of one step on the run's grid (tau on the substrate; u of the substrate relative to the sphere,
    the tangential displacement A tau (+ A^tz p when coupled); slip of the step, mm)."""
    nr, tr = rec.normal, rec.tangential
    u = tr.displacement
    return {"p": nr.pressure, "u_z": nr.displacement, "tau_x": tr.traction[0], "tau_y": tr.traction[1],
            "slip_x": tr.slip[0], "slip_y": tr.slip[1], "u_x": u[0], "u_y": u[1], "region": tr.region,
            **friction_fields(getattr(rec, "friction", None))}

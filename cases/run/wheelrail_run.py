"""One run of a [wheelrail] scene (solver.wheelrail; docs/wheelrail.md): the wheel on its rail at the scene's position,
its contact patches and the forces.

What is stored (cases.results.run_result, WHEELRAIL_SUMMARY_UNITS, PATCH_UNITS): the summary arrays over the patches
(patch_y_rail, ..., n_patches) and the totals F_track_x, F_track_y, F_track_z in the track frame (x along the
direction of travel, y to the left, z up; forces on the wheel); per patch a group /patches/<k>/ with its grid in its
tangent plane (x along the track, y along s = n x x) and the usual fields, the wheel in the sphere's part and the
rail in the substrate's: p, u_z; tau_x, tau_y the traction the wheel exerts on the rail; u_x, u_y the rail's
displacement relative to the wheel; slip_x, slip_y the rail's slip relative to the wheel over a rolling step of one
element (dx, mm); region 0 / 1 / 2; and gap, the undeformed distance h(x, s) along n. The root's /grid and /fields
are empty; /history has the one step (Fn: the patches' normal forces summed; F_x, F_y: F_track_x, F_track_y).
output.fields = "none" stores the patches' values without their fields. With [rolling] mode = "transient" each
patch is then rolled from its initial state over the distance (solver.wheelrail.transient): its fields are the last
step's on the world-fixed grid, its forces (patch_Fx, patch_Fy, patch_Mz and the totals) the last step's, the steady
state's beside them (patch_Fx_steady, ...), and /patches/<k>/history holds every step. Units: mm, N, MPa, rad, s.
"""
from __future__ import annotations

import math
import time

import numpy as np

from rollcontact.bem.errors import RollcontactError
from rollcontact.cases.results.hdf5 import version
from rollcontact.cases.results.run_result import PatchData, RunResult
from rollcontact.cases.scene import wheelrail as wheelrail_scene
from rollcontact.cases.scene.scene import Scene

#: the summary arrays over the patches and the PatchResult attribute (or function) each comes from
PATCH_ARRAYS = {"patch_y_rail": "y_rail", "patch_y_wheel": "y_wheel", "patch_x": "x_track",
                "patch_contact_angle": "contact_angle", "patch_rolling_radius": "rolling_radius", "patch_Fn": "Fn",
                "patch_Fx": "Fx", "patch_Fy": "Fs", "patch_Mz": "Mz", "patch_pmax": "pmax", "patch_length": "length",
                "patch_width": "width", "patch_penetration": "penetration", "patch_angle_spread": "angle_spread"}


def run_wheelrail(scene: Scene, *, progress=None) -> RunResult:
    """Run a [wheelrail] scene and return its result (written by the caller). A solver that does not converge, or a
    contact the profiles do not cover, gives status 'failed' with the error; nothing but the scene is stored then."""
    from rollcontact.solver.wheelrail.solve import WheelRailParams, solve_wheel
    t_start, cpu_start = time.perf_counter(), time.process_time()
    wr = scene.wheelrail
    dx, dy = scene.spacing
    sv = scene.solver
    params = WheelRailParams(tol=sv.tol, max_iter=sv.max_iter, threads=sv.threads, fidelity=sv.fidelity)
    transient = None
    if scene.rolling.mode == "transient":
        from rollcontact.solver.wheelrail.transient import TransientSpec
        ro = scene.rolling
        transient = TransientSpec(ro.distance, ro.step, ro.initial or "rest")
    try:
        rail, wheel = wheelrail_scene.geometry(wr)
        solved = solve_wheel(rail, wheel, wr.side, wr.y, wr.Fz, wheelrail_scene.omega_per_speed(wr),
                             scene.material_pair, scene.load.mu, dx, dy, yaw=wr.yaw, roll=wr.roll, params=params,
                             transient=transient, progress=progress)
    except RollcontactError as exc:
        return RunResult(scene_toml=scene.to_toml(), status="failed", error=f"{type(exc).__name__}: {exc}",
                         x=np.zeros(0), y=np.zeros(0),
                         summary={"state": "failed", "wall_time": time.perf_counter() - t_start},
                         version=version())
    wall, cpu = time.perf_counter() - t_start, time.process_time() - cpu_start
    patches = [_patch_data(p, scene.output.fields != "none") for p in solved.patches]
    summary = _summary(scene, solved, wall, cpu)
    history = {k: np.asarray(v) for k, v in dict(
        step=[0], period=[0], approach=[solved.dz], Fn=[sum(p.Fn for p in solved.patches)],
        contact_area=[sum(float(p.contact.sum()) * p.grid.cell_area for p in solved.patches)],
        stick_area=[sum(float(p.stick.sum()) * p.grid.cell_area for p in solved.patches)],
        F_x=[solved.force_track[0]], F_y=[solved.force_track[1]],
        iterations=[summary["iterations"]], normal_iterations=[sum(p.normal_iterations for p in solved.patches)],
        tangential_iterations=[sum(p.sweeps for p in solved.patches)], outer_iterations=[solved.outer],
        wall_time=[wall]).items()}
    return RunResult(scene_toml=scene.to_toml(), status="complete", x=np.zeros(0), y=np.zeros(0), history=history,
                     summary=summary, version=version(), patches=patches)


def _summary(scene: Scene, solved, wall: float, cpu: float) -> dict:
    wr = scene.wheelrail
    ps = solved.patches
    out = {"state": "steady", "side": wr.side, "n_patches": len(ps),
           "mode": "transient" if ps and ps[0].transient is not None else "steady"}
    for name, attr in PATCH_ARRAYS.items():
        out[name] = np.array([getattr(p, attr) for p in ps], dtype=float)
    if out["mode"] == "transient":
        for name, k in (("Fx", 0), ("Fy", 1)):
            out[f"patch_{name}_steady"] = out[f"patch_{name}"]
            out[f"patch_{name}"] = np.array([p.transient.force[k] for p in ps])
        out["patch_Mz_steady"], out["patch_Mz"] = out["patch_Mz"], np.array([p.transient.moment for p in ps])
        out.update(state="transient", distance=max(p.transient.distance for p in ps),
                   step=ps[0].transient.step)
    for k, name in enumerate(("patch_xi", "patch_eta", "patch_phi")):
        out[name] = np.array([p.creepages[k] for p in ps], dtype=float)
    out.update(F_track_x=solved.force_track[0], F_track_y=solved.force_track[1], F_track_z=solved.force_track[2],
               z_ws=solved.z_centre - wr.wheel_radius, lowering=solved.dz,
               xi_nominal=wheelrail_scene.nominal_xi(wr), outer_iterations=solved.outer,
               nx=max(p.grid.nx for p in ps), ny=max(p.grid.ny for p in ps),
               elements=sum(p.grid.size for p in ps), steps=1, steps_planned=1,
               iterations=sum(p.normal_iterations + p.sweeps for p in ps), wall_time=wall, cpu_time=cpu,
               fidelity=scene.solver.fidelity, p0=max(p.pmax for p in ps))
    if wr.speed is not None:
        out["speed"] = wr.speed
        out["omega"] = wheelrail_scene.omega_per_speed(wr) * wr.speed
    return out


def _patch_data(p, with_fields: bool) -> PatchData:
    """A solved patch (solver.wheelrail.PatchResult) as stored: the run-file fields (module docstring) and values."""
    if p.transient is not None:
        return _transient_data(p, with_fields)
    g = p.grid
    values = dict(y_rail=p.y_rail, y_wheel=p.y_wheel, x_track=p.x_track, contact_angle=p.contact_angle,
                  rolling_radius=p.rolling_radius, Fn=p.Fn, Fx=p.Fx, Fy=p.Fs, Mz=p.Mz, xi=p.creepages[0],
                  eta=p.creepages[1], phi=p.creepages[2], pmax=p.pmax, length=p.length, width=p.width,
                  penetration=p.penetration, angle_spread=p.angle_spread, dx=g.dx, dy=g.dy, normal_iterations=p.normal_iterations,
                  sweeps=p.sweeps, contact_elements=int(p.contact.sum()), stick_elements=int(p.stick.sum()))
    fields = {}
    if with_fields:
        region = np.where(p.stick, 1, np.where(p.contact, 2, 0)).astype(np.int8)
        fields = {"p": p.pressure, "u_z": p.u_z, "tau_x": -p.traction[0], "tau_y": -p.traction[1],
                  "slip_x": -p.slip[0] * g.dx, "slip_y": -p.slip[1] * g.dx, "u_x": -p.u12[0], "u_y": -p.u12[1],
                  "region": region, "gap": p.gap}
    return PatchData(g.x, g.y, fields, values)


def _transient_data(p, with_fields: bool) -> PatchData:
    """A patch rolled transiently: the last step's fields on the world grid, the forces after rolling beside the
    steady ones, the history per step (run-file meaning: F_x, F_y on the rail; M_z on the wheel)."""
    t = p.transient
    g, steady = t.grid, _patch_data(_steady_only(p), False).values
    values = dict(steady, Fx=t.force[0], Fy=t.force[1], Mz=t.moment, Fx_steady=p.Fx, Fy_steady=p.Fs, Mz_steady=p.Mz,
                  distance=t.distance, step=t.step, steps=int(t.history["step"][-1]), dx=g.dx, dy=g.dy,
                  contact_elements=int((t.region > 0).sum()), stick_elements=int((t.region == 1).sum()))
    h = t.history
    history = {"step": h["step"].astype(np.int64), "W_x": h["centre"], "Fn": h["Fn"], "F_x": -h["Fx"],
               "F_y": -h["Fs"], "M_z": h["Mz"], "stick_area": h["stick_area"],
               "iterations": h["iterations"].astype(np.int64), "cpu_time": h["cpu_time"]}
    fields = {}
    if with_fields:
        fields = {"p": t.pressure, "u_z": t.u_z, "tau_x": t.traction[0], "tau_y": t.traction[1], "slip_x": t.slip[0],
                  "slip_y": t.slip[1], "u_x": t.u[0], "u_y": t.u[1], "region": t.region.astype(np.int8)}
    return PatchData(g.x, g.y, fields, values, history)


def _steady_only(p):
    from dataclasses import replace
    return replace(p, transient=None)


def format_wheelrail(result: RunResult) -> str:
    """Short summary of a [wheelrail] run for `rollcontact run`."""
    s = result.summary
    wr = result.scene.wheelrail
    lines = [f"{wr.side} wheel at y = {wr.y:.6g} mm (towards the field side), yaw {wr.yaw:.6g} rad, roll "
             f"{wr.roll:.6g} rad, Fz = {wr.Fz:.6g} N, xi at the nominal radius {s.get('xi_nominal', math.nan):.6g}"]
    if result.status != "complete":
        lines.append(f"status: {result.status}: {result.error}")
        return "\n".join(lines)
    lines.append(f"{s['n_patches']} contact patch(es); wheelset centre z_ws = {s['z_ws']:.6g} mm above nominal "
                 f"(lowered {s['lowering']:.5g} mm beyond the first touch); {s['elements']} elements, wall time "
                 f"{s['wall_time']:.2f} s")
    for k in range(int(s["n_patches"])):
        a = {name: float(np.asarray(s[name])[k]) for name in s if name.startswith("patch_")}
        lines.append(f"  patch {k}: rail y {a['patch_y_rail']:.4f} mm, wheel y {a['patch_y_wheel']:.4f} mm, contact "
                     f"angle {a['patch_contact_angle']:.5f} rad, rolling radius {a['patch_rolling_radius']:.4f} mm; "
                     f"Fn {a['patch_Fn']:.6g} N, Fx {a['patch_Fx']:.6g} N, Fy {a['patch_Fy']:.6g} N, Mz "
                     f"{a['patch_Mz']:.6g} N mm; xi {a['patch_xi']:.4g}, eta {a['patch_eta']:.4g}, phi "
                     f"{a['patch_phi']:.4g} 1/mm; pmax {a['patch_pmax']:.5g} MPa, {a['patch_length']:.3g} x "
                     f"{a['patch_width']:.3g} mm")
    if s.get("mode") == "transient":
        lines.append(f"forces after rolling {s['distance']:.4g} mm in steps of {s['step']:.4g} mm from the "
                     f"{result.scene.rolling.initial or 'rest'} state; the steady state's: Fx "
                     + ", ".join(f"{v:.6g}" for v in np.atleast_1d(s["patch_Fx_steady"])) + " N, Fy "
                     + ", ".join(f"{v:.6g}" for v in np.atleast_1d(s["patch_Fy_steady"])) + " N")
    lines.append(f"total force on the wheel (track frame: x forward, y left, z up): F_track = ({s['F_track_x']:.6g}, "
                 f"{s['F_track_y']:.6g}, {s['F_track_z']:.6g}) N")
    if result.path is not None:
        from pathlib import Path
        lines.append(f"results written to {Path(result.path).resolve()}")
    return "\n".join(lines)

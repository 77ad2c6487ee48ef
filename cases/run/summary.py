"""The summary of a BEM run (`summarise`: seed Eq. 9 normalisations, the state of the period-end shifts) and the
short text `rollcontact run` prints (`format_summary`). Units: mm, N, MPa; names and units of the summary:
cases.results.run_result.SUMMARY_UNITS."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from rollcontact.bem.grid import Grid
from rollcontact.cases.results.run_result import RunResult
from rollcontact.cases.run.friction_outputs import friction_lines, friction_summary
from rollcontact.cases.run.viscoelastic import viscous_per_period
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.rolling.shakedown import SETTLED_STATES, classify, cyclic_slip
from rollcontact.solver.rolling.stepping import LoadPath


#: |U_perp| (mm) above which `rollcontact run` prints the sideways walk (the solver's round-off is far below it).
SIDEWAYS_REPORTED = 1e-9


def summarise(scene: Scene, path: LoadPath, history: dict, state_label, grid: Grid, wall: float) -> dict:
    """Run summary: normalisations of seed Eq. 9 with the consistent constants (docs/theory.md §8.2, P3)."""
    pair = scene.material_pair
    hertz = scene.normal_reference        # Hertz (sphere, ellipsoid's equivalent sphere) or the shape's MDR
    n_done = len(history["U_x"])
    if scene.tangential_reference is not None:
        d, U0 = hertz.approach, scene.tangential_reference.U0
    else:  # the cylinder and a file profile: no closed-form approach, the solved one of the first step
        d = float(history["approach"][0]) if n_done else None
        U0 = scene.load.mu * pair.E_star * d / pair.G_star if n_done else None
    e_f = np.array(scene.load_direction)
    U = np.asarray(history["U_x"]) * e_f[0] + np.asarray(history["U_y"]) * e_f[1]
    U_perp = np.asarray(history["U_perp"])
    summary = dict(a=hertz.a, d=d, p0=hertz.p0, U0=U0, f_t=scene.f_t,
                   w=scene.amplitude / hertz.a, W=scene.amplitude, dW_used=path.dW, nx=grid.nx, ny=grid.ny,
                   elements=grid.size, steps=n_done, steps_planned=path.n_steps,
                   iterations=int(np.sum(history["iterations"])) if n_done else 0, wall_time=wall)
    # the static shift: the end of the ramp (to f_t, or to an oscillating load's starting value), before any further
    # force levels (load.levels); no ramp when the loading phase carries no tangential force
    n_load = int(np.count_nonzero(path.period == 0))
    ramped = scene.Ft > 0 or (scene.oscillating and bool(np.any(np.asarray(path.forces)[:n_load] != 0)))
    n_ramp = scene.load.ramp_steps if ramped else 0
    if n_done > n_ramp:
        summary.update(U_stat=float(U[n_ramp]), u_stat=float(U[n_ramp] / U0))
    if n_done:
        summary["U_perp"] = float(U_perp[-1])
    summary["dissipation_per_period"] = dissipation_per_period(path.period, history)
    if scene.viscoelastic and n_done:     # docs/viscoelastic.md; cases.run.viscoelastic
        xc = float(history["pressure_centroid_x"][-1])
        summary.update(pressure_centroid_x=xc, rolling_resistance_moment=float(history["Fn"][-1]) * xc,
                       viscous_dissipation_per_period=viscous_per_period(path.period, history))
    if scene.speed is not None:
        summary.update(speed=scene.speed, step_time=path.step_time)
    if scene.friction_on:
        summary.update(friction_summary(scene, history))
    if state_label:
        summary["state"] = state_label
    elif path.period.max() == 0:
        summary["state"] = "static" if n_done == path.n_steps else "incomplete"
    else:
        ends = [e for e in path.period_ends() if e < n_done]
        if len(ends) >= 2:
            cls = classify(U[ends], U0, tol=scene.solver.shakedown_tol)
            if scene.oscillating:      # loads varying within the period may slip to and fro with U settled
                cls = cyclic_slip(cls, works_per_period(path.period, history), scene.load.mu * scene.load.Fn * U0)
            summary.update(state=cls.state, periods_to_shakedown=cls.periods_to_shakedown,
                           U_sd=float(U[ends[-1]]) if cls.state in SETTLED_STATES else None,
                           u_sd=cls.u_sd if cls.state in SETTLED_STATES else None,
                           dU_per_period=float(U[ends[-1]] - U[ends[-2]]), du=cls.du,
                           dU_perp_per_period=float(U_perp[ends[-1]] - U_perp[ends[-2]]))
        else:
            summary["state"] = "incomplete"
    return summary


def works_per_period(period, history: dict) -> np.ndarray:
    """Frictional work of each complete period 1, 2, ... (N mm): /history/dissipation summed over its steps.
    period: the period index of every planned step (LoadPath.period)."""
    period = np.asarray(period)
    n_done = len(history["step"])
    dissipation = np.asarray(history["dissipation"])
    complete = [k for k in range(1, int(period.max()) + 1) if np.flatnonzero(period == k)[-1] < n_done]
    return np.array([float(np.sum(dissipation[np.flatnonzero(period == k)])) for k in complete])


def dissipation_per_period(period, history: dict) -> float | None:
    """Frictional work of the last complete period (N mm); None when no period is complete."""
    works = works_per_period(period, history)
    return float(works[-1]) if works.size else None


def format_summary(result: RunResult) -> str:
    """Short human summary printed by `rollcontact run`."""
    d = result
    s, h = d.summary, d.history
    if "n_patches" in s or (d.status == "failed" and d.scene.wheelrail_on):
        from rollcontact.cases.run.wheelrail_run import format_wheelrail
        return format_wheelrail(d)
    if s.get("state") in ("steady", "transient", "failed") and "xi" in s:
        return _format_creep(d)
    lines = []
    if len(h.get("step", [])):
        a_eq = math.sqrt(h["contact_area"][-1] / math.pi)
        shape = d.scene.shape
        ref = {"sphere": "Hertz", "ellipsoid": "Hertz", "cylinder": "2-D line contact",
               "file": "estimated (MDR of the radial envelope)"}.get(shape, "MDR")
        scale = {"sphere": "Hertz p0", "ellipsoid": "Hertz p0", "cylinder": "2-D line contact p0"}.get(
            shape, "scale p0 = 3 Fn/(2 pi a^2)")
        pressure = ""
        if len(d.field_steps):
            pressure = (f", max pressure {float(np.max(d.fields['p'][-1])):.5f} MPa ({scale} = {s['p0']:.5f} MPa)")
        lines.append(f"contact radius {a_eq:.4f} mm (equivalent; {ref} a = {s['a']:.4f} mm), approach "
                     f"{h['approach'][-1]:.6f} mm ({'first step' if shape in ('cylinder', 'file') else ref} d = {s['d']:.6f} mm)"
                     f"{pressure}")
        model = (f"MDR model, {s['springs']} springs" if s.get("fidelity") == "mdr"
                 else f"grid {s['nx']} x {s['ny']}")
        lines.append(f"steps {s['steps']}/{s['steps_planned']}, iterations {s['iterations']} "
                     f"(normal + tangential), {model}, wall time {d.wall_time:.2f} s")
    if "u_stat" in s:
        lines.append(f"f_t = {s['f_t']:.4g}: U_stat = {s['U_stat']:.6f} mm, u_stat = {s['u_stat']:.5f}")
    state = s.get("state", "?")
    line = f"state: {state}"
    if state == "gross_sliding" and "stopped_at_step" in s:
        line += (f" at step {s['stopped_at_step']} (of {s['steps_planned']} planned): {s.get('state_message', '')}"
                 "\ngross sliding: the tangential force reached the friction capacity mu Fn (f_t = Ft/(mu Fn) = "
                 f"{s['f_t']:.4g}), so no static equilibrium exists and the run stopped there; this is a result "
                 "(status complete), the steps before it are written")
    elif state in SETTLED_STATES:
        line += (f" after {s['periods_to_shakedown']} period(s); U_sd = {s['U_sd']:.6f} mm, "
                 f"u_sd = {s['u_sd']:.5f} (w = {s['w']:.4g})")
        if state == "cyclic_slip":
            line += "; U returns every period, but the contact slips to and fro (frictional work below)"
    elif state in ("ratcheting", "undecided"):
        line += f"; dU per period = {s['dU_per_period']:.3e} mm, du = {s['du']:.3e} (w = {s['w']:.4g})"
    lines.append(line)
    if s.get("U_perp") is not None and abs(s["U_perp"]) > SIDEWAYS_REPORTED:
        walk = (f", {s['dU_perp_per_period']:.3e} mm in the last period" if s.get("dU_perp_per_period") is not None
                else "")
        lines.append(f"sideways (across Ft): U_perp = {s['U_perp']:.6f} mm{walk}")
    if s.get("dissipation_per_period") is not None and d.scene.oscillating:
        lines.append(f"frictional work of the last period: {s['dissipation_per_period']:.6g} N mm")
    lines += friction_lines(s)
    lines += _visco_lines(s)
    if d.status != "complete":
        lines.append(f"status: {d.status}: {d.error}")
    if d.path is not None:
        lines.append(f"results written to {Path(d.path).resolve()}")
    return "\n".join(lines)


def _creep_work(s: dict, h: dict) -> str:
    """What the tangential model did: the exact solver's sweeps (steady) or products (last transient step), or the
    fast model's one pass over the strips."""
    model = s.get("fidelity_used", "bem")
    if model in ("fastsim", "fastrip"):
        bound = f", bound '{s['traction_bound']}'" if "traction_bound" in s else ""
        return f"{'FASTSIM' if model == 'fastsim' else 'FaStrip'} (one pass over the strips{bound})"
    return (f"{int(h['tangential_iterations'][-1])} "
            f"{'sweeps' if s.get('mode') == 'steady' else 'products in the last step'}")


def _format_creep(d: RunResult) -> str:
    """Short summary of a [rolling] run (cases.run.creep_run): Kalker's convention, forces on the rolling sphere."""
    s, h = d.summary, d.history
    lines = [f"{s.get('mode', 'steady')} rolling, creepages xi = {s['xi']:.6g}, eta = {s['eta']:.6g}, phi = {s['phi']:.6g} 1/mm "
             f"(direction {s['direction']:.4g} deg)"]
    if d.status == "complete":
        lines.append(f"contact area {h['contact_area'][-1]:.5g} mm^2 (stick {100 * s['stick_fraction']:.1f} %), "
                     f"max pressure {s['p0']:.5g} MPa, approach {h['approach'][-1]:.6g} mm, grid {s['nx']} x "
                     f"{s['ny']}, {_creep_work(s, h)}, wall time {d.wall_time:.2f} s")
        lines.append(f"forces on the rolling sphere (Kalker's convention, opposing the creepages): F_x = "
                     f"{s['F_x']:.6g} N, F_y = {s['F_y']:.6g} N, M_z = {s['M_z']:.6g} N mm; |F|/(mu Fn) = "
                     f"{math.hypot(s['F_x'], s['F_y']) / s['mu_Fn']:.4f}; linear theory F_x = {s['F_x_linear']:.6g} N, "
                     f"F_y = {s['F_y_linear']:.6g} N")
        if s.get("mode") == "transient":
            lines.append(f"after rolling {s['distance']:.6g} mm in {s['steps'] - 1} steps of {s['step']:.6g} mm from "
                         f"the {s['initial']} state on the {s['rolling_grid']}-fixed grid {s['grid_extent']} ("
                         f"{1e3 * s['time_per_step']:.3g} ms per step); the steady state: F_x = {s['F_x_steady']:.6g} "
                         f"N, F_y = {s['F_y_steady']:.6g} N, M_z = {s['M_z_steady']:.6g} N mm"
                         + (f", xi = {s['xi_steady']:.6g}, eta = {s['eta_steady']:.6g}" if s['forces_prescribed']
                            else ""))
        lines += friction_lines(s)
    else:
        lines.append(f"status: {d.status}: {d.error}")
    lines += _visco_lines(s)
    if d.path is not None:
        lines.append(f"results written to {Path(d.path).resolve()}")
    return "\n".join(lines)


def _visco_lines(s: dict) -> list:
    """The viscoelastic outputs of a summary (cases.run.viscoelastic), one line; none for an elastic run."""
    if s.get("pressure_centroid_x") is None:
        return []
    line = (f"viscoelastic: pressure centroid {s['pressure_centroid_x']:.5g} mm ahead of the lowest point, rolling "
            f"resistance moment {s['rolling_resistance_moment']:.5g} N mm")
    if s.get("viscous_dissipation_per_period") is not None:
        line += f", viscous work of the last period {s['viscous_dissipation_per_period']:.5g} N mm"
    if s.get("viscous_power") is not None:
        line += f", viscous power {s['viscous_power']:.5g} W"
    return [line]

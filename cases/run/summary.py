"""The summary of a BEM run (`summarise`: seed Eq. 9 normalisations, the state of the period-end shifts) and the
short text `rollcontact run` prints (`format_summary`). Units: mm, N, MPa; names and units of the summary:
cases.results.run_result.SUMMARY_UNITS."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from rollcontact.bem.grid import Grid
from rollcontact.cases.results.run_result import RunResult
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere
from rollcontact.solver.rolling.shakedown import classify
from rollcontact.solver.rolling.stepping import LoadPath


def summarise(scene: Scene, path: LoadPath, history: dict, state_label, grid: Grid, wall: float) -> dict:
    """Run summary: normalisations of seed Eq. 9 with the consistent constants (theory §8.2, P3)."""
    pair = scene.material_pair
    hertz = HertzSphere(scene.equivalent_radius, pair.E_star, scene.load.Fn)
    cm = CattaneoMindlin(hertz, scene.load.mu, pair.G_star)
    U0 = cm.U0
    e_f = np.array(scene.load_direction)
    U = np.asarray(history["U_x"]) * e_f[0] + np.asarray(history["U_y"]) * e_f[1]
    n_done = len(U)
    summary = dict(a=hertz.a, d=hertz.approach, p0=hertz.p0, U0=U0, f_t=scene.f_t,
                   w=scene.amplitude / hertz.a, W=scene.amplitude, dW_used=path.dW, nx=grid.nx, ny=grid.ny,
                   elements=grid.size, steps=n_done, steps_planned=path.n_steps,
                   iterations=int(np.sum(history["iterations"])) if n_done else 0, wall_time=wall)
    # the static shift at f_t: the end of the ramp, before any further force levels (load.levels)
    n_ramp = scene.load.ramp_steps if scene.Ft > 0 else 0
    if n_done > n_ramp:
        summary.update(U_stat=float(U[n_ramp]), u_stat=float(U[n_ramp] / U0))
    summary["dissipation_per_period"] = dissipation_per_period(path.period, history)
    if state_label:
        summary["state"] = state_label
    elif path.period.max() == 0:
        summary["state"] = "static" if n_done == path.n_steps else "incomplete"
    else:
        ends = [e for e in path.period_ends() if e < n_done]
        if len(ends) >= 2:
            cls = classify(U[ends], U0, tol=scene.solver.shakedown_tol)
            summary.update(state=cls.state, periods_to_shakedown=cls.periods_to_shakedown,
                           U_sd=float(U[ends[-1]]) if cls.state == "shakedown" else None,
                           u_sd=cls.u_sd if cls.state == "shakedown" else None,
                           dU_per_period=float(U[ends[-1]] - U[ends[-2]]), du=cls.du)
        else:
            summary["state"] = "incomplete"
    return summary


def dissipation_per_period(period, history: dict) -> float | None:
    """Frictional work of the last complete period (N mm): /history/dissipation summed over its steps; None when
    no period is complete. period: the period index of every planned step (LoadPath.period)."""
    period = np.asarray(period)
    n_done = len(history["step"])
    complete = [k for k in range(1, int(period.max()) + 1) if np.flatnonzero(period == k)[-1] < n_done]
    if not complete:
        return None
    steps = np.flatnonzero(period == complete[-1])
    return float(np.sum(np.asarray(history["dissipation"])[steps]))


def format_summary(result: RunResult) -> str:
    """Short human summary printed by `rollcontact run`."""
    d = result
    s, h = d.summary, d.history
    lines = []
    if len(h.get("step", [])):
        a_eq = math.sqrt(h["contact_area"][-1] / math.pi)
        pressure = ""
        if len(d.field_steps):
            pressure = (f", max pressure {float(np.max(d.fields['p'][-1])):.5f} MPa "
                        f"(Hertz p0 = {s['p0']:.5f} MPa)")
        lines.append(f"contact radius {a_eq:.4f} mm (equivalent; Hertz a = {s['a']:.4f} mm), approach "
                     f"{h['approach'][-1]:.6f} mm (Hertz d = {s['d']:.6f} mm){pressure}")
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
    elif state == "shakedown":
        line += (f" after {s['periods_to_shakedown']} period(s); U_sd = {s['U_sd']:.6f} mm, "
                 f"u_sd = {s['u_sd']:.5f} (w = {s['w']:.4g})")
    elif state in ("ratcheting", "undecided"):
        line += f"; dU per period = {s['dU_per_period']:.3e} mm, du = {s['du']:.3e} (w = {s['w']:.4g})"
    lines.append(line)
    if s.get("dissipation_per_period") is not None and d.scene.oscillating:
        lines.append(f"frictional work of the last period: {s['dissipation_per_period']:.6g} N mm")
    if d.status != "complete":
        lines.append(f"status: {d.status}: {d.error}")
    if d.path is not None:
        lines.append(f"results written to {Path(d.path).resolve()}")
    return "\n".join(lines)

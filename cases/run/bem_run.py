"""Run one scene: scene -> grid and operator (bem) -> stepping solver (solver) -> HDF5 file (cases).

`run_scene` is the single entry point used by the CLI and the sweeps. It never loses finished work: a
run that fails (no convergence, contact at the grid edge, Ctrl-C) still writes the steps it completed,
with status 'failed' and the error message; gross sliding is a result (state 'gross_sliding'), not a
failure. Units: mm, N, MPa.
"""
from __future__ import annotations

from dataclasses import dataclass
import math
from pathlib import Path
import sys
import time

import numpy as np

from rollcontact.bem.errors import GrossSlidingError, InputError, RollcontactError, SceneError
from rollcontact.bem.grid import MAX_ELEMENTS, Grid, contact_box
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere
from rollcontact.solver.normal.normcg import NormalParams
from rollcontact.solver.rolling.profiles import QuadricProfile
from rollcontact.solver.rolling.shakedown import classify
from rollcontact.solver.rolling.stepping import LoadPath, StepParams, StepState, build_path, run_path
from rollcontact.solver.tangential import TangentialParams, kernels_cached

from rollcontact.cases.results.hdf5 import RunData, is_complete, version, write_run
from rollcontact.cases.scene.scene import Scene

HISTORY_NAMES = ("step", "period", "W_x", "W_y", "approach", "Fn", "contact_area", "stick_area", "U_x",
                 "U_y", "F_x", "F_y", "iterations", "normal_iterations", "tangential_iterations",
                 "outer_iterations", "residual", "wall_time")
FIELD_NAMES = ("p", "u_z", "tau_x", "tau_y", "slip_x", "slip_y", "u_x", "u_y", "region")


@dataclass
class RunOutcome:
    path: Path
    data: RunData
    wall_time: float


def scene_path(scene: Scene) -> LoadPath:
    """The scene's loading phase and oscillation as a LoadPath (solver.rolling.stepping.build_path)."""
    e_f = np.array(scene.load_direction)
    mu_fn = scene.load.mu * scene.load.Fn
    return build_path(force=scene.Ft * e_f, ramp_steps=scene.load.ramp_steps,
                      levels=[lv * mu_fn * e_f for lv in scene.load.levels],
                      rolling_direction=scene.rolling_direction, amplitude=scene.amplitude,
                      max_step=scene.motion.dW, periods=scene.motion.periods)


def scene_grid(scene: Scene, path: LoadPath | None = None) -> Grid:
    """Grid just large enough for every contact the path can produce, plus the scene's margin.

    The Hertz semi-axes of an ellipse are estimated from the equivalent sphere, c (Rx/Ry)^(+-1/3), with
    a 10 % allowance; the run stops with ContactEdgeError if a contact still reaches the edge. The margin is
    at least one element (max(dx, dy)). Without a path, the centres are the extremes of the scene's
    oscillation (0 and +-W along the rolling direction), so an over-large scene is refused (SceneError,
    bem.grid.MAX_ELEMENTS) before its path is built.
    """
    rx, ry = scene.radii
    semi_x, semi_y = scene.semi_axes
    if rx != ry:  # the ellipse's semi-axes are estimates: 10 % allowance
        semi_x, semi_y = 1.1 * semi_x, 1.1 * semi_y
    dx, dy = scene.spacing
    if path is not None:
        centres = path.centres
    elif scene.amplitude > 0 and scene.motion.periods > 0:
        reach = scene.amplitude * np.array(scene.rolling_direction)
        centres = np.array([(0.0, 0.0), reach, -reach])
    else:
        centres = np.zeros((1, 2))
    # at least one element of margin: with half an element the discrete contact, slightly wider than Hertz's,
    # touched the grid's edge at step 0 (ContactEdgeError) on the paper scene
    margin = max(scene.grid.margin, dx, dy)
    try:
        return Grid.covering(*contact_box(semi_x, semi_y, centres, margin), dx, dy)
    except InputError as exc:  # too many elements: name the keys that set the size
        x0, x1, y0, y1 = contact_box(semi_x, semi_y, centres, 0.0)
        w0, h0 = x1 - x0, y1 - y0
        # largest margin m with (w0 + 2m)(h0 + 2m) <= MAX_ELEMENTS dx dy
        m_max = (math.sqrt((w0 - h0) ** 2 + 4.0 * MAX_ELEMENTS * dx * dy) - (w0 + h0)) / 4.0
        hint = (f"the allowed range at this dx, dy and amplitude is [grid] margin <= {m_max:.4g} mm"
                if m_max >= max(dx, dy) else "even without a margin the swept contact needs more elements: use a "
                "larger [grid] dx or a smaller [motion] W or w")
        raise SceneError(f"{exc} ([grid] margin = {scene.grid.margin!r} mm, [motion] W = "
                         f"{scene.amplitude:.4g} mm); {hint}") from None


def field_steps(scene: Scene, path: LoadPath) -> np.ndarray:
    """Steps whose fields are stored ([output] fields)."""
    n = path.n_steps
    mode = scene.output.fields
    if mode == "all":
        return np.arange(n)
    if mode == "none":
        return np.zeros(0, dtype=int)
    if mode == "last":
        return np.array([n - 1])
    keep = path.reversal.copy()
    keep[np.flatnonzero(path.period == 0)[-1]] = True
    keep[-1] = True
    return np.flatnonzero(keep)


def run_scene(scene: Scene, out, *, progress=None, restart: StepState | None = None,
              restart_history: dict | None = None, restart_snapshots: tuple | None = None,
              attrs: dict | None = None) -> RunOutcome:
    """Run `scene` and write the results to `out` (HDF5). Returns the outcome (also on failure).

    progress: callable(message) for progress lines (None: silent). restart / restart_history: continue
    from a stored step (see cases.run.restart); restart_snapshots = (steps, fields): the stored snapshots up to
    it, written into the new file too; attrs: further root attributes of the file. A scene that cannot be
    discretised (grid over the element limit) raises InputError before anything is computed or written; a
    failure during the run writes the finished steps with status 'failed'.
    """
    if scene.solver.fidelity == "mdr":
        from rollcontact.cases.run.mdr_run import run_scene_mdr
        return run_scene_mdr(scene, out, progress=progress)
    t_start = time.perf_counter()
    scene_grid(scene)          # refuses a scene whose grid would exceed the element limit, before any work
    path = scene_path(scene)
    grid = scene_grid(scene, path)
    pair = scene.material_pair
    coupling = {"auto": "auto", "on": True, "off": False}[scene.solver.coupling]
    op = HalfSpaceOperator(grid, pair, threads=scene.solver.threads, coupling=coupling)
    profile = QuadricProfile(*scene.radii)
    tol, max_iter = scene.solver.tol, scene.solver.max_iter
    params = StepParams(NormalParams(tol=tol, max_iter=max_iter), TangentialParams(tol=tol, max_iter=max_iter),
                        coupling_tol=max(tol, 1e-10))
    snap = set(field_steps(scene, path).tolist())
    history = {k: [] for k in HISTORY_NAMES}
    if restart_history:
        for k in HISTORY_NAMES:
            history[k] = list(np.asarray(restart_history[k])[: restart.step + 1])
    fields = {k: [] for k in FIELD_NAMES}
    stored = []
    if restart_snapshots:
        stored = [int(s) for s in restart_snapshots[0]]
        fields = {k: list(restart_snapshots[1][k]) for k in FIELD_NAMES}
    status, error, state_label, interrupted = "complete", "", None, None
    dA = grid.cell_area
    if progress:
        progress(f"grid {grid.nx} x {grid.ny} = {grid.size} elements (dx = {grid.dx}, dy = {grid.dy} mm), "
                 f"{path.n_steps} steps, coupling {'on' if op.coupled else 'off'} (beta = {pair.beta:.2e})")
        if not kernels_cached():
            progress("compiling the numerical kernels (first run after an install: about 10 s on 2 cores, "
                     "cached for later runs)")
    last_report = time.perf_counter()
    last = None

    def keep(rec):
        stored.append(rec.step)
        nr, tr = rec.normal, rec.tangential
        for k, v in (("p", nr.pressure), ("u_z", nr.displacement), ("tau_x", tr.traction[0]),
                     ("tau_y", tr.traction[1]), ("slip_x", tr.slip[0]), ("slip_y", tr.slip[1]),
                     ("u_x", tr.displacement[0]), ("u_y", tr.displacement[1]), ("region", tr.region)):
            fields[k].append(v.copy())

    try:
        for rec in run_path(op, profile, path, Fn=scene.load.Fn, mu=scene.load.mu, params=params,
                            state=restart):
            last = rec
            nr, tr, st = rec.normal, rec.tangential, rec.state
            row = dict(step=rec.step, period=int(path.period[rec.step]), W_x=rec.centre[0], W_y=rec.centre[1],
                       approach=nr.approach, Fn=nr.force, contact_area=float(nr.contact.sum()) * dA,
                       stick_area=float((tr.region == 1).sum()) * dA, U_x=st.rigid_shift[0],
                       U_y=st.rigid_shift[1], F_x=tr.force[0], F_y=tr.force[1],
                       iterations=nr.iterations + tr.iterations, normal_iterations=nr.iterations,
                       tangential_iterations=tr.iterations, outer_iterations=rec.outer_iterations,
                       residual=max(nr.residual, tr.residual), wall_time=rec.wall_time)
            for k, v in row.items():
                history[k].append(v)
            if rec.step in snap:
                keep(rec)
            if progress and (time.perf_counter() - last_report > 2.0 or rec.step == path.n_steps - 1):
                last_report = time.perf_counter()
                progress(f"step {rec.step + 1}/{path.n_steps}  period {row['period']}/{scene.motion.periods}  "
                         f"U_x = {row['U_x']:.6f} mm  iterations {nr.iterations}+{tr.iterations}")
    except GrossSlidingError as exc:
        state_label, error = "gross_sliding", str(exc)
    except (RollcontactError, KeyboardInterrupt) as exc:
        status, interrupted = "failed", exc if isinstance(exc, KeyboardInterrupt) else None
        error = "interrupted by the user" if interrupted else f"{type(exc).__name__}: {exc}"
        if interrupted:  # the interrupt may have come between the appends of one step: keep whole steps only
            last = _whole_steps(history, fields, stored, last)
    # a run that stopped early (gross sliding, a solver failure, an interrupt) keeps the fields of its last completed
    # step, the 'last step' that output.fields = "reversals" and "last" promise (and --restart needs)
    if (last is not None and scene.output.fields in ("reversals", "last")
            and (not stored or stored[-1] != last.step)):
        keep(last)
    wall = time.perf_counter() - t_start
    summary = summarise(scene, path, history, state_label, grid, wall)
    if state_label == "gross_sliding":   # the step that found no equilibrium; the solver's message
        summary.update(stopped_at_step=len(history["step"]), state_message=error)
    if status != "complete":
        out = _beside_a_complete_run(out)
    data = _write(scene, out, grid, history, fields, stored, status, error, summary, attrs)
    outcome = RunOutcome(Path(out), data, wall)
    if interrupted:
        raise RunInterrupted(outcome) from interrupted
    return outcome


class RunInterrupted(KeyboardInterrupt):
    """Ctrl-C (or SIGTERM through the CLI) during `run_scene`: the finished steps were written; `outcome` says where."""

    def __init__(self, outcome):
        super().__init__(f"interrupted; {len(outcome.data.history['step'])} step(s) written to {outcome.path}")
        self.outcome = outcome


def _whole_steps(history, fields, stored, last):
    """Trim the history and the stored fields to the steps recorded in full; returns the last such step's record
    (or None when it is not `last`, whose appends were cut short)."""
    n = min(len(v) for v in history.values())
    for v in history.values():
        del v[n:]
    m = min([len(stored)] + [len(v) for v in fields.values()])
    del stored[m:]
    for v in fields.values():
        del v[m:]
    return last if last is not None and n and history["step"][-1] == last.step else None


def _beside_a_complete_run(out):
    """A run that did not complete is not written over a complete run file: it goes to <stem>.partial.h5 beside it
    (an interrupted rerun would otherwise replace a finished result with a part of one)."""
    out = Path(out)
    if out.exists() and is_complete(out):
        return out.with_name(out.stem + ".partial" + out.suffix)
    return out


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
    return {k: v for k, v in summary.items()}


def _write(scene, out, grid, history, fields, stored, status, error, summary, attrs=None) -> RunData:
    n = len(stored)
    ny, nx = grid.shape
    flds = {}
    for k, v in fields.items():
        dtype = np.int8 if k == "region" else np.float64
        flds[k] = np.array(v, dtype=dtype) if n else np.zeros((0, ny, nx), dtype=dtype)
    hist = {k: np.asarray(v) for k, v in history.items()}
    data = RunData(scene_toml=scene.to_toml(), status=status, error=error, x=grid.x, y=grid.y,
                   history=hist, fields=flds, field_steps=np.array(stored, dtype=np.int64),
                   summary=summary, version=version(), attrs=dict(attrs or {}))
    write_run(out, data)
    return data


def print_progress(message: str):
    print(message, file=sys.stderr, flush=True)


def format_summary(outcome: RunOutcome) -> str:
    """Short human summary printed by `rollcontact run`."""
    d = outcome.data
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
                     f"(normal + tangential), {model}, wall time {outcome.wall_time:.2f} s")
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
    if d.status != "complete":
        lines.append(f"status: {d.status}: {d.error}")
    lines.append(f"results written to {Path(outcome.path).resolve()}")
    return "\n".join(lines)

"""Run a scene on the 1-D MDR model ([solver] fidelity = "mdr"), with the same HDF5 history layout.

The MDR model (solver.mdr) maps the rotationally symmetric, uncoupled contact onto a row of springs; it
cannot tell rolling directions apart, so W_x, W_y and U_x, U_y are the 1-D values placed along the
scene's rolling and force directions; U_perp is 0 (the 1-D model cannot walk sideways). The 1-D model has
no 2-D fields: /fields holds no snapshots, /grid/x holds the spring positions (mm) and /grid/y is [0]. contact_area and stick_area are the areas
of circles whose diameters are the loaded and the stuck spring lengths (pi L^2/4); iterations are 0
(both 1-D solves are exact). Units mm, N, MPa.
"""
from __future__ import annotations

import math
import time

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.solver.mdr.simulate import LoadSchedule, simulate_mdr
from rollcontact.solver.rolling.shakedown import cyclic_slip

from rollcontact.cases.results.hdf5 import version
from rollcontact.cases.results.run_result import HISTORY_NAMES, RunResult
from rollcontact.cases.scene.geometry import AXISYMMETRIC
from rollcontact.cases.run.discretise import scene_path
from rollcontact.cases.run.summary import dissipation_per_period, works_per_period
from rollcontact.cases.scene.scene import Scene


def mdr_schedule(scene: Scene) -> LoadSchedule:
    """The scene's load path (cases.run.discretise.scene_path, the BEM run's path) as the MDR model's schedule:
    the centres along the rolling direction, the tangential force along the force direction, Fn per step."""
    path = scene_path(scene)
    e_r, e_f = np.array(scene.rolling_direction), np.array(scene.load_direction)
    normal = path.normal_forces if path.normal_forces is not None else np.full(path.n_steps, scene.load.Fn)
    return LoadSchedule(Fn=normal, Ft=path.forces @ e_f, centre=path.centres @ e_r, period=path.period,
                        dW_used=path.dW)


def run_mdr(scene: Scene, *, progress=None) -> RunResult:
    """Run `scene` on the 1-D MDR model; the result is not written (its path is None). The sphere and the other
    axisymmetric shapes (cone, power, flat_rounded: their MDR profiles g(s), docs/theory.md §11.4). InputError for a
    scene
    the model cannot represent (an ellipse, coupled materials, load levels)."""
    quadric = scene.shape in ("sphere", "ellipsoid")
    rx, ry = scene.radii if quadric else (None, None)
    if rx != ry or scene.shape not in AXISYMMETRIC + ("ellipsoid",):
        got = f"Rx = {rx}, Ry = {ry} mm" if quadric else f"shape = {scene.shape!r}"
        raise InputError(f"[solver] fidelity = 'mdr' needs an axisymmetric shape ({', '.join(AXISYMMETRIC)}), got "
                         f"{got}: the MDR maps rotationally symmetric contacts only; use fidelity = 'bem'")
    if abs(scene.material_pair.beta) > 1e-4:
        raise InputError(f"[solver] fidelity = 'mdr' needs uncoupled materials (|beta| <= 1e-4), got beta = "
                         f"{scene.material_pair.beta:.3g}; use fidelity = 'bem'")
    if scene.load.levels:
        raise InputError("[load] levels are not supported by fidelity = 'mdr'; use fidelity = 'bem'")
    t0 = time.perf_counter()
    pair = scene.material_pair
    shape = dict(R=rx) if quadric else dict(profile=scene.profile)
    res = simulate_mdr(**shape, E_star=pair.E_star, G_star=pair.G_star, Fn=scene.load.Fn, mu=scene.load.mu,
                       Ft=scene.Ft, W=scene.amplitude, dW=scene.motion.dW,
                       periods=scene.motion.periods if scene.amplitude > 0 else 0,
                       ramp_steps=scene.load.ramp_steps, shakedown_tol=scene.solver.shakedown_tol,
                       schedule=mdr_schedule(scene) if scene.oscillating else None)
    wall = time.perf_counter() - t0
    h = res.history
    n = len(h["step"])
    e_r, e_f = np.array(scene.rolling_direction), np.array(scene.load_direction)
    zero = np.zeros(n)
    history = dict(step=h["step"], period=h["period"], W_x=h["W"] * e_r[0], W_y=h["W"] * e_r[1],
                   approach=h["approach"], Fn=h["Fn"],
                   contact_area=math.pi * h["contact_length"] ** 2 / 4,
                   stick_area=math.pi * h["stick_length"] ** 2 / 4, U_x=h["U"] * e_f[0], U_y=h["U"] * e_f[1],
                   U_perp=zero, F_x=h["Ft"] * e_f[0], F_y=h["Ft"] * e_f[1], iterations=zero.astype(int),
                   normal_iterations=zero.astype(int), tangential_iterations=zero.astype(int),
                   outer_iterations=zero.astype(int), residual=zero, wall_time=np.full(n, wall / max(n, 1)),
                   dissipation=h["dissipation"])
    assert set(history) == set(HISTORY_NAMES)
    cls = res.classification
    if scene.oscillating:          # loads varying within the period may slip to and fro with U settled
        cls = cyclic_slip(cls, works_per_period(_planned_periods(h["period"], res), history),
                          scene.load.mu * scene.load.Fn * res.U0)
    summary = dict(fidelity="mdr", a=res.a, d=res.d, p0=1.5 * scene.load.Fn / (math.pi * res.a ** 2), U0=res.U0,
                   f_t=res.f_t, w=res.w, W=scene.amplitude, dW_used=res.dW_used, springs=res.n_springs,
                   ds=res.ds, steps=n, steps_planned=n, iterations=0, wall_time=wall,
                   U_stat=res.U_stat, u_stat=res.U_stat / res.U0,
                   dissipation_per_period=dissipation_per_period(_planned_periods(h["period"], res), history))
    if (scene.amplitude > 0 or scene.oscillating) and scene.motion.periods > 0:
        summary.update(state=cls.state, periods_to_shakedown=cls.periods_to_shakedown,
                       U_sd=None if cls.u_sd is None else cls.u_sd * res.U0, u_sd=cls.u_sd,
                       dU_per_period=cls.dU_per_period, du=cls.du)
    else:
        summary["state"] = "gross_sliding" if cls.state == "gross_sliding" else "static"
    s = (res.ds * (np.arange(res.n_springs) - (res.n_springs - 1) / 2))
    if progress:
        progress(f"MDR model: {res.n_springs} springs, {n} steps in {wall * 1e3:.1f} ms")
    return RunResult(scene_toml=scene.to_toml(), status="complete", x=s, y=np.zeros(1), history=history,
                     fields={}, field_steps=np.zeros(0, dtype=np.int64), summary=summary, version=version())


def _planned_periods(period, res):
    """The period index of the steps as planned, as far as dissipation_per_period needs it: a run that stopped on
    gross sliding did not finish its last recorded period, so that period gets one more (missing) step."""
    period = np.asarray(period)
    if res.classification.state == "gross_sliding" and period.size:
        return np.append(period, period[-1])
    return period

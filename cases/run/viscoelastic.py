"""What a scene with viscoelastic bodies (materials.visco<i> = 'sls'; docs/viscoelastic.md) adds to a run: the
effective pair of its step time, the element states on the world-fixed grid, the steady operator of [rolling] steady
scenes, and the outputs (the pressure centroid along the rolling direction, the rolling resistance moment, the
viscous dissipation). Units: mm, N, MPa, s, W.

Outputs (names and units in cases.results.run_result: VISCO_HISTORY_UNITS, VISCO_SUMMARY_UNITS):
    pressure_centroid_x        int x p dA / int p dA (mm), x along the rolling direction from the rolling body's
                               lowest point (the sphere's centre W in oscillating scenes, the contact centre in
                               [rolling] scenes); > 0: the pressure leans forward, as on a viscoelastic substrate
    rolling_resistance_moment  Fn x pressure_centroid_x (N mm): the moment of the pressure about the lowest point,
                               which resists the rolling (for a sphere of radius R the force to roll it is M / R)
    viscous_dissipation        work of the viscous dashpots in a step (N mm; history), and its sum over the last
                               complete period (viscous_dissipation_per_period, N mm)
    viscous_power              the power the dashpots dissipate in steady rolling (W), in a transient its last step's
"""
from __future__ import annotations

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.visco.memory import ViscoMemory
from rollcontact.solver.visco.sls import effective_pair

#: mm N / s per W
MILLI = 1e-3


def step_pair(scene: Scene):
    """The elastic pair every step of a stepped viscoelastic scene sees (the effective moduli of its step time)."""
    if scene.step_time is None:
        raise InputError("a steady viscoelastic scene has no step time: its operator is the steady one "
                         "(cases.run.viscoelastic.steady_visco)")
    return effective_pair(*scene.bodies, scene.step_time)


def scene_memory(scene: Scene, op) -> ViscoMemory | None:
    """The element states of the scene's viscoelastic bodies on `op`'s grid (None for an elastic scene)."""
    if not scene.viscoelastic:
        return None
    return ViscoMemory(op, scene.sls_bodies, scene.step_time)


def steady_visco(scene: Scene, grid):
    """The steady viscoelastic operator and problems of a [rolling] steady scene on its contact-fixed grid."""
    from rollcontact.solver.visco.steady import SteadyVisco
    coupling = {"auto": "auto", "on": True, "off": False}[scene.solver.coupling]
    return SteadyVisco(grid, *scene.bodies, scene.speed, coupling=coupling, threads=scene.solver.threads)


def pressure_centroid(grid, pressure, centre=(0.0, 0.0), direction=(1.0, 0.0)) -> float:
    """int ((x, y) - centre) . direction p dA / int p dA (mm), NaN without contact."""
    X, Y = grid.mesh()
    p = np.asarray(pressure, dtype=float)
    total = float(p.sum())
    if total <= 0.0:
        return float("nan")
    arm = (X - centre[0]) * direction[0] + (Y - centre[1]) * direction[1]
    return float((arm * p).sum() / total)


def steady_outputs(visco, grid, pressure, traction_on_substrate, force) -> dict:
    """Summary values of a steady viscoelastic state: pressure_centroid_x (mm), rolling_resistance_moment (N mm),
    viscous_power (W)."""
    xc = pressure_centroid(grid, pressure)
    t = np.concatenate([np.asarray(pressure, float)[None], np.asarray(traction_on_substrate, float)])
    return dict(pressure_centroid_x=xc, rolling_resistance_moment=force * xc, viscous_power=visco.viscous_power(t))


def viscous_per_period(period, history: dict) -> float | None:
    """The viscous work of the last complete period (N mm): /history/viscous_dissipation summed over it; None when
    no period is complete."""
    period = np.asarray(period)
    n_done = len(history["step"])
    work = np.asarray(history["viscous_dissipation"])
    complete = [k for k in range(1, int(period.max()) + 1) if np.flatnonzero(period == k)[-1] < n_done]
    if not complete:
        return None
    return float(np.sum(work[np.flatnonzero(period == complete[-1])]))

"""Creep-force curves of a [rolling] scene (`rollcontact creep-curve`; theory.md §7.3, §11.5), as CSV.

One creepage of the scene (xi, eta or phi) is varied from the linear range to full sliding, the other two held at
zero, on the scene's contact-fixed grid and pressure (solved once: the normal problem does not depend on the
traction for uncoupled materials; coupled ones are refused), each steady solution the warm start of the next
(solver.creep.creep_curve). The creepages are `fractions` of the saturation creepage, at which Kalker's linear
force with Hertz's semi-axes would reach mu Fn: xi* = mu Fn/(G c^2 C11), eta* = mu Fn/(G c^2 C22),
phi* = mu Fn/(G c^3 C23) (1/mm). Kalker's convention: forces on the rolling sphere, opposing the creepage.
Units: mm, N, MPa; creepages dimensionless, phi in 1/mm.
"""
from __future__ import annotations

import csv
from dataclasses import dataclass
import math
import os
from pathlib import Path

import numpy as np

from rollcontact.bem.errors import InputError, OutputExistsError
from rollcontact.cases.run.discretise import scene_operator
from rollcontact.cases.run.rolling_frame import creep_grid, rolling_frame_profile, rolling_semi_axes
from rollcontact.cases.scene.friction import local_friction
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.creep import (SteadyParams, SteadyRolling, creep_curve, kalker_coefficients,
                                      saturation_creepage, vermeulen_johnson)
from rollcontact.solver.friction import solve_steady_friction
from rollcontact.solver.normal import NormalParams, solve_normal

#: The creepage varied -> (index in (xi, eta, phi), force component, Kalker coefficient index)
VARIED = {"xi": (0, 0, 0), "eta": (1, 1, 1), "phi": (2, 1, 2)}
COLUMNS = ("creepage", "creepage_over_saturation", "F_x", "F_y", "M_z", "F_over_muFn", "linear_over_muFn",
           "vermeulen_johnson", "stick_fraction", "sweeps")


@dataclass
class CurveTable:
    """The curve: `rows` (one dict per creepage, keys COLUMNS), what was varied, the saturation creepage."""
    varied: str
    saturation: float
    rows: list
    mu_fn: float
    law: str = ""                  # a friction law in words (mu_fn then uses its static coefficient)
    lowest_ratio: float | None = None   # the law's lowest coefficient over its static one (mu_kin / mu_static)


def compute_curve(scene: Scene, varied: str = "xi", fractions=None) -> CurveTable:
    """Steady states of `scene` at creepages `fractions` x the saturation creepage of `varied` (default: 20 values
    geometrically from 0.02 to 4). F_over_muFn is -F/(mu Fn) of the component the creepage drives (positive)."""
    if varied not in VARIED:
        raise InputError(f"creep-curve --of {varied!r}: allowed values are {list(VARIED)}")
    fractions = np.geomspace(0.02, 4.0, 20) if fractions is None else np.asarray(fractions, dtype=float)
    grid, pair = creep_grid(scene), scene.material_pair
    op = scene_operator(scene, grid)
    if op.coupled:
        raise InputError(f"creep-curve: coupled materials (Dundurs beta = {pair.beta:.3g}) need the normal problem "
                         "at every creepage; run the scene per creepage (rollcontact run), or set "
                         "solver.coupling = \"off\"")
    normal = solve_normal(op, rolling_frame_profile(scene, grid), force=scene.load.Fn,
                          params=NormalParams(tol=scene.solver.tol, max_iter=scene.solver.max_iter))
    axes = rolling_semi_axes(scene)
    if axes is None:
        raise InputError(f"creep-curve: [rolling] direction = {scene.rolling.direction} deg is oblique to the axes of "
                         "the elongated contact; Kalker's linear theory, which scales the curve, needs the rolling "
                         "along an axis (direction 0 or 90 deg here); run the scene per creepage (rollcontact run)")
    a, b = axes
    nu = min(max(pair.nu, 0.0), 0.5)
    index, component, which = VARIED[varied]
    coefficient = kalker_coefficients(a / b, nu)[which]
    c = math.sqrt(a * b)
    mu_fn = scene.load.mu * normal.force
    saturation = saturation_creepage(pair.G, c, coefficient * (c if varied == "phi" else 1.0), scene.load.mu,
                                     normal.force)
    creep = np.zeros((len(fractions), 3))
    creep[:, index] = fractions * saturation
    friction = local_friction(scene, grid)      # a friction law or [thermal]: None without them
    states = []
    curve = creep_curve(SteadyRolling(grid, pair, coupled=False, operator=op), normal.pressure, scene.load.mu, creep,
                        params=SteadyParams(tol=scene.solver.tol, max_sweeps=max(scene.solver.max_iter, 100)),
                        **({} if friction is None else {"solve": _law_solver(friction, states)}))
    ratio = -curve.force[:, component] / mu_fn
    rows = [dict(zip(COLUMNS, (creep[k, index], fractions[k], curve.force[k, 0], curve.force[k, 1],
                               curve.moment[k], ratio[k], fractions[k], float(vermeulen_johnson(fractions[k])),
                               curve.stick_fraction[k], int(curve.sweeps[k])))) for k in range(len(fractions))]
    for row, state in zip(rows, states):
        row.update(_friction_columns(state, normal.pressure > 0))
    law = friction.law if friction is not None else None
    return CurveTable(varied, saturation, rows, mu_fn, "" if law is None else law.describe(),
                      None if law is None else law.mu_lowest / law.mu_static)


def _law_solver(friction, states):
    """solve_steady's stand-in for a friction law: each point warm-started from the coefficient field of the one
    before, its FrictionState appended to `states`."""
    def solve(problem, pressure, mu, xi, eta, phi, *, initial=None, params=None):
        res = solve_steady_friction(problem, pressure, friction, xi, eta, phi, initial=initial,
                                    mu_initial=states[-1].mu if states else None, params=params)
        states.append(res.friction)
        return res
    return solve


def _friction_columns(state, contact) -> dict:
    """The columns a friction law adds: the lowest local mu in the contact, the largest slip velocity (mm/s), the
    frictional power (W) and, with temperatures, the largest surface temperature (degC)."""
    out = {"mu_min": float(state.mu[contact].min()), "slip_velocity_max": float(state.slip_velocity.max()),
           "frictional_power": state.power}
    if state.temperatures is not None:
        out["T_max"] = float(max(state.temperatures.T1.max(), state.temperatures.T2.max()))
    return out


def write_csv(table: CurveTable, path: Path, overwrite: bool = False) -> Path:
    """The curve as CSV (header: COLUMNS, and with a friction law mu_min, slip_velocity_max (mm/s), frictional_power
    (W) and with temperatures T_max (degC); a comment line first with the units and the saturation creepage),
    through a temporary file renamed into place; an existing file only with `overwrite`."""
    path = Path(path)
    if path.exists() and not overwrite:
        raise OutputExistsError(f"{path}: exists; rollcontact does not replace a file unless asked: add --overwrite")
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    unit = "1/mm" if table.varied == "phi" else "-"
    with open(tmp, "w", newline="") as fh:
        fh.write(f"# creep-force curve over {table.varied} ({unit}); saturation creepage {table.saturation:.6g} "
                 f"{unit}; mu Fn = {table.mu_fn:.6g} N; F_x, F_y (N), M_z (N mm) on the rolling sphere (Kalker)"
                 + (f"; friction law {table.law} (mu = its static coefficient)" if table.law else "") + "\n")
        writer = csv.DictWriter(fh, fieldnames=list(table.rows[0]) if table.rows else COLUMNS)
        writer.writeheader()
        for row in table.rows:
            writer.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in row.items()})
    os.replace(tmp, path)
    return path

"""Creep-force curves of a [rolling] scene (`rollcontact creep-curve`; docs/theory.md §7.3, §11.5), as CSV.

One creepage of the scene (xi, eta or phi) is varied from the linear range to full sliding, the other two held at
zero, on the scene's contact-fixed grid and pressure (solved once: the normal problem does not depend on the
traction for uncoupled materials; coupled ones are refused), each steady solution the warm start of the next
(solver.creep.creep_curve). The creepages are `fractions` of the saturation creepage, at which Kalker's linear
force with Hertz's semi-axes would reach mu Fn: xi* = mu Fn/(G c^2 C11), eta* = mu Fn/(G c^2 C22),
phi* = mu Fn/(G c^3 C23) (1/mm). Kalker's convention: forces on the rolling sphere, opposing the creepage.

`fidelities` draws the curve with several models on the same grid and pressure: 'bem' (the exact theory above),
'fastsim' and 'fastrip' (solver.fastsim: the scene's traction bound and the flexibilities of cases.run.creep_fast,
each point on its own, no warm start needed); one table per model, each point with the model's CPU time.
Units: mm, N, MPa; creepages dimensionless, phi in 1/mm.
"""
from __future__ import annotations

import csv
from dataclasses import dataclass
import io
import math
from pathlib import Path
import time

import numpy as np

from rollcontact.bem.errors import InputError, OutputExistsError
from rollcontact.cases.arguments import arg, flag, on_command_line
from rollcontact.cases.results.writing import write_text
from rollcontact.cases.run.creep_fast import SOLVERS, bound_pressure, contact_ellipse, fast_operator
from rollcontact.cases.run.discretise import scene_operator
from rollcontact.cases.run.viscoelastic import steady_visco
from rollcontact.cases.run.rolling_frame import creep_grid, rolling_frame_profile, rolling_semi_axes
from rollcontact.cases.scene.friction import local_friction
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.creep import (SteadyParams, SteadyRolling, creep_curve, kalker_coefficients,
                                      saturation_creepage, vermeulen_johnson)
from rollcontact.solver.fastsim import kalker_flexibilities
from rollcontact.solver.friction import solve_steady_friction
from rollcontact.solver.normal import NormalParams, solve_normal

#: The creepage varied -> (index in (xi, eta, phi), force component, Kalker coefficient index)
VARIED = {"xi": (0, 0, 0), "eta": (1, 1, 1), "phi": (2, 1, 2)}
COLUMNS = ("creepage", "creepage_over_saturation", "F_x", "F_y", "M_z", "F_over_muFn", "linear_over_muFn",
           "vermeulen_johnson", "stick_fraction", "sweeps", "cpu_time")
#: The models a curve can be drawn with.
CURVE_FIDELITIES = ("bem", "fastsim", "fastrip")


@dataclass
class CurveTable:
    """The curve: `rows` (one dict per creepage, keys COLUMNS; cpu_time in s, sweeps 1 for a fast model's one
    pass), what was varied, the saturation creepage, mu Fn (N) and the model ('bem', 'fastsim', 'fastrip')."""
    varied: str
    saturation: float
    rows: list
    mu_fn: float
    fidelity: str = "bem"
    law: str = ""                  # a friction law in words (mu_fn then uses its static coefficient)
    lowest_ratio: float | None = None   # the law's lowest coefficient over its static one (mu_kin / mu_static)


def compute_curve(scene: Scene, varied: str = "xi", fractions=None, fidelity: str = "bem") -> CurveTable:
    """Steady states of `scene` at creepages `fractions` x the saturation creepage of `varied` (default: 20 values
    geometrically from 0.02 to 4) on one model. F_over_muFn is -F/(mu Fn) of the component the creepage drives
    (positive)."""
    return compute_curves(scene, varied, fractions, (fidelity,))[0]


def compute_curves(scene: Scene, varied: str = "xi", fractions=None, fidelities=("bem",)) -> list[CurveTable]:
    """The curve of `compute_curve` on each model of `fidelities` (CURVE_FIDELITIES), on the same grid and
    pressure."""
    if varied not in VARIED:
        raise InputError(f"{arg('of')} {varied!r}: allowed values are {list(VARIED)}")
    fidelities = tuple(dict.fromkeys(fidelities))
    for f in fidelities:
        if f not in CURVE_FIDELITIES:
            raise InputError(f"{arg('fidelity')} {f!r}: allowed values are {list(CURVE_FIDELITIES)}")
    fractions = np.geomspace(0.02, 4.0, 20) if fractions is None else np.asarray(fractions, dtype=float)
    grid, pair = creep_grid(scene), scene.material_pair
    visco = steady_visco(scene, grid) if scene.viscoelastic else None     # docs/viscoelastic.md
    if visco is not None and set(fidelities) - {"bem"}:
        raise InputError(f"{arg('fidelity')} {[f for f in fidelities if f != 'bem']}: the fast models are elastic; a "
                         "viscoelastic scene's curve is the boundary elements' (fidelity 'bem')")
    if visco is not None:
        op = visco.operator
    else:
        op = scene_operator(scene, grid) if "bem" in fidelities else fast_operator(scene, grid)
    if op.coupled:
        raise InputError(f"creep-curve: coupled materials (Dundurs beta = {pair.beta:.3g}) need the normal problem "
                         "at every creepage; run the scene per creepage (rollcontact run), or set "
                         "solver.coupling = \"off\"")
    nparams = NormalParams(tol=scene.solver.tol, max_iter=scene.solver.max_iter)
    if visco is None:
        normal = solve_normal(op, rolling_frame_profile(scene, grid), force=scene.load.Fn, params=nparams)
    else:
        normal = visco.solve_normal(rolling_frame_profile(scene, grid), scene.load.Fn, params=nparams)
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
    if friction is not None and set(fidelities) - {"bem"}:
        raise InputError(f"{arg('fidelity')} {[f for f in fidelities if f != 'bem']}: the fast models take one "
                         "coefficient of friction; a scene with [friction] or [thermal] draws its curve with the "
                         "boundary elements (fidelity 'bem')")
    law = friction.law if friction is not None else None
    tables = []
    for fidelity in fidelities:
        states = []
        if fidelity == "bem":
            problem = (SteadyRolling(grid, pair, coupled=False, operator=op) if visco is None
                       else visco.tangential_problem)
            curve = creep_curve(problem, normal.pressure, scene.load.mu, creep,
                                params=SteadyParams(tol=scene.solver.tol, max_sweeps=max(scene.solver.max_iter, 100)),
                                **({} if friction is None else {"solve": _law_solver(friction, states)}))
            force, moment, stick, sweeps, seconds = (curve.force, curve.moment, curve.stick_fraction, curve.sweeps,
                                                     curve.cpu_time)
        else:
            force, moment, stick, sweeps, seconds = _fast_points(scene, grid, normal, creep, fidelity)
        ratio = -force[:, component] / mu_fn
        rows = [dict(zip(COLUMNS, (creep[k, index], fractions[k], force[k, 0], force[k, 1], moment[k], ratio[k],
                                   fractions[k], float(vermeulen_johnson(fractions[k])), stick[k], int(sweeps[k]),
                                   float(seconds[k])))) for k in range(len(fractions))]
        for row, state in zip(rows, states):
            row.update(_friction_columns(state, normal.pressure > 0))
        tables.append(CurveTable(varied, saturation, rows, mu_fn, fidelity,
                                 law="" if law is None else law.describe(),
                                 lowest_ratio=None if law is None else law.mu_lowest / law.mu_static))
    return tables


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


def _fast_points(scene, grid, normal, creep, fidelity):
    """A fast model at each creepage on the grid and pressure of the exact curve (cases.run.creep_fast)."""
    pressure, edges = bound_pressure(scene, grid, normal.pressure)
    a, b = contact_ellipse(scene, grid, normal.pressure)
    pair = scene.material_pair
    flex = kalker_flexibilities(a, b, pair.G, pair.nu)
    solve = SOLVERS[fidelity]
    force, moment = np.zeros((len(creep), 2)), np.zeros(len(creep))
    stick, seconds = np.zeros(len(creep)), np.zeros(len(creep))
    for k, row in enumerate(creep):
        c0 = time.process_time()
        res = solve(grid, pressure, scene.load.mu, *row, flexibilities=flex, edges=edges)
        seconds[k] = time.process_time() - c0
        force[k], moment[k], stick[k] = res.force, res.moment, res.stick.sum() / res.contact.sum()
    return force, moment, stick, np.ones(len(creep), dtype=np.int64), seconds


def write_csv(table: CurveTable, path: Path, overwrite: bool = False) -> Path:
    """The curve as CSV (header: COLUMNS; a comment line first with the units and the saturation creepage),
    through a temporary file renamed into place (cases.results.writing); an existing file only with `overwrite`."""
    path = Path(path)
    if path.exists() and not overwrite:
        raise OutputExistsError(f"{path}: exists; rollcontact does not replace a file unless asked: "
                                f"{'add' if on_command_line() else 'pass'} {flag('overwrite')}")
    unit = "1/mm" if table.varied == "phi" else "-"
    text = io.StringIO(newline="")
    text.write(f"# creep-force curve over {table.varied} ({unit}) by fidelity = '{table.fidelity}'; saturation "
               f"creepage {table.saturation:.6g} "
               f"{unit}; mu Fn = {table.mu_fn:.6g} N; F_x, F_y (N), M_z (N mm) on the rolling sphere (Kalker)"
               + (f"; friction law {table.law} (mu = its static coefficient)" if table.law else "") + "\n")
    writer = csv.DictWriter(text, fieldnames=list(table.rows[0]) if table.rows else COLUMNS)
    writer.writeheader()
    for row in table.rows:
        writer.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in row.items()})
    return write_text(path, text.getvalue(), "creep curve")


@dataclass
class CreepCurve:
    """What `creep_curve_files` computed and wrote: the curve of each model (`tables`, `table` the first: rows,
    saturation creepage), the files (`paths`: a CSV per model, PNG, PDF; none without an output folder), the creepage
    varied (`of`) and the time (`seconds`, wall). `report()` is what `rollcontact creep-curve` prints."""
    tables: list
    paths: list
    of: str
    seconds: float

    @property
    def table(self) -> CurveTable:
        return self.tables[0]

    def report(self) -> str:
        unit = " 1/mm" if self.of == "phi" else ""
        if len(self.tables) == 1 and self.table.fidelity == "bem":
            work = f"{sum(r['sweeps'] for r in self.table.rows)} sweeps"
        else:
            work = ", ".join(f"{t.fidelity} {sum(r['cpu_time'] for r in t.rows):.3g} s CPU" for t in self.tables)
        return "\n".join([f"{len(self.table.rows)} creepages of {self.of} in {self.seconds:.2f} s ({work}); "
                          f"saturation creepage {self.table.saturation:.6g}{unit}"]
                         + [str(Path(p).resolve()) for p in self.paths])

    def __repr__(self) -> str:
        return (f"CreepCurve(of={self.of!r}, models={[t.fidelity for t in self.tables]}, points={len(self.table.rows)}, "
                f"saturation={self.table.saturation:.6g}, files={len(self.paths)})")


def creep_curve_files(scene: Scene, of: str = "xi", points: int = 20, max_ratio: float = 4.0, output="creep",
                      overwrite: bool = False, fidelity=None) -> CreepCurve:
    """The creep-force curve of the steady [rolling] scene over `of` at `points` creepages geometrically from 0.02 to
    `max_ratio` times the saturation creepage, on each model of `fidelity` ('bem', 'fastsim', 'fastrip' or a list of
    them, drawn side by side; default the scene's [solver] fidelity when it is one of them, else 'bem'), written to
    `output`/<scene>_creep_<of>.csv (the exact theory; <scene>_creep_<of>_<model>.csv for a fast model) and the figure
    .png, .pdf (all of them or none; output None: the tables alone). Refused before any work (InputError naming the
    argument): a scene without [rolling] or with mode = 'transient' (the curve is of the steady state), points < 2,
    max_ratio outside (0, 100], an unknown model, a file that exists (unless `overwrite`)."""
    from rollcontact.cases.plots.common import all_or_none
    from rollcontact.cases.plots.creep_figures import plot_curve
    from rollcontact.cases.results.outputs import output_folder
    if not scene.rolling_on:
        raise InputError(f"scene {scene.name}: no [rolling] section (mode = \"steady\"); add one, or "
                         f"{arg('overrides')} rolling.mode=\"steady\"")
    if scene.rolling.mode != "steady":
        raise InputError(f"scene {scene.name}: [rolling] mode = {scene.rolling.mode!r}: a creep curve is of the "
                         f"steady state (each creepage solved in contact-fixed coordinates); use "
                         f"{arg('overrides')} rolling.mode=\"steady\", or run the transient per creepage")
    if of not in VARIED:
        raise InputError(f"{arg('of')} {of!r}: allowed values are {list(VARIED)}")
    if isinstance(points, bool) or not isinstance(points, int) or not points >= 2:
        raise InputError(f"{arg('points')} {points!r}: allowed range is an integer >= 2")
    if not (isinstance(max_ratio, (int, float)) and 0 < max_ratio <= 100):
        raise InputError(f"{arg('max_ratio')} {max_ratio!r}: allowed range is 0 < {arg('max_ratio')} <= 100")
    if fidelity is None:
        fidelity = [scene.solver.fidelity if scene.solver.fidelity in CURVE_FIDELITIES else "bem"]
    fidelity = [fidelity] if isinstance(fidelity, str) else list(dict.fromkeys(fidelity))
    for f in fidelity:
        if f not in CURVE_FIDELITIES:
            raise InputError(f"{arg('fidelity')} {f!r}: allowed values are {list(CURVE_FIDELITIES)}")
    stem = f"{scene.name}_creep_{of}"
    targets = []
    if output is not None:
        out = Path(output)
        targets = [out / (f"{stem}.csv" if f == "bem" else f"{stem}_{f}.csv") for f in fidelity]
        existing = [t for t in targets + [out / f"{stem}{ext}" for ext in (".png", ".pdf")] if t.exists()]
        if existing and not overwrite:
            raise OutputExistsError(f"{existing[0]}: exists; rollcontact does not replace a file unless asked: "
                                    f"{'add' if on_command_line() else 'pass'} {flag('overwrite')}, or give another "
                                    f"folder with {arg('output')}")
        output_folder(out)
    t0 = time.perf_counter()
    tables = compute_curves(scene, of, np.geomspace(0.02, max_ratio, points), fidelity)
    seconds = time.perf_counter() - t0
    paths = []
    if output is not None:
        with all_or_none():
            figures = plot_curve(tables, out, stem, overwrite=overwrite)
            paths = [write_csv(t, p, overwrite=overwrite) for t, p in zip(tables, targets)] + figures
    return CreepCurve(tables, paths, of, seconds)

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
import io
import math
from pathlib import Path

import numpy as np

from rollcontact.bem.errors import InputError, OutputExistsError
from rollcontact.cases.arguments import arg, flag, on_command_line
from rollcontact.cases.results.writing import write_text
from rollcontact.cases.run.discretise import scene_operator
from rollcontact.cases.run.viscoelastic import steady_visco
from rollcontact.cases.run.rolling_frame import creep_grid, rolling_frame_profile, rolling_semi_axes
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.creep import (SteadyParams, SteadyRolling, creep_curve, kalker_coefficients,
                                      saturation_creepage, vermeulen_johnson)
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


def compute_curve(scene: Scene, varied: str = "xi", fractions=None) -> CurveTable:
    """Steady states of `scene` at creepages `fractions` x the saturation creepage of `varied` (default: 20 values
    geometrically from 0.02 to 4). F_over_muFn is -F/(mu Fn) of the component the creepage drives (positive)."""
    if varied not in VARIED:
        raise InputError(f"{arg('of')} {varied!r}: allowed values are {list(VARIED)}")
    fractions = np.geomspace(0.02, 4.0, 20) if fractions is None else np.asarray(fractions, dtype=float)
    grid, pair = creep_grid(scene), scene.material_pair
    visco = steady_visco(scene, grid) if scene.viscoelastic else None     # docs/viscoelastic.md
    op = scene_operator(scene, grid) if visco is None else visco.operator
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
    problem = SteadyRolling(grid, pair, coupled=False, operator=op) if visco is None else visco.tangential_problem
    curve = creep_curve(problem, normal.pressure, scene.load.mu, creep,
                        params=SteadyParams(tol=scene.solver.tol, max_sweeps=max(scene.solver.max_iter, 100)))
    ratio = -curve.force[:, component] / mu_fn
    rows = [dict(zip(COLUMNS, (creep[k, index], fractions[k], curve.force[k, 0], curve.force[k, 1],
                               curve.moment[k], ratio[k], fractions[k], float(vermeulen_johnson(fractions[k])),
                               curve.stick_fraction[k], int(curve.sweeps[k])))) for k in range(len(fractions))]
    return CurveTable(varied, saturation, rows, mu_fn)


def write_csv(table: CurveTable, path: Path, overwrite: bool = False) -> Path:
    """The curve as CSV (header: COLUMNS; a comment line first with the units and the saturation creepage),
    through a temporary file renamed into place (cases.results.writing); an existing file only with `overwrite`."""
    path = Path(path)
    if path.exists() and not overwrite:
        raise OutputExistsError(f"{path}: exists; rollcontact does not replace a file unless asked: "
                                f"{'add' if on_command_line() else 'pass'} {flag('overwrite')}")
    unit = "1/mm" if table.varied == "phi" else "-"
    text = io.StringIO(newline="")
    text.write(f"# creep-force curve over {table.varied} ({unit}); saturation creepage {table.saturation:.6g} "
               f"{unit}; mu Fn = {table.mu_fn:.6g} N; F_x, F_y (N), M_z (N mm) on the rolling sphere (Kalker)\n")
    writer = csv.DictWriter(text, fieldnames=COLUMNS)
    writer.writeheader()
    for row in table.rows:
        writer.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in row.items()})
    return write_text(path, text.getvalue(), "creep curve")


@dataclass
class CreepCurve:
    """What `creep_curve_files` computed and wrote: the curve (`table`: rows, saturation creepage), the files
    (`paths`: CSV, PNG, PDF), the creepage varied (`of`) and the time (`seconds`, wall). `report()` is what
    `rollcontact creep-curve` prints."""
    table: CurveTable
    paths: list
    of: str
    seconds: float

    def report(self) -> str:
        sweeps = sum(r["sweeps"] for r in self.table.rows)
        unit = " 1/mm" if self.of == "phi" else ""
        return "\n".join([f"{len(self.table.rows)} creepages of {self.of} in {self.seconds:.2f} s ({sweeps} sweeps); "
                          f"saturation creepage {self.table.saturation:.6g}{unit}"]
                         + [str(Path(p).resolve()) for p in self.paths])

    def __repr__(self) -> str:
        return (f"CreepCurve(of={self.of!r}, points={len(self.table.rows)}, saturation={self.table.saturation:.6g}, "
                f"files={len(self.paths)})")


def creep_curve_files(scene: Scene, of: str = "xi", points: int = 20, max_ratio: float = 4.0, output="creep",
                      overwrite: bool = False) -> CreepCurve:
    """The creep-force curve of the steady [rolling] scene over `of` at `points` creepages geometrically from 0.02 to
    `max_ratio` times the saturation creepage, written to `output`/<scene>_creep_<of>.csv and .png, .pdf (all of
    them or none). Refused before any work (InputError naming the argument): a scene without [rolling] or with
    mode = 'transient' (the curve is of the steady state), points < 2, max_ratio outside (0, 100], a file that exists
    (unless `overwrite`)."""
    import time
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
    out = Path(output)
    stem = f"{scene.name}_creep_{of}"
    targets = [out / f"{stem}{ext}" for ext in (".csv", ".png", ".pdf")]
    existing = [t for t in targets if t.exists()]
    if existing and not overwrite:
        raise OutputExistsError(f"{existing[0]}: exists; rollcontact does not replace a file unless asked: "
                                f"{'add' if on_command_line() else 'pass'} {flag('overwrite')}, or give another "
                                f"folder with {arg('output')}")
    output_folder(out)
    t0 = time.perf_counter()
    table = compute_curve(scene, of, np.geomspace(0.02, max_ratio, points))
    seconds = time.perf_counter() - t0
    with all_or_none():
        figures = plot_curve(table, out, stem, overwrite=overwrite)
        paths = [write_csv(table, targets[0], overwrite=overwrite)] + figures
    return CreepCurve(table, paths, of, seconds)

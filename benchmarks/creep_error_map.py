"""The force error map of the fast models (FASTSIM, FaStrip) against the exact steady theory, and its held-out set
(solver/fastsim/error_map.py reads the map; docs/creep_fidelity.md).

    .venv/bin/python benchmarks/creep_error_map.py [-o DIR] [--quick] [--elements 41]
        # writes DIR/error_map.json and DIR/held_out.json (default DIR: results/creep_error_map)
    .venv/bin/python benchmarks/creep_error_map.py --map-out solver/fastsim/error_map.json \\
        --held-out-out tests/solver/data/fastsim_held_out.json     # refresh the committed files (~45 min)
    .venv/bin/python benchmarks/creep_error_map.py --held-out-only --seed N --held-out-out FILE   # a new draw

For each Poisson ratio nu and a/b of the map, identical bodies (G = 1 MPa, K = 0) with Hertz's pressure on the
ellipse's cells (solver.creep.ellipse_grid, `--elements` across each axis), mu = 0.3: along each direction of the
normalised creepage (theta from the +phi axis, alpha in the xi-eta plane; solver.fastsim.error_map) the creepage
grows through the map's t values; the exact steady solver (solver.creep.creep_curve, warm-started, tol 1e-7) and
both fast models solve each point on the same grid and pressure, and the map stores |F - F_exact| / |F_exact| per
model, |F_exact| / (mu Fn), and the median CPU time per case of each model (the exact solver's from cold solves).
The resolution margin: at a/b = 0.2, 1, 5 (nu = 0.28) and a coarser grid of directions and t, each model's error is
measured again at 81 elements across; twice its largest growth from 41 to 81 (per theta and t) is stored and added
to the predictions (both models converge at first order in the element size, most slowly with spin: the continuum
lies about twice that growth beyond). The held-out set: 100 scenes drawn at random (seeded; --seed) inside the map's
ranges but off its nodes, each solved cold by the exact solver and both fast models at 41 elements across, and 40
more at 81; tests/cases/test_fidelity_auto.py checks on them that the map's prediction never lets `auto` choose a
model whose measured error exceeds the request.
"""
from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import platform
from pathlib import Path
import statistics
import sys
import time

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from rollcontact.bem import MaterialPair  # noqa: E402
from rollcontact.solver.creep import (SteadyParams, SteadyRolling, creep_curve, ellipse_grid,  # noqa: E402
                                      hertz_pressure, kalker_coefficients, solve_steady)
from rollcontact.solver.fastsim import kalker_flexibilities, solve_fastrip, solve_fastsim  # noqa: E402
from rollcontact.solver.fastsim.error_map import creep_coordinates  # noqa: E402

MU = 0.3
MODELS = {"fastsim": solve_fastsim, "fastrip": solve_fastrip}
FULL = dict(nu=(0.0, 0.28, 0.5), ratio=(0.2, 0.35, 0.5, 1.0, 2.0, 3.0, 5.0),
            theta=(0, 15, 30, 45, 60, 75, 90, 105, 120, 135, 150, 165, 180), alpha=(0, 22.5, 45, 67.5, 90),
            t=(0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 1.0, 1.4, 2.0, 3.0, 5.0, 10.0, 20.0), held_out=100,
            margin=dict(ratio=(0.2, 1.0, 5.0), theta=(0, 30, 60, 90, 120, 150, 180), alpha=(0, 45, 90),
                        t=(0.1, 0.35, 1.0, 3.0, 10.0), fine=81), held_out_fine=40)
QUICK = dict(nu=(0.28,), ratio=(0.5, 2.0), theta=(0, 90, 180), alpha=(0, 90), t=(0.1, 0.5, 1.0, 3.0), held_out=4,
             margin=dict(ratio=(1.0,), theta=(0, 90, 180), alpha=(0,), t=(0.35, 3.0), fine=61), held_out_fine=2)
PARAMS = SteadyParams(tol=1e-7, max_sweeps=5000)


class Ellipse:
    """The problem of one (nu, a/b): grid, pressure, exact solver set-up, flexibilities and saturation creepages."""

    def __init__(self, nu, ratio, elements):
        a, b = math.sqrt(ratio), 1.0 / math.sqrt(ratio)
        self.grid = ellipse_grid(a, b, elements)
        self.pressure = hertz_pressure(self.grid, a, b, 1.0)
        pair = MaterialPair.from_moduli(2 * (1 + nu), nu, 2 * (1 + nu), nu)      # G = 1 MPa, K = 0
        self.problem = SteadyRolling(self.grid, pair)
        self.flex = kalker_flexibilities(a, b, 1.0, nu)
        c11, c22, c23 = kalker_coefficients(ratio, nu)
        self.mu_fn = MU * self.pressure.sum() * self.grid.cell_area
        self.unit = np.array([self.mu_fn / c11, self.mu_fn / c22, self.mu_fn / c23])   # c = 1

    def creepages(self, direction, t):
        """(xi, eta, phi) at normalised magnitude t along the unit direction (xi/xi*, eta/eta*, phi/phi*)."""
        return t * np.asarray(direction) * self.unit

    def fast(self, model, creep):
        t0 = time.process_time()
        res = MODELS[model](self.grid, self.pressure, MU, *creep, flexibilities=self.flex)
        return np.array(res.force), time.process_time() - t0


def unit_vector(theta, alpha):
    th, al = math.radians(theta), math.radians(alpha)
    return (math.sin(th) * math.cos(al), math.sin(th) * math.sin(al), math.cos(th))


def relative_error(force, exact):
    return float(np.hypot(*(force - exact)) / max(np.hypot(*exact), 1e-300))


def build_map(config, elements, log=print):
    """The map's arrays: errors[model] and exact |F|/(mu Fn) of shape (nu, ratio, theta, alpha, t), and the CPU
    seconds per case (median; the exact solver's from one cold solve per direction at t = 0.5)."""
    shape = tuple(len(config[k]) for k in ("nu", "ratio", "theta", "alpha", "t"))
    errors = {m: np.full(shape, np.nan) for m in MODELS}
    exact_force = np.full(shape, np.nan)
    seconds = {m: [] for m in MODELS} | {"bem": []}
    for i, nu in enumerate(config["nu"]):
        for j, ratio in enumerate(config["ratio"]):
            case = Ellipse(nu, ratio, elements)
            t0 = time.perf_counter()
            for k, theta in enumerate(config["theta"]):
                for m, alpha in enumerate(config["alpha"]):
                    if theta in (0, 180) and m > 0:           # the poles have no alpha: copy the first
                        for model in MODELS:
                            errors[model][i, j, k, m] = errors[model][i, j, k, 0]
                        exact_force[i, j, k, m] = exact_force[i, j, k, 0]
                        continue
                    direction = unit_vector(theta, alpha)
                    creeps = np.array([case.creepages(direction, t) for t in config["t"]])
                    curve = creep_curve(case.problem, case.pressure, MU, creeps, params=PARAMS)
                    for n, creep in enumerate(creeps):
                        exact = curve.force[n]
                        exact_force[i, j, k, m, n] = np.hypot(*exact) / case.mu_fn
                        for model in MODELS:
                            force, sec = case.fast(model, creep)
                            errors[model][i, j, k, m, n] = relative_error(force, exact)
                            seconds[model].append(sec)
                    if nu == config["nu"][len(config["nu"]) // 2]:
                        c0 = time.process_time()
                        solve_steady(case.problem, case.pressure, MU, *case.creepages(direction, 0.5), params=PARAMS)
                        seconds["bem"].append(time.process_time() - c0)
            log(f"nu {nu} a/b {ratio}: {time.perf_counter() - t0:.1f} s; largest error fastsim "
                f"{np.nanmax(errors['fastsim'][i, j]):.3f}, fastrip {np.nanmax(errors['fastrip'][i, j]):.3f}")
    return errors, exact_force, {m: statistics.median(v) for m, v in seconds.items() if v}


def resolution_margin(config, elements, log=print):
    """How much a model's error grows from `elements` to `fine` elements across (nu = 0.28, the largest increase over
    the margin grid's a/b and alpha, per theta and t), doubled: both discretisations converge at first order in the
    element size, so the continuum's error lies about twice the 41 -> 81 change beyond the 41-element one. The map's
    predictions add it (solver.fastsim.error_map)."""
    grid_cfg = config["margin"]
    out = {m: np.zeros((len(grid_cfg["theta"]), len(grid_cfg["t"]))) for m in MODELS}
    nu = 0.28
    for ratio in grid_cfg["ratio"]:
        cases = {n: Ellipse(nu, ratio, n) for n in (elements, grid_cfg["fine"])}
        for k, theta in enumerate(grid_cfg["theta"]):
            for alpha in grid_cfg["alpha"]:
                direction = unit_vector(theta, alpha)
                for n_t, t in enumerate(grid_cfg["t"]):
                    err = {}
                    for n, case in cases.items():
                        creep = case.creepages(direction, t)
                        exact = np.array(solve_steady(case.problem, case.pressure, MU, *creep, params=PARAMS).force)
                        err[n] = {m: relative_error(case.fast(m, creep)[0], exact) for m in MODELS}
                    for m in MODELS:
                        grow = 2.0 * max(0.0, err[grid_cfg["fine"]][m] - err[elements][m])
                        out[m][k, n_t] = max(out[m][k, n_t], grow)
        log(f"resolution margin a/b {ratio}: largest fastsim {out['fastsim'].max():.4f}, fastrip "
            f"{out['fastrip'].max():.4f}")
    return out


def held_out(config, elements, count, seed, log=print):
    """`count` scenes at random inside the map's ranges (nu uniform, a/b log-uniform, direction uniform on the
    reduced sphere, t log-uniform over the map's t range), each solved cold: their coordinates and errors."""
    rng = np.random.default_rng(seed)
    rows = []
    lo_r, hi_r = math.log(min(config["ratio"])), math.log(max(config["ratio"]))
    lo_t, hi_t = math.log(min(config["t"])), math.log(max(config["t"]))
    for _ in range(count):
        nu = float(rng.uniform(min(config["nu"]), max(config["nu"])))
        ratio = float(math.exp(rng.uniform(lo_r, hi_r)))
        v = rng.normal(size=3)
        v = np.abs(v[:2]).tolist() + [float(v[2])]
        v = np.array(v) / np.linalg.norm(v)
        t = float(math.exp(rng.uniform(lo_t, hi_t)))
        case = Ellipse(nu, ratio, elements)
        creep = case.creepages(v, t)
        exact = np.array(solve_steady(case.problem, case.pressure, MU, *creep, params=PARAMS).force)
        theta, alpha, tt = creep_coordinates(*(t * v))
        row = dict(nu=nu, ratio=ratio, xi_hat=float(t * v[0]), eta_hat=float(t * v[1]), phi_hat=float(t * v[2]),
                   theta=theta, alpha=alpha, t=tt, exact_force=float(np.hypot(*exact) / case.mu_fn))
        for model in MODELS:
            row[model] = relative_error(case.fast(model, creep)[0], exact)
        rows.append(row)
        log(f"held-out {len(rows)}/{count}: nu {nu:.3f} a/b {ratio:.3f} theta {theta:.0f} alpha {alpha:.0f} "
            f"t {t:.3g}: fastsim {row['fastsim']:.3f}, fastrip {row['fastrip']:.3f}")
    return rows


def _rounded(a):
    return np.vectorize(lambda v: float(f"{v:.4g}") if math.isfinite(v) else None, otypes=[object])(a).tolist()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--output", default="results/creep_error_map", help="folder for both JSON files")
    parser.add_argument("--map-out", help="write the map here instead (e.g. solver/fastsim/error_map.json)")
    parser.add_argument("--held-out-out", help="write the held-out set here instead")
    parser.add_argument("--quick", action="store_true", help="a small map and 4 held-out scenes (seconds)")
    parser.add_argument("--elements", type=int, default=41, help="elements across each axis (default 41)")
    parser.add_argument("--held-out-only", action="store_true", help="measure the held-out set alone (no map)")
    parser.add_argument("--seed", type=int, default=20261130, help="seed of the held-out draw (and + 1 for the fine one)")
    args = parser.parse_args(argv)
    config = QUICK if args.quick else FULL
    out = Path(args.output)
    map_path = Path(args.map_out) if args.map_out else out / "error_map.json"
    held_path = Path(args.held_out_out) if args.held_out_out else out / "held_out.json"
    load = os.getloadavg()
    start = time.perf_counter()
    if not args.held_out_only:
        errors, exact_force, seconds = build_map(config, args.elements)
        margin = resolution_margin(config, args.elements)
    rows = held_out(config, args.elements, config["held_out"], seed=args.seed)
    fine = config["margin"]["fine"]
    rows_fine = held_out(config, fine, config["held_out_fine"], seed=args.seed + 1)
    info = dict(date=datetime.date.today().isoformat(), machine=platform.machine(), python=platform.python_version(),
                cpu_count=os.cpu_count(), loadavg_before=load, loadavg_after=os.getloadavg(),
                wall_time_s=time.perf_counter() - start, quick=args.quick,
                command="benchmarks/creep_error_map.py" + (" --quick" if args.quick else ""), seed=args.seed)
    outputs = [(held_path, dict(info, elements=args.elements, rows=rows, fine_elements=fine, rows_fine=rows_fine))]
    if not args.held_out_only:
        info.pop("seed")
        data = dict(quantity="|F - F_exact| / |F_exact| of (Fx, Fy) on the same grid and pressure",
                    reference="solver.creep.solve_steady (Kalker's steady theory on the grid), tol 1e-7",
                    setting=f"identical bodies, G = 1 MPa, K = 0; Hertz pressure on {args.elements} elements across "
                            f"each axis of the ellipse (solver.creep.ellipse_grid), c = sqrt(ab) = 1 mm, mu = {MU}",
                    elements=args.elements, models=list(MODELS),
                    axes={k: list(config[k]) for k in ("nu", "ratio", "theta", "alpha", "t")},
                    errors={m: _rounded(e) for m, e in errors.items()}, exact_force=_rounded(exact_force),
                    resolution_margin=dict(elements=[args.elements, fine], theta=list(config["margin"]["theta"]),
                                           t=list(config["margin"]["t"]), ratio=list(config["margin"]["ratio"]),
                                           **{m: _rounded(v) for m, v in margin.items()}),
                    seconds_per_case=seconds, **info)
        outputs.insert(0, (map_path, data))
    for path, payload in outputs:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(payload, indent=None, separators=(",", ":")) + "\n")
        print(path.resolve())
    return 0


if __name__ == "__main__":
    sys.exit(main())

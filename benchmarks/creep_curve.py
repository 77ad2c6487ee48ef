"""Speed of a creep-force curve of the steady rolling solver (solver.creep; docs/theory.md §7.3, §11.5).

    .venv/bin/python benchmarks/creep_curve.py [--n 59 89 119] [--repeats 3] [-o DIR]

Steel on steel (E = 210 GPa, nu = 0.28), Hertz ellipse a = 6 mm (rolling direction), b = 4 mm, Fn = 50 kN,
mu = 0.3, n elements across each axis (`ellipse_grid`: (n + 2) x n cells). Measured per grid: the set-up
(dense kernels and row spectra), one steady case from zero traction at xi = 0.5 xi* (xi* = mu Fn/(G c^2 C11),
CONTACT's normalising creepage), and a whole curve of 20 longitudinal creepages xi = xi* geomspace(0.02, 4)
from the linear range to full sliding, each solution the warm start of the next (creep_curve), with the
solver's default tolerance. Wall time and CPU time (process_time: the machine is shared, wall time includes
waiting for a core), medians of --repeats, after a warm-up solve (numba compiled, cached on disk); the floor is
one FFT tangential product (bem HalfSpaceOperator.tangential) on the same grid, measured in the same run.
Also the curve's largest difference to Vermeulen-Johnson's saturation model. JSON to
DIR/creep_curve.json (default results/benchmarks/).
"""
import math
import statistics
import time

import numpy as np

import _record
from rollcontact.bem import HalfSpaceOperator, MaterialPair
from rollcontact.solver.creep import (SteadyRolling, creep_curve, ellipse_grid, hertz_pressure,
                                      kalker_coefficients, saturation_creepage, solve_steady, vermeulen_johnson)

A, B, FN, MU, NU = 6.0, 4.0, 50e3, 0.3, 0.28
MATS = MaterialPair.from_moduli(210e3, NU, 210e3, NU)


def timed(fn, repeats):
    walls, cpus, out = [], [], None
    for _ in range(repeats):
        w, c = time.perf_counter(), time.process_time()
        out = fn()
        walls.append(time.perf_counter() - w)
        cpus.append(time.process_time() - c)
    return out, statistics.median(walls), statistics.median(cpus)


def run(n, repeats):
    grid = ellipse_grid(A, B, n)
    pressure = hertz_pressure(grid, A, B, FN)
    problem, t_setup, _ = timed(lambda: SteadyRolling(grid, MATS), 1)
    c = math.sqrt(A * B)
    xi_star = saturation_creepage(MATS.G, c, kalker_coefficients(A / B, NU)[0], MU, FN)
    solve_steady(problem, pressure, MU, 0.5 * xi_star)  # warm-up: numba compiled or loaded from its cache
    single, t_single, c_single = timed(lambda: solve_steady(problem, pressure, MU, 0.5 * xi_star), repeats)
    creep = np.zeros((20, 3))
    creep[:, 0] = xi_star * np.geomspace(0.02, 4.0, 20)
    curve, t_curve, c_curve = timed(lambda: creep_curve(problem, pressure, MU, creep), repeats)
    op = HalfSpaceOperator(grid, MATS, threads=1)
    tx, ty = np.random.default_rng(0).random((2,) + grid.shape)
    out = np.zeros((2,) + grid.shape)
    _, t_floor, _ = timed(lambda: op.tangential(tx, ty, out=out), 50)
    ratio = -curve.force[:, 0] / (MU * FN)
    vj = vermeulen_johnson(creep[:, 0] / xi_star)
    row = {"n": n, "grid": list(grid.shape), "contact_cells": int((pressure > 0).sum()),
           "setup_s": t_setup, "single_wall_s": t_single, "single_cpu_s": c_single, "single_sweeps": single.sweeps,
           "curve_wall_s": t_curve, "curve_cpu_s": c_curve, "curve_sweeps": curve.sweeps.tolist(),
           "floor_product_s": t_floor, "curve_over_floor": c_curve / t_floor,
           "Fx_over_muFn": ratio.tolist(), "vermeulen_johnson": vj.tolist(),
           "max_diff_vermeulen_johnson": float(np.max(np.abs(ratio - vj)))}
    print(f"n = {n:3d} ({grid.ny} x {grid.nx}, {row['contact_cells']} in contact): set-up {t_setup:.3f} s; single "
          f"case {t_single:.3f} s wall / {c_single:.3f} s CPU ({single.sweeps} sweeps); curve of 20: {t_curve:.2f} s "
          f"wall / {c_curve:.2f} s CPU ({curve.sweeps.sum()} sweeps, {curve.sweeps.min()}-{curve.sweeps.max()} "
          f"per point); floor {t_floor * 1e3:.3f} ms -> curve = {c_curve / t_floor:.0f} floors; max |F/muFn - VJ| "
          f"{row['max_diff_vermeulen_johnson']:.3f}", flush=True)
    return row


def main(argv=None):
    ap = _record.parser(__doc__)
    ap.add_argument("--n", type=int, nargs="+", default=[59, 89, 119], help="elements across each axis")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    rows = [run(n, args.repeats if n <= 60 else 1) for n in args.n]
    _record.write("creep_curve", {"rows": rows}, args.output)


if __name__ == "__main__":
    main()

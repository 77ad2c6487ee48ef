"""Benchmark of the transient tangential solver on the seed's Cattaneo scene (docs/theory.md §5, §7.2).

    .venv/bin/python benchmarks/tangential_cattaneo.py [--repeats 5] [-o DIR]

For dx = 0.2, 0.1, 0.05 mm (CONTACT's grids: 55^2, 109^2, 217^2) and 0.0211 mm (511^2): wall time (median of
--repeats, single FFTW thread, after a warm-up solve so that numba compilation and FFTW planning are excluded),
op.tangential products ("iterations"; also the CG search directions, "cg_steps", the unit of TangCG's
iteration counts) cold (f_t = 0.5 from zero traction) and warm (f_t 0.5 -> 0.52; and the pressure shifted by
one cell in y at f_t = 0.5), the errors of the stick radius (along y = 0) and of the shift against Mindlin, the
time of one op.tangential product measured
in the same run, and the shift error near the traction bound (f_t = 0.9 .. 0.999). Pressure: solve_normal.
JSON to DIR/tangential_cattaneo.json (default results/benchmarks/). Timings are medians on a shared 2-core machine: noisy.
"""
import statistics
import time

import numpy as np

import _record
from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere
from rollcontact.solver.normal.normcg import solve_normal
from rollcontact.solver.tangential.shift import solve_tangential

R, FN, MU = 40.0, 21.19, 0.93
MATS = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
HERTZ = HertzSphere(R, MATS.E_star, FN)
MINDLIN = CattaneoMindlin(HERTZ, MU, MATS.G_star)
CONTACT = {0.2: (103, 0.11), 0.1: (127, 0.76), 0.05: (177, 3.5)}  # TangCG iterations, CPU s (the issue)


def median_time(fn, repeats):
    out, times = None, []
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return out, statistics.median(times)


def cattaneo_scene(dx):
    """Grid (contact + 0.6 mm), one-thread operator, mesh, and the bounds g = mu p of the Hertz contact and of
    the same contact moved by one cell in y (MPa)."""
    a = HERTZ.a
    grid = Grid.covering(-a - 0.6, a + 0.6, -a - 0.6, a + 0.6, dx, dx)
    op = HalfSpaceOperator(grid, MATS, threads=1)
    X, Y = grid.mesh()
    normal = solve_normal(op, (X ** 2 + Y ** 2) / (2 * R), force=FN)
    shifted = solve_normal(op, (X ** 2 + (Y - dx) ** 2) / (2 * R), force=FN, initial=normal.pressure)
    return grid, op, X, Y, MU * normal.pressure, MU * shifted.pressure


def run(dx, repeats, near_bound):
    grid, op, X, Y, g, g2 = cattaneo_scene(dx)
    zero = np.zeros((2,) + grid.shape)
    F = lambda f: (f * MU * FN, 0.0)
    tx, ty = np.random.default_rng(0).random((2,) + grid.shape)
    _, t_pair = median_time(lambda: op.tangential(tx, ty, out=zero.copy()), max(repeats, 20))
    _, t_inv = median_time(lambda: op.tangential_inverse(tx, ty, out=zero.copy()), max(repeats, 20))
    solve_tangential(op, g, zero, force=F(0.5))  # warm-up (compilation, caches)
    cold, t_cold = median_time(lambda: solve_tangential(op, g, zero, force=F(0.5)), repeats)
    warm, t_warm = median_time(lambda: solve_tangential(op, g, cold.traction, force=F(0.52)), repeats)
    moved, t_moved = median_time(lambda: solve_tangential(op, g2, cold.traction, force=F(0.5)), repeats)
    stick_row = (cold.region == 1) & np.isclose(Y, 0.0)
    c_num = np.abs(X[stick_row]).max() + dx / 2
    row = {
        "dx_mm": dx, "grid": list(grid.shape), "elements": grid.size,
        "pair_time_s": t_pair, "inverse_time_s": t_inv,
        "cold_iterations": cold.iterations, "cold_time_s": t_cold,
        "cold_time_per_iteration_in_pairs": t_cold / cold.iterations / t_pair,
        "warm_load_iterations": warm.iterations, "warm_load_time_s": t_warm,
        "warm_profile_iterations": moved.iterations, "warm_profile_time_s": t_moved,
        "cg_steps": {"cold": cold.steps, "warm_load": warm.steps, "warm_profile": moved.steps},
        "stick_radius_mm": c_num, "stick_radius_error_mm": c_num - MINDLIN.stick_radius(0.5),
        "shift_error_rel": cold.shift_increment[0] / MINDLIN.shift(0.5) - 1,
        "warm_shift_error_rel": (cold.shift_increment[0] + warm.shift_increment[0]) / MINDLIN.shift(0.52) - 1,
        "contact_tangcg": ({"iterations": CONTACT[dx][0], "cpu_s": CONTACT[dx][1]} if dx in CONTACT else None),
        "near_bound": {},
    }
    for f in near_bound:
        try:
            r, t = median_time(lambda: solve_tangential(op, g, zero, force=F(f)), 1)
            row["near_bound"][str(f)] = {"iterations": r.iterations, "cg_steps": r.steps, "time_s": t,
                                         "shift_error_rel": r.shift_increment[0] / MINDLIN.shift(f) - 1,
                                         "stick_elements": int((r.region == 1).sum())}
        except Exception as exc:  # report, do not hide
            row["near_bound"][str(f)] = {"error": f"{type(exc).__name__}: {exc}"}
    return row


def main():
    ap = _record.parser(__doc__)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--dx", type=float, nargs="*", default=[0.2, 0.1, 0.05, 0.0211])
    args = ap.parse_args()
    rows = []
    for dx in args.dx:
        row = run(dx, args.repeats, (0.9, 0.95, 0.99, 0.999))
        rows.append(row)
        print(f"dx={dx}: grid {row['grid']}, cold {row['cold_iterations']} it {row['cold_time_s']:.3f} s, "
              f"warm {row['warm_load_iterations']} / {row['warm_profile_iterations']} it "
              f"(CG steps {row['cg_steps']['cold']}; "
              f"{row['cg_steps']['warm_load']} / {row['cg_steps']['warm_profile']}), "
              f"pair {row['pair_time_s'] * 1e3:.2f} ms, per-it {row['cold_time_per_iteration_in_pairs']:.2f} pairs, "
              f"dc {row['stick_radius_error_mm']:+.3f} mm, dU {row['shift_error_rel']:+.3%}", flush=True)
        for f, v in row["near_bound"].items():
            print(f"    f_t={f}: {v}", flush=True)
    _record.write("tangential_cattaneo", {"benchmark": "tangential_cattaneo", "rows": rows,
                                          "note": "wall times are medians, single FFTW thread"}, args.output)


if __name__ == "__main__":
    main()

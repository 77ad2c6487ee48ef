"""Accuracy of the steady rolling solver in the linear limit against Kalker's table (docs/theory.md §7.3).

    .venv/bin/python benchmarks/creep_linear.py [--quick] [--n 21 41 81] [-o DIR]

For a/b = 0.5, 1, 2 and nu = 0, 0.25, 0.5 (identical bodies, G = 1 MPa: K = 0), on the Hertzian ellipse with n
elements across each axis (`solver.creep.ellipse_grid`, cells whose centre is inside the ellipse), no friction
limit (full adhesion): C11 = -Fx/(G c^2 xi), C22 = -Fy/(G c^2 eta), C23 = -Fy/(G c^3 phi) and
C33 = -Mz/(G c^4 phi), c = sqrt(a b), against the table (C11-C23, CONTACT's interpolation) and the published C33
values. Also the error after correcting the discrete contact area: c^2 -> (cells in contact) dA / pi.
Prints a table and writes DIR/creep_linear.json (default results/benchmarks/; errors in %, sweeps, seconds per
solve).
"""
import math
import time

import _record
from rollcontact.bem import MaterialPair
from rollcontact.solver.creep import (SteadyParams, SteadyRolling, ellipse_grid, hertz_pressure,
                                      kalker_coefficients, solve_steady)
from rollcontact.solver.creep.kalker import C33_PUBLISHED

RATIOS = (0.5, 1.0, 2.0)
NUS = (0.0, 0.25, 0.5)


def coefficients(ratio, nu, n, tol=1e-8):
    """(C11, C22, C23, C33, sweeps, seconds per solve, area ratio) from three steady solves."""
    a, b = math.sqrt(ratio), 1.0 / math.sqrt(ratio)  # c = 1 mm
    mats = MaterialPair.from_moduli(2 * (1 + nu), nu, 2 * (1 + nu), nu)  # G1 = G2 = 1: G = 1, K = 0
    grid = ellipse_grid(a, b, n)
    pressure = hertz_pressure(grid, a, b, 1.0)
    problem = SteadyRolling(grid, mats)
    params = SteadyParams(tol=tol)
    t = time.perf_counter()
    rx = solve_steady(problem, pressure, math.inf, xi=1e-3, params=params)
    ry = solve_steady(problem, pressure, math.inf, eta=1e-3, params=params)
    rs = solve_steady(problem, pressure, math.inf, phi=1e-3, params=params)
    seconds = (time.perf_counter() - t) / 3
    area = (pressure > 0).sum() * grid.cell_area / (math.pi * a * b)
    return (-rx.force[0] / 1e-3, -ry.force[1] / 1e-3, -rs.force[1] / 1e-3, -rs.moment / 1e-3,
            max(rx.sweeps, ry.sweeps, rs.sweeps), seconds, area)


def main(argv=None):
    ap = _record.parser(__doc__)
    ap.add_argument("--n", type=int, nargs="+", default=[21, 41, 81], help="elements across each axis (odd)")
    ap.add_argument("--quick", action="store_true", help="the circle with nu = 0.25 only")
    args = ap.parse_args(argv)
    rows = []
    for ratio in (1.0,) if args.quick else RATIOS:
        for nu in (0.25,) if args.quick else NUS:
            table = kalker_coefficients(ratio, nu)
            for n in args.n:
                c11, c22, c23, c33, sweeps, seconds, area = coefficients(ratio, nu, n)
                err = [100 * (v / t - 1) for v, t in zip((c11, c22, c23), table)]
                err_area = [100 * (v / area / t - 1) for v, t in zip((c11, c22), table[:2])]
                row = {"a_over_b": ratio, "nu": nu, "n": n, "C11": c11, "C22": c22, "C23": c23, "C33": c33,
                       "table": table, "C33_published": C33_PUBLISHED[(ratio, nu)], "error_pct": err,
                       "error_area_corrected_pct": err_area, "area_ratio": area, "sweeps": sweeps,
                       "seconds_per_solve": seconds}
                rows.append(row)
                print(f"a/b={ratio:4.2f} nu={nu:4.2f} n={n:3d}  C11 {c11:6.3f} ({err[0]:+5.2f}%)  C22 {c22:6.3f} "
                      f"({err[1]:+5.2f}%)  C23 {c23:6.3f} ({err[2]:+5.2f}%)  C33 {c33:6.3f} (pub "
                      f"{C33_PUBLISHED[(ratio, nu)]:5.3f}, {100 * (c33 / C33_PUBLISHED[(ratio, nu)] - 1):+5.1f}%)  "
                      f"area {100 * (area - 1):+5.2f}%  {sweeps} sweeps {seconds:.2f} s", flush=True)
    _record.write("creep_linear", {"rows": rows}, args.output)


if __name__ == "__main__":
    main()

"""Cost of one coupled step (beta != 0): the nested normal/tangential (Panagiotopoulos) loop, per outer iteration.

    .venv/bin/python benchmarks/coupled_step.py [--repeats 3] [-o DIR]

Steel sphere (E = 210e3 MPa, nu = 0.3, R = 10 mm) on aluminium (E = 70e3 MPa, nu = 0.33; Dundurs beta = -0.117),
Fn = 500 N (a = 0.40 mm), mu = 0.3, one step from the unloaded state to Ft = f_t mu Fn along x (f_t = 0.3, 0.6,
0.9) with `solver.rolling.coupled.solve_coupled_step` at its default tolerances, on grids of a/dx = 20 and 40 (contact
+ 20 % margin, 49^2 and 97^2). For each case: outer iterations, the normal iterations (`op.normal` products) and
the tangential products (`op.tangential` calls, re-synchronisations included) of every outer iteration, their
totals, the wall time (median of --repeats, one FFTW thread, after a warm-up) and the rigid shift U_x.
The counts are deterministic; the times are from a shared 2-core machine (noisy).
JSON to DIR/coupled_step.json (default results/benchmarks/).
"""
import statistics
import time

import numpy as np

from rollcontact.solver.rolling import coupled
from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.solver.analytic import HertzSphere

import _record

R, FN, MU = 10.0, 500.0, 0.3
MATS = MaterialPair.from_moduli(210e3, 0.3, 70e3, 0.33)


class Counts:
    """Iterations of every inner solve of solve_coupled_step, read from the results the solvers return."""

    def __init__(self):
        self.normal, self.tangential = [], []
        self._n, self._t = coupled.solve_normal, coupled.solve_tangential

    def __enter__(self):
        def normal(*a, **k):
            r = self._n(*a, **k)
            self.normal.append(r.iterations)
            return r

        def tangential(*a, **k):
            r = self._t(*a, **k)
            self.tangential.append(r.iterations)
            return r

        coupled.solve_normal, coupled.solve_tangential = normal, tangential
        return self

    def __exit__(self, *exc):
        coupled.solve_normal, coupled.solve_tangential = self._n, self._t


def case(op, h, f_t, repeats):
    zero = np.zeros((2,) + op.grid.shape)
    F = (f_t * MU * FN, 0.0)
    step = lambda: coupled.solve_coupled_step(op, h, FN, F, None, zero, mu=MU)
    step()  # warm-up: numba loading, FFTW planning
    with Counts() as counts:
        _, tang, outer = step()
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        step()
        times.append(time.perf_counter() - t)
    return dict(f_t=f_t, outer=outer, normal_iterations=counts.normal, tangential_products=counts.tangential,
                normal_total=sum(counts.normal), tangential_total=sum(counts.tangential),
                wall_s=statistics.median(times), U_x_mm=float(tang.shift_increment[0]))


def main():
    ap = _record.parser(__doc__)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    a = HertzSphere(R, MATS.E_star, FN).a
    rows = []
    for per_a in (20, 40):
        dx = a / per_a
        grid = Grid.covering(-1.2 * a, 1.2 * a, -1.2 * a, 1.2 * a, dx, dx)
        op = HalfSpaceOperator(grid, MATS, threads=1)
        X, Y = grid.mesh()
        h = (X ** 2 + Y ** 2) / (2 * R)
        for f_t in (0.3, 0.6, 0.9):
            row = dict(grid=list(grid.shape), dx_mm=dx, **case(op, h, f_t, args.repeats))
            rows.append(row)
            print(f"{grid.shape[0]}^2 f_t={f_t}: outer {row['outer']}, normal {row['normal_iterations']} "
                  f"(sum {row['normal_total']}), tangential {row['tangential_products']} "
                  f"(sum {row['tangential_total']}), {row['wall_s']:.3f} s, U_x {row['U_x_mm']:.8e} mm", flush=True)
    _record.write("coupled_step", dict(beta=MATS.beta, a_mm=a, rows=rows), args.output)


if __name__ == "__main__":
    main()

"""Benchmark of the normal solver (solver/normal/normcg.py, NormCG) on the Hertz sphere of the seed's scene.

Scene (docs/theory.md §7.1): R = 40 mm, E1 = 206e3 MPa, nu1 = 0.3, E2 = 4.35 MPa, nu2 = 0.5, Fn = 21.19 N
(a = 4.7857 mm, d = 0.572572 mm, p0 = 0.441756 MPa). Square grids of n^2 cells with dx chosen so that
the contact diameter fills 65 % of the grid width, plus the paper's own grid (dx = 0.2 mm covering
1.25 a). For each grid:

* cold solve (default Hertz-shaped start) and a solve from a uniform pressure (an uninformed start);
* warm solve: the sphere centre moved by one cell along x, started from the unshifted solution;
* wall times are medians of `--repeat` runs (2-core machine shared with other jobs: timings are noisy);
* `pair`: median time of one `op.normal` (one padded forward + inverse FFT), timed before every solve run,
  `inv`: one `op.normal_inverse`; `t/it / pair` = solve time / iterations / pair time (the whole solve,
  including the initial A p and any extra A p recomputations after large active-set changes, whose
  number is reported as `extra`);
* errors against Hertz: approach, peak pressure, contact area (cells with p > 0, docs/theory.md P11).

Usage: .venv/bin/python benchmarks/normal_hertz.py [--quick] [--repeat N] [--sizes 64 128 ...] [-o DIR]
Writes DIR/normal_hertz.json (default results/benchmarks/; the committed one: -o benchmarks/results) and prints a
Markdown table.
"""
import math
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

import _record  # noqa: E402

from rollcontact.bem.grid import Grid  # noqa: E402
from rollcontact.bem.materials import MaterialPair  # noqa: E402
from rollcontact.bem.operator import HalfSpaceOperator  # noqa: E402
from rollcontact.solver.analytic import HertzSphere  # noqa: E402
from rollcontact.solver.normal.normcg import NormalParams, solve_normal  # noqa: E402

MATERIALS = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
R, FN = 40.0, 21.19
HERTZ = HertzSphere(R, MATERIALS.E_star, FN)
FILL = 0.65


class CountingOperator:
    """Delegates to a HalfSpaceOperator and counts the convolutions (op.normal calls)."""

    def __init__(self, op):
        self._op = op
        self.normal_calls = 0

    def __getattr__(self, name):
        return getattr(self._op, name)

    def normal(self, pressure, out=None):
        self.normal_calls += 1
        return self._op.normal(pressure, out=out)


def median_time(fn, repeat, pair=None, pair_samples=None):
    """Median wall time of fn() over `repeat` runs; if given, one `pair()` is timed before each run
    (interleaved, so the pair time sees the same machine load as the solves)."""
    times, result = [], None
    for _ in range(repeat):
        if pair is not None:
            t0 = time.perf_counter()
            pair()
            pair_samples.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), result


def run_grid(label, grid, repeat, params):
    t0 = time.perf_counter()
    op = HalfSpaceOperator(grid, MATERIALS)
    setup = time.perf_counter() - t0
    X, Y = grid.mesh()
    h = (X ** 2 + Y ** 2) / (2.0 * R)
    h_shift = ((X - grid.dx) ** 2 + Y ** 2) / (2.0 * R)
    field = np.random.default_rng(1).random(grid.shape)
    work = np.empty(grid.shape)
    solve_normal(op, h, force=FN, params=params)            # numba cache load, kernel cache
    inv, _ = median_time(lambda: op.normal_inverse(field, out=work), max(5, repeat))
    samples = []
    timed_pair = dict(pair=lambda: op.normal(field, out=work), pair_samples=samples)

    counting = CountingOperator(op)
    t_cold, cold = median_time(lambda: solve_normal(counting, h, force=FN, params=params), repeat,
                               **timed_pair)
    calls_cold = counting.normal_calls // repeat
    uniform = np.ones(grid.shape)
    t_unif, unif = median_time(lambda: solve_normal(op, h, force=FN, initial=uniform, params=params),
                               repeat)
    counting.normal_calls = 0
    t_warm, warm = median_time(
        lambda: solve_normal(counting, h_shift, force=FN, initial=cold.pressure, params=params), repeat,
        **timed_pair)
    calls_warm = counting.normal_calls // repeat
    pair = statistics.median(samples)

    dA = grid.cell_area
    area = np.count_nonzero(cold.contact) * dA
    row = dict(
        label=label, nx=grid.nx, ny=grid.ny, dx=grid.dx, elements=grid.size,
        contact_elements=int(np.count_nonzero(cold.contact)), setup_s=setup,
        pair_s=pair, inverse_s=inv,
        cold_iterations=cold.iterations, cold_s=t_cold, cold_extra_products=calls_cold - cold.iterations,
        cold_per_iteration_over_pair=t_cold / cold.iterations / pair,
        uniform_iterations=unif.iterations, uniform_s=t_unif,
        warm_iterations=warm.iterations, warm_s=t_warm, warm_extra_products=calls_warm - warm.iterations,
        warm_per_iteration_over_pair=t_warm / warm.iterations / pair,
        residual_cold=cold.residual, residual_warm=warm.residual,
        approach_error=cold.approach / HERTZ.approach - 1.0,
        p0_error=cold.pressure.max() / HERTZ.p0 - 1.0,
        area_error=area / (math.pi * HERTZ.a ** 2) - 1.0,
        force_error=cold.force / FN - 1.0,
    )
    return row


def markdown(rows, command):
    head = ("| grid | dx (mm) | contact cells | pair (ms) | inv/pair | cold it | uniform it | warm it "
            "| cold t (ms) | warm t (ms) | cold t/it/pair | warm t/it/pair | extra A p cold/warm "
            "| d err | p0 err | area err |")
    sep = "|" + "---|" * 16
    lines = [f"Command: `{command}`", "", head, sep]
    for r in rows:
        lines.append(
            f"| {r['label']} | {r['dx']:.4f} | {r['contact_elements']} | {1e3 * r['pair_s']:.2f} "
            f"| {r['inverse_s'] / r['pair_s']:.2f} | {r['cold_iterations']} | {r['uniform_iterations']} "
            f"| {r['warm_iterations']} | {1e3 * r['cold_s']:.1f} | {1e3 * r['warm_s']:.1f} "
            f"| {r['cold_per_iteration_over_pair']:.2f} | {r['warm_per_iteration_over_pair']:.2f} "
            f"| {r['cold_extra_products']}/{r['warm_extra_products']} "
            f"| {r['approach_error']:+.1e} | {r['p0_error']:+.1e} | {r['area_error']:+.1e} |")
    return "\n".join(lines)


def main(argv=None):
    parser = _record.parser(__doc__)
    parser.add_argument("--quick", action="store_true", help="sizes 64, 128, 256 and the paper grid, 3 runs")
    parser.add_argument("--repeat", type=int, default=5, help="runs per timing (median), >= 3")
    parser.add_argument("--sizes", type=int, nargs="*", default=None)
    parser.add_argument("--tol", type=float, default=NormalParams().tol)
    args = parser.parse_args(argv)
    sizes = args.sizes or ([64, 128, 256] if args.quick else [64, 128, 256, 512, 1024])
    repeat = 3 if args.quick else max(3, args.repeat)
    params = NormalParams(tol=args.tol)

    rows = []
    half = 1.25 * HERTZ.a
    paper = Grid.covering(-half, half, -half, half, 0.2, 0.2)
    rows.append(run_grid(f"paper {paper.nx}^2", paper, repeat, params))
    print(rows[-1], flush=True)
    for n in sizes:
        dx = 2.0 * HERTZ.a / (FILL * n)
        grid = Grid(n, n, dx, dx, -(n // 2), -(n // 2))
        rows.append(run_grid(f"{n}^2", grid, repeat if n < 1024 else 3, params))
        print(rows[-1], flush=True)

    command = "benchmarks/normal_hertz.py " + " ".join(argv if argv is not None else sys.argv[1:])
    out = dict(benchmark="normal_hertz", command=command.strip(), tol=args.tol, repeat=repeat,
               hertz=dict(a=HERTZ.a, approach=HERTZ.approach, p0=HERTZ.p0), fill=FILL, rows=rows)
    _record.write("normal_hertz", out, args.output)
    print(markdown(rows, command.strip()))


if __name__ == "__main__":
    main()

"""Where a NormCG solve spends its time, in convolution pairs (issue #2's per-iteration cost).

    .venv/bin/python benchmarks/normal_breakdown.py [--n 512] [--repeats 5]

The Hertz sphere of `normal_hertz.py` on an n^2 grid (contact diameter 65 % of the width): `--repeats` cold solves
(Hertz-shaped start) and warm solves (centre moved by one cell, started from the cold solution, product memo
cleared) under cProfile. Every cost is divided by the number of CG iterations and by the time of one
convolution pair (`op.normal`, median of 20, timed in the same run):

* products: `op.normal` calls (one per iteration, plus the initial A p and the exact recomputations after large
  truncations), split into the per-iteration part (= 1) and the extra part;
* preconditioner: `op.normal_inverse`;
* element loops: the numba kernels (direction, step, residual, influence-column corrections);
* rest: set-up, cold start, results, Python.

Prints a Markdown row per start; nothing is written.
"""
import argparse
import cProfile
import pstats
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np  # noqa: E402

from rollcontact.solver.normal import normcg as sn  # noqa: E402
from rollcontact.bem.grid import Grid  # noqa: E402
from rollcontact.bem.operator import HalfSpaceOperator  # noqa: E402
from normal_hertz import FILL, FN, HERTZ, MATERIALS, R  # noqa: E402

KERNELS = ("_direction", "_step", "_residual_and_entries", "_add_columns")


def breakdown(op, solve, repeats):
    """Profile `repeats` calls of solve(); returns (iterations per solve, {part: seconds per solve})."""
    pr = cProfile.Profile()
    iterations = 0
    t0 = time.perf_counter()
    pr.enable()
    for _ in range(repeats):
        iterations += solve().iterations
    pr.disable()
    total = (time.perf_counter() - t0) / repeats
    stats = pstats.Stats(pr).stats
    parts = dict(normal=0.0, normal_inverse=0.0, kernels=0.0)
    calls = 0
    for (path, _, name), (_, ncalls, tottime, cumtime, _) in stats.items():
        if path.endswith("operator.py") and name in ("normal", "normal_inverse"):
            parts[name] += cumtime / repeats
            calls += ncalls if name == "normal" else 0
        elif path.endswith("_normal_kernels.py") and name in KERNELS:
            parts["kernels"] += tottime / repeats
    parts["rest"] = total - sum(parts.values())
    parts["total"] = total
    return iterations / repeats, calls / repeats, parts


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=512)
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    n = args.n
    dx = 2.0 * HERTZ.a / (FILL * n)
    grid = Grid(n, n, dx, dx, -(n // 2), -(n // 2))
    op = HalfSpaceOperator(grid, MATERIALS)
    X, Y = grid.mesh()
    h = (X ** 2 + Y ** 2) / (2.0 * R)
    h_shift = ((X - dx) ** 2 + Y ** 2) / (2.0 * R)
    cold = sn.solve_normal(op, h, force=FN)          # compile, plan, and the warm start's pressure
    field, out = np.random.default_rng(0).random(grid.shape), np.empty(grid.shape)
    pair_times = []
    for _ in range(20):
        t = time.perf_counter()
        op.normal(field, out=out)
        pair_times.append(time.perf_counter() - t)
    pair = statistics.median(pair_times)

    def warm():
        sn._memo.clear()
        return sn.solve_normal(op, h_shift, force=FN, initial=cold.pressure)

    print(f"{n}^2 grid, pair {pair * 1e3:.2f} ms; costs per CG iteration in pairs")
    print("| start | iterations | products | per-iteration product | extra products | preconditioner "
          "| element loops | rest | loop (product + preconditioner + loops) | whole solve |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for label, solve in (("cold", lambda: sn.solve_normal(op, h, force=FN)), ("warm (one-cell shift)", warm)):
        it, calls, parts = breakdown(op, solve, args.repeats)
        per = {k: v / it / pair for k, v in parts.items()}
        product_per_call = parts["normal"] / calls
        extra = (calls - it) * product_per_call / it / pair
        loop = it * product_per_call / it / pair + per["normal_inverse"] + per["kernels"]
        print(f"| {label} | {it:.0f} | {calls:.0f} | {product_per_call / pair:.2f} | {extra:.2f} "
              f"| {per['normal_inverse']:.2f} | {per['kernels']:.2f} | {per['rest']:.2f} | {loop:.2f} "
              f"| {per['total']:.2f} |")


if __name__ == "__main__":
    main()

"""Where the tangential iterations go: the fixed-division PCG floor against `solve_tangential`.

Issue #3 asks for <= 15 iterations per step warm-started after a small load or profile change and for
nearly flat cold counts under refinement. On the Cattaneo scene of `tangential_cattaneo.py` (seed scene,
grid = contact + 0.6 mm, dx = 0.2 / 0.1 / 0.05 / 0.0211 mm, tol = 1e-8) this separates the linear algebra from the
identification of the stick/slip division:

* floor: with the final division of the solve known in advance and the slip tractions fixed at their final
  values, the step is linear in the stick tractions: A_SS (tau_S - tau'_S) = dU - (A (tau_slip - tau'_slip))_S
  with sum tau = F. Plain deflated PCG (force constraint as in the solver, preconditioner P_S M P_S with
  M = `op.tangential_inverse`) is counted until max_S |slip| <= tol a_self max g (the solver's criterion),
  from the previous step's traction restricted to S (warm) or from zero (cold). Products counted:
  one per iteration plus the start product.
* `solve_tangential` on the same steps, all products counted (`TangentialResult.iterations`).

Usage: .venv/bin/python benchmarks/tangential_warm_limits.py [--quick] [--dx 0.2 0.1 0.05 0.0211] [-o DIR]
Writes DIR/tangential_warm_limits.json (default results/benchmarks/; the committed one: -o benchmarks/results) and
prints a Markdown table. --quick: dx = 0.2 and 0.1 only.
"""
import sys
from pathlib import Path

import numpy as np

import _record
from tangential_cattaneo import FN, MU, cattaneo_scene

ROOT = Path(__file__).resolve().parents[1]

from rollcontact.solver.tangential.shift import TangentialParams, solve_tangential  # noqa: E402


def fixed_division_pcg(op, final, previous, start, force, dA, bound, max_iter=500):
    """Deflated PCG for the stick tractions of `final`'s division (slip tractions fixed at final values).

    previous: tau' (2, ny, nx); start: initial traction on S (2, ny, nx); force: (Fx, Fy) N.
    Returns (products, max relative error of tau against final.traction) at max_S |slip| <= bound.
    """
    stick = final.region == 1
    mask = stick[None].astype(float)
    slip_part = np.where(final.region == 2, final.traction, 0.0)
    tau = slip_part + mask * start
    count = stick.sum()
    for k in range(2):   # the iterate carries the prescribed force: shift the stick tractions uniformly
        tau[k][stick] += (force[k] / dA - tau[k].sum()) / count
    products = 1
    u = op.tangential(*(tau - previous))
    def residual(u):
        du = np.array([u[k][stick].mean() for k in range(2)])     # dU: least-squares multiplier
        return mask * -(u - du[:, None, None])
    r = residual(u)
    v = np.zeros_like(r)
    rz_old = 0.0
    while np.abs(r).max() > bound and products < max_iter:
        z = mask * op.tangential_inverse(*r)
        for k in range(2):
            z[k][stick] -= z[k][stick].mean()
        rz = float((r * z).sum())
        v = z + (rz / rz_old) * v if rz_old else z
        rz_old = rz
        q = op.tangential(*v)
        products += 1
        qs = mask * q
        alpha = rz / float((v * qs).sum())
        tau += alpha * v
        u += alpha * q
        r = residual(u)
    err = np.abs(tau - final.traction).max() / final.traction.max()
    return products, float(err)


def run(dx, params):
    grid, op, X, Y, g, g2 = cattaneo_scene(dx)
    zero = np.zeros((2,) + grid.shape)
    F = lambda f: (f * MU * FN, 0.0)
    dA = grid.cell_area
    a_self = max(op.self_coefficients["xx"], op.self_coefficients["yy"])  # the solver's residual scale
    bound = params.tol * a_self * g.max()
    cold = solve_tangential(op, g, zero, force=F(0.5), params=params)
    load = solve_tangential(op, g, cold.traction, force=F(0.52), params=params)
    moved = solve_tangential(op, g2, cold.traction, force=F(0.5), params=params)
    floor_cold = fixed_division_pcg(op, cold, zero, zero, F(0.5), dA, bound)
    floor_load = fixed_division_pcg(op, load, cold.traction, cold.traction, F(0.52), dA, bound)
    floor_moved = fixed_division_pcg(op, moved, cold.traction, cold.traction, F(0.5), dA, bound)
    return dict(dx=dx, grid=list(grid.shape), stick_elements=int((cold.region == 1).sum()),
                solver=dict(cold=cold.iterations, load=load.iterations, profile=moved.iterations),
                floor=dict(cold=floor_cold, load=floor_load, profile=floor_moved))


def markdown(rows):
    lines = ["| dx mm | grid | stick elements | cold: solver / floor | warm load: solver / floor "
             "| warm profile: solver / floor |", "|---|---|---|---|---|---|"]
    for r in rows:
        s, f = r["solver"], r["floor"]
        lines.append(f"| {r['dx']} | {r['grid'][0]}^2 | {r['stick_elements']} | {s['cold']} / {f['cold'][0]} "
                     f"| {s['load']} / {f['load'][0]} | {s['profile']} / {f['profile'][0]} |")
    return "\n".join(lines)


def main(argv=None):
    parser = _record.parser(__doc__)
    parser.add_argument("--quick", action="store_true", help="dx = 0.2 and 0.1 mm only")
    parser.add_argument("--dx", type=float, nargs="*", default=None, help="default 0.2 0.1 0.05 0.0211")
    args = parser.parse_args(argv)
    args.dx = args.dx or ([0.2, 0.1] if args.quick else [0.2, 0.1, 0.05, 0.0211])
    params = TangentialParams()
    rows = []
    for dx in args.dx:
        rows.append(run(dx, params))
        print(rows[-1], flush=True)
    _record.write("tangential_warm_limits", dict(benchmark="tangential_warm_limits", tol=params.tol, quick=args.quick,
                                                 rows=rows), args.output)
    print(markdown(rows))


if __name__ == "__main__":
    sys.exit(main())

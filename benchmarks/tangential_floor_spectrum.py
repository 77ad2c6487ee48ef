"""Why the fixed-division floor of the tangential solver is 10-16 products: the preconditioned stick spectrum.

`tangential_warm_limits.py` showed that, with the final stick/slip division known in advance, deflated PCG
still needs 10 / 11 / 13 / 15 products for the warm load step of the Cattaneo scene (55^2 ... 511^2, tol 1e-8).
This measures the spectrum behind that floor: the stick block A_SS of the warm load step's final division
(f_t 0.5 -> 0.52), deflated by the force constraint (zero-sum subspace per component) and preconditioned by
the solver's stick preconditioner P_S M P_S (M = `op.tangential_inverse`, the Strang-circulant inverse of
A^tt on the unpadded grid).

* Ritz extremes: Lanczos values of deflated PCG from a seeded random right-hand side (the CG coefficients
  give the tridiagonal matrix; run until r.z < 1e-24 of its start, at most 60 products). They bound the
  contraction per product, rho = (sqrt(kappa) - 1)/(sqrt(kappa) + 1), kappa = lambda_max/lambda_min, and the
  products needed for `--decades` decades, ln(10^decades / 2)/ln(1/rho).
* The same with the cheapest local correction of the boundary: (A_SS)^-1 = B_SS - B_SE B_EE^-1 B_ES exactly
  for B = M (the inverse of a principal block from the inverse of the whole), here with E cut to the ring of
  non-stick elements within `--ring` cells of the stick area and B_EE^-1 replaced by its diagonal (one more
  circulant inverse per iteration).
* `--dense` (grids with at most 1500 stick elements): all eigenvalues (generalised symmetric problem of the
  dense blocks), their quantiles, and the mean distance to the stick boundary of the extreme eigenvectors.

Usage: .venv/bin/python benchmarks/tangential_floor_spectrum.py [--dx 0.2 0.1 0.05 0.0211] [--dense]
Writes benchmarks/results/tangential_floor_spectrum.json and prints a Markdown table.
"""
import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np
from scipy import linalg, ndimage

from tangential_cattaneo import FN, MU, cattaneo_scene

ROOT = Path(__file__).resolve().parents[1]

from rollcontact.solver.tangential.shift import TangentialParams, solve_tangential  # noqa: E402


def deflate(x, stick):
    """Project onto sum x = 0 over the stick elements, per component (the force constraint), in place."""
    for k in range(2):
        x[k][stick] -= x[k][stick].mean()
    return x


def ritz_extremes(op, stick, precondition, max_products=60, seed=0):
    """(lambda_min, lambda_max, products) of the deflated preconditioned stick operator, by Lanczos from PCG."""
    mask = stick[None].astype(float)
    r = deflate(mask * np.random.default_rng(seed).standard_normal((2,) + stick.shape), stick)
    v = np.zeros_like(r)
    alphas, betas = [], []
    rz_old = rz0 = 0.0
    for _ in range(max_products):
        z = deflate(precondition(r), stick)
        rz = float((r * z).sum())
        rz0 = rz0 or rz
        if rz < 1e-24 * rz0:
            break
        if rz_old:
            betas.append(rz / rz_old)
        v = z + (rz / rz_old) * v if rz_old else z
        rz_old = rz
        q = deflate(mask * op.tangential(*v), stick)
        alphas.append(rz / float((v * q).sum()))
        r = r - alphas[-1] * q
    m = len(alphas)
    T = np.zeros((m, m))
    for j in range(m):
        T[j, j] = 1.0 / alphas[j] + (betas[j - 1] / alphas[j - 1] if j else 0.0)
        if j + 1 < m:
            T[j, j + 1] = T[j + 1, j] = math.sqrt(betas[j]) / alphas[j]
    lam = np.linalg.eigvalsh(T)
    return float(lam[0]), float(lam[-1]), m


def circulant_kernel(op, shape):
    """Columns of M = op.tangential_inverse for unit tractions x and y at element (0, 0): (2, 2, ny, nx)."""
    e = np.zeros((2,) + shape)
    cols = []
    for k in range(2):
        e[...] = 0.0
        e[k, 0, 0] = 1.0
        cols.append(op.tangential_inverse(*e).copy())
    return np.array(cols)


def stick_preconditioner(op, stick):
    mask = stick[None].astype(float)
    return lambda r: mask * op.tangential_inverse(*r)


def ring_corrected_preconditioner(op, stick, ring_cells):
    """z = P_S (M - M_E D_E^-1 M_E) P_S r: the diagonal-Schur correction on the ring E (see the docstring)."""
    mask = stick[None].astype(float)
    ring = (~stick) & (ndimage.distance_transform_edt(~stick) <= ring_cells)
    kern = circulant_kernel(op, stick.shape)
    inv_diag = np.array([1.0 / kern[0, 0, 0, 0], 1.0 / kern[1, 1, 0, 0]])[:, None, None] * ring[None]

    def apply(r):
        z = op.tangential_inverse(*(mask * r))
        return mask * (z - op.tangential_inverse(*(inv_diag * z)))
    return apply


def dense_spectrum(op, stick):
    """All eigenvalues of the deflated M A_SS and the mean distance (cells) to the stick boundary of the
    5 lowest and 5 highest eigenvectors (weighted by |v|^2), with the mean over the stick area."""
    rows, cols = np.nonzero(stick)
    n = rows.size
    xx, xy, yy = op.tangential_block(rows, cols)
    A = np.block([[xx, xy], [xy.T, yy]])
    M = np.empty((2 * n, 2 * n))
    e = np.zeros((2,) + stick.shape)
    for k in range(2):
        for m in range(n):
            e[...] = 0.0
            e[k, rows[m], cols[m]] = 1.0
            z = op.tangential_inverse(*e)
            M[:n, k * n + m], M[n:, k * n + m] = z[0][stick], z[1][stick]
    C = np.zeros((2 * n, 2))
    C[:n, 0] = C[n:, 1] = 1.0
    Q = np.linalg.qr(C, mode="complete")[0][:, 2:]        # basis of the force-deflated subspace
    sym = lambda X: 0.5 * (X + X.T)
    lam, V = linalg.eigh(sym(Q.T @ A @ Q), np.linalg.inv(sym(Q.T @ M @ Q)))
    V = Q @ V
    dist = ndimage.distance_transform_edt(stick)[stick]
    where = lambda vecs: [float(((vecs[:n, j] ** 2 + vecs[n:, j] ** 2) * dist).sum()
                                / (vecs[:n, j] ** 2 + vecs[n:, j] ** 2).sum()) for j in range(vecs.shape[1])]
    return dict(quantiles={q: float(np.quantile(lam, q)) for q in (0.0, 0.05, 0.5, 0.95, 0.99, 1.0)},
                distance_lowest=where(V[:, :5]), distance_highest=where(V[:, -5:]),
                distance_mean=float(dist.mean()))


def products_for(kappa, decades):
    rho = (math.sqrt(kappa) - 1.0) / (math.sqrt(kappa) + 1.0)
    return rho, math.log(2.0 * 10.0 ** decades) / math.log(1.0 / rho)


def run(dx, ring_cells, decades, dense):
    grid, op, X, Y, g, g2 = cattaneo_scene(dx)
    zero = np.zeros((2,) + grid.shape)
    F = lambda f: (f * MU * FN, 0.0)
    params = TangentialParams()
    cold = solve_tangential(op, g, zero, force=F(0.5), params=params)
    stick = solve_tangential(op, g, cold.traction, force=F(0.52), params=params).region == 1
    row = dict(dx=dx, grid=list(grid.shape), stick_elements=int(stick.sum()))
    for name, prec in (("plain", stick_preconditioner(op, stick)),
                       ("ring", ring_corrected_preconditioner(op, stick, ring_cells))):
        lo, hi, m = ritz_extremes(op, stick, prec)
        rho, k = products_for(hi / lo, decades)
        row[name] = dict(lambda_min=lo, lambda_max=hi, kappa=hi / lo, rho=rho, products_bound=k, lanczos=m)
    if dense and stick.sum() <= 1500:
        row["dense"] = dense_spectrum(op, stick)
    return row


def markdown(rows, decades):
    lines = [f"| dx mm | grid | stick elements | lambda min / max | kappa | rho | products for {decades:g} decades "
             "| ring-corrected: lambda max, kappa, products |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        p, c = r["plain"], r["ring"]
        lines.append(f"| {r['dx']} | {r['grid'][0]}^2 | {r['stick_elements']} | {p['lambda_min']:.3f} / "
                     f"{p['lambda_max']:.3f} | {p['kappa']:.2f} | {p['rho']:.3f} | {p['products_bound']:.1f} "
                     f"| {c['lambda_max']:.3f}, {c['kappa']:.2f}, {c['products_bound']:.1f} |")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--dx", type=float, nargs="*", default=[0.2, 0.1, 0.05, 0.0211])
    parser.add_argument("--ring", type=float, default=2.0, help="ring width of the Schur correction (cells)")
    parser.add_argument("--decades", type=float, default=7.0,
                        help="residual reduction of a warm step (about 7 decades at tol 1e-8)")
    parser.add_argument("--dense", action="store_true", help="full spectrum on grids of <= 1500 stick elements")
    parser.add_argument("--output", default=str(ROOT / "benchmarks" / "results" / "tangential_floor_spectrum.json"))
    args = parser.parse_args(argv)
    rows = []
    for dx in args.dx:
        rows.append(run(dx, args.ring, args.decades, args.dense))
        print(json.dumps(rows[-1]), flush=True)
    path = Path(args.output)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(dict(benchmark="tangential_floor_spectrum", ring_cells=args.ring,
                                    decades=args.decades, rows=rows), indent=1))
    print(markdown(rows, args.decades))
    print(f"\nwritten {path}")


if __name__ == "__main__":
    sys.exit(main())

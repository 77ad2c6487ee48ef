"""Where the stresses below a sliding Hertz sphere peak: Hamilton's closed form (solver/hamilton.py) and the grid.

For each friction coefficient mu (full slip, q_x = mu p, nu = 0.3, a = p0 = 1): the largest von Mises and max shear
(Tresca) below the surface (a local maximum found by Nelder-Mead in the plane y = 0, which holds it by symmetry; once the surface wins
it may climb to z = 0) and
on the surface (a 1e-4 a scan of y = 0, the edges x = -a, +a taken 1e-9 a below the surface), and the friction
coefficient at which the surface maximum overtakes the one below (Brent's method, 1e-6). Then the same maxima on the
default grid (a/dx = 12, cell-averaged Hertz pressure; depths 0 ... a in steps of a/100) from bem.subsurface, beside
Hamilton's at the same cell centres. First, the frictionless Hertz axis on that grid against the closed forms
(docs/theory.md §11.6). --quick: mu = 0.3 only. JSON to DIR/hamilton_sliding.json (-o DIR, default results/benchmarks/).
"""
import argparse
from pathlib import Path

import numpy as np
from scipy.optimize import brentq, minimize

import _record
from rollcontact.bem.grid import Grid
from rollcontact.bem.subsurface import SubsurfaceStresses, invariants
from rollcontact.solver.hamilton import hamilton_stresses

HERE = Path(__file__).resolve().parent
NU = 0.3


def _value(x, z, mu, name):
    return invariants(hamilton_stresses(x, 0.0, z, 1.0, 1.0, mu, NU))[name]


def interior(mu, name):
    res = minimize(lambda v: -float(_value(v[0], abs(v[1]), mu, name)), (0.2, 0.45), method="Nelder-Mead",
                   options=dict(xatol=1e-9, fatol=1e-13, maxiter=4000))
    return {"value": -res.fun, "x": float(res.x[0]), "z": float(abs(res.x[1]))}


def surface(mu, name):
    x = np.linspace(-1.2, 1.2, 24001)
    v = _value(x, np.where(np.abs(np.abs(x) - 1) < 1e-9, 1e-9, 0.0), mu, name)
    k = int(np.argmax(v))
    return {"value": float(v[k]), "x": float(x[k])}


def switch(name):
    return brentq(lambda m: surface(m, name)["value"] - interior(m, name)["value"], 0.1, 0.4, xtol=1e-6)


def _cell_averaged_hertz(grid, sub=16):
    """Hertz's pressure (a = p0 = 1) averaged over each cell (sub x sub midpoints), as the tests do."""
    X, Y = grid.mesh()
    off = (np.arange(sub) + 0.5) / sub - 0.5
    p = sum(np.sqrt(np.clip(1 - (X + ox * grid.dx) ** 2 - (Y + oy * grid.dy) ** 2, 0, None)) for ox in off for oy in off)
    return p / sub**2


def hertz_axis(n=15):
    """Frictionless Hertz (a = p0 = 1, nu = 0.3) on the default grid a/12: the largest error of sigma_r and sigma_z on
    the axis (z = 0 ... 2a, 101 depths) against the closed forms of docs/theory.md §11.6, in units of p0, and the
    maxima of the max shear and von Mises on the axis with the depth of the max shear."""
    g = Grid(2 * n + 1, 2 * n + 1, 1 / 12, 1 / 12, -n, -n)
    p = _cell_averaged_hertz(g)
    op = SubsurfaceStresses(g, NU)
    op.set_tractions(p, 0 * p, 0 * p)
    depths = np.linspace(0.0, 2.0, 101)
    axis = np.array([op.layer(z)[:, n, n] for z in depths]).T
    with np.errstate(divide="ignore"):
        s_r = -((1 + NU) * (1 - np.where(depths > 0, depths * np.arctan(1 / np.where(depths > 0, depths, 1)), 0.0))
                - 0.5 / (1 + depths**2))
    s_z = -1 / (1 + depths**2)
    error = max(float(np.abs(axis[0] - s_r).max()), float(np.abs(axis[1] - s_r).max()), float(np.abs(axis[2] - s_z).max()))
    inv = invariants(axis)
    k = int(np.argmax(inv["tresca"]))
    return {"axis_error": error, "tresca_max": float(inv["tresca"][k]), "tresca_depth": float(depths[k]),
            "von_mises_max": float(inv["von_mises"].max())}


def on_grid(mu, n=18):
    """Grid maxima (value, z, x, y) of von Mises and Tresca, and Hamilton's at the same cell centres."""
    g = Grid(2 * n + 1, 2 * n + 1, 1 / 12, 1 / 12, -n, -n)
    p = _cell_averaged_hertz(g)
    op = SubsurfaceStresses(g, NU)
    op.set_tractions(p, mu * p, 0 * p)
    depths = np.linspace(0.0, 1.0, 101)
    X, Y = g.mesh()
    out = {}
    layers = [invariants(op.layer(z)) for z in depths]
    Z = np.broadcast_to(depths[:, None, None], (len(depths),) + X.shape)
    Z = np.where((Z == 0) & (np.abs(np.hypot(X, Y) - 1) < 1e-12), 1e-12, Z)
    exact = invariants(hamilton_stresses(np.broadcast_to(X, Z.shape), np.broadcast_to(Y, Z.shape), Z, 1.0, 1.0,
                                         mu, NU))
    for name in ("von_mises", "tresca"):
        block = np.array([layer[name] for layer in layers])
        for label, b in (("grid", block), ("hamilton_on_cells", exact[name])):
            k = np.unravel_index(int(np.argmax(b)), b.shape)
            out[f"{name}_{label}"] = {"value": float(b[k]), "z": float(depths[k[0]]), "x": float(g.x[k[2]]),
                                      "y": float(g.y[k[1]])}
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("--mu", type=float, nargs="+", default=None,
                        help="friction coefficients (default 0 0.1 0.2 0.3 0.4 0.5)")
    parser.add_argument("--quick", action="store_true", help="mu = 0.3 only")
    _record.add_output(parser)
    args = parser.parse_args(argv)
    args.mu = args.mu or ([0.3] if args.quick else [0.0, 0.1, 0.2, 0.3, 0.4, 0.5])
    hertz = hertz_axis()
    print(f"Hertz on the axis, a/dx = 12: sigma_r, sigma_z within {hertz['axis_error']:.5f} p0 of the closed form; "
          f"max shear {hertz['tresca_max']:.4f} p0 at z = {hertz['tresca_depth']:.2f} a, von Mises "
          f"{hertz['von_mises_max']:.4f} p0", flush=True)
    rows = []
    for mu in args.mu:
        row = {"mu": mu}
        for name in ("von_mises", "tresca"):
            row[name] = {"below": interior(mu, name), "surface": surface(mu, name)}
        row["grid"] = on_grid(mu)
        rows.append(row)
        vm, tr, gv = row["von_mises"], row["tresca"], row["grid"]["von_mises_grid"]
        print(f"mu = {mu}: von Mises below {vm['below']['value']:.4f} at x = {vm['below']['x']:.3f}, z = "
              f"{vm['below']['z']:.3f}; surface {vm['surface']['value']:.4f} at x = {vm['surface']['x']:.3f} | "
              f"Tresca below {tr['below']['value']:.4f}, surface {tr['surface']['value']:.4f} at x = "
              f"{tr['surface']['x']:.3f} | grid von Mises max {gv['value']:.4f} at x = {gv['x']:.3f}, z = {gv['z']:.2f}",
              flush=True)
    switches = {name: switch(name) for name in ("von_mises", "tresca")}
    print(f"the surface maximum overtakes the one below at mu = {switches['von_mises']:.4f} (von Mises), "
          f"{switches['tresca']:.4f} (Tresca)")
    result = {"nu": NU, "hertz_axis": hertz, "rows": rows, "switch_mu": switches}
    _record.write("hamilton_sliding", result, args.output)


if __name__ == "__main__":
    main()

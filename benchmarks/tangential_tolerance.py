"""Products of the tangential solver against its stopping tolerance, and the accuracy each tolerance gives.

    .venv/bin/python benchmarks/tangential_tolerance.py [--dx 0.2 0.1 0.05 0.0211]

Cattaneo scene of `tangential_cattaneo.py` (cold f_t = 0.5 from zero; warm load f_t 0.5 -> 0.52; warm profile: the
pressure moved by one cell in y), for tol = 1e-5 ... 1e-8 (`TangentialParams.tol`, the default 1e-8), each chain
started from the cold solve at the same tol (as in a rolling run). Errors against a reference chain solved to the
tightest tolerance that converges on the grid (1e-11 up to 109^2, 1e-10 at 217^2, 1e-9 at 511^2): max traction
error relative to max g, relative error of the accumulated shift U, and elements whose region differs. Product
counts only (no timing). JSON to benchmarks/results/tangential_tolerance.json.
"""
import argparse
import json
from pathlib import Path

import numpy as np

from rollcontact.solver.tangential.shift import TangentialParams, solve_tangential
from tangential_cattaneo import FN, MU, cattaneo_scene

TOLS = (1e-5, 1e-6, 1e-7, 1e-8)


def chain(op, g, g2, zero, params):
    F = lambda f: (f * MU * FN, 0.0)
    cold = solve_tangential(op, g, zero, force=F(0.5), params=params)
    load = solve_tangential(op, g, cold.traction, force=F(0.52), params=params)
    prof = solve_tangential(op, g2, cold.traction, force=F(0.5), params=params)
    return {"cold": cold, "load": load, "profile": prof}


def run(dx):
    grid, op, X, Y, g, g2 = cattaneo_scene(dx)
    zero = np.zeros((2,) + grid.shape)
    ref_tol = 1e-11 if grid.size <= 109 ** 2 else 1e-10 if grid.size <= 217 ** 2 else 1e-9
    ref = chain(op, g, g2, zero, TangentialParams(tol=ref_tol, max_iter=3000))
    shift = lambda c, r: c["cold"].shift_increment[0] + (0.0 if r is c["cold"] else r.shift_increment[0])
    rows = []
    for tol in TOLS:
        res = chain(op, g, g2, zero, TangentialParams(tol=tol))
        row = {"tol": tol}
        for name, r in res.items():
            q = ref[name]
            row[name] = {"products": r.iterations, "cg_steps": r.steps,
                         "traction_error_rel_max_g": float(np.abs(r.traction - q.traction).max() / g.max()),
                         "shift_error_rel": float(abs(shift(res, r) / shift(ref, q) - 1)),
                         "region_differs": int((r.region != q.region).sum())}
        rows.append(row)
        print(f"{grid.shape[0]}^2 tol {tol:.0e}: products cold/load/profile "
              + "/".join(str(row[k]["products"]) for k in ("cold", "load", "profile"))
              + "  CG steps " + "/".join(str(row[k]["cg_steps"]) for k in ("cold", "load", "profile"))
              + "  traction error / max g " + "/".join(f"{row[k]['traction_error_rel_max_g']:.1e}"
                                                       for k in ("cold", "load", "profile"))
              + "  U error " + "/".join(f"{row[k]['shift_error_rel']:.1e}" for k in ("cold", "load", "profile")),
              flush=True)
    return {"dx_mm": dx, "grid": list(grid.shape), "reference_tol": ref_tol, "rows": rows}


def grids_main(doc, name, run, default_dx):
    """Command line of the Cattaneo grid benchmarks: run(dx) for each --dx, JSON to benchmarks/results/<name>.json."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("--dx", type=float, nargs="*", default=list(default_dx))
    args = ap.parse_args()
    out = Path(__file__).parent / "results" / f"{name}.json"
    data = {"benchmark": name, "grids": [run(dx) for dx in args.dx]}
    out.write_text(json.dumps(data, indent=1))
    print(f"wrote {out}")


if __name__ == "__main__":
    grids_main(__doc__, "tangential_tolerance", run, (0.2, 0.1, 0.05, 0.0211))

"""Speed of the fast models against the exact steady solver on the same grids (solver.fastsim; issue targets:
FASTSIM's 20-point creep curve on 60 x 60 elements under 0.2 s, one case under 10 ms, once compiled).

    .venv/bin/python benchmarks/fastsim_speed.py [--quick] [-o DIR]     # DIR default results/; ~1 min (--quick ~10 s)

Process CPU time (time.process_time), medians over --repeats. On a 60 x 60 grid (the ellipse a/b = 1 across 58 x 60
cells, Hertz pressure, nu = 0.28, mu = 0.3):
* one case (xi = eta = phi at half their saturation values) by FASTSIM, FaStrip and the exact solver (cold);
* a 20-point creep curve in xi from 0.02 to 4 times saturation: the fast models point by point, the exact solver
  warm-started along the curve (solver.creep.creep_curve);
* the same through the API (`rollcontact.creep_curve`, a [rolling] scene on a 61 x 61 grid: the normal problem,
  the operator, the curve; the figure not drawn), per model;
* the first call of each model in the process (numba's on-disk cache loaded, or compiled without it), apart.
Ratios are against the exact solver of the same run (the peer), which the machine's load affects alike.
"""
from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
from pathlib import Path
import statistics
import sys
import time

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from rollcontact.bem import MaterialPair  # noqa: E402
from rollcontact.bem.grid import Grid  # noqa: E402
from rollcontact.cases import api  # noqa: E402
from rollcontact.solver.creep import (SteadyRolling, creep_curve, hertz_pressure, kalker_coefficients,  # noqa: E402
                                      solve_steady)
from rollcontact.solver.fastsim import kalker_flexibilities, solve_fastrip, solve_fastsim  # noqa: E402

MU, NU = 0.3, 0.28
MODELS = {"fastsim": solve_fastsim, "fastrip": solve_fastrip}


def cpu(fn, repeats):
    """Median process CPU time of fn() over `repeats` calls (s)."""
    times = []
    for _ in range(repeats):
        c0 = time.process_time()
        fn()
        times.append(time.process_time() - c0)
    return statistics.median(times)


def grid_60():
    """60 x 60 elements: 58 across 2a plus a free column ahead and behind, 60 across 2b (a = b = 1 mm)."""
    return Grid(60, 60, 2.0 / 58, 2.0 / 60, -30, -30)


def solver_level(repeats):
    grid = grid_60()
    pressure = hertz_pressure(grid, 1.0, 1.0, 1.0)
    flex = kalker_flexibilities(1.0, 1.0, 1.0, NU)
    c11, c22, c23 = kalker_coefficients(1.0, NU)
    mu_fn = MU * pressure.sum() * grid.cell_area
    one = (0.5 * mu_fn / c11, 0.5 * mu_fn / c22, 0.5 * mu_fn / c23)
    curve = [(f * mu_fn / c11, 0.0, 0.0) for f in np.geomspace(0.02, 4.0, 20)]
    out = {"grid": list(grid.shape), "contact_cells": int((pressure > 0).sum())}
    for name, solve in MODELS.items():
        c0 = time.process_time()
        solve(grid, pressure, MU, *one, flexibilities=flex)
        out[f"{name}_first_call_s"] = time.process_time() - c0
        out[f"{name}_case_s"] = cpu(lambda: solve(grid, pressure, MU, *one, flexibilities=flex), repeats * 10)
        out[f"{name}_curve_s"] = cpu(lambda: [solve(grid, pressure, MU, *c, flexibilities=flex) for c in curve],
                                     repeats)
    pair = MaterialPair.from_moduli(2 * (1 + NU), NU, 2 * (1 + NU), NU)
    problem = SteadyRolling(grid, pair)
    out["bem_case_s"] = cpu(lambda: solve_steady(problem, pressure, MU, *one), max(1, repeats // 2))
    out["bem_curve_s"] = cpu(lambda: creep_curve(problem, pressure, MU, curve), max(1, repeats // 2))
    for name in MODELS:
        out[f"{name}_case_ratio"] = out[f"{name}_case_s"] / out["bem_case_s"]
        out[f"{name}_curve_ratio"] = out[f"{name}_curve_s"] / out["bem_curve_s"]
    return out


SCENE = """
[materials]
E1 = 210e3
nu1 = 0.28
E2 = 210e3
nu2 = 0.28
[geometry]
R = 40.0
[load]
Fn = 1000.0
mu = 0.3
[rolling]
mode = "steady"
xi = 1e-4
[grid]
dx = {dx}
margin = 0.0
"""


def api_level(repeats):
    """rollcontact.creep_curve on a scene whose grid is about 60 x 60 (dx = 2a/58, a the Hertz radius)."""
    from rollcontact.cases.run.rolling_frame import creep_grid
    from rollcontact.cases.scene.scene import Scene
    a = Scene.from_toml_text(SCENE.format(dx=1.0), run_limits=False).contact_radius
    scene = Scene.from_toml_text(SCENE.format(dx=f"{2 * a / 58:.6g}"), name="speed")
    out = {"api_grid": list(creep_grid(scene).shape)}
    for model in ("fastsim", "fastrip", "bem"):
        api.creep_curve(scene, "xi", points=20, fidelity=model)            # first call: operator, caches
        out[f"api_{model}_curve_s"] = cpu(lambda: api.creep_curve(scene, "xi", points=20, fidelity=model),
                                          max(1, repeats // (2 if model == "bem" else 1)))
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="fewer repeats (seconds)")
    parser.add_argument("--repeats", type=int, default=None, help="repeats per median (default 7, quick 3)")
    parser.add_argument("-o", "--output", default="results", help="folder for fastsim_speed.json (default results/)")
    args = parser.parse_args(argv)
    repeats = args.repeats or (3 if args.quick else 7)
    load = os.getloadavg()
    data = dict(benchmark="fastsim_speed", date=datetime.date.today().isoformat(), machine=platform.machine(),
                processor=platform.processor(), python=platform.python_version(), cpu_count=os.cpu_count(),
                loadavg_before=load, repeats=repeats, quick=args.quick)
    data.update(solver_level(repeats))
    data.update(api_level(repeats))
    data["loadavg_after"] = os.getloadavg()
    data["targets"] = dict(fastsim_curve_s=0.2, fastsim_case_s=0.01)
    data["met"] = dict(curve=data["fastsim_curve_s"] < 0.2 and data["api_fastsim_curve_s"] < 0.2,
                       case=data["fastsim_case_s"] < 0.01)
    out = Path(args.output) / ("fastsim_speed_quick.json" if args.quick else "fastsim_speed.json")
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(data, indent=1) + "\n")
    for k, v in data.items():
        if k.endswith(("_s", "_ratio")):
            print(f"{k:28s} {v * (1e3 if k.endswith('_s') else 1):10.4g}{' ms' if k.endswith('_s') else ''}")
    print(f"load {load[0]:.2f} -> {data['loadavg_after'][0]:.2f}; targets met: {data['met']}")
    print(out.resolve())
    return 0


if __name__ == "__main__":
    sys.exit(main())

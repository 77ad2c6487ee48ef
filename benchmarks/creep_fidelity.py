"""The tables and the chart of docs/creep_fidelity.md: the force errors of FASTSIM and FaStrip against the exact
steady theory (from the map `auto` uses), accuracy against time per case beside the MDR-versus-3-D chart of the
shakedown scenes, and CONTACT's `fastsim` example posed.

    .venv/bin/python benchmarks/creep_fidelity.py [-o DIR] [--quick]
        # DIR default results/creep_fidelity; `-o docs/figures` refreshes the page's figure (and its JSON)

Reads solver/fastsim/error_map.json and solver/mdr/error_map.json (benchmarks/creep_error_map.py and
benchmarks/mdr_error_map.py measure them) and benchmarks/results/default_resolution.json (the 3-D solver's u_sd at
a/dx = 6 and 12 against a/24); measures, at nu = 0.28: the exact solver's own discretisation error (21 and 41
elements across against 81) and CPU time per case, on the table's curves (pure xi, eta, phi; eta with spin adding
to it and against it; xi with eta) at a/b = 0.2 ... 5; and CONTACT's example (a = 8, b = 4 mm, Fn = 82 kN,
G = 82 GPa, nu = 0.28, mu = 0.3, eta = -6.25e-4, phi = 6.25e-4 1/mm) on its 44 x 44 and 220 x 220 grids.
Writes DIR/creep_fidelity.png and DIR/creep_fidelity.json and prints the page's tables.
"""
from __future__ import annotations

import argparse
import datetime
import json
import math
import os
from pathlib import Path
import statistics
import sys
import time

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

from rollcontact.bem import MaterialPair  # noqa: E402
from rollcontact.bem.grid import Grid  # noqa: E402
from rollcontact.bem.operator import HalfSpaceOperator  # noqa: E402
from rollcontact.solver.creep import (SteadyParams, SteadyRolling, ellipse_grid, hertz_pressure,  # noqa: E402
                                      kalker_coefficients, solve_steady)
from rollcontact.solver.fastsim import kalker_flexibilities, solve_fastrip, solve_fastsim  # noqa: E402
from rollcontact.solver.normal import NormalParams, solve_normal  # noqa: E402

#: The table's curves: name -> (theta, alpha) of the map (solver.fastsim.error_map).
CURVES = {"xi": (90, 0), "eta": (90, 90), "phi": (0, 0), "eta+phi": (60, 90), "eta-phi": (120, 90),
          "xi+eta": (90, 45)}
NU = 0.28
MU = 0.3


def load_json(path):
    return json.loads(Path(path).read_text())


def error_table(creep_map):
    """Per (a/b, curve): the largest and the median error over the map's t of each model, at nu = 0.28."""
    ax = creep_map["axes"]
    i_nu = ax["nu"].index(NU)
    rows = []
    for j, ratio in enumerate(ax["ratio"]):
        for name, (theta, alpha) in CURVES.items():
            k, m = ax["theta"].index(theta), ax["alpha"].index(alpha)
            row = dict(ratio=ratio, curve=name)
            for model in creep_map["models"]:
                e = np.array([np.nan if v is None else v for v in creep_map["errors"][model][i_nu][j][k][m]])
                row[f"{model}_max"], row[f"{model}_median"] = float(np.nanmax(e)), float(np.nanmedian(e))
                row[f"{model}_errors"] = e.tolist()
            row["fastrip_closer"] = row["fastrip_max"] < row["fastsim_max"]
            rows.append(row)
    return rows


def exact_discretisation(creep_map, quick):
    """Along the table's curves (a subset of the map's t): the exact solver's force at 21 and 41 elements across
    against 81 and its cold CPU time per case ('exact' rows); and each fast model's error against the exact solver on
    the same grid at 41 and at 81 elements ('resolution' rows: how far the map's 41-element measure is from a finer
    one, the margin its predictions carry, solver.fastsim.error_map.RESOLUTION_MARGIN)."""
    ax = creep_map["axes"]
    ratios = (1.0,) if quick else tuple(r for r in ax["ratio"] if r in (0.2, 0.5, 1.0, 2.0, 5.0))
    ts = (0.2, 1.0) if quick else (0.1, 0.35, 1.0, 3.0)
    levels = (21, 41) if quick else (21, 41, 81)
    pair = MaterialPair.from_moduli(2 * (1 + NU), NU, 2 * (1 + NU), NU)
    exact_rows, resolution_rows = [], []
    for ratio in ratios:
        a, b = math.sqrt(ratio), 1 / math.sqrt(ratio)
        c11, c22, c23 = kalker_coefficients(ratio, NU)
        flex = kalker_flexibilities(a, b, 1.0, NU)
        cases = {}
        for n in levels:
            grid = ellipse_grid(a, b, n)
            p = hertz_pressure(grid, a, b, 1.0)
            problem = SteadyRolling(grid, pair)
            unit = np.array([1 / c11, 1 / c22, 1 / c23]) * MU * p.sum() * grid.cell_area
            for name, (theta, alpha) in CURVES.items():
                th, al = math.radians(theta), math.radians(alpha)
                d = np.array([math.sin(th) * math.cos(al), math.sin(th) * math.sin(al), math.cos(th)])
                for t in ts:
                    creep = t * d * unit
                    c0 = time.process_time()
                    res = solve_steady(problem, p, MU, *creep, params=SteadyParams(tol=1e-7))
                    seconds = time.process_time() - c0
                    F = np.array(res.force)
                    fast = {m: float(np.hypot(*(np.array(solve(grid, p, MU, *creep, flexibilities=flex).force) - F))
                                     / np.hypot(*F)) for m, solve in (("fastsim", solve_fastsim),
                                                                      ("fastrip", solve_fastrip))}
                    cases.setdefault((name, t), {})[n] = (F, seconds, fast)
        ref = levels[-1]
        for (name, t), by_n in cases.items():
            F = by_n[ref][0]
            for n in levels[:-1]:
                exact_rows.append(dict(ratio=ratio, curve=name, t=t, elements=n, seconds=by_n[n][1],
                                       error=float(np.hypot(*(by_n[n][0] - F)) / np.hypot(*F))))
            if 41 in by_n and ref != 41:
                resolution_rows.append(dict(ratio=ratio, curve=name, t=t, **{
                    f"{m}_{n}": by_n[n][2][m] for m in ("fastsim", "fastrip") for n in (41, ref)}))
    return exact_rows, resolution_rows


def contact_example(quick):
    """CONTACT's examples/fastsim.inp posed (module docstring): the exact solver on its grid (cell centres on half
    cells: the creepages are moved to the contact centre), FASTSIM (one weighted flexibility and three flexibilities;
    elliptical and parabolic bounds) and FaStrip; Fy (N) and Mz (N mm) beside CONTACT's reference output."""
    a, b, fn, G, nu, mu = 8.0, 4.0, 82000.0, 82000.0, 0.28, 0.3
    eta, phi = -0.000625, 0.000625
    contact = {"exact": (-1.494e4, -4.821e4), "fastsim_parabolic_3flex": (-1.505e4, -3.900e4),
               "fastsim_ellipsoid_3flex": (-1.480e4, -4.829e4), "fastrip": (-1.583e4, -4.816e4),
               "fine_fastsim_parabolic_3flex": (-1.564e4, -3.798e4), "fine_fastsim_ellipsoid_3flex": (-1.465e4, -4.530e4),
               "fine_fastrip": (-1.585e4, -4.757e4)}
    out = {"contact": contact}
    flex = kalker_flexibilities(a, b, G, nu)
    for tag, m in (("", 44), ("fine_", 220)):
        dx, dy = 1.1 * 2 * a / m, 1.1 * 2 * b / m
        grid = Grid(m + 2, m, dx, dy, -(m // 2) - 1, -(m // 2))      # one free column ahead and behind
        xc, yc = -0.5 * dx, -0.5 * dy            # the contact centre: CONTACT's cell centres lie on half cells
        creep = (phi * yc, eta - phi * xc, phi)  # the rigid slip about the contact centre, on grid coordinates
        for bound in ("ellipsoid", "parabolic"):
            p = _ellipse_off(grid, a, b, fn, bound, xc, yc)
            edges = _edges_off(grid, a, b, p > 0, xc, yc)
            for flexibility in ("weighted", "three"):
                r = solve_fastsim(grid, p, mu, *creep, flexibilities=flex, edges=edges, flexibility=flexibility)
                out[f"{tag}fastsim_{bound}_{flexibility}"] = _about_centre(r, xc, yc)
            if bound == "ellipsoid":
                r = solve_fastrip(grid, p, mu, *creep, flexibilities=flex, edges=edges)
                out[f"{tag}fastrip"] = _about_centre(r, xc, yc)
        if tag == "":
            X, Y = grid.mesh()
            pair = MaterialPair.from_moduli(2 * G * (1 + nu), nu, 2 * G * (1 + nu), nu)
            op = HalfSpaceOperator(grid, pair, coupling=False)
            gap = 0.8464e-3 * (X - xc) ** 2 + 0.2406e-2 * (Y - yc) ** 2        # CONTACT's curvatures A1, B1
            normal = solve_normal(op, gap, force=fn, params=NormalParams(tol=1e-10))
            res = solve_steady(SteadyRolling(grid, pair, operator=op), normal.pressure, mu, *creep,
                               params=SteadyParams(tol=1e-8))
            out["exact"] = _about_centre(res, xc, yc)
            out["exact_pmax"] = float(normal.pressure.max())
    del quick
    return out


def _ellipse_off(grid, a, b, fn, bound, xc, yc):
    X, Y = grid.mesh()
    rest = np.clip(1 - ((X - xc) / a) ** 2 - ((Y - yc) / b) ** 2, 0, None)
    if bound == "ellipsoid":
        return 3 * fn / (2 * math.pi * a * b) * np.sqrt(rest)
    return 2 * fn / (math.pi * a * b) * rest


def _edges_off(grid, a, b, contact, xc, yc):
    half = a * np.sqrt(np.clip(1 - ((grid.y - yc) / b) ** 2, 0, None))[:, None] * np.ones(grid.nx)
    half = np.where(contact, half, np.nan)
    return xc + half, xc - half


def _about_centre(res, xc, yc):
    """(Fy, Mz about the contact centre) of a result whose moment is about the grid origin."""
    fx, fy = res.force
    return (float(fy), float(res.moment - (xc * fy - yc * fx)))


def chart(table, exact_rows, creep_map, mdr_map, resolution, path):
    """Accuracy against CPU time per case: left the rolling scenes (FASTSIM, FaStrip against the exact theory on
    the same grid, the exact theory's own error at 21 and 41 elements across against 81), right the shakedown scenes
    (the MDR model against the 3-D solver, the 3-D solver at a/dx = 6 and 12 against 24)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(11.0, 4.4), layout="constrained")
    floor = 1e-4
    sec = creep_map["seconds_per_case"]
    styles = {"fastsim": ("s", "C3", "FASTSIM"), "fastrip": ("^", "C4", "FaStrip")}
    rng = np.random.default_rng(1)
    for model, (marker, colour, label) in styles.items():
        errs = np.concatenate([np.array(r[f"{model}_errors"], dtype=float) for r in table])
        errs = errs[np.isfinite(errs)]
        x = sec[model] * np.exp(rng.normal(0, 0.08, errs.size))
        left.scatter(x, np.maximum(errs, floor), s=6, marker=marker, color=colour, alpha=0.35,
                     label=f"{label} (median {100 * np.median(errs):.1f} %, {1e3 * sec[model]:.2g} ms)")
    for n, colour in ((21, "C9"), (41, "C0")):
        rows = [r for r in exact_rows if r["elements"] == n]
        if rows:
            left.scatter([r["seconds"] for r in rows], [max(r["error"], floor) for r in rows], s=10, color=colour,
                         marker="o", alpha=0.6, label=f"exact theory, {n} across vs 81 (median "
                         f"{100 * statistics.median(r['error'] for r in rows):.1f} %)")
    left.set_xscale("log"), left.set_yscale("log")
    left.set_xlabel("CPU time per case (s)")
    left.set_ylabel("|F - F_ref| / |F_ref|")
    left.set_title("rolling with creepage: fast models vs exact theory\n(a/b 0.2-5, nu 0.28; the map auto uses)",
                   fontsize=10)
    left.legend(fontsize=7, loc="lower left")
    mdr_errors = [e for plane in mdr_map["errors"] for row in plane for e in row if e is not None]
    t_mdr, t_3d = mdr_map["seconds_per_run"]["mdr"], mdr_map["seconds_per_run"]["bem"]
    right.scatter(t_mdr * np.exp(rng.normal(0, 0.08, len(mdr_errors))), np.maximum(mdr_errors, floor), s=12,
                  marker="D", color="C2", alpha=0.6, label=f"MDR model vs 3-D (median "
                  f"{100 * np.median(mdr_errors):.1f} %, {1e3 * t_mdr:.2g} ms/run)")
    for setting, colour in zip(resolution["settings"], ("C9", "C0")):
        per_run = setting["total_wall_s"] / setting["runs"]
        devs = [abs(r["dev"]) for r in setting["rows"] if r.get("dev") is not None]
        right.scatter(per_run * np.exp(rng.normal(0, 0.05, len(devs))), np.maximum(devs, floor), s=12, color=colour,
                      label=f"3-D, a/dx = {setting['a_over_dx']:g} vs 24 (max {100 * max(devs):.2f} %)")
    right.scatter([t_3d], [floor], marker="*", s=80, color="k", label=f"3-D, a/dx = 24 (reference, {t_3d:.2g} s/run)")
    right.set_xscale("log"), right.set_yscale("log")
    right.set_xlabel("CPU time per run (s)")
    right.set_ylabel("|u_sd - u_sd,ref| / u_sd,ref")
    right.set_title("shakedown: MDR vs 3-D (seed's scene, w 0.1-0.4, f_t 0.1-0.9)", fontsize=10)
    right.legend(fontsize=7, loc="lower right")
    for ax in (left, right):
        ax.axhline(0.02, color="0.6", lw=0.8, ls=":")
        ax.set_ylim(floor * 0.8, 10.0)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def print_tables(table, example):
    """The page's tables: per a/b of the issue (0.2, 0.5, 1, 2, 5) and curve the largest and the median error over
    the map's t (FASTSIM / FaStrip, %); CONTACT's example beside CONTACT's output."""
    names = {"xi": "xi", "eta": "eta", "phi": "phi", "eta+phi": "eta + phi", "eta-phi": "eta - phi",
             "xi+eta": "xi + eta"}
    for stat in ("max", "median"):
        print(f"\n{'Largest' if stat == 'max' else 'Median'} error over t = 0.05 ... 20 (FASTSIM / FaStrip):\n")
        print("| a/b | " + " | ".join(names.values()) + " |")
        print("|---" * (len(names) + 1) + "|")
        for ratio in (0.2, 0.5, 1.0, 2.0, 5.0):
            cells = []
            for curve in names:
                r = next(r for r in table if r["ratio"] == ratio and r["curve"] == curve)
                cells.append(f"{100 * r[f'fastsim_{stat}']:.1f} / {100 * r[f'fastrip_{stat}']:.1f}")
            print(f"| {ratio:g} | " + " | ".join(cells) + " |")
    labels = {"exact": "exact theory, 44 x 44", "fastsim_ellipsoid_weighted": "FASTSIM, weighted L, ellipsoid, 44",
              "fastsim_ellipsoid_three": "FASTSIM, 3 L, ellipsoid, 44 (case 3)",
              "fastsim_parabolic_weighted": "FASTSIM, weighted L, parabolic, 44",
              "fastsim_parabolic_three": "FASTSIM, 3 L, parabolic, 44 (case 2)", "fastrip": "FaStrip, 44 (case 4)",
              "fine_fastsim_ellipsoid_weighted": "FASTSIM, weighted L, ellipsoid, 220",
              "fine_fastsim_ellipsoid_three": "FASTSIM, 3 L, ellipsoid, 220 (case 6)",
              "fine_fastsim_parabolic_weighted": "FASTSIM, weighted L, parabolic, 220",
              "fine_fastsim_parabolic_three": "FASTSIM, 3 L, parabolic, 220 (case 5)",
              "fine_fastrip": "FaStrip, 220 (case 7)"}
    refs = {"exact": "exact", "fastsim_parabolic_three": "fastsim_parabolic_3flex",
            "fastsim_ellipsoid_three": "fastsim_ellipsoid_3flex", "fastrip": "fastrip",
            "fine_fastsim_parabolic_three": "fine_fastsim_parabolic_3flex",
            "fine_fastsim_ellipsoid_three": "fine_fastsim_ellipsoid_3flex", "fine_fastrip": "fine_fastrip"}
    print("\n| CONTACT's fastsim example | Fy (N) | Mz (N mm) | CONTACT Fy, Mz | Fy against CONTACT |")
    print("|---|---|---|---|---|")
    for key, label in labels.items():
        fy, mz = example[key]
        ref = example["contact"].get(refs.get(key, ""))
        beside = f"{ref[0]:.4g}, {ref[1]:.4g}" if ref else ""
        diff = f"{100 * (fy / ref[0] - 1):+.1f} %" if ref else f"{100 * (fy / example['exact'][0] - 1):+.1f} % (exact)"
        print(f"| {label} | {fy:.5g} | {mz:.5g} | {beside} | {diff} |")


def print_auto_tables(mdr_map):
    """The page's `auto` numbers: the MDR map's u_sd errors, and both held-out sets against the maps' predictions
    (how many fast models or MDR runs `auto` takes per request; the largest measured / predicted)."""
    from rollcontact.solver.fastsim.error_map import load_error_map
    from rollcontact.solver.mdr.error_map import load_mdr_map
    ax = mdr_map["axes"]
    print("\n| alignment | w | " + " | ".join(f"f_t = {f:g}" for f in ax["f_t"]) + " |")
    print("|---" * (len(ax["f_t"]) + 2) + "|")
    for angle, plane in zip(ax["angle"], mdr_map["errors"]):
        for w, row in zip(ax["w"], plane):
            cells = " | ".join("-" if v is None else f"{100 * v:.1f}" for v in row)
            print(f"| {angle:g} deg | {w:g} | {cells} |")
    emap, mmap = load_error_map(), load_mdr_map()
    held = load_json(ROOT / "tests" / "solver" / "data" / "fastsim_held_out.json")
    for key in ("rows", "rows_fine"):
        worst, taken = 0.0, {}
        for row in held[key]:
            predicted = {m: emap.predict(m, row["ratio"], row["nu"], row["xi_hat"], row["eta_hat"], row["phi_hat"])
                         for m in emap.models}
            worst = max([worst] + [row[m] / p for m, p in predicted.items() if p])
            for request in (0.02, 0.05, 0.1, 0.2):
                fast = any(p is not None and p <= request for p in predicted.values())
                taken[request] = taken.get(request, 0) + fast
        print(f"held-out rolling ({key}, {len(held[key])} scenes): largest measured / predicted {worst:.3f}; a fast "
              f"model taken at requests 2 / 5 / 10 / 20 %: {' / '.join(str(taken[r]) for r in sorted(taken))}")
    rows = load_json(ROOT / "tests" / "cases" / "data" / "mdr_held_out.json")["rows"]
    pairs = [(r["error"], mmap.predict(dict(angle=r["angle"], w=r["w"], f_t=r["f_t"]))) for r in rows]
    finite = [(e, p) for e, p in pairs if p is not None and math.isfinite(p)]
    print(f"held-out shakedown ({len(rows)} scenes): {len(finite)} with a finite prediction, largest measured / "
          f"predicted {max(e / p for e, p in finite):.3f}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--output", default="results/creep_fidelity", help="folder for the PNG and the JSON")
    parser.add_argument("--quick", action="store_true", help="a/b = 1 only for the exact solver's error (seconds)")
    args = parser.parse_args(argv)
    start, load = time.perf_counter(), os.getloadavg()
    creep_map = load_json(ROOT / "solver" / "fastsim" / "error_map.json")
    mdr_map = load_json(ROOT / "solver" / "mdr" / "error_map.json")
    resolution = load_json(HERE / "results" / "default_resolution.json")
    table = error_table(creep_map)
    exact_rows, resolution_rows = exact_discretisation(creep_map, args.quick)
    example = contact_example(args.quick)
    out = Path(args.output)
    chart(table, exact_rows, creep_map, mdr_map, resolution, out / "creep_fidelity.png")
    data = dict(date=datetime.date.today().isoformat(), loadavg_before=load, loadavg_after=os.getloadavg(),
                wall_time_s=time.perf_counter() - start, quick=args.quick,
                table=[{k: v for k, v in r.items() if not k.endswith("_errors")} for r in table],
                exact_discretisation=exact_rows, resolution=resolution_rows,
                resolution_largest_change={m: max((abs(r[f"{m}_41"] - r[f"{m}_81"]) for r in resolution_rows),
                                                  default=None) for m in ("fastsim", "fastrip")},
                contact_example=example,
                seconds_per_case=creep_map["seconds_per_case"], mdr_seconds_per_run=mdr_map["seconds_per_run"])
    (out / "creep_fidelity.json").write_text(json.dumps(data, indent=1) + "\n")
    print_tables(table, example)
    print_auto_tables(mdr_map)
    print((out / "creep_fidelity.png").resolve())
    return 0


if __name__ == "__main__":
    sys.exit(main())

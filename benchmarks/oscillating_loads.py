"""Mindlin-Deresiewicz cycles on the paper's grid: the cost of one period of an oscillating tangential force
without rolling, and its accuracy against the closed forms (docs/theory.md §11.2).

    .venv/bin/python benchmarks/oscillating_loads.py [--quick] [--repeats 5] [--periods 4] [-o DIR]   # DIR/oscillating_loads.json
    .venv/bin/python benchmarks/oscillating_loads.py --accuracy [--quick] [-o DIR]   # DIR/oscillating_loads_accuracy.json

The paper scene (`cases.scene.default_scene`: its materials, Fn, mu, dx = 0.2 mm) with motion.w = 0, load.ft = 0
and load.ft_amplitude = x for x = 0.3, 0.6, 0.9 (Ft = x mu Fn sin(2 pi k/24), 24 steps per period, the default),
--periods periods, one FFTW thread, output.fields = "none", kept in memory. Per x, after one warm-up run (numba
cache, FFTW wisdom), --repeats runs round robin; reported as medians:

* wall per period: (wall of the run - wall of its loading step) / periods (s), the figure the issue asks for
  (target: well under 1 s);
* products per step (normal, tangential) and the floor per period: the products of the steady periods times the
  product times measured on the same grid right before and after each run (one `op.normal`, one `op.tangential`,
  medians of 50), i.e. what the FFTs alone cost; wall / floor;
* accuracy of the last period: the largest |U - U_MD| over it relative to U(F*), and the frictional work of the
  period (/summary dissipation_per_period) against the Mindlin-Deresiewicz loop area
  4 mu Fn U0 [6/5 - x - x(1-x)^(2/3) - (6/5)(1-x)^(5/3)]; the paper's nu2 = 0.5 makes Mindlin's closed form a few
  0.1 % off in U (docs/theory.md P10), more in the loop area (docs/oscillating_loads.md).

--accuracy instead: (1) the Mindlin-Deresiewicz cycle (2 periods of 24 steps, the second compared) on the
scene's default grid for the amplitude (grid.dx left out: 4 elements across the slip annulus, at least a/12,
cases.scene.limits) and at dx = 0.4 / 0.2 / 0.1 mm (a/12, a/24, a/48) for the paper's materials and for two identical bodies with nu = 0 and
the same E* (where the closed form is exact), the loop error max |U - U_MD| / U(F*) and the frictional work of the
cycle against the closed form; (2) four histories of varying Fn and Ft without rolling on the default grid,
the 3-D U against the 1-D MDR model with per-spring memory (max |U_3D - U_MDR| / max |U_MDR|) and the work per
period of both (docs/theory.md §11.3); (3) the same with rolling at w = 0.23, both settings, where the MDR is not exact.
--accuracy --quick: only x = 0.6 on the default grid and the Mindlin-Deresiewicz history without rolling (seconds).
"""
import argparse
from pathlib import Path
import statistics

import numpy as np

import _record
from rollcontact.cases import api
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere

from rolling_paper import product_times   # one op.normal / op.tangential, medians (benchmarks/rolling_paper.py)

HERE = Path(__file__).resolve().parent
AMPLITUDES = (0.3, 0.6, 0.9)


def accuracy(scene, result, x):
    """(max |U - U_MD| / U(F*) over the last period, dissipation of the last period / closed form - 1)."""
    pair, ld = scene.material_pair, scene.load
    cm = CattaneoMindlin(HertzSphere(scene.equivalent_radius, pair.E_star, ld.Fn), ld.mu, pair.G_star)
    h = result.history
    last = np.flatnonzero(h["period"] == h["period"].max())
    n = last.size
    f = np.clip(h["F_x"][last] / (ld.mu * ld.Fn), -x, x)
    ref = [cm.unloading_shift(x, fi) if n // 4 <= k + 1 <= 3 * n // 4 else cm.reloading_shift(x, fi)
           for k, fi in enumerate(f)]
    loop = float(np.max(np.abs(h["U_x"][last] - ref)) / cm.shift(x))
    return loop, result.summary["dissipation_per_period"] / cm.cycle_dissipation(x) - 1.0


PAPER = {"materials.E1": 206e3, "materials.nu1": 0.3, "materials.E2": 4.35, "materials.nu2": 0.5, "geometry.R": 40.0,
         "load.Fn": 21.19, "load.mu": 0.93}   # the paper scene's keys but its grid (Table 1, cases/paper_parallel.toml)
NU0 = {"materials.E1": 11.5997, "materials.nu1": 0.0, "materials.E2": 11.5997, "materials.nu2": 0.0}
HISTORIES = {"proportional (Ft = 0.3 mu Fn(t), Fn 0.5-1.5 Fn)":
             {"load.ft": 0.3, "load.ft_amplitude": 0.15, "load.fn_amplitude": 0.5, "load.phase": -90.0},
             "Fn +-40 % at constant Ft (f_t = 0.3)": {"load.ft": 0.3, "load.fn_amplitude": 0.4},
             "Ft/Fn changing, Ft reversing (0.2 +- 0.3, Fn +-30 %)":
             {"load.ft": 0.2, "load.ft_amplitude": 0.3, "load.fn_amplitude": 0.3},
             "Ft 0 +- 0.6 (Mindlin-Deresiewicz)": {"load.ft": 0.0, "load.ft_amplitude": 0.6}}


def accuracy_tables(quick=False):
    """The --accuracy tables (see the module docstring) as lists of dicts, printed as they come; `quick`: x = 0.6 on
    the default grid and the Mindlin-Deresiewicz history without rolling only."""
    md, hist = [], []
    base = {"motion.w": 0, "motion.periods": 2, "load.ft": 0, "output.fields": "none"}
    for dx in ("default",) if quick else ("default", 0.4, 0.2, 0.1):
        for name, mats in (("nu = 0", NU0), ("paper", {})):
            for x in (0.6,) if quick else AMPLITUDES:
                over = {**base, **mats, "load.ft_amplitude": x}
                if dx == "default":   # the paper scene without grid.dx: cases.scene.limits' default for the amplitude
                    scene = rollcontact_scene({**PAPER, **over})
                else:
                    scene = api.load_scene(overrides={**over, "grid.dx": dx})
                loop, work = accuracy(scene, api.run(scene), x)
                md.append(dict(materials=name, dx=dx if dx != "default" else scene.grid.dx, default=dx == "default",
                               x=x, loop_error=loop, dissipation_error=work))
                print(f"MD {name:6s} dx = {dx} ({scene.grid.dx} mm): x = {x}: loop {100 * loop:.3f} %, work "
                      f"{100 * work:+.3f} %", flush=True)
    plain = {"geometry.R": 40.0, "motion.periods": 2, "output.fields": "none"}
    for w, angle in ((0.0, 90.0),) if quick else ((0.0, 90.0), (0.23, 0.0), (0.23, 90.0)):
        for name, mats in (("nu = 0", NU0), ("paper", {})):
            for label, loads in HISTORIES.items():
                if quick and "Mindlin" not in label:
                    continue
                over = {**plain, **mats, **loads, "motion.w": w, "motion.angle": angle}
                scene = rollcontact_scene(over)
                bem, mdr = api.run(scene), api.run(scene.with_overrides({"solver.fidelity": "mdr"}))
                U3, U1 = bem.history["U_x"], mdr.history["U_x"]
                row = dict(history=label, materials=name, w=w, angle=angle,
                           error=float(np.max(np.abs(U3 - U1)) / np.max(np.abs(U1))),
                           work_bem=bem.summary["dissipation_per_period"],
                           work_mdr=mdr.summary["dissipation_per_period"], grid_dx=scene.grid.dx)
                hist.append(row)
                print(f"MDR {name:6s} w = {w} angle {angle:g}: {label}: max|U3 - U1|/max|U1| = "
                      f"{100 * row['error']:.3f} %, work per period {row['work_bem']:.4g} / {row['work_mdr']:.4g} "
                      "N mm (3-D / MDR)", flush=True)
    return md, hist


def rollcontact_scene(overrides):
    """A scene with only the given keys (the geometry from geometry.R), not the paper scene's."""
    from rollcontact.cases.scene.scene import Scene
    data = {}
    for key, value in overrides.items():
        sec, name = key.split(".")
        data.setdefault(sec, {})[name] = value
    return Scene.from_dict(data)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("--repeats", type=int, default=5, help="timed runs per amplitude (median; default 5)")
    parser.add_argument("--periods", type=int, default=4, help="periods per run (default 4)")
    _record.add_output(parser)
    parser.add_argument("--accuracy", action="store_true", help="the accuracy tables instead of the timing")
    parser.add_argument("--quick", action="store_true", help="timing: 1 repeat of 2 periods; --accuracy: a subset")
    args = parser.parse_args(argv)
    if args.quick:
        args.repeats, args.periods = 1, 2
    if args.accuracy:
        md, hist = accuracy_tables(args.quick)
        _record.write("oscillating_loads_accuracy", {"quick": args.quick, "mindlin_deresiewicz": md, "mdr": hist},
                      args.output)
        return
    scenes = {x: api.load_scene(overrides={"motion.w": 0, "load.ft": 0, "load.ft_amplitude": x,
                                           "motion.periods": args.periods, "output.fields": "none"})
              for x in AMPLITUDES}
    for scene in scenes.values():
        api.run(scene)                                  # warm-up
    walls = {x: [] for x in AMPLITUDES}
    ratios = {x: [] for x in AMPLITUDES}
    results = {}
    for _ in range(args.repeats):
        for x, scene in scenes.items():
            _, tn0, tt0 = product_times(scene)
            r = api.run(scene)
            _, tn1, tt1 = product_times(scene)
            h = r.history
            steady = h["period"] > 0
            per_period = float(np.sum(h["wall_time"][steady]) / args.periods)
            floor = (np.sum(h["normal_iterations"][steady]) * 0.5 * (tn0 + tn1)
                     + np.sum(h["tangential_iterations"][steady]) * 0.5 * (tt0 + tt1)) / args.periods
            walls[x].append((r.wall_time - float(h["wall_time"][~steady].sum())) / args.periods)
            ratios[x].append(per_period / floor)
            results[x] = (r, floor, tn0, tt0)
    rows = []
    for x, scene in scenes.items():
        r, floor, tn, tt = results[x]
        h = r.history
        steady = h["period"] > 0
        loop, work = accuracy(scene, r, x)
        row = dict(x=x, grid=f"{r.summary['nx']}x{r.summary['ny']}", dx=scene.grid.dx,
                   steps_per_period=scene.motion.steps_per_period, periods=args.periods,
                   wall_per_period_s=statistics.median(walls[x]), walls_per_period=walls[x],
                   normal_it_per_step=float(np.mean(h["normal_iterations"][steady])),
                   tangential_it_per_step=float(np.mean(h["tangential_iterations"][steady])),
                   floor_per_period_s=floor, wall_over_floor=statistics.median(ratios[x]),
                   pair_ms=tn * 1e3, tangential_product_ms=tt * 1e3, loop_error=loop, dissipation_error=work,
                   dissipation_per_period=r.summary["dissipation_per_period"], state=r.state)
        rows.append(row)
        print(f"x = {x}: grid {row['grid']}, wall per period {row['wall_per_period_s']:.3f} s (runs "
              f"{', '.join(f'{w:.3f}' for w in walls[x])}), products/step {row['normal_it_per_step']:.1f} + "
              f"{row['tangential_it_per_step']:.1f}, floor {floor:.3f} s, wall/floor {row['wall_over_floor']:.2f}; "
              f"loop max|U - U_MD|/U* = {100 * loop:.3f} %, work per period {row['dissipation_per_period']:.5g} N mm "
              f"({100 * work:+.2f} % against the closed form)", flush=True)
    _record.write("oscillating_loads", {"repeats": args.repeats, "rows": rows}, args.output)


if __name__ == "__main__":
    main()

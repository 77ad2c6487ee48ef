"""Speed of the friction laws and temperatures against the same runs without them (issue #34's targets):

    .venv/bin/python benchmarks/friction_speed.py [--quick] [--repeats 3] [-o DIR]

* creep curve: a 20-point creep-force curve (xi = 0.02 ... 4 xi*, solver.creep.creep_curve) with the exponential law
  (mu_kin = 0.15, mu_1 = 0.15, s_1 = 100 mm/s at V = 30 m/s: the curve peaks near 1.7 xi* and falls) against the
  Coulomb curve (mu = 0.3) on 60 x 60 elements (ellipse_grid n = 58; steel on steel, a = 6, b = 4 mm, Fn = 50 kN),
  both to tol 1e-8; target: within 2x;
* steady with temperatures: cases/creep_steady.toml at rolling.speed = 30 m/s with [thermal] (steel, 50 W/(m K),
  7850 kg/m^3, 450 J/(kg K)) against the same scene without, through `rollcontact.run` (the moving heat source's
  influence coefficients are built once per run); target: within 1.5x;
* paper scene with a velocity law: cases/paper_perpendicular.toml at motion.speed = 10 mm/s with the exponential law
  mu_kin = 0.62, mu_1 = 0.31 (mu_static = 0.93, the scene's mu), s_1 = 10 mm/s (and 1 mm/s, steeper) against the
  scene as it is; target: within 1.5x.

Process CPU time (the machine is shared: wall time includes waiting for a core), medians of --repeats after one
warm-up (numba kernels compiled and FFTW plans made); the ratio to the run without the law in the same process is the
figure to compare across machines. --quick: one repeat, the paper scene over 3 periods. Writes DIR/friction_speed.json
(default results/benchmarks/; the committed JSON: -o benchmarks/results) with the machine's load (os.getloadavg) before and after.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import platform
import statistics
import time
from pathlib import Path

import numpy as np


def cpu(fn, repeats):
    """(result, median CPU seconds, median wall seconds) of fn() over `repeats` runs."""
    cpus, walls, out = [], [], None
    for _ in range(repeats):
        c, w = time.process_time(), time.perf_counter()
        out = fn()
        cpus.append(time.process_time() - c)
        walls.append(time.perf_counter() - w)
    return out, statistics.median(cpus), statistics.median(walls)


def creep_curve_case(repeats):
    from rollcontact.bem import MaterialPair
    from rollcontact.solver.creep import (SteadyParams, SteadyRolling, creep_curve, ellipse_grid, hertz_pressure,
                                          kalker_coefficients, saturation_creepage)
    from rollcontact.solver.friction import FrictionLaw, FrictionParams, LocalFriction, solve_steady_friction
    a, b, fn, nu = 6.0, 4.0, 50e3, 0.28
    pair = MaterialPair.from_moduli(210e3, nu, 210e3, nu)
    grid = ellipse_grid(a, b, 58)
    p = hertz_pressure(grid, a, b, fn)
    problem = SteadyRolling(grid, pair)
    xs = saturation_creepage(pair.G, math.sqrt(a * b), kalker_coefficients(a / b, nu)[0], 0.3, fn)
    creep = np.zeros((20, 3))
    creep[:, 0] = xs * np.geomspace(0.02, 4.0, 20)
    params = SteadyParams(tol=1e-8)
    friction = LocalFriction(FrictionLaw("exponential", mu_kin=0.15, mu_1=0.15, s_1=100.0), speed=30000.0,
                             params=FrictionParams(tol=1e-8))

    def law_curve():
        states = []

        def solve(problem, pressure, mu, xi, eta, phi, *, initial=None, params=None):
            res = solve_steady_friction(problem, pressure, friction, xi, eta, phi, initial=initial, params=params,
                                        mu_initial=states[-1] if states else None)
            states.append(res.friction.mu)
            return res
        return creep_curve(problem, p, 0.3, creep, params=params, solve=solve)

    creep_curve(problem, p, 0.3, creep[:2], params=params)          # warm-up
    coulomb, c_cpu, c_wall = cpu(lambda: creep_curve(problem, p, 0.3, creep, params=params), repeats)
    law, l_cpu, l_wall = cpu(law_curve, repeats)
    force = -law.force[:, 0] / (0.3 * fn)
    return {"grid": list(grid.shape), "coulomb_cpu_s": c_cpu, "law_cpu_s": l_cpu, "coulomb_wall_s": c_wall,
            "law_wall_s": l_wall, "ratio": l_cpu / c_cpu, "target": 2.0, "coulomb_sweeps": int(coulomb.sweeps.sum()),
            "law_sweeps": int(law.sweeps.sum()), "law_F_over_mu_static_Fn": force.tolist(),
            "peak_at_xi_over_xi_star": float(creep[int(np.argmax(force)), 0] / xs)}


def steady_thermal_case(repeats):
    import rollcontact
    from rollcontact.cases.scene.scene import shipped_scene_path
    base = rollcontact.load_scene(shipped_scene_path("creep_steady.toml"), overrides={"rolling.speed": 30000.0})
    hot = base.with_overrides({f"thermal.{k}{i}": v for i in (1, 2) for k, v in
                               (("conductivity", 50.0), ("density", 7850.0), ("heat_capacity", 450.0))})
    rollcontact.run(base)                                          # warm-up
    rollcontact.run(hot)
    plain, p_cpu, p_wall = cpu(lambda: rollcontact.run(base), repeats)
    warm, h_cpu, h_wall = cpu(lambda: rollcontact.run(hot), repeats)
    return {"grid": [plain.summary["nx"], plain.summary["ny"]], "plain_cpu_s": p_cpu, "thermal_cpu_s": h_cpu,
            "plain_wall_s": p_wall, "thermal_wall_s": h_wall, "ratio": h_cpu / p_cpu, "target": 1.5,
            "T1_max": warm.summary["T1_max"], "frictional_power_W": warm.summary["frictional_power"]}


def paper_case(repeats, periods):
    import rollcontact
    scene = rollcontact.load_scene(overrides={"motion.periods": periods, "motion.speed": 10.0})
    rollcontact.run(scene.with_overrides({"motion.periods": 1}))      # warm-up
    plain, p_cpu, p_wall = cpu(lambda: rollcontact.run(scene), repeats)
    out = {"periods": periods, "coulomb_cpu_s": p_cpu, "coulomb_wall_s": p_wall, "target": 1.5,
           "coulomb_state": plain.summary["state"], "coulomb_u_sd": plain.summary.get("u_sd")}
    for s1 in (10.0, 1.0):
        law = scene.with_overrides({"friction.law": "exponential", "friction.mu_kin": 0.62, "friction.mu_1": 0.31,
                                    "friction.s_1": s1})
        res, l_cpu, l_wall = cpu(lambda: rollcontact.run(law), repeats)
        its = np.asarray(res.history["friction_iterations"])
        out[f"s_1={s1:g}"] = {"cpu_s": l_cpu, "wall_s": l_wall, "ratio": l_cpu / p_cpu, "state": res.summary["state"],
                              "u_sd": res.summary.get("u_sd"), "du": res.summary.get("du"),
                              "solves_per_step": float(its.mean()), "most_solves": int(its.max()),
                              "friction_feedback": res.summary.get("friction_feedback")}
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="one repeat; the paper scene over 3 periods")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("-o", "--out", type=Path, default=Path("results") / "benchmarks",
                    help="output folder (default results/benchmarks; the committed figures: benchmarks/results)")
    args = ap.parse_args(argv)
    repeats = 1 if args.quick else args.repeats
    load = os.getloadavg()
    rows = {"creep_curve": creep_curve_case(repeats), "steady_thermal": steady_thermal_case(repeats),
            "paper_velocity_law": paper_case(repeats, 3 if args.quick else 10)}
    rows.update(date=time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), load_before=load, load_after=os.getloadavg(),
                machine=f"{platform.machine()} {platform.processor() or ''}".strip(), quick=args.quick,
                command="benchmarks/friction_speed.py" + (" --quick" if args.quick else f" --repeats {repeats}"))
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / ("friction_speed_quick.json" if args.quick else "friction_speed.json")
    path.write_text(json.dumps(rows, indent=1) + "\n")
    cc, st, pp = rows["creep_curve"], rows["steady_thermal"], rows["paper_velocity_law"]
    print(f"creep curve (60 x 60, 20 points): Coulomb {cc['coulomb_cpu_s']:.2f} s, exponential law "
          f"{cc['law_cpu_s']:.2f} s CPU: {cc['ratio']:.2f}x (target 2x)")
    print(f"steady with temperatures: {st['plain_cpu_s']:.2f} s without, {st['thermal_cpu_s']:.2f} s with: "
          f"{st['ratio']:.2f}x (target 1.5x)")
    for key in ("s_1=10", "s_1=1"):
        print(f"paper scene, {pp['periods']} periods, law {key} mm/s: {pp[key]['cpu_s']:.2f} s against "
              f"{pp['coulomb_cpu_s']:.2f} s: {pp[key]['ratio']:.2f}x (target 1.5x), {pp[key]['solves_per_step']:.2f} "
              f"solves per step")
    print(f"load average {load[0]:.1f} -> {rows['load_after'][0]:.1f}; written to {path}")


if __name__ == "__main__":
    main()

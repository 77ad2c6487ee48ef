"""How many steps a load cycle needs: the frictional work of a Mindlin-Deresiewicz cycle against the number of steps
per cycle and the load phase (the rule of cases.scene.limits: MIN_STEPS_PER_LOAD_CYCLE, PEAK_MISS).

    .venv/bin/python benchmarks/load_cycle_sampling.py [--quick] [-o DIR]

The paper scene (its materials, Fn, mu) without rolling (motion.w = 0), load.ft = 0, load.ft_amplitude = x for
x = 0.3, 0.6, 0.9 (quick: 0.6), on the grid dx = 0.4 mm (a/12), 2 periods of N steps (motion.steps_per_period = N,
one load cycle per period), the work of the second (/summary dissipation_per_period), for N = 4, 6, 8, 12, 16, 24,
32, 48, 96, 192 (quick: 4, 8, 24, 96), at phase 0 (the peaks on steps when N is a multiple of 4) and at the phase
90 - 180/N deg that puts the peaks half a step off (the worst). Reported: the work, its deviation from the 192-step
phase-0 value (the converged work on this grid), the peak shortfall 1 - cos(d) of the sampled load (d the phase from
a peak to its nearest step), and the closed-form loop area 4 mu Fn U0 [6/5 - x - x(1-x)^(2/3) - (6/5)(1-x)^(5/3)]
(which the grid's own error separates from the sampling's). Scenes the rule refuses are run without the scene's run
checks (Scene.from_dict(run_limits=False)), to measure what they would give. Writes DIR/load_cycle_sampling.json
(default DIR: results/benchmarks; benchmarks/results to refresh the committed figures) and prints a table.
"""
import argparse
import json
import math
from pathlib import Path
import time

from rollcontact.cases import api
from rollcontact.cases.scene.scene import Scene, default_scene
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere


def md_scene(x: float, n: int, phase: float) -> Scene:
    data = default_scene().with_overrides({"motion.w": 0, "load.ft": 0, "load.ft_amplitude": x, "load.phase": phase,
                                           "motion.steps_per_period": 24, "motion.periods": 2, "grid.dx": 0.4,
                                           "grid.dy": 0.4, "motion.dW": 0.4, "output.fields": "none"}).to_dict()
    data["motion"]["steps_per_period"] = n
    return Scene.from_dict(data, name="md", run_limits=False)


def peak_miss(n: int, phase: float) -> float:
    """1 - cos(d), d the load phase from a peak (or trough) to its nearest step, of N steps per cycle."""
    spacing = 2 * math.pi / n
    worst = 0.0
    for p in (math.pi / 2, 3 * math.pi / 2):
        r = (p - math.radians(phase)) % spacing
        worst = max(worst, min(r, spacing - r))
    return 1 - math.cos(worst)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="x = 0.6 and N = 4, 8, 24, 96 only")
    parser.add_argument("-o", "--output", default="results/benchmarks", help="output folder (default results/benchmarks)")
    args = parser.parse_args(argv)
    amplitudes = (0.6,) if args.quick else (0.3, 0.6, 0.9)
    counts = (4, 8, 24, 96) if args.quick else (4, 6, 8, 12, 16, 24, 32, 48, 96, 192)
    base = default_scene()
    hertz = HertzSphere(base.geometry.R, base.material_pair.E_star, base.load.Fn)
    md = CattaneoMindlin(hertz, base.load.mu, base.material_pair.G_star)
    rows, t0 = [], time.process_time()
    for x in amplitudes:
        reference = api.run(md_scene(x, 192, 0.0)).summary["dissipation_per_period"]
        closed = md.cycle_dissipation(x)
        for n in counts:
            for phase in (0.0, 90.0 - 180.0 / n):
                work = (reference if (n, phase) == (192, 0.0)
                        else api.run(md_scene(x, n, phase)).summary["dissipation_per_period"])
                rows.append(dict(x=x, steps_per_cycle=n, phase=phase, work=work,
                                 deviation=work / reference - 1.0, peak_miss=peak_miss(n, phase),
                                 closed_form=closed))
                print(f"x = {x:.1f}  N = {n:3d}  phase {phase:7.3f}: work {work:.6g} N mm, {100 * (work / reference - 1):+7.2f} %"
                      f" of 192 steps, peak {100 * rows[-1]['peak_miss']:.3g} % short (closed form {closed:.6g})",
                      flush=True)
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "load_cycle_sampling.json"
    path.write_text(json.dumps({"date": time.strftime("%Y-%m-%d"), "cpu_seconds": time.process_time() - t0,
                                "quick": args.quick, "rows": rows}, indent=1) + "\n")
    print(path)


if __name__ == "__main__":
    main()

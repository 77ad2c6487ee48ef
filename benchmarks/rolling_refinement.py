"""Tangential products per rolling step of the paper scene under grid refinement (issue #3's warm steps in use).

    .venv/bin/python benchmarks/rolling_refinement.py [--dx 0.2 0.1 0.05] [--ft 0.46 0.77] [--angle 90]

The seed scene (`cases.scene.default_scene`, perpendicular, w = 0.23, 10 periods) with grid.dx = grid.dy =
motion.dW = dx (mm); the step used is W/ceil(W/dx), so every rolling step moves the profile by at most one
cell: the "small profile change" after which issue #3 asks for <= 15 products per warm-started step. For each (f_t, dx): the run's state, the tangential products
(every `op.tangential` call, re-synchronisations included) per rolling step (period >= 1; mean, median, 90th
percentile, max, share of steps at <= 15), normal iterations per step and the wall time of the whole run (one
FFTW thread, shared machine: indicative). JSON to DIR/rolling_refinement.json (-o DIR, default
results/benchmarks/).
"""
from pathlib import Path
import tempfile
import time

import numpy as np

import _record
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import default_scene


def measure(dx, ft, angle, periods):
    scene = default_scene().with_overrides([f"grid.dx={dx}", f"grid.dy={dx}", f"motion.dW={dx}",
                                            f"motion.periods={periods}", f"load.ft={ft}", f"motion.angle={angle}",
                                            "output.fields=last"])
    with tempfile.TemporaryDirectory() as tmp:
        t = time.perf_counter()
        data = run_scene(scene, Path(tmp) / "run.h5")
        wall = time.perf_counter() - t
    h = data.history
    rolling = np.asarray(h["period"]) >= 1
    t_it = np.asarray(h["tangential_iterations"])[rolling]
    return dict(dx_mm=dx, f_t=ft, angle_deg=angle, periods=periods, state=data.summary.get("state"),
                grid=[len(data.y), len(data.x)], rolling_steps=int(t_it.size),
                tangential_mean=float(t_it.mean()), tangential_median=float(np.median(t_it)),
                tangential_p90=float(np.percentile(t_it, 90)), tangential_max=int(t_it.max()),
                share_at_most_15=float(np.mean(t_it <= 15)),
                normal_mean=float(np.mean(h["normal_iterations"])), wall_s=wall)


def main():
    ap = _record.parser(__doc__)
    ap.add_argument("--dx", type=float, nargs="*", default=[0.2, 0.1, 0.05])
    ap.add_argument("--ft", type=float, nargs="*", default=[0.46, 0.77])
    ap.add_argument("--angle", type=float, default=90.0)
    ap.add_argument("--periods", type=int, default=10)
    args = ap.parse_args()
    rows = []
    for ft in args.ft:
        for dx in args.dx:
            row = measure(dx, ft, args.angle, args.periods)
            rows.append(row)
            print(f"f_t={ft} dx={dx} (grid {row['grid'][0]}x{row['grid'][1]}): {row['state']}, "
                  f"{row['rolling_steps']} rolling steps, tangential products "
                  f"mean {row['tangential_mean']:.1f} median {row['tangential_median']:.0f} "
                  f"p90 {row['tangential_p90']:.0f} max {row['tangential_max']}, "
                  f"{row['share_at_most_15']:.0%} at <= 15; normal {row['normal_mean']:.1f}; "
                  f"wall {row['wall_s']:.1f} s", flush=True)
    _record.write("rolling_refinement", {"benchmark": "rolling_refinement", "rows": rows}, args.output)


if __name__ == "__main__":
    main()

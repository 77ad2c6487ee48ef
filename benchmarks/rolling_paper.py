"""Rolling at the paper's resolution: cost per rolling step of the nested normal/tangential iteration.

    .venv/bin/python benchmarks/rolling_paper.py [--repeats 3] [-o DIR]    # DIR/rolling_paper.json

The seed scene (`cases.scene.default_scene`, dx = dW = 0.2 mm, 10 periods) in both settings
(motion.angle = 0: rolling parallel to Ft; 90: perpendicular) at (f_t, w) = (0.46, 0.23) (shakedown) and
(0.77, 0.23) (ratcheting), one FFTW thread. For each case: the wall time of the whole `run_scene` (median
of --repeats, after one warm-up run that pays numba loading and FFTW planning; the four cases run round robin,
so that a noisy minute on the shared machine touches all of them), the number of steps, normal and tangential
iterations per step (each iteration = one `op.normal` resp. one `op.tangential` product), and the product times
measured on the same grid around each run:

* t_n  = one `op.normal` (one padded forward + inverse real FFT with the spectral product: "the convolution
  pair");
* t_t  = one `op.tangential` (two forward + two inverse: about two pairs).

floor = sum over steps of (normal iterations x t_n + tangential iterations x t_t), i.e. what the FFT products
alone cost; ratio = wall time / floor (target <= 2), taken per run with t_n and t_t timed right before and
after that run (the mean of the two medians of 50), and reported as the median over the runs. The table also
gives the ratio against the simpler floor (all products x t_n). Timings on a shared 2-core machine are noisy
by 10-40 %: the per-run ratios are listed.
"""
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

import _record
from rollcontact.cases.run.discretise import scene_grid, scene_path
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import default_scene
from rollcontact.bem.operator import HalfSpaceOperator

CASES = [("parallel", 0, 0.46), ("perpendicular", 90, 0.46), ("parallel", 0, 0.77), ("perpendicular", 90, 0.77)]


def product_times(scene, repeats=50):
    path = scene_path(scene)
    grid = scene_grid(scene, path)
    op = HalfSpaceOperator(grid, scene.material_pair, threads=1)
    rng = np.random.default_rng(0)
    p = rng.random(grid.shape)
    tx, ty = rng.random((2,) + grid.shape)
    out1, out2 = np.empty(grid.shape), np.empty((2,) + grid.shape)

    def med(fn):
        ts = []
        for _ in range(repeats):
            t = time.perf_counter()
            fn()
            ts.append(time.perf_counter() - t)
        return statistics.median(ts)

    return grid, med(lambda: op.normal(p, out=out1)), med(lambda: op.tangential(tx, ty, out=out2))


class Case:
    """One setting: its scene and the measurements of its runs."""

    def __init__(self, name, angle, ft, tmp):
        self.name, self.angle, self.ft, self.tmp = name, angle, ft, Path(tmp)
        self.tmp.mkdir(parents=True, exist_ok=True)
        self.scene = default_scene().with_overrides([f"motion.angle={angle}", f"load.ft={ft}", "motion.w=0.23",
                                                     "output.fields=last"])
        run_scene(self.scene, self.tmp / "warm.h5")  # warm-up: numba cache, FFTW wisdom
        self.walls, self.t_n, self.t_t, self.ratios, self.data = [], [], [], [], None

    def run_once(self):
        """One timed run with the products timed right before and after it, so its ratio sees the load the
        run saw (the shared machine's speed drifts by 20-40 % over minutes)."""
        self.grid, tn0, tt0 = product_times(self.scene)
        t = time.perf_counter()
        out = run_scene(self.scene, self.tmp / f"run{len(self.walls)}.h5")
        self.walls.append(time.perf_counter() - t)
        _, tn1, tt1 = product_times(self.scene)
        self.t_n.append(0.5 * (tn0 + tn1))
        self.t_t.append(0.5 * (tt0 + tt1))
        self.data = out
        h = self.data.history
        self.ratios.append(self.walls[-1] / (np.sum(h["normal_iterations"]) * self.t_n[-1]
                                             + np.sum(h["tangential_iterations"]) * self.t_t[-1]))

    def row(self):
        h = self.data.history
        n_it = np.asarray(h["normal_iterations"])
        t_it = np.asarray(h["tangential_iterations"])
        wall = statistics.median(self.walls)
        tn, tt = statistics.median(self.t_n), statistics.median(self.t_t)
        floor = n_it.sum() * tn + t_it.sum() * tt
        s = self.data.summary
        return dict(setting=self.name, angle=self.angle, f_t=self.ft, state=s.get("state"), u_sd=s.get("u_sd"),
                    du=s.get("du"), grid=f"{self.grid.nx}x{self.grid.ny}", steps=len(n_it), wall_s=wall,
                    walls=self.walls, normal_it_per_step=float(n_it.mean()),
                    tangential_it_per_step=float(t_it.mean()), normal_it_max=int(n_it.max()),
                    tangential_it_max=int(t_it.max()), pair_ms=tn * 1e3, tangential_product_ms=tt * 1e3,
                    floor_s=floor, ratio=statistics.median(self.ratios), ratios=self.ratios,
                    ratio_of_medians=wall / floor, ratio_all_pairs=wall / ((n_it.sum() + t_it.sum()) * tn),
                    solver_time_s=float(np.sum(h["wall_time"])))


def main():
    ap = _record.parser(__doc__)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--only", type=int, default=None, help="run only case index 0..3")
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        cases = [Case(name, angle, ft, Path(tmp) / str(i)) for i, (name, angle, ft) in enumerate(CASES)
                 if args.only is None or i == args.only]
        # round robin, so that a noisy minute on the shared machine touches every case alike
        for _ in range(args.repeats):
            for c in cases:
                c.run_once()
        for c in cases:
            row = c.row()
            rows.append(row)
            print(f"{c.name:13s} f_t={c.ft:.2f} {row['state']:>10s} u_sd={row['u_sd']} grid {row['grid']} "
                  f"steps {row['steps']} wall {row['wall_s']:.2f} s (runs {', '.join(f'{w:.2f}' for w in row['walls'])}) "
                  f"it/step n {row['normal_it_per_step']:.1f} t {row['tangential_it_per_step']:.1f} "
                  f"(max {row['normal_it_max']}/{row['tangential_it_max']}) pair {row['pair_ms']:.3f} ms "
                  f"tprod {row['tangential_product_ms']:.3f} ms floor {row['floor_s']:.2f} s "
                  f"ratio {row['ratio']:.2f} (runs {', '.join(f'{x:.2f}' for x in row['ratios'])}) "
                  f"(all-pairs {row['ratio_all_pairs']:.2f})", flush=True)
    if args.only is None:
        _record.write("rolling_paper", {"rows": rows}, args.output)


if __name__ == "__main__":
    main()

"""Model no more than a scene needs: the economies of rollcontact, measured (issue #7).

    .venv/bin/python benchmarks/economies.py [--repeats 3]

1. Grid sized to the swept contact (cases.run.discretise.scene_grid: contact box of every centre the path visits plus
   grid.margin): element counts for W = 1.2 ... 3.4 mm (the seed's range, dx = dy = 0.2 mm), both
   alignments, against the seed's 3050-4200 elements and against a naive square grid that covers the swept
   region in both directions ([-a - W - m, a + W + m]^2); the padded FFT size (what a product costs) too.
2. No coupling work when beta = 0: the paper scene (beta = 0, the substrate is incompressible) run with
   coupling 'auto' (off) and forced 'on' (Panagiotopoulos loop, two extra kernel spectra): FFT products
   counted by wrapping HalfSpaceOperator._apply and _apply_symbols (the padded convolutions, not the
   preconditioners; one product = one forward + inverse of 1-3 fields), wall time, and the difference in u_sd
   (0 up to the tolerance).
3. Field snapshots only where asked: HDF5 file size of the default run with output.fields = 'none', 'last',
   'reversals' (default), 'all'.
4. The MDR model when only limits are needed: `rollcontact limits --w 0.23 --ft 0.46` (a fresh process, so
   interpreter start-up included), the closed forms in-process, `simulate_mdr` of the scene (10 periods) and
   `rollcontact run --set solver.fidelity=mdr`, against the 3-D run of the same scene.

JSON to DIR/economies.json (-o DIR, default results/benchmarks/). Times: medians of --repeats on a shared 2-core machine (noisy).
"""
from __future__ import annotations

import math
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import _record
from rollcontact.bem.operator import HalfSpaceOperator, fft_length
from rollcontact.cases.run.discretise import scene_grid, scene_path
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import default_scene
from rollcontact.solver.mdr import limits as lim
from rollcontact.solver.mdr.simulate import simulate_mdr

ROOT = Path(__file__).resolve().parents[1]
SEED_ELEMENTS = (3050, 4200)


def median_time(fn, repeats):
    out, times = None, []
    for _ in range(max(1, repeats)):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return out, statistics.median(times)


def grid_economy():
    rows = []
    for W in (1.2, 2.0, 3.4):
        for angle in (90, 0):
            scene = default_scene().with_overrides([f"motion.W={W}", f"motion.angle={angle}"], replaces=("motion.W",))
            path = scene_path(scene)
            g = scene_grid(scene, path)
            a, m, dx = scene.contact_radius, scene.grid.margin, scene.grid.dx
            n_naive = math.ceil(2 * (a + W + m) / dx) ** 2
            padded = fft_length(2 * g.ny - 1) * fft_length(2 * g.nx - 1)
            n_side = math.ceil(2 * (a + W + m) / dx)
            padded_naive = fft_length(2 * n_side - 1) ** 2
            rows.append(dict(W=W, angle=angle, nx=g.nx, ny=g.ny, elements=g.size, steps=path.n_steps,
                             naive_square=n_naive, saving_vs_naive=1 - g.size / n_naive,
                             padded=padded, padded_naive=padded_naive,
                             in_seed_range=SEED_ELEMENTS[0] * 0.9 <= g.size <= SEED_ELEMENTS[1] * 1.15))
            print(f"grid W={W} angle={angle}: {g.nx} x {g.ny} = {g.size} (naive {n_naive}, "
                  f"-{rows[-1]['saving_vs_naive']:.0%}), {path.n_steps} steps", flush=True)
    return rows


class ProductCounter:
    """Counts the padded convolutions while active: HalfSpaceOperator._apply (coupling blocks) and the
    _apply_symbols calls on the padded transforms (op.normal, op.tangential; not the preconditioners)."""

    def __enter__(self):
        self.count, self.fields = 0, 0
        self._orig = HalfSpaceOperator._apply
        self._orig_symbols = HalfSpaceOperator._apply_symbols
        counter = self

        def counted(op, fields, blocks, out, ffts=None):
            counter.count += 1
            counter.fields += len(fields)
            return counter._orig(op, fields, blocks, out, ffts)

        def counted_symbols(op, fields, y, ffts, out):
            if ffts is op._fft:
                counter.count += 1
                counter.fields += len(fields)
            return counter._orig_symbols(op, fields, y, ffts, out)
        HalfSpaceOperator._apply = counted
        HalfSpaceOperator._apply_symbols = counted_symbols
        return self

    def __exit__(self, *exc):
        HalfSpaceOperator._apply = self._orig
        HalfSpaceOperator._apply_symbols = self._orig_symbols


def coupling_economy(repeats):
    rows = []
    for coupling in ("auto", "on"):
        scene = default_scene().with_overrides([f"solver.coupling={coupling}", "output.fields=none"])
        with tempfile.TemporaryDirectory() as tmp:
            run_scene(scene, Path(tmp) / "w.h5")   # warm-up: FFTW wisdom, numba
            with ProductCounter() as pc:
                out = run_scene(scene, Path(tmp) / "r.h5")
            times = [out.wall_time] + [run_scene(scene, Path(tmp) / "r.h5").wall_time for _ in range(repeats - 1)]
        op = HalfSpaceOperator(scene_grid(scene, scene_path(scene)), scene.material_pair,
                               coupling={"auto": "auto", "on": True}[coupling])
        h = out.history
        rows.append(dict(coupling=coupling, beta=scene.material_pair.beta, coupled=op.coupled,
                         spectra=sorted(op.spectra), products=pc.count, fields_convolved=pc.fields,
                         outer_iterations=int(np.sum(h["outer_iterations"])), time_s=statistics.median(times),
                         u_sd=out.summary.get("u_sd"), iterations=out.summary.get("iterations")))
        print(f"coupling {coupling}: {rows[-1]}", flush=True)
    return rows


def snapshot_economy():
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for mode in ("none", "last", "reversals", "all"):
            scene = default_scene().with_overrides([f"output.fields={mode}"])
            path = Path(tmp) / f"{mode}.h5"
            out = run_scene(scene, path)
            rows.append(dict(fields=mode, snapshots=len(out.field_steps), bytes=path.stat().st_size))
            print(f"fields={mode}: {rows[-1]}", flush=True)
    return rows


def mdr_economy(repeats):
    scene = default_scene()
    pair = scene.material_pair
    rows = {}
    cli = ROOT / ".venv" / "bin" / "rollcontact"
    cmd = [str(cli), "limits", "--w", "0.23", "--ft", "0.46"]
    _, t_cli = median_time(lambda: subprocess.run(cmd, check=True, capture_output=True), repeats)
    rows["rollcontact_limits_cli_s"] = t_cli
    _, t_cf = median_time(lambda: (lim.f_t_lim(0.23, lim.KAPPA_PERPENDICULAR),
                                   lim.u_shakedown(0.46, 0.23, lim.KAPPA_PERPENDICULAR)), max(repeats, 100))
    rows["closed_forms_in_process_s"] = t_cf
    kw = dict(R=scene.equivalent_radius, E_star=pair.E_star, G_star=pair.G_star, Fn=scene.load.Fn, mu=scene.load.mu,
              Ft=scene.Ft, W=scene.amplitude, dW=scene.motion.dW, periods=scene.motion.periods)
    simulate_mdr(**kw)
    res, t_mdr = median_time(lambda: simulate_mdr(**kw), repeats)
    rows["simulate_mdr_s"] = t_mdr
    with tempfile.TemporaryDirectory() as tmp:
        mdr_scene = scene.with_overrides(["solver.fidelity=mdr"])
        _, t_run_mdr = median_time(lambda: run_scene(mdr_scene, Path(tmp) / "m.h5"), repeats)
        out_mdr = run_scene(mdr_scene, Path(tmp) / "m.h5")
        run_scene(scene, Path(tmp) / "w.h5")
        out3d, t3d = median_time(lambda: run_scene(scene, Path(tmp) / "b.h5"), repeats)
    rows.update(run_scene_mdr_s=t_run_mdr, run_scene_3d_s=t3d, u_sd_mdr=out_mdr.summary.get("u_sd"),
                u_sd_3d=out3d.summary.get("u_sd"),
                u_sd_eq13_kappa_perp=float(lim.u_shakedown(0.46, 0.23, lim.KAPPA_PERPENDICULAR)),
                speedup_mdr_vs_3d=t3d / t_run_mdr, speedup_cli_vs_3d=t3d / t_cli)
    print(f"mdr: {rows}", flush=True)
    return rows


def main():
    ap = _record.parser(__doc__)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    result = dict(benchmark="economies", note="times: medians on a shared 2-core machine, noisy",
                  grid=grid_economy(), coupling=coupling_economy(args.repeats), snapshots=snapshot_economy(),
                  mdr=mdr_economy(args.repeats))
    _record.write("economies", result, args.output)


if __name__ == "__main__":
    sys.exit(main())

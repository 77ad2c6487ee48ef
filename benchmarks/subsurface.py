"""What the subsurface stresses cost: one step on the paper's grid at the 30 default depths, and the memory of a
256 x 256 x 64 block.

    .venv/bin/python benchmarks/subsurface.py [--repeats 7] [-o DIR]    # DIR/subsurface.json

Measured:
* warm, in this process after a warm-up (numba kernels loaded, FFTW plans from wisdom): one step = the tractions
  transformed once, then 30 layers (kernels, 15 + 6 FFTs, products) and the invariants (von Mises, Tresca,
  principal_1), on the grid a paper run uses (scene_grid of the default scene, dx = 0.2 mm), as a median over
  --repeats; its ratio to the floor, one FFT convolution pair (`HalfSpaceOperator.normal`) on the same grid timed in
  the same run; the set-up of the operator (plans);
* `add_subsurface` on a run file with one snapshot (the same step with the HDF5 rebuild and writes), median;
* cold: the process `rollcontact stresses RUN.h5 -q` (import, numba's cache, plans, the step, the file), median of 3;
* memory: a fresh process that adds 64 depths of a 256 x 256 grid to a run file, its peak resident set against the
  same process stopped before the computation (imports done, file read), and the file's growth.
"""
import argparse
import os
from pathlib import Path
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import _record

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

MEMORY_PROBE = r"""
import resource, sys, numpy as np
from rollcontact.cases.run import stresses as S
stop = sys.argv[2] == "baseline"
import h5py
with h5py.File(sys.argv[1]) as h5:
    p = h5["fields/p"][0]
if not stop:
    S.add_subsurface(sys.argv[1], depths=np.linspace(0.0, 2.0, 64))
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0)
"""


def _hertz_fields(grid, a, p0, ft_mu):
    X, Y = grid.mesh()
    p = p0 * np.sqrt(np.clip(1 - (X**2 + Y**2) / a**2, 0, None))
    return p, ft_mu * p, np.zeros_like(p)


def _run_file(path, scene, grid, fields, a, p0):
    from rollcontact.cases.results.hdf5 import write_run
    from rollcontact.cases.results.run_result import RunResult
    p, tx, ty = fields
    data = RunResult(scene_toml=scene.to_toml(), status="complete", x=grid.x, y=grid.y,
                     history={"step": np.array([0])}, fields={"p": p[None], "tau_x": tx[None], "tau_y": ty[None]},
                     field_steps=np.array([0]), summary={"a": a, "p0": p0})
    write_run(path, data)


def _median_time(fn, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def paper_step(repeats, tmp):
    from rollcontact.bem.operator import HalfSpaceOperator
    from rollcontact.bem.subsurface import SubsurfaceStresses, invariants
    from rollcontact.cases.run.stresses import add_subsurface, default_depths
    from rollcontact.cases.run.discretise import scene_grid
    from rollcontact.cases.scene.scene import default_scene
    from rollcontact.solver.analytic import HertzSphere
    scene = default_scene()
    grid = scene_grid(scene)
    h = HertzSphere(R=scene.equivalent_radius, E_star=scene.material_pair.E_star, Fn=scene.load.Fn)
    a, p0 = h.a, h.p0
    fields = _hertz_fields(grid, a, p0, 0.46 * scene.load.mu)
    depths = default_depths(a)
    t = time.perf_counter()
    op = SubsurfaceStresses(grid, scene.materials.nu2)
    setup = time.perf_counter() - t

    def step():
        op.set_tractions(*fields)
        for z in depths:
            invariants(op.layer(float(z)))
    step()
    step_s = _median_time(step, repeats)
    pair_op = HalfSpaceOperator(grid, scene.material_pair)
    pair_op.normal(fields[0])
    pair_s = _median_time(lambda: pair_op.normal(fields[0]), 50 * repeats)
    path = Path(tmp) / "paper.h5"
    _run_file(path, scene, grid, fields, a, p0)
    add_subsurface(path)
    calls = []
    file_s = _median_time(lambda: calls.append(add_subsurface(path)["seconds"]), repeats)
    colds = []
    for _ in range(3):
        t = time.perf_counter()
        subprocess.run([str(Path(sys.executable).parent / "rollcontact"), "stresses", str(path), "-q"], check=True,
                       capture_output=True)
        colds.append(time.perf_counter() - t)
    return dict(grid=[grid.nx, grid.ny], padded=list(op.padded), depths=len(depths), a=a, setup_s=setup,
                step_s=step_s, per_layer_ms=1e3 * step_s / len(depths), pair_ms=1e3 * pair_s,
                step_over_pair=step_s / pair_s, add_subsurface_s=file_s,
                add_subsurface_compute_s=statistics.median(calls), cold_process_s=statistics.median(colds))


def memory_block(tmp):
    from rollcontact.bem.grid import Grid
    from rollcontact.cases.scene.scene import default_scene
    grid = Grid(256, 256, 0.04, 0.04, -128, -128)
    path = Path(tmp) / "block.h5"
    _run_file(path, default_scene(), grid, _hertz_fields(grid, 4.0, 1.0, 0.3), 4.0, 1.0)
    size0 = os.path.getsize(path)
    out = {}
    for kind in ("baseline", "compute"):
        t = time.perf_counter()
        res = subprocess.run([sys.executable, "-c", MEMORY_PROBE, str(path), kind], check=True, capture_output=True,
                             text=True)
        out[f"{kind}_s"] = time.perf_counter() - t
        out[f"{kind}_peak_mb"] = float(res.stdout.split()[-1])
    out["added_peak_mb"] = out["compute_peak_mb"] - out["baseline_peak_mb"]
    out["file_growth_mb"] = (os.path.getsize(path) - size0) / 1e6
    out["block_mb_uncompressed"] = 9 * 64 * 256 * 256 * 8 / 1e6
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("--repeats", type=int, default=7, help="timed repeats (median; default 7)")
    _record.add_output(parser)
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        paper = paper_step(args.repeats, tmp)
        print(f"paper grid {paper['grid'][0]} x {paper['grid'][1]} (padded {paper['padded']}), {paper['depths']} "
              f"depths: one step {paper['step_s'] * 1e3:.0f} ms ({paper['per_layer_ms']:.1f} ms a layer) = "
              f"{paper['step_over_pair']:.0f} pairs of {paper['pair_ms']:.3f} ms; set-up {paper['setup_s'] * 1e3:.0f} "
              f"ms; add_subsurface {paper['add_subsurface_s'] * 1e3:.0f} ms (computing "
              f"{paper['add_subsurface_compute_s'] * 1e3:.0f} ms); cold process {paper['cold_process_s']:.2f} s",
              flush=True)
        memory = memory_block(tmp)
        print(f"256 x 256 x 64: peak resident {memory['compute_peak_mb']:.0f} MB against "
              f"{memory['baseline_peak_mb']:.0f} MB before computing (+{memory['added_peak_mb']:.0f} MB), {memory['compute_s']:.1f} s, file +"
              f"{memory['file_growth_mb']:.0f} MB (uncompressed block {memory['block_mb_uncompressed']:.0f} MB)")
    _record.write("subsurface", {"repeats": args.repeats, "paper": paper, "memory_256x256x64": memory}, args.output)


if __name__ == "__main__":
    main()

"""Speed of the wheel-rail runs (solver.wheelrail, cases.run.wheelrail_run; docs/wheelrail.md).

    .venv/bin/python benchmarks/wheelrail_speed.py [--quick] [--contact BIN] [-o DIR]

1. One position with two patches: the S1002 wheel on the UIC60 rail of the Manchester benchmark (shipped scene
   mbench_s1002_uic60.toml) at the lateral position where tread and flange root touch first together (y = 5.02 mm,
   both patches loaded), steady rolling, mu = 0.3, on the benchmark's grid 0.2 x 0.2 mm and on 0.14 x 0.1 mm (patches
   of about 40 x 60 elements and more). CPU time (process_time) of the whole run (search, grids, vertical balance,
   normal and tangential solves), median of --repeats after a warm-up run (numba compiled or loaded), and the cold
   run of a fresh process (`rollcontact run`, wall time, with its start-up).
2. The sweep of wheelrail.y over 0-10 mm in 0.5 mm steps (21 runs) on 2 worker processes, then its figures
   (`rollcontact sweep ... --jobs 2` and `rollcontact plot`, as a user runs them): wall time of each command, the CPU
   time of the runs (their summaries' cpu_time) and of each command's own process.
With --contact BIN (the reference program CONTACT built for comparison, e.g. path/to/contact_linux64)
the same cases are run by it too (one deck per measurement, OMP_NUM_THREADS=1) as the peer: its CPU time (user + sys
of the child process). --quick: 3 repeats and a sweep of 5 positions. Results printed and written to DIR/speed.json
(default results/wheelrail_speed/), with the machine's load average.
"""
from __future__ import annotations

import argparse
import json
import os
from pathlib import Path
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import time

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "cases" / "mbench_s1002_uic60.toml"
TWO_POINT_Y = 5.0226               # tests/cases/test_wheelrail_run.py: two_point_position
ROLLCONTACT = Path(sys.executable).with_name("rollcontact")


def child_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def one_position(repeats: int) -> list[dict]:
    import rollcontact
    from rollcontact.cases.run.wheelrail_run import run_wheelrail
    base = rollcontact.load_scene(SCENE)
    out = []
    for dx, dy in ((0.2, 0.2), (0.14, 0.1)):
        scene = base.with_overrides({"wheelrail.y": TWO_POINT_Y, "grid.dx": dx, "grid.dy": dy})
        run_wheelrail(scene)                                  # warm-up
        cpus, result = [], None
        for _ in range(repeats):
            c = time.process_time()
            result = run_wheelrail(scene)
            cpus.append(time.process_time() - c)
        s = result.summary
        grids = [f"{p.x.size} x {p.y.size}" for p in result.patches]
        out.append({"dx": dx, "dy": dy, "patches": int(s["n_patches"]), "grids (x by s)": grids,
                    "elements": int(s["elements"]), "cpu_median_s": statistics.median(cpus), "cpu_all_s": cpus,
                    "patch_Fn": [float(v) for v in s["patch_Fn"]]})
        print(f"one position, dx {dx}, dy {dy}: {s['n_patches']} patches, grids {', '.join(grids)}, Fn "
              f"{', '.join(f'{v:.0f}' for v in s['patch_Fn'])} N: CPU {statistics.median(cpus):.3f} s (median of "
              f"{repeats})", flush=True)
    return out


def cold_run(folder: Path) -> dict:
    w, c = time.perf_counter(), child_cpu()
    subprocess.run([str(ROLLCONTACT), "run", str(SCENE), "-q", "-o", str(folder / "cold.h5"), "--overwrite",
                    "--set", f"wheelrail.y={TWO_POINT_Y}"], check=True, capture_output=True)
    out = {"wall_s": time.perf_counter() - w, "cpu_s": child_cpu() - c}
    print(f"cold `rollcontact run` of the two-patch position (fresh process): wall {out['wall_s']:.2f} s, CPU "
          f"{out['cpu_s']:.2f} s", flush=True)
    return out


def sweep(folder: Path, count: int) -> dict:
    target = folder / "sweep"
    shutil.rmtree(target, ignore_errors=True)
    w, c = time.perf_counter(), child_cpu()
    subprocess.run([str(ROLLCONTACT), "sweep", str(SCENE), "--vary", f"wheelrail.y=0:10:{count}", "-o", str(target),
                    "--jobs", "2", "-q"], check=True, capture_output=True)
    w_sweep, c_sweep = time.perf_counter() - w, child_cpu() - c
    import h5py
    runs_cpu = 0.0
    for f in target.glob("y=*.h5"):
        with h5py.File(f, "r") as h5:
            runs_cpu += float(h5["summary"].attrs["cpu_time"])
    w, c = time.perf_counter(), child_cpu()
    subprocess.run([str(ROLLCONTACT), "plot", str(target), "-o", str(folder / "plots"), "--overwrite"], check=True,
                   capture_output=True)
    out = {"runs": count, "sweep_wall_s": w_sweep, "sweep_command_cpu_s": c_sweep, "runs_cpu_s": runs_cpu,
           "plot_wall_s": time.perf_counter() - w, "plot_cpu_s": child_cpu() - c}
    print(f"sweep of {count} positions on 2 workers: wall {w_sweep:.1f} s (the runs' CPU {runs_cpu:.1f} s, the command's "
          f"own {c_sweep:.1f} s; the workers' start-up is not counted), its figures: wall {out['plot_wall_s']:.1f} s "
          f"(CPU {out['plot_cpu_s']:.1f} s); together {w_sweep + out['plot_wall_s']:.1f} s", flush=True)
    return out


def contact_peer(binary: str, folder: Path, count: int) -> dict:
    """CONTACT on the same positions: the two-patch one (its D_SEP = 8 mm joins the patches into one), and the y sweep
    as one deck of `count` cases."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from wheelrail_contact_deck import write_deck
    work = folder / "contact"
    work.mkdir(parents=True, exist_ok=True)
    for name in ("MBench_S1002_v3.prw", "MBench_UIC60_v3.prr"):
        shutil.copy(ROOT / "cases" / "data" / "wheelrail" / name, work / name)
    out = {}
    for label, ys in (("one_position", [TWO_POINT_Y]), ("sweep", [10.0 * i / (count - 1) for i in range(count)])):
        write_deck(work / f"{label}.inp", ys)
        c = child_cpu()
        subprocess.run([binary, "2", label], cwd=work, check=True, capture_output=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
        out[label + "_cpu_s"] = child_cpu() - c
    print(f"CONTACT: the two-patch position CPU {out['one_position_cpu_s']:.3f} s (with its start-up), the {count} "
          f"positions {out['sweep_cpu_s']:.2f} s", flush=True)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="3 repeats, 5 sweep positions")
    ap.add_argument("--repeats", type=int, default=None)
    ap.add_argument("--contact", metavar="BIN", help="the CONTACT executable, to time it on the same cases")
    ap.add_argument("-o", "--output", default=str(ROOT / "results" / "wheelrail_speed"))
    args = ap.parse_args()
    folder = Path(args.output)
    folder.mkdir(parents=True, exist_ok=True)
    repeats = args.repeats or (3 if args.quick else 7)
    count = 5 if args.quick else 21
    meta = {"machine": f"{platform.node()} {platform.processor() or platform.machine()}", "cores": os.cpu_count(),
            "date": time.strftime("%Y-%m-%d %H:%M"), "load_before": list(os.getloadavg())}
    meta["one_position"] = one_position(repeats)
    meta["cold_run"] = cold_run(folder)
    meta["sweep"] = sweep(folder, count)
    if args.contact:
        meta["contact"] = contact_peer(args.contact, folder, count)
    meta["load_after"] = list(os.getloadavg())
    print(f"load average before {meta['load_before'][0]:.2f}, after {meta['load_after'][0]:.2f}")
    (folder / "speed.json").write_text(json.dumps(meta, indent=1))


if __name__ == "__main__":
    main()

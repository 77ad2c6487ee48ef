"""Start-up: what a user waits for beyond the solve, timed as whole processes as a user meets them.

    .venv/bin/python benchmarks/startup.py [--repeats 5] [-o DIR]    # DIR/startup.json

* `rollcontact --version`, `rollcontact --help` and `python -c "import rollcontact"`: process wall time, median of
  --repeats (targets 0.3 s, 0.3 s and 0.5 s); `python -c pass` is timed beside them (the interpreter's own start).
* The four paper scenes (seed Table 1: rolling parallel / perpendicular to Ft, f_t = 0.46 shakedown / 0.77
  ratcheting, dx = dW = 0.2 mm, 10 periods): `rollcontact run -q -o FILE` as a process, against the in-process
  solve time that the same process reports (the run's wall_time in its summary, from the start of the run to its
  summary: grid, operator, numba kernels from their cache, stepping). ratio = process / solve (target <= 1.3),
  median of --repeats, with numba's cache and the FFTW wisdom warm (one run of each scene first). CONTACT's stored
  figures for these scenes (issue #3): 5.7-6.0 s CPU in shakedown, 10.7-11.0 s ratcheting.
"""
import argparse
import os
from pathlib import Path
import statistics
import subprocess
import sys
import tempfile
import time

import h5py

import _record

HERE = Path(__file__).resolve().parent
BIN = Path(sys.executable).parent
SCENES = [("parallel", 0.46, ["--set", "motion.angle=0"]), ("perpendicular", 0.46, []),
          ("parallel", 0.77, ["--set", "motion.angle=0", "--set", "load.ft=0.77"]),
          ("perpendicular", 0.77, ["--set", "load.ft=0.77"])]
CONTACT_CPU_S = {0.46: "5.7-6.0", 0.77: "10.7-11.0"}


def process_time(args, cwd) -> float:
    t = time.perf_counter()
    subprocess.run(args, cwd=cwd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   env=dict(os.environ, OMP_NUM_THREADS="1"))
    return time.perf_counter() - t


def commands(repeats, cwd) -> dict:
    cases = {"rollcontact --version": [str(BIN / "rollcontact"), "--version"],
             "rollcontact --help": [str(BIN / "rollcontact"), "--help"],
             "import rollcontact": [sys.executable, "-c", "import rollcontact"],
             "python -c pass": [sys.executable, "-c", "pass"]}
    out = {}
    for name, args in cases.items():
        process_time(args, cwd)
        times = [process_time(args, cwd) for _ in range(repeats)]
        out[name] = {"median_s": statistics.median(times), "runs_s": times}
        print(f"{name:24s} {out[name]['median_s']:.3f} s", flush=True)
    return out


def paper_scenes(repeats, cwd) -> list:
    rows = []
    for setting, f_t, overrides in SCENES:
        args = [str(BIN / "rollcontact"), "run", "-q", "-o", "run.h5", "--overwrite", *overrides]
        process_time(args, cwd)       # warm: numba's cache, FFTW wisdom
        procs, solves = [], []
        for _ in range(repeats):
            procs.append(process_time(args, cwd))
            with h5py.File(Path(cwd) / "run.h5") as h5:
                solves.append(float(h5["summary"].attrs["wall_time"]))
                state = h5["summary"].attrs["state"]
        ratios = [p / s for p, s in zip(procs, solves)]
        row = dict(setting=setting, f_t=f_t, state=str(state), process_s=statistics.median(procs),
                   solve_s=statistics.median(solves), ratio=statistics.median(ratios), ratios=ratios,
                   contact_cpu_s=CONTACT_CPU_S[f_t])
        rows.append(row)
        print(f"{setting:13s} f_t = {f_t}: process {row['process_s']:.2f} s, solve {row['solve_s']:.2f} s, "
              f"ratio {row['ratio']:.2f} ({min(ratios):.2f}-{max(ratios):.2f}); CONTACT {row['contact_cpu_s']} s CPU",
              flush=True)
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("--repeats", type=int, default=5, help="timed runs per case (median; default 5)")
    parser.add_argument("--skip-scenes", action="store_true", help="time the commands only")
    _record.add_output(parser)
    args = parser.parse_args(argv)
    load = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        result = {"date": time.strftime("%Y-%m-%d"), "machine": f"{os.cpu_count()} cores", "load_before": load,
                  "repeats": args.repeats, "commands": commands(args.repeats, tmp)}
        if not args.skip_scenes:
            result["paper_scenes"] = paper_scenes(args.repeats, tmp)
    result["load_after"] = os.getloadavg()[0]
    _record.write("startup", result, args.output)
    print(f"load {load:.2f} -> {result['load_after']:.2f}")


if __name__ == "__main__":
    main()

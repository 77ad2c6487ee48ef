"""What holds the memory of a run: resident memory (RSS) at points of one `rollcontact run` in this process, and the
sizes of the blocks it keeps, for the paper scene and its fine-grid variant.

    .venv/bin/python benchmarks/memory_consumers.py [--quick] [--scene paper|fine ...] [-o DIR]

* RSS (Linux /proc/self/statm; peak from getrusage) at: the interpreter, numpy, the run path imported
  (rollcontact.cases.run.bem_run with h5py, pyfftw and the compiled kernels, rollcontact.bem.compiled), the
  operator built (bem.HalfSpaceOperator: influence spectra, real symbols, FFT buffers and plans of the padded and the
  preconditioner grids), the first step solved (solver work arrays, the product memo), the end of the run; a thread
  samples RSS every 2 ms for the peak and when it occurs.
* Block sizes (bytes held, not RSS): the compiled kernel libraries (their resident pages), the operator's arrays,
  the stored snapshots (gzip chunks, the run's /fields; and what they would take as arrays), the history, the largest
  in-memory checkpoint file.
Scenes: the default perpendicular paper scene at f_t = 0.77 (10 periods, dx = 0.2 mm, 55 x 65 elements), and 'fine'
the same at dx = 0.05 mm (217 x 261 elements; about a minute and a half of CPU). --quick: the paper scene only.
JSON: DIR/memory_consumers.json (-o DIR, default results/benchmarks/; benchmarks/_record.py). Units: MB (2^20 bytes).
"""
import argparse
import json
import os
from pathlib import Path
import resource
import subprocess
import sys
import tempfile
import threading
import time

import _record

HERE = Path(__file__).resolve().parent
SCENES = {"paper": ["load.ft=0.77"], "fine": ["load.ft=0.77", "grid.dx=0.05"]}
MB = 2.0 ** 20


def _rss() -> float:
    with open("/proc/self/statm") as fh:
        return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / MB


def _mapped_rss(name: str) -> float:
    """Resident MB of the memory mappings of files whose path contains `name` (/proc/self/smaps)."""
    total, current = 0, False
    with open("/proc/self/smaps") as fh:
        for line in fh:
            first = line.split(maxsplit=1)[0]
            if "-" in first and not first.endswith(":"):
                current = name in line
            elif current and first == "Rss:":
                total += int(line.split()[1])
    return total / 1024.0


def _nbytes(obj, seen=None) -> int:
    """Bytes of the numpy arrays reachable from obj's attributes (one level into dicts, lists, tuples)."""
    import numpy as np
    seen = set() if seen is None else seen
    total = 0
    values = list(vars(obj).values()) if hasattr(obj, "__dict__") else [obj]
    for v in values:
        items = list(v.values()) if isinstance(v, dict) else list(v) if isinstance(v, (list, tuple)) else [v]
        for x in items:
            if isinstance(x, np.ndarray):
                address = x.__array_interface__["data"][0]      # views of one buffer are counted once
                if address not in seen:
                    seen.add(address)
                    total += x.nbytes
            elif hasattr(x, "real_in") and id(x) not in seen:       # an FFT pair's buffers
                seen.add(id(x))
                total += _nbytes(x, seen)
    return total


def probe(overrides) -> dict:
    """One run in this process (fresh: call from a child), with RSS at its stages and the blocks it holds."""
    points = [("interpreter", _rss())]
    samples, stop = [], threading.Event()

    def sample():
        while not stop.is_set():
            samples.append((time.perf_counter(), _rss()))
            time.sleep(0.002)
    threading.Thread(target=sample, daemon=True).start()
    import numpy  # noqa: F401
    points.append(("numpy", _rss()))
    import rollcontact.cases.run.bem_run as bem_run
    from rollcontact.cases.api import load_scene, run
    points.append(("run path imported (h5py, pyfftw, rollcontact, its compiled kernels)", _rss()))
    held = {}
    make_operator = bem_run.scene_operator

    def scene_operator(*args, **kwargs):
        op = make_operator(*args, **kwargs)
        held["op"] = op
        points.append(("operator built", _rss()))
        return op
    bem_run.scene_operator = scene_operator
    path_steps = bem_run.run_path

    def run_path(*args, **kwargs):
        for k, rec in enumerate(path_steps(*args, **kwargs)):
            if k == 1:
                points.append(("first step solved", _rss()))
            yield rec
    bem_run.run_path = run_path
    from rollcontact.cases.results import growing_file
    from rollcontact.cases.run import recorder as recorder_module
    save_file, init_recorder = growing_file.GrowingRunFile.save, recorder_module.StepRecorder.__init__

    def file_save(self, path):
        with self._buffer.getbuffer() as image:
            held["checkpoint"] = max(held.get("checkpoint", 0), image.nbytes)
        return save_file(self, path)

    def recorder_init(self, *args, **kwargs):
        init_recorder(self, *args, **kwargs)
        held["recorder"] = self
    growing_file.GrowingRunFile.save, recorder_module.StepRecorder.__init__ = file_save, recorder_init
    scene = load_scene(None, overrides)
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        run(scene, Path(tmp) / "run.h5")
        points.append(("run written", _rss()))
    stop.set()
    peak_at, peak = max(samples, key=lambda s: s[1])
    op, rec = held["op"], held["recorder"]
    chunks = sum(len(c) for v in rec.chunks.values() for c in v)
    history = sum(8 * len(v) for v in rec.history.values())
    checkpoint = held.get("checkpoint", 0)
    grid = op.grid
    libraries = _mapped_rss("_kernels_")
    return {"scene": overrides, "grid": [grid.nx, grid.ny], "padded": list(op.padded),
            "rss_mb": [[name, round(v, 1)] for name, v in points],
            "peak_rss_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
            "peak_at_s": round(peak_at - t0, 2), "run_wall_s": round(time.perf_counter() - t0, 2),
            "held_mb": {"compiled kernel libraries (resident)": round(libraries, 1),
                        "operator arrays": round(_nbytes(op) / MB, 1),
                        "stored snapshots (gzip chunks)": round(chunks / MB, 1),
                        "snapshots uncompressed": round(len(rec.stored) * 8.125 * 8 * grid.size / MB, 1),
                        "history": round(history / MB, 2),
                        "checkpoint file in memory (largest)": round(checkpoint / MB, 1)}}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--quick", action="store_true", help="the paper scene only")
    ap.add_argument("--scene", nargs="+", choices=sorted(SCENES), help="scenes to probe (default: paper fine)")
    _record.add_output(ap)
    ap.add_argument("--child", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child:
        print(json.dumps(probe(SCENES[args.child])))
        return
    names = args.scene or (["paper"] if args.quick else ["paper", "fine"])
    out = {"scenes": {}}
    for name in names:
        proc = subprocess.run([sys.executable, __file__, "--child", name], capture_output=True, text=True,
                              check=True)
        res = out["scenes"][name] = json.loads(proc.stdout.strip().splitlines()[-1])
        print(f"{name}: grid {res['grid'][0]} x {res['grid'][1]} (padded {res['padded'][1]} x {res['padded'][0]}), "
              f"peak RSS {res['peak_rss_mb']} MB at {res['peak_at_s']} s of {res['run_wall_s']} s")
        for label, value in res["rss_mb"]:
            print(f"    RSS {value:7.1f} MB  {label}")
        for label, value in res["held_mb"].items():
            print(f"    held {value:6.1f} MB  {label}")
    _record.write("memory_consumers", out, args.output)


if __name__ == "__main__":
    main()

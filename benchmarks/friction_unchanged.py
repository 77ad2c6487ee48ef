"""Runs without [friction] are bit for bit what they were before the friction laws (issue #34): digests of every array.

    .venv/bin/python benchmarks/friction_unchanged.py --write DIGESTS.json      # on the reference tree (e.g. main)
    .venv/bin/python benchmarks/friction_unchanged.py --check DIGESTS.json      # on the tree under test

Runs the paper scene (cases/paper_perpendicular.toml; one period with --quick, its ten otherwise), the shipped steady
[rolling] scene (cases/creep_steady.toml) and a short transient of it, through the Python API, writes each to HDF5,
reads it back and takes the SHA-256 of every stored array and summary value (the run's times aside: wall_time,
cpu_time, time_per_step, checkpoint_time). --write stores the digests with the machine and the library versions;
--check recomputes them and lists every array that differs (exit status 1). Digests are bitwise: they hold on the
machine and the FFTW wisdom they were taken with (the planner may choose other algorithms elsewhere, which changes the
last bits); --check says so when the machine or the versions differ. The suite's test
(tests/cases/test_friction_unchanged.py) checks the quick set against tests/cases/data/unchanged_digests.json.
"""
from __future__ import annotations

import argparse
import hashlib
import json
import platform
import sys
import tempfile
from pathlib import Path

import numpy as np

#: the run's own times, which differ from run to run
TIMES = ("wall_time", "cpu_time", "time_per_step", "checkpoint_time")


def scenes(quick: bool) -> dict:
    """name -> (scene file under cases/, overrides)."""
    return {"paper_perpendicular": ("paper_perpendicular.toml", {"motion.periods": 1} if quick else {}),
            "creep_steady": ("creep_steady.toml", {}),
            "creep_transient": ("creep_steady.toml", {"rolling.mode": "transient", "rolling.distance": 3.0})}


def digest(value) -> str:
    arr = np.ascontiguousarray(np.asarray(value))
    if arr.dtype.kind in "OUS":
        return hashlib.sha256(repr(arr.tolist()).encode()).hexdigest()
    return hashlib.sha256(arr.dtype.str.encode() + repr(arr.shape).encode() + arr.tobytes()).hexdigest()


def run_digests(quick: bool) -> dict:
    import rollcontact
    from rollcontact.cases.scene.scene import shipped_scene_path
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, (file, overrides) in scenes(quick).items():
            scene = rollcontact.load_scene(shipped_scene_path(file), overrides=overrides or None)
            path = Path(tmp) / f"{name}.h5"
            rollcontact.run(scene, path)
            res = rollcontact.read_run(path)
            d = {f"history/{k}": digest(v) for k, v in res.history.items() if k not in TIMES}
            d.update({f"fields/{k}": digest(v) for k, v in res.fields.items()})
            d["field_steps"] = digest(res.field_steps)
            d.update({f"summary/{k}": digest(v) for k, v in res.summary.items() if k not in TIMES and v is not None})
            out[name] = d
    return out


def machine() -> dict:
    import numba
    import pyfftw
    cpu = ""
    try:
        cpu = next(line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return {"cpu": cpu or platform.processor(), "python": platform.python_version(), "numpy": np.__version__,
            "numba": numba.__version__, "pyfftw": pyfftw.__version__}


def compare(stored: dict, now: dict) -> list[str]:
    """The names whose digests differ (or are missing on either side)."""
    bad = []
    for scene, ref in stored.items():
        got = now.get(scene, {})
        for key in sorted(set(ref) | set(got)):
            if ref.get(key) != got.get(key):
                bad.append(f"{scene}: {key}")
    return bad


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    group = ap.add_mutually_exclusive_group(required=True)
    group.add_argument("--write", type=Path, help="store the digests of this tree in this JSON file")
    group.add_argument("--check", type=Path, help="compare this tree's digests with this JSON file")
    ap.add_argument("--quick", action="store_true", help="one period of the paper scene (the suite's set)")
    args = ap.parse_args(argv)
    now = run_digests(args.quick)
    if args.write:
        args.write.parent.mkdir(parents=True, exist_ok=True)
        args.write.write_text(json.dumps({"quick": args.quick, "machine": machine(), "digests": now}, indent=1) + "\n")
        print(f"digests of {sum(len(v) for v in now.values())} arrays written to {args.write}")
        return 0
    stored = json.loads(args.check.read_text())
    if stored["quick"] != args.quick:
        ap.error(f"{args.check} holds the {'quick' if stored['quick'] else 'full'} set: give --quick accordingly")
    if stored["machine"] != machine():
        print(f"note: digests taken on {stored['machine']}, this is {machine()}: bitwise equality is not expected")
    bad = compare(stored["digests"], now)
    print("\n".join(bad) if bad else f"all {sum(len(v) for v in now.values())} arrays bit for bit the same")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

"""Runs without [friction] are bit for bit what they were before the friction laws (issue #34): every stored array of
the same scenes, run by a reference tree and by this one, compared bitwise.

    git archive <commit> | tar -x -C /tmp/base          # the reference tree (e.g. the merge base with main)
    .venv/bin/python benchmarks/friction_unchanged.py --base /tmp/base [--quick] [-o DIR]

Runs the paper scene (cases/paper_perpendicular.toml; one period with --quick, its ten otherwise), the shipped steady
[rolling] scene (cases/creep_steady.toml) and a 3 mm transient of it, once with the reference tree's package and once
with this one, each in its own process, and compares the SHA-256 of every stored array and summary value (the run's
times aside: wall_time, cpu_time, time_per_step, checkpoint_time), and the scene text stored in each file. Both
processes use one private FFTW wisdom file (ROLLCONTACT_CACHE in the output folder), so that both plan the same FFT
algorithms: FFTW_MEASURE plans chosen under different loads may differ in the last bits, and the shared cache of
~/.cache/rollcontact changes as other runs add to it. Writes DIR/friction_unchanged.json (default
results/friction_unchanged/) and exits with status 1 when any array differs.
"""
from __future__ import annotations

import argparse
import hashlib
import json
import os
from pathlib import Path
import subprocess
import sys
import tempfile

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
    """The digests of the scenes run by the rollcontact package this process imports."""
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
            d["scene_toml"] = digest(res.scene_toml)
            out[name] = d
    return out


def compare(reference: dict, now: dict) -> list[str]:
    """The names whose digests differ (or are missing on either side)."""
    bad = []
    for scene, ref in reference.items():
        got = now.get(scene, {})
        for key in sorted(set(ref) | set(got)):
            if ref.get(key) != got.get(key):
                bad.append(f"{scene}: {key}")
    return bad


def _shim(base: Path, folder: Path) -> Path:
    """A folder that imports the reference tree as `rollcontact` (its layers live beside the package, as in the
    repository: pyproject.toml maps them)."""
    pkg = folder / "reference_import" / "rollcontact"
    pkg.mkdir(parents=True, exist_ok=True)
    (pkg / "__init__.py").write_text((base / "rollcontact" / "__init__.py").read_text())
    for layer in ("bem", "solver", "cases"):
        link = pkg / layer
        if not link.exists():
            link.symlink_to((base / layer).resolve())
    return pkg.parent


def _digests_in_process(quick: bool, pythonpath: Path | None, cache: Path, out: Path) -> dict:
    env = dict(os.environ, ROLLCONTACT_CACHE=str(cache))
    if pythonpath is not None:
        env["PYTHONPATH"] = str(pythonpath)
    cmd = [sys.executable, str(Path(__file__).resolve()), "--digests-to", str(out)] + (["--quick"] if quick else [])
    subprocess.run(cmd, env=env, check=True, cwd=tempfile.gettempdir())
    return json.loads(out.read_text())


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--base", type=Path, help="source tree of the reference commit (git archive of it)")
    ap.add_argument("--quick", action="store_true", help="one period of the paper scene")
    ap.add_argument("-o", "--out", type=Path, default=Path("results") / "friction_unchanged",
                    help="folder for the report and the private FFTW wisdom (default results/friction_unchanged)")
    ap.add_argument("--digests-to", type=Path, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.digests_to:
        args.digests_to.write_text(json.dumps(run_digests(args.quick)))
        return 0
    if args.base is None:
        ap.error("--base DIR: the reference tree is required")
    args.out.mkdir(parents=True, exist_ok=True)
    cache = args.out / "cache"
    reference = _digests_in_process(args.quick, _shim(args.base, args.out), cache, args.out / "reference.json")
    now = _digests_in_process(args.quick, None, cache, args.out / "this_tree.json")
    bad = compare(reference, now)
    report = {"quick": args.quick, "base": str(args.base), "arrays": sum(len(v) for v in now.values()),
              "differing": bad}
    (args.out / "friction_unchanged.json").write_text(json.dumps(report, indent=1) + "\n")
    print("\n".join(bad) if bad else f"all {report['arrays']} arrays and values bit for bit the same")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

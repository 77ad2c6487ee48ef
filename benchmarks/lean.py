"""Lean and fast: whole processes and in-process steps timed against an install of an earlier rollcontact (the
baseline) and the reference program CONTACT, in the same run, interleaved; and the outputs compared with the
baseline's.

    .venv/bin/python benchmarks/lean.py --baseline BASE/.venv/bin/python [--contact BIN --decks DIR]
                                        [--quick] [--repeats 5] [-o DIR]

--baseline: the Python of another install of rollcontact (e.g. a git worktree at an earlier commit with its own
venv); its `rollcontact` command beside it. --contact: CONTACT's stand-alone program, run one thread
(OMP_NUM_THREADS=1) as `BIN 2 NAME` on the inputs NAME.inp in --decks (c_osc_perp_ft0.77_w0.23, d_transient,
c_creep_circle: the paper scene, the transient and the creep curve below). Times are the CPU (user + sys) of each
process (os.wait4) and peak resident memory (ru_maxrss), medians of --repeats, the variants of a case interleaved;
`uptime`'s load is recorded before and after. --quick: 2 repeats, no dx = 0.05 scene.

Cases
* paper: `rollcontact run --set load.ft=0.77` (the default perpendicular paper scene, ratcheting, 10 periods).
* fixed cost: the paper process's CPU minus the CPU of the same run repeated in one process (its second run:
  imports, compiled kernels, FFTW plans from wisdom and one-time set-ups excluded), per install.
* fine: the paper scene at grid.dx = 0.05 mm (217 x 261 elements): CPU and peak memory.
* transient: benchmarks/scenes/d_transient.toml (rolled from rest over 4 contact lengths, 241 steps): this install's
  default grid (moving with the contact), its world-fixed grid ([rolling] grid = "world") and the baseline; the
  forces of every step against the baseline's world-fixed run.
* creep curve: `rollcontact creep-curve benchmarks/scenes/creep_circle.toml` (20 steady creepages): CPU, memory.
* subsurface: one stored paper step at the 30 default depths, in one process: the computation (tractions
  transformed, 30 layers, invariants) and `rollcontact.stresses` on the run file (read, compute, write), medians.
* outputs: the paper run file, a steady creep run (creep_circle.toml) and the subsurface stresses of the paper file,
  this install against the baseline, dataset by dataset (identical, or the largest difference relative to the
  largest value of the quantity: a vector's components share one scale).
JSON: DIR/lean.json (-o DIR, default results/benchmarks/; benchmarks/_record.py records date, machine, load).
Units: s, MB (2^20 bytes).
"""
import argparse
import json
import os
from pathlib import Path
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import _record

HERE = Path(__file__).resolve().parent
SCENES = HERE / "scenes"
PAPER = ["--set", "load.ft=0.77"]
FINE = PAPER + ["--set", "grid.dx=0.05"]
DECKS = {"paper": "c_osc_perp_ft0.77_w0.23", "transient": "d_transient", "creep_curve": "c_creep_circle"}
#: vectors whose components are compared on one scale
FAMILIES = (("F_x", "F_y"), ("U_x", "U_y", "U_perp"), ("W_x", "W_y"), ("tau_x", "tau_y"), ("slip_x", "slip_y"),
            ("u_x", "u_y"))
#: datasets that record the run rather than its result
SKIP = ("wall_time", "cpu_time", "residual")

#: one scene run twice in one process: the CPU (s) of the second run (process_time), printed last
WARM_RUN = """
import sys, tempfile, time
from pathlib import Path
from rollcontact.cases.api import load_scene, run
scene = load_scene(None, sys.argv[1:])
with tempfile.TemporaryDirectory() as tmp:
    run(scene, Path(tmp) / "a.h5")
    t = time.process_time()
    run(scene, Path(tmp) / "b.h5")
    print(time.process_time() - t)
"""

#: one stored step of a run file at the 30 default depths, in one process (argv: the run file, repeats)
SUBSURFACE = """
import json, shutil, statistics, sys, tempfile, time
from pathlib import Path
import h5py
from rollcontact.bem.subsurface import SubsurfaceStresses, invariants
from rollcontact.cases.run.stresses import add_subsurface, default_depths, grid_of
src, repeats = Path(sys.argv[1]), int(sys.argv[2])
from rollcontact.cases.scene.scene import Scene
with h5py.File(src, "r") as h5:
    x, y, a = h5["grid/x"][()], h5["grid/y"][()], float(h5["summary"].attrs["a"])
    p, tx, ty = (h5[f"fields/{n}"][-1] for n in ("p", "tau_x", "tau_y"))
    scene = h5.attrs["scene"]
    nu = Scene.from_toml_text(scene.decode() if isinstance(scene, bytes) else scene, run_limits=False).materials.nu2
op = SubsurfaceStresses(grid_of(x, y), nu)
depths = default_depths(a)
def step():
    op.set_tractions(p, tx, ty)
    for z in depths:
        invariants(op.layer(float(z)))
step()
compute, files = [], []
for _ in range(repeats):
    t = time.process_time(); step(); compute.append(time.process_time() - t)
with tempfile.TemporaryDirectory() as tmp:
    for _ in range(repeats + 1):
        copy = Path(tmp) / "run.h5"
        shutil.copyfile(src, copy)
        t = time.process_time(); add_subsurface(copy); files.append(time.process_time() - t)
print(json.dumps({"compute_s": statistics.median(compute), "add_subsurface_s": statistics.median(files[1:])}))
"""


def process_env(extra=None) -> dict:
    """The environment of a measured process: the caller's with one OpenMP thread and bytecode caching on, as an
    installed Python has it (a shell with PYTHONDONTWRITEBYTECODE=1 makes every process compile rollcontact's ~80
    modules again, about 0.09 s of CPU on the development machine; the warm-up runs write the caches)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    return dict(env, OMP_NUM_THREADS="1", **(extra or {}))


def measure(argv, env=None, cwd=None) -> dict:
    """CPU (user + sys, s), peak RSS (MB) and wall time (s) of one process."""
    t = time.perf_counter()
    proc = subprocess.Popen(argv, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=process_env(env))
    _, status, usage = os.wait4(proc.pid, 0)
    err = proc.stderr.read().decode(errors="replace")
    proc.stderr.close()
    if status != 0:
        raise RuntimeError(f"{' '.join(map(str, argv))} failed:\n{err[-2000:]}")
    return {"cpu_s": usage.ru_utime + usage.ru_stime, "rss_mb": usage.ru_maxrss / 1024.0,
            "wall_s": time.perf_counter() - t}


def interleaved(variants: dict, repeats: int, cwd) -> dict:
    """{name: {cpu_s, rss_mb, wall_s (medians), runs}} of the commands `variants` (name -> argv or (argv, env)),
    run in turn `repeats` times."""
    runs = {name: [] for name in variants}
    for _ in range(repeats):
        for name, spec in variants.items():
            argv, env = spec if isinstance(spec, tuple) else (spec, None)
            runs[name].append(measure(argv, env, cwd))
    return {name: {**{k: statistics.median(r[k] for r in rs) for k in ("cpu_s", "rss_mb", "wall_s")},
                   "runs": rs} for name, rs in runs.items()}


def rollcontact(python) -> str:
    return str(Path(python).parent / "rollcontact")


def contact_variant(args, case, tmp):
    """The argv running CONTACT on its input for `case` in its own folder, or None without --contact."""
    if not args.contact:
        return None
    folder = Path(tmp) / f"contact_{case}"
    folder.mkdir(exist_ok=True)
    shutil.copyfile(Path(args.decks) / f"{DECKS[case]}.inp", folder / f"{DECKS[case]}.inp")
    return (["sh", "-c", f'cd "{folder}" && exec "{args.contact}" 2 {DECKS[case]}'], None)


def compare(a_path, b_path) -> dict:
    """Datasets of two HDF5 files: the count identical, and for the others the largest difference relative to the
    largest absolute value of the quantity (its vector's components together)."""
    import h5py
    import numpy as np

    def datasets(path):
        out = {}
        with h5py.File(path, "r") as h5:
            h5.visititems(lambda n, o: out.__setitem__(n, o[()]) if isinstance(o, h5py.Dataset) else None)
        return out
    a, b = datasets(a_path), datasets(b_path)
    scale = {}
    for name, x in list(a.items()) + list(b.items()):
        if x.dtype.kind in "fi":
            scale[name] = max(scale.get(name, 0.0), float(np.abs(x).max()) if x.size else 0.0)
    same, differ, counts = 0, {}, {}
    for name in sorted(set(a) | set(b)):
        if name.rsplit("/", 1)[-1] in SKIP:
            continue
        if name.endswith("iterations"):             # the work done, not the result
            counts[name] = int(np.abs(a[name].sum() - b[name].sum())) if name in a and name in b else None
            continue
        if name not in a or name not in b or a[name].shape != b[name].shape:
            differ[name] = "missing or reshaped"
            continue
        if np.array_equal(a[name], b[name]):
            same += 1
            continue
        group, leaf = name.rsplit("/", 1) if "/" in name else ("", name)
        family = next((f for f in FAMILIES if leaf in f), (leaf,))
        s = max(scale.get(f"{group}/{m}" if group else m, 0.0) for m in family) or 1.0
        differ[name] = float(np.abs(a[name].astype(float) - b[name].astype(float)).max() / s)
    with h5py.File(a_path, "r") as fa, h5py.File(b_path, "r") as fb:
        summary = _summary_differences(dict(fa["summary"].attrs), dict(fb["summary"].attrs))
        totals = [(float(f["history/iterations"][()].sum()) if "history/iterations" in f else None) for f in (fa, fb)]
    return {"identical": same, "differ": differ, "summary": summary, "iteration_totals": totals}


def _summary_differences(a: dict, b: dict) -> dict:
    """Summary values that differ: relative difference of numbers (times and iteration counts left out, and values
    that are zero to round-off in both, below 1e-12 in their unit), or both texts."""
    import numpy as np
    out = {}
    for key in sorted(set(a) & set(b)):
        if "time" in key or "iterations" in key:
            continue
        x, y = a[key], b[key]
        if isinstance(x, (bytes, str)) or isinstance(y, (bytes, str)):
            if x != y:
                out[key] = [str(x), str(y)]
        elif np.size(x) == 1 and np.size(y) == 1:
            x, y = float(np.asarray(x)), float(np.asarray(y))
            if not (x == y or (np.isnan(x) and np.isnan(y)) or max(abs(x), abs(y)) < 1e-12):
                out[key] = abs(x - y) / max(abs(x), abs(y), 1e-300)
    return out


def transient_forces(contact_file, world_file) -> dict:
    """Per step |F_contact - F_world| / |F_world| (F = (F_x, F_y) of each step, the initial state's zero force
    left out): the largest, and the largest relative to mu Fn."""
    import h5py
    import numpy as np
    with h5py.File(contact_file, "r") as c, h5py.File(world_file, "r") as w:
        fc = np.stack([c["history/F_x"][()], c["history/F_y"][()]], axis=1)
        fw = np.stack([w["history/F_x"][()], w["history/F_y"][()]], axis=1)
        mu_fn = float(w["summary"].attrs["mu_Fn"])
    diff = np.linalg.norm(fc - fw, axis=1)[1:]
    size = np.linalg.norm(fw, axis=1)[1:]
    return {"steps": int(len(diff)), "max_relative": float((diff / size).max()), "max_of_mu_fn": float(diff.max() / mu_fn)}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--baseline", required=True, help="Python of the install compared against")
    ap.add_argument("--contact", help="CONTACT's stand-alone program (needs --decks)")
    ap.add_argument("--decks", help="folder of CONTACT's inputs " + ", ".join(f"{d}.inp" for d in DECKS.values()))
    ap.add_argument("--repeats", type=int, default=5, help="runs per variant (median; default 5)")
    ap.add_argument("--quick", action="store_true", help="2 repeats, no dx = 0.05 scene")
    _record.add_output(ap)
    args = ap.parse_args(argv)
    if bool(args.contact) != bool(args.decks):
        ap.error("--contact and --decks go together")
    repeats = 2 if args.quick else args.repeats
    lean, base = sys.executable, str(Path(args.baseline).absolute())
    result = {"repeats": repeats, "baseline": base}
    with tempfile.TemporaryDirectory() as tmp:
        def run_cmd(python, extra, name):
            return [rollcontact(python), "run", "-q", "--overwrite", "-o", str(Path(tmp) / name), *extra]

        variants = {"lean": run_cmd(lean, PAPER, "paper_lean.h5"), "baseline": run_cmd(base, PAPER, "paper_base.h5")}
        if contact_variant(args, "paper", tmp):
            variants["contact"] = contact_variant(args, "paper", tmp)
        for spec in variants.values():                  # warm: compiled kernels, FFTW wisdom
            measure(*(spec if isinstance(spec, tuple) else (spec, None)), cwd=tmp)
        result["paper"] = interleaved(variants, repeats, tmp)
        _report("paper", result["paper"])

        warm = {}
        for name, python in (("lean", lean), ("baseline", base)):
            warm[name] = statistics.median(
                float(subprocess.run([python, "-c", WARM_RUN, *PAPER[1::2]], capture_output=True, text=True,
                                     env=process_env(), check=True, cwd=tmp).stdout.split()[-1])
                for _ in range(repeats))
        result["fixed_cost"] = {name: {"process_cpu_s": result["paper"][name]["cpu_s"], "warm_run_cpu_s": warm[name],
                                       "fixed_cpu_s": result["paper"][name]["cpu_s"] - warm[name]}
                                for name in warm}
        for name, v in result["fixed_cost"].items():
            print(f"fixed cost {name:9s} {v['fixed_cpu_s']:.3f} s CPU (process {v['process_cpu_s']:.2f} s, warm run "
                  f"{v['warm_run_cpu_s']:.2f} s)", flush=True)

        if not args.quick:
            result["fine"] = interleaved({"lean": run_cmd(lean, FINE, "fine_lean.h5"),
                                          "baseline": run_cmd(base, FINE, "fine_base.h5")}, min(repeats, 2), tmp)
            _report("fine (dx = 0.05)", result["fine"])

        scene = str(SCENES / "d_transient.toml")
        variants = {"lean": [rollcontact(lean), "run", scene, "-q", "--overwrite", "-o", f"{tmp}/tr_lean.h5"],
                    "lean_world": [rollcontact(lean), "run", scene, "-q", "--overwrite", "-o", f"{tmp}/tr_world.h5",
                                   "--set", 'rolling.grid="world"'],
                    "baseline": [rollcontact(base), "run", scene, "-q", "--overwrite", "-o", f"{tmp}/tr_base.h5"]}
        if contact_variant(args, "transient", tmp):
            variants["contact"] = contact_variant(args, "transient", tmp)
        result["transient"] = interleaved(variants, repeats, tmp)
        result["transient"]["forces_vs_baseline"] = transient_forces(f"{tmp}/tr_lean.h5", f"{tmp}/tr_base.h5")
        result["transient"]["world_vs_baseline"] = transient_forces(f"{tmp}/tr_world.h5", f"{tmp}/tr_base.h5")
        _report("transient", result["transient"])

        scene = str(SCENES / "creep_circle.toml")
        variants = {name: [rollcontact(python), "creep-curve", scene, "--overwrite", "-o", f"{tmp}/curve_{name}"]
                    for name, python in (("lean", lean), ("baseline", base))}
        if contact_variant(args, "creep_curve", tmp):
            variants["contact"] = contact_variant(args, "creep_curve", tmp)
        result["creep_curve"] = interleaved(variants, repeats, tmp)
        _report("creep curve", result["creep_curve"])

        result["subsurface"] = {}
        for name, python in (("lean", lean), ("baseline", base)):
            out = subprocess.run([python, "-c", SUBSURFACE, f"{tmp}/paper_lean.h5", str(max(repeats, 3))],
                                 capture_output=True, text=True, check=True, cwd=tmp)
            result["subsurface"][name] = json.loads(out.stdout.strip().splitlines()[-1])
        print("subsurface, one paper step, 30 depths (CPU s): " + ", ".join(
            f"{n}: compute {v['compute_s']:.3f}, stresses on the file {v['add_subsurface_s']:.3f}"
            for n, v in result["subsurface"].items()), flush=True)

        outputs = {"paper run": compare(f"{tmp}/paper_lean.h5", f"{tmp}/paper_base.h5")}
        for name, python in (("lean", lean), ("base", base)):
            subprocess.run([rollcontact(python), "run", scene, "-q", "--overwrite", "-o", f"{tmp}/creep_{name}.h5"],
                           check=True, cwd=tmp, capture_output=True)
            shutil.copyfile(f"{tmp}/paper_base.h5", f"{tmp}/stress_{name}.h5")
            subprocess.run([rollcontact(python), "stresses", f"{tmp}/stress_{name}.h5", "-q"], check=True, cwd=tmp,
                           capture_output=True)
        outputs["steady creep run"] = compare(f"{tmp}/creep_lean.h5", f"{tmp}/creep_base.h5")
        outputs["subsurface stresses"] = compare(f"{tmp}/stress_lean.h5", f"{tmp}/stress_base.h5")
        result["outputs"] = outputs
        for name, c in outputs.items():
            worst = max((v for v in c["differ"].values() if isinstance(v, float)), default=0.0)
            texts = {k: v for k, v in c["summary"].items() if isinstance(v, list)}
            numbers = max((v for v in c["summary"].values() if isinstance(v, float)), default=0.0)
            print(f"outputs, {name}: {c['identical']} datasets identical, {len(c['differ'])} differ (largest "
                  f"{worst:.2g} of the quantity's largest value); summary numbers within {numbers:.2g} relative"
                  + (f", texts differ: {texts}" if texts else ", texts equal")
                  + f"; FFT products {c['iteration_totals'][0]:.0f} against {c['iteration_totals'][1]:.0f}",
                  flush=True)
    path = _record.write("lean", result, args.output)
    load = json.loads(path.read_text())["recorded"]["load"]
    print(f"load {load['start'][0]:.2f} -> {load['end'][0]:.2f}")


def _report(case, res):
    line = ", ".join(f"{name} {v['cpu_s']:.2f} s / {v['rss_mb']:.0f} MB" for name, v in res.items()
                     if isinstance(v, dict) and "cpu_s" in v)
    base = res.get("baseline")
    ratios = ", ".join(f"{name}/baseline {v['cpu_s'] / base['cpu_s']:.3f}" for name, v in res.items()
                       if isinstance(v, dict) and "cpu_s" in v and name != "baseline")
    print(f"{case}: {line}; {ratios}", flush=True)


if __name__ == "__main__":
    main()

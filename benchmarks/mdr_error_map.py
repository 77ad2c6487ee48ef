"""The u_sd error map of the 1-D MDR model against the 3-D solver for shakedown scenes, and its held-out set
(solver/mdr/error_map.py reads the map; docs/creep_fidelity.md).

    .venv/bin/python benchmarks/mdr_error_map.py [-o DIR] [--quick]
        # writes DIR/error_map.json and DIR/held_out.json (default DIR: results/mdr_error_map)
    .venv/bin/python benchmarks/mdr_error_map.py --map-out solver/mdr/error_map.json \\
        --held-out-out tests/cases/data/mdr_held_out.json          # refresh the committed files (~5 min)

The seed's scene (cases/paper_perpendicular.toml: a steel sphere R = 40 mm on rubber, mu = 0.93, Fn = 21.19 N, 10
periods, dx = dW = 0.2 mm, a/dx = 24) at the alignment angles 0 and 90 deg, w = 0.1, 0.23, 0.4 and f_t = 0.1 ...
0.9 (the seed's Fig. 8 family, benchmarks/sweep_paper.py): each scene is run on the boundary elements and on the MDR
model ([solver] fidelity = "mdr"), and the map stores |u_sd(MDR) - u_sd(3-D)| / u_sd(3-D) where both shake down,
null where either does not, with the states and the runs' CPU times. The held-out set: w = 0.15, 0.3 and f_t =
0.15 ... 0.65 at both alignments, off the map's nodes; tests/cases/test_fidelity_auto.py checks on them that the
map never lets `auto` choose the MDR model beyond the requested accuracy.
"""
from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
from pathlib import Path
import statistics
import sys
import time

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from rollcontact.cases import api  # noqa: E402

SCENE = HERE.parent / "cases" / "paper_perpendicular.toml"
FULL = dict(angle=(0.0, 90.0), w=(0.1, 0.23, 0.4), f_t=(0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9),
            held_w=(0.15, 0.3), held_f_t=(0.15, 0.25, 0.35, 0.45, 0.55, 0.65))
QUICK = dict(angle=(0.0, 90.0), w=(0.1, 0.23), f_t=(0.2, 0.4), held_w=(0.15,), held_f_t=(0.3,), dx=0.4)


def compare(angle, w, f_t, dx=None):
    """Both models on the scene at (angle, w, f_t): the states, u_sd of each, the error and the CPU seconds."""
    overrides = {"motion.angle": angle, "motion.w": w, "load.ft": f_t}
    if dx is not None:
        overrides["grid.dx"] = dx
    out = dict(angle=angle, w=w, f_t=f_t)
    for model in ("bem", "mdr"):
        scene = api.load_scene(SCENE, dict(overrides, **{"solver.fidelity": model}))
        c0 = time.process_time()
        s = api.run(scene).summary
        out[f"{model}_seconds"] = time.process_time() - c0
        out[f"{model}_state"], out[f"{model}_u_sd"] = s["state"], s.get("u_sd")
    both = out["bem_state"] == out["mdr_state"] == "shakedown"
    out["error"] = abs(out["mdr_u_sd"] - out["bem_u_sd"]) / out["bem_u_sd"] if both else None
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--output", default="results/mdr_error_map", help="folder for both JSON files")
    parser.add_argument("--map-out", help="write the map here instead (e.g. solver/mdr/error_map.json)")
    parser.add_argument("--held-out-out", help="write the held-out set here instead")
    parser.add_argument("--quick", action="store_true", help="a 2 x 2 x 2 map at dx = 0.4 mm and 2 held-out runs")
    args = parser.parse_args(argv)
    config = QUICK if args.quick else FULL
    dx = config.get("dx")
    load, start = os.getloadavg(), time.perf_counter()
    rows = []
    for angle in config["angle"]:
        for w in config["w"]:
            for f_t in config["f_t"]:
                rows.append(compare(angle, w, f_t, dx))
                r = rows[-1]
                print(f"angle {angle:g} w {w:g} f_t {f_t:g}: 3-D {r['bem_state']} {r['bem_u_sd']}, MDR "
                      f"{r['mdr_state']} {r['mdr_u_sd']}, error {r['error']}", flush=True)
    held = [compare(angle, w, f_t, dx) for angle in config["angle"] for w in config["held_w"]
            for f_t in config["held_f_t"]]
    errors = [[[next(r["error"] for r in rows if (r["angle"], r["w"], r["f_t"]) == (a, w, f))
                for f in config["f_t"]] for w in config["w"]] for a in config["angle"]]
    nu = api.load_scene(SCENE).material_pair.nu
    info = dict(date=datetime.date.today().isoformat(), machine=platform.machine(), python=platform.python_version(),
                cpu_count=os.cpu_count(), loadavg_before=load, loadavg_after=os.getloadavg(),
                wall_time_s=time.perf_counter() - start, quick=args.quick,
                command="benchmarks/mdr_error_map.py" + (" --quick" if args.quick else ""))
    data = dict(quantity="|u_sd(MDR) - u_sd(3-D)| / u_sd(3-D); null where either run does not shake down",
                reference=f"the boundary elements on {SCENE.name} (dx = dW = {dx or 0.2} mm), 10 periods",
                nu=nu, axes={k: list(config[k]) for k in ("angle", "w", "f_t")}, errors=errors,
                seconds_per_run={m: statistics.median(r[f"{m}_seconds"] for r in rows) for m in ("bem", "mdr")},
                runs=rows, **info)
    out = Path(args.output)
    map_path = Path(args.map_out) if args.map_out else out / "error_map.json"
    held_path = Path(args.held_out_out) if args.held_out_out else out / "held_out.json"
    for path, payload in ((map_path, data), (held_path, dict(info, rows=held))):
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(payload, indent=1) + "\n")
        print(path.resolve())
    return 0


if __name__ == "__main__":
    sys.exit(main())

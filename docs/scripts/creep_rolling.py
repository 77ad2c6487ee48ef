"""The tables of docs/creep_rolling.md: steady and transient rolling with creepage and spin against Kalker.

    .venv/bin/python docs/scripts/creep_rolling.py [-o results/creep_rolling] [--quick]

    python benchmarks/creep_linear.py --n 41 81 -o OUT           Kalker's C11, C22, C23 (and C33) in full adhesion
    python benchmarks/creep_transient.py --n 41 61 --initial rest cattaneo -o OUT       rolled from rest on the world grid
    rollcontact run SCENE (sphere, cone, rounded flat punch, cylinder; steel on steel, xi = 1e-5 and 0.05)

--quick: the circle with nu = 0.25 at n = 41, one contact length rolled from rest at n = 41, the sphere's row.
"""
from __future__ import annotations

import json
import math
from pathlib import Path
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _study import SKIPPED, Study  # noqa: E402

RATIOS = [0.5, 1.0, 2.0]
NUS = [0.0, 0.25, 0.5]
STEEL = """
[materials]
E1 = 210e3
nu1 = 0.28
E2 = 210e3
nu2 = 0.28
[load]
Fn = 1000.0
mu = 0.3
"""
SHAPES = {"sphere R = 40 mm": "R = 40.0", "cone, slope 3°": 'shape = "cone"\nslope = 3.0',
          "flat punch b = 0.5 mm, edge R = 40 mm": 'shape = "flat_rounded"\nb = 0.5\nR = 40.0',
          "cylinder R = 40, length 5, edge R = 20 mm, axis y":
              'shape = "cylinder"\nR = 40.0\nlength = 5.0\nedge_R = 20.0\naxis = "y"'}


def signed(values):
    return " / ".join(f"{v:+.2f}" for v in values)


def linear(study):
    ns = ["41"] if study.quick else ["41", "81"]
    study.python("benchmarks/creep_linear.py", *(["--quick"] if study.quick else []), "--n", *ns, "-o", study.out)
    rows = {(r["a_over_b"], r["nu"], r["n"]): r for r in
            json.loads((study.out / "creep_linear.json").read_text())["rows"]}
    out = []
    for ratio in RATIOS:
        for nu in NUS:
            r41, r81 = rows.get((ratio, nu, 41)), rows.get((ratio, nu, 81))
            out.append([f"{ratio:g}", f"{nu:g}",
                        signed(r41["error_pct"]) if r41 else SKIPPED,
                        signed(r81["error_pct"]) if r81 else SKIPPED,
                        signed(r81["error_area_corrected_pct"] + [100 * ((1 + r81["error_pct"][2] / 100)
                                                                        / r81["area_ratio"] ** 1.5 - 1)])
                        if r81 else SKIPPED,
                        f"{r81['C33']:.3f} ({r81['C33_published']:g})" if r81 else SKIPPED])
    study.table("linear", ["a/b", "ν", "error % at n = 41 (C11 / C22 / C23)", "at n = 81", "area-corrected at 81",
                           "C33 at 81 (published)"], out)


def shapes(study):
    from rollcontact.cases.run.scene_run import run_scene
    from rollcontact.cases.scene.scene import Scene
    out = []
    for label, geometry in SHAPES.items():
        if study.quick and not label.startswith("sphere"):
            out.append([label, SKIPPED, SKIPPED, SKIPPED, SKIPPED])
            continue

        def scene(xi):
            return Scene.from_toml_text(f"{STEEL}\n[geometry]\n{geometry}\n[rolling]\nmode = \"steady\"\nxi = {xi}\n")
        small = run_scene(scene(1e-5))
        s = small.summary
        ratio = s["F_x"] / s["F_x_linear"]
        area = float(small.history["contact_area"][-1]) / (math.pi * s["a"] * s["b"])
        sliding = run_scene(scene(0.05)).summary
        out.append([label, f"{ratio:.4f}", f"{area:.4f}", f"{100 * (ratio / area - 1):+.1f} %",
                    f"{1 - abs(sliding['F_x']) / sliding['mu_Fn']:.1e}"])
    study.table("shapes", ["shape", "F_x / linear theory (ξ = 1e-5)", "contact area / πab", "area-corrected",
                           "1 − abs(F_x)/(μFn) at ξ = 0.05"], out)


def transient(study):
    if study.quick:
        study.python("benchmarks/creep_transient.py", "--quick", "-o", study.out)
    else:
        study.python("benchmarks/creep_transient.py", "--n", "41", "61", "--initial", "rest", "cattaneo",
                     "-o", study.out)
    data = json.loads((study.out / "creep_transient.json").read_text())
    runs = {(r["n"], r["initial"]): {row["lengths"]: row for row in r["rows"]} for r in data["results"]}
    out = []
    for lengths in (1, 2, 3, 4, 6, 8):
        cells = []
        for key in ((41, "rest"), (41, "cattaneo"), (61, "rest")):
            row = runs.get(key, {}).get(lengths)
            cells.append(SKIPPED if row is None else
                         " / ".join(f"{100 * row[k]:+.3g}" for k in ("dFx", "dFy", "dMz")))
        out.append([str(lengths), *cells])
    study.table("transient", ["contact lengths rolled", "n = 41, rest: Fx / Fy / Mz %", "n = 41, cattaneo",
                              "n = 61, rest"], out)


def main(argv=None) -> int:
    study = Study.from_command_line("creep_rolling", __doc__, argv)
    linear(study)
    shapes(study)
    transient(study)
    return study.finish()


if __name__ == "__main__":
    sys.exit(main())

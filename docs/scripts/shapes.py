"""The tables and figures of docs/shapes.md: shakedown of the cone, the power law n = 4 and the rounded flat punch.

    .venv/bin/python docs/scripts/shapes.py [-o results/shapes] [--figures DIR] [--quick] [--jobs N]

For each profile of docs/shapes/ (cone.toml, power4.toml, flat_rounded.toml: the seed's materials and load, w = 0.23,
20 periods, the default grid a/12 and dW = dx):

    rollcontact sweep SCENE --vary load.ft=0.1:0.8:8 --vary motion.angle=0,90 -o OUT/<shape>_sweep
    rollcontact sweep SCENE --vary load.ft=0.1:0.8:8 --set solver.fidelity=mdr -o OUT/<shape>_mdr
    rollcontact limit-search SCENE --vary motion.w=0.23 --vary motion.angle=0,90 --tol 0.005 -o OUT/<shape>_limits
    rollcontact plot OUT/<shape>_sweep -o OUT/figures          (with the limit brackets copied beside the sweep)

and the maps of the rounded flat punch at f_t = 0.5, perpendicular. Tables: the scenes, the limits, u_sd and the
ratcheting increments (OUT/tables.md), compared with the page. --quick: the cone at f_t = 0.3 only (3-D in both
settings and the 1-D MDR), and the closed forms.
"""
from __future__ import annotations

import csv
from pathlib import Path
import shutil
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _study import DOCS, SKIPPED, Study, fmt  # noqa: E402

SHAPES = {"cone": "cone 6°", "power4": "power n = 4", "flat_rounded": "rounded flat"}
PROFILES = {"cone": "h = r tan 6°", "power4": "h = r⁴/(4 R³), R = 10 mm",
            "flat_rounded": "flat radius b = 4 mm, edge radius R = 5 mm"}
FT = [round(0.1 * k, 1) for k in range(1, 9)]
W = 0.23


def scene_table(study):
    import rollcontact
    from rollcontact.cases.run.discretise import scene_grid
    rows = []
    for s in SHAPES:
        scene = rollcontact.load_scene(DOCS / "shapes" / f"{s}.toml")
        ref = scene.normal_reference
        grid = scene_grid(scene)
        rows.append([f"`{s}.toml`", PROFILES[s], f"{ref.a:.3f} mm", f"{ref.approach:.4f} mm",
                     f"{scene.spacing[0]:.2f} mm", f"{grid.shape[0]} × {grid.shape[1]}"])
    study.table("scenes", ["scene (docs/shapes/)", "profile", "MDR contact radius a", "approach d",
                           "default grid dx = a/12", "elements (ny × nx)"], rows)


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def runs(study, s):
    """The sweeps and the limit search of shape s (quick: the cone at f_t = 0.3)."""
    scene = DOCS / "shapes" / f"{s}.toml"
    ft = "0.3" if study.quick else "0.1:0.8:8"
    sweep, mdr, limits = (study.out / f"{s}_{k}" for k in ("sweep", "mdr", "limits"))
    study.rc("sweep", scene, "--vary", f"load.ft={ft}", "--vary", "motion.angle=0,90", "-o", sweep, "-q")
    study.rc("sweep", scene, "--vary", f"load.ft={ft}", "--set", "solver.fidelity=mdr", "-o", mdr, "-q")
    if not study.quick:
        study.rc("limit-search", scene, "--vary", f"motion.w={W}", "--vary", "motion.angle=0,90", "--tol", "0.005",
                 "-o", limits, "-q")
        shutil.copyfile(limits / "limits.csv", sweep / "limits.csv")
        study.rc("plot", sweep, "-o", study.out / "plots", "--overwrite", capture=True)
        study.figure(study.out / "plots" / f"{s}_sweep_usd.png", f"{s}_sweep_usd.png")
    rows = {(round(float(r["f_t"]), 6), float(r["angle"])): r for r in read_csv(sweep / "summary.csv")}
    rows_mdr = {round(float(r["f_t"]), 6): r for r in read_csv(mdr / "summary.csv")}
    brackets = {}
    if not study.quick:
        for r in read_csv(limits / "limits.csv"):
            brackets[float(r["motion.angle"])] = (float(r["lower"]), float(r["upper"]))
    return rows, rows_mdr, brackets


def grid_check(study, s, bracket):
    """The perpendicular runs on the a/24 grid (40 periods) at both ends of the a/12 bracket of shape s."""
    import rollcontact
    scene = rollcontact.load_scene(DOCS / "shapes" / f"{s}.toml")
    dx = round(scene.normal_reference.a / 24, 2)
    if bracket is None:
        return [SHAPES[s], f"{dx:.2f} mm", SKIPPED, SKIPPED]
    cells = []
    for f in bracket:
        path = study.out / f"{s}_a24_ft{f:.4f}.h5"
        if not path.exists():
            study.rc("run", DOCS / "shapes" / f"{s}.toml", "--set", f"load.ft={f:.4f}", "--set", "motion.angle=90",
                     "--set", f"grid.dx={dx}", "--set", "motion.periods=40", "-o", path, "-q")
        r = rollcontact.read_run(path).summary
        cells.append(f"f_t = {f:.4f}: " + (f"shakedown (u_sd = {r['u_sd']:.4f})" if r["state"] == "shakedown" else
                                           f"ratcheting (Δu = {r['du']:.4f})" if r["state"] == "ratcheting" else
                                           r["state"]))
    return [SHAPES[s], f"{dx:.2f} mm", *cells]


def main(argv=None) -> int:
    study = Study.from_command_line("shapes", __doc__, argv)
    import rollcontact
    scene_table(study)
    limits, usd, du = [], {f: [] for f in FT}, {f: [] for f in (0.6, 0.7, 0.8)}
    brackets_perp = {}
    for s in SHAPES:
        scene = rollcontact.load_scene(DOCS / "shapes" / f"{s}.toml")
        tg = scene.tangential_reference
        f_lim, u_lim = tg.limit(W * scene.contact_radius)
        computed = not study.quick or s == "cone"
        rows, rows_mdr, brackets = runs(study, s) if computed else ({}, {}, {})
        if 90.0 in brackets:
            brackets_perp[s] = brackets[90.0]
        cells = [f"[{brackets[a][0]:.4f}, {brackets[a][1]:.4f}]" if a in brackets else SKIPPED for a in (0.0, 90.0)]
        limits.append([SHAPES[s], *cells, f"{f_lim:.4f}", f"{u_lim:.3f}"])
        for f in FT:
            par, perp, m = rows.get((f, 0.0)), rows.get((f, 90.0)), rows_mdr.get(f)
            if par is None or perp is None or m is None:
                usd[f].append(SKIPPED)
                if f in du:
                    du[f].append(SKIPPED)
                continue
            mdr_sd = tg.shakedown_shift(f, W * scene.contact_radius) if f < f_lim else None
            states = [par["state"], perp["state"]]
            cell = [fmt(float(r["u_sd"])) if r["state"] == "shakedown" else r["state"] for r in (par, perp)]
            cell.append(fmt(mdr_sd) if mdr_sd is not None else "ratchets")
            usd[f].append(" / ".join(cell))
            if f in du:
                if all(st == "ratcheting" for st in states):
                    mdr_du = fmt(float(m["du"])) if m["state"] == "ratcheting" else "sd"
                    du[f].append(f"{fmt(float(par['du']))} / {fmt(float(perp['du']))} / {mdr_du}")
                else:
                    du[f].append(" / ".join(st if st != "shakedown" else "sd" for st in states) + " / "
                                 + ("sd" if m["state"] == "shakedown" else m["state"]))
    study.table("limits", ["w = 0.23", "3-D f_t,lim, parallel", "3-D f_t,lim, perpendicular",
                           "MDR f_t,lim of the profile", "MDR u_lim"], limits)
    study.table("usd", ["f_t", *(f"{SHAPES[s]} par / perp / MDR" for s in SHAPES)],
                [[f"{f:.1f}", *usd[f]] for f in FT])
    study.table("du", ["f_t", *SHAPES.values()], [[f"{f:.1f}", *du[f]] for f in du])
    study.table("grid_check", ["profile", "dx (a/24)", "lower end of the bracket: state", "upper end: state"],
                [grid_check(study, s, brackets_perp.get(s)) for s in SHAPES])
    if not study.quick:
        flat = sorted((study.out / "flat_rounded_sweep").glob("ft=0.5_angle=90__*.h5"))[0]
        study.rc("plot", flat, "-o", study.out / "plots", "--overwrite", capture=True)
        maps = sorted((study.out / "plots").glob(f"{flat.stem}_maps_step*.png"))[-1]
        study.figure(maps, "flat_rounded_maps.png")
    return study.finish()


if __name__ == "__main__":
    sys.exit(main())

"""The tables and figure of docs/alignment.md: any angle between the tangential load and the rolling direction.

    .venv/bin/python docs/scripts/alignment.py [-o results/alignment] [--figures DIR] [--quick] [--jobs N]

The paper scene rolled parallel (cases/paper_parallel.toml: dx = dW = 0.2 mm, 10 periods) at every angle:

    rollcontact sweep cases/paper_parallel.toml --vary motion.angle=0,15,30,45,60,75,90 \\
        --vary motion.w=0.1,0.23,0.4 --vary load.ft=0.2,0.4,0.6,0.8 -o OUT/alignment
    rollcontact limit-search cases/paper_parallel.toml --vary motion.w=0.1,0.23,0.4 \\
        --vary motion.angle=0,15,30,45,60,75,90 --tol 0.01 -o OUT/alignment
    rollcontact limit-search ... --vary motion.angle=0,45,90 --tol 0.0025 -o OUT/alignment --overwrite
    rollcontact plot OUT/alignment -o OUT/plots
    rollcontact run cases/paper_parallel.toml --set load.ft=F --set motion.periods=120 -o OUT/near_F.h5
        (F = 0.655, 0.66, 0.6611, 0.665)

The fine limit search reuses the probes of the coarse one (same folder; the coarse limits.csv is kept as
limits_coarse.csv). Tables: kappa per angle, u_sd, the sideways walk, the limits, the decay near the limit.
--quick: the run at 30 deg, w = 0.23, f_t = 0.4, and the closed forms.
"""
from __future__ import annotations

import csv
import math
from pathlib import Path
import shutil
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _study import ROOT, SKIPPED, Study, fmt  # noqa: E402

ANGLES = [0, 15, 30, 45, 60, 75, 90]
WS = [0.1, 0.23, 0.4]
FTS = [0.2, 0.4, 0.6, 0.8]
NEAR = [0.655, 0.66, 0.6611, 0.665]
SCENE = ROOT / "cases" / "paper_parallel.toml"


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def runs(study):
    folder = study.out / "alignment"
    if study.quick:
        study.rc("sweep", SCENE, "--vary", "motion.angle=30", "--vary", "motion.w=0.23", "--vary", "load.ft=0.4",
                 "-o", folder, "-q")
        return read_csv(folder / "summary.csv"), [], []
    study.rc("sweep", SCENE, "--vary", "motion.angle=" + ",".join(map(str, ANGLES)),
             "--vary", "motion.w=" + ",".join(map(str, WS)), "--vary", "load.ft=" + ",".join(map(str, FTS)),
             "-o", folder, "-q")
    study.rc("limit-search", SCENE, "--vary", "motion.w=" + ",".join(map(str, WS)),
             "--vary", "motion.angle=" + ",".join(map(str, ANGLES)), "--tol", "0.01", "-o", folder, "-q")
    shutil.copyfile(folder / "limits.csv", folder / "limits_coarse.csv")
    study.rc("limit-search", SCENE, "--vary", "motion.w=" + ",".join(map(str, WS)),
             "--vary", "motion.angle=0,45,90", "--tol", "0.0025", "-o", folder, "--overwrite", "-q")
    study.rc("plot", folder, "-o", study.out / "plots", "--overwrite", capture=True)
    study.figure(study.out / "plots" / "alignment_angles.png", "alignment_angles.png")
    return (read_csv(folder / "summary.csv"), read_csv(folder / "limits_coarse.csv"),
            read_csv(folder / "limits.csv"))


def key(r):
    return round(float(r["motion.angle"])), round(float(r["motion.w"]), 6), round(float(r["load.ft"]), 6)


def kappa_table(study, rows):
    from rollcontact.solver.mdr.limits import fit_kappa
    fits, counts = [], []
    for angle in ANGLES:
        sd = [r for r in rows if key(r)[0] == angle and r["state"] == "shakedown"]
        if study.quick or not sd:
            fits.append(SKIPPED)
            counts.append(SKIPPED)
            continue
        fit = fit_kappa([float(r["f_t"]) for r in sd], [float(r["w"]) for r in sd], [float(r["u_sd"]) for r in sd])
        fits.append(f"{fit.kappa:.3f} ± {fit.stderr:.3f}")
        counts.append(str(fit.n))
    study.table("kappa", ["θ (deg)", *map(str, ANGLES)], [["κ", *fits], ["runs", *counts]])
    return fits


def usd_table(study, rows):
    by = {key(r): r for r in rows}
    out = []
    for w in WS:
        for f in FTS:
            cells = []
            for angle in ANGLES:
                r = by.get((angle, w, f))
                if r is None:
                    cells.append(SKIPPED)
                else:
                    cells.append(fmt(float(r["u_sd"])) if r["state"] == "shakedown" else r["state"])
            out.append([f"{w:g}", f"{f:g}", *cells])
    study.table("usd", ["w", "f_t", *(f"{a}°" for a in ANGLES)], out)


def walk_table(study, rows, U0):
    by = {key(r): r for r in rows}
    oblique = [15, 30, 45, 60, 75]

    def cell(angle, w, f, column, scale=1.0 / U0):
        r = by.get((angle, w, f))
        return SKIPPED if r is None or not r[column] else f"{float(r[column]) * scale:.4f}"

    rest = [cell(a, 0.23, 0.4, "U_perp") for a in oblique]
    amplitude = cell(45, 0.23, 0.4, "U_perp")
    fitted = [SKIPPED if amplitude == SKIPPED else f"{float(amplitude) * math.sin(math.radians(2 * a)):.4f}"
              for a in oblique]
    walk = [cell(a, 0.4, 0.8, "dU_perp_per_period") for a in oblique]
    along = [cell(a, 0.4, 0.8, "du", 1.0) for a in oblique]
    study.table("walk", ["", *(f"{a}°" for a in oblique)],
                [["U⊥/U0 at rest, w = 0.23, f_t = 0.4", *rest],
                 ["U⊥/U0(45°) sin 2θ", *fitted],
                 ["ΔU⊥/U0 per period, w = 0.4, f_t = 0.8", *walk],
                 ["Δu along Ft per period, same run", *along]])


def limits_table(study, coarse, fine):
    from rollcontact.solver.mdr import limits as lim

    def bracket(rows, w, angles):
        got = {(round(float(r["motion.angle"])), round(float(r["motion.w"]), 6)): r for r in rows}
        cells = {f"[{float(got[a, w]['lower']):.4f}, {float(got[a, w]['upper']):.4f}]"
                 for a in angles if (a, w) in got}
        if len(cells) == 0 or len([a for a in angles if (a, w) in got]) < len(angles):
            return SKIPPED
        return cells.pop() if len(cells) == 1 else "differs: " + ", ".join(sorted(cells))

    out = []
    for w in WS:
        out.append([f"{w:g}", bracket(coarse, w, ANGLES), bracket(fine, w, [0, 45, 90]),
                    f"{lim.f_t_lim(w, 1.5):.4f}", f"{lim.f_t_lim(w, 1.0):.3f}", f"{lim.f_t_lim(w, 1.1):.3f}"])
    study.table("limits", ["w", "3-D bracket, every θ (tol 0.01)", "3-D bracket, θ = 0°, 45°, 90° (tol 0.0025)",
                           "1 − 1.5w + 0.5w³", "seed Eq. 18 (κ = 1, ∥)", "seed Eq. 19 (κ = 1.1, ⊥)"], out)


def near_limit_table(study, U0):
    rows = []
    for f in NEAR:
        if study.quick:
            rows.append([f"{f:g}", SKIPPED, SKIPPED, SKIPPED, SKIPPED])
            continue
        path = study.out / f"near_{f:g}.h5"
        if not path.exists():
            study.rc("run", SCENE, "--set", f"load.ft={f}", "--set", "motion.periods=120", "-o", path, "-q")
        import rollcontact
        r = rollcontact.read_run(path)
        period, U = r.history["period"], r.history["U_x"]
        ends = [U[period <= 0][-1]] + [U[period == k][-1] for k in range(1, int(period.max()) + 1)]
        dU = [b - a for a, b in zip(ends, ends[1:])]
        below = next((k + 1 for k, d in enumerate(dU) if abs(d) < 1e-5), None)
        q = [b / a for a, b in zip(dU, dU[1:]) if a != 0]
        early = sum(q[9:19]) / len(q[9:19])
        last = q[max(0, (below or len(dU)) - 11):(below or len(dU)) - 1]
        state = r.summary["state"] + (f" after {r.summary['periods_to_shakedown']} periods"
                                      if r.summary["state"] == "shakedown" else "")
        rows.append([f"{f:g}", f"{early:.3f} → {sum(last) / len(last):.3f}",
                     str(below) if below else f"not within 120 (ΔU = {dU[-1]:.1e} mm)", state,
                     f"{dU[-1] / U0:.1e}"])
    study.table("near", ["f_t", "ratio q per period, periods 11-20 → the last 10",
                         "periods until ΔU < 1e-5 mm", "state after 120 periods", "Δu of period 120"], rows)


def main(argv=None) -> int:
    study = Study.from_command_line("alignment", __doc__, argv)
    import rollcontact
    U0 = rollcontact.load_scene(SCENE).tangential_reference.U0
    rows, coarse, fine = runs(study)
    kappa_table(study, rows)
    usd_table(study, rows)
    walk_table(study, rows, U0)
    limits_table(study, coarse, fine)
    near_limit_table(study, U0)
    return study.finish()


if __name__ == "__main__":
    sys.exit(main())

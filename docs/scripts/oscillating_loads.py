"""The tables and figures of docs/oscillating_loads.md: loads oscillating within each period, with and without rolling.

    .venv/bin/python docs/scripts/oscillating_loads.py [-o results/oscillating_loads] [--figures DIR] [--quick]

    python benchmarks/oscillating_loads.py --accuracy -o OUT          Mindlin-Deresiewicz and the MDR, without rolling
    rollcontact run ... (x = 0.6, dx = 0.4 mm, 24 ... 192 steps per period)       the work per cycle against the steps
    rollcontact run --set motion.w=0 --set load.ft=0 --set load.ft_amplitude=0.6 --set motion.periods=3 -o OUT/md06.h5
    rollcontact sweep --vary motion.angle=0,90 --vary load.ft_amplitude=0.1,0.2,0.3 --vary load.phase=0:315:8 \\
        --set output.fields=none -o OUT/osc_ft                 (and load.fn_amplitude into OUT/osc_fn)
    rollcontact limit-search --vary motion.w=0.23 --vary motion.angle=0,90 --vary load.phase=0:270:4 \\
        --set load.ft_amplitude=0.2 --set output.fields=none -o OUT/osc_lim   (and load.fn_amplitude=0.3: osc_fn_lim)
    rollcontact plot OUT/md06.h5, OUT/osc_ft, OUT/osc_fn, OUT/osc_lim, OUT/osc_fn_lim

--quick: the accuracy benchmark's quick subset (x = 0.6 on the default grid) and one run of the Ft map (W ⊥ Ft,
amplitude 0.1, phase 0°).
"""
from __future__ import annotations

import csv
import json
from pathlib import Path
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _study import SKIPPED, Study  # noqa: E402

STATE = {"cyclic_slip": "c", "shakedown": "s", "ratcheting": "r", "undecided": "u", "gross_sliding": "g"}
SETTINGS = {0.0: "W ∥ Ft", 90.0: "W ⊥ Ft"}
AMPLITUDES = [0.3, 0.6, 0.9]
PHASES = [0, 45, 90, 135, 180, 225, 270, 315]
STEPS = [24, 48, 96, 192]


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def pct(value, signed=False):
    return SKIPPED if value is None else (f"{100 * value:+.2f} %" if signed else f"{100 * value:.3f} %")


def accuracy(study):
    study.python("benchmarks/oscillating_loads.py", "--accuracy", *(["--quick"] if study.quick else []),
                 "-o", study.out)
    data = json.loads((study.out / "oscillating_loads_accuracy.json").read_text())
    md = {(r["materials"], r["default"], r["dx"] if not r["default"] else "default", r["x"]): r
          for r in data["mindlin_deresiewicz"]}
    rows = []
    for dx in ("default", 0.4, 0.2, 0.1):
        for name, label in (("nu = 0", "ν = 0 (identical bodies)"), ("paper", "paper (ν2 = 0.5)")):
            got = [md.get((name, dx == "default", dx, x)) for x in AMPLITUDES]
            if dx == "default":
                grid = "default (4 elements across the slip annulus)"
            else:
                grid = {0.4: "0.4 (a/12)", 0.2: "0.2 (a/24, paper)", 0.1: "0.1 (a/48)"}[dx]
            rows.append([label, grid, *(pct(r["loop_error"]) if r else SKIPPED for r in got),
                         *(pct(r["dissipation_error"], True) if r else SKIPPED for r in got)])
    study.table("md", ["materials", "dx (mm)", *(f"loop, x = {x}" for x in AMPLITUDES),
                       *(f"work per cycle, x = {x}" for x in AMPLITUDES)], rows)
    hist = {(r["history"], r["materials"], r["w"], r["angle"]): r for r in data["mdr"]}
    labels = HISTORY_LABELS
    rows = []
    for w, angle, where in ((0.0, 90.0, "0"), (0.23, 0.0, "0.23, W ∥ Ft"), (0.23, 90.0, "0.23, W ⊥ Ft")):
        for label in labels:
            cells = []
            for name in ("nu = 0", "paper"):
                r = hist.get((label, name, w, angle))
                cells += ([pct(r["error"]), f"{r['work_bem']:.3g} / {r['work_mdr']:.3g}"] if r else [SKIPPED, SKIPPED])
            rows.append([label, where, *cells])
    study.table("mdr", ["history", "w", "ν = 0: U error", "ν = 0: work 3-D / MDR (N·mm)", "paper: U error",
                        "paper: work 3-D / MDR (N·mm)"], rows)


#: the histories of benchmarks/oscillating_loads.py, in its order (the quick run computes only the last)
HISTORY_LABELS = ["proportional (Ft = 0.3 mu Fn(t), Fn 0.5-1.5 Fn)", "Fn +-40 % at constant Ft (f_t = 0.3)",
                  "Ft/Fn changing, Ft reversing (0.2 +- 0.3, Fn +-30 %)", "Ft 0 +- 0.6 (Mindlin-Deresiewicz)"]


def steps_table(study):
    """The work per Mindlin-Deresiewicz cycle and the trapezoidal loop area against the steps per period."""
    import numpy as np
    import rollcontact
    rows = []
    for n in STEPS:
        if study.quick:
            rows.append([str(n), SKIPPED, SKIPPED])
            continue
        path = study.out / f"md_steps{n}.h5"
        if not path.exists():
            study.rc("run", "--set", "motion.w=0", "--set", "load.ft=0", "--set", "load.ft_amplitude=0.6",
                     "--set", "grid.dx=0.4", "--set", f"motion.steps_per_period={n}", "--set", "motion.periods=2",
                     "--set", "output.fields=none", "-o", path, "-q")
        r = rollcontact.read_run(path)
        h = r.history
        last = np.flatnonzero(h["period"] == 2)
        F, U = h["F_x"][np.r_[last[0] - 1, last]], h["U_x"][np.r_[last[0] - 1, last]]
        area = abs(float(np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(U))))
        rows.append([str(n), f"{r.summary['dissipation_per_period']:.5f}", f"{area:.4f}"])
    study.table("steps", ["steps per period", "work per cycle (N·mm)", "trapezoidal loop area ∮F dU (N·mm)"], rows)


def maps(study, mu_Fn_U0):
    """The Ft and Fn maps (state letter and work of the last period over mu Fn U0)."""
    if study.quick:
        study.rc("sweep", "--vary", "motion.angle=90", "--vary", "load.ft_amplitude=0.1", "--vary", "load.phase=0",
                 "--set", "output.fields=none", "-o", study.out / "osc_ft", "-q")
    else:
        for kind in ("ft", "fn"):
            study.rc("sweep", "--vary", "motion.angle=0,90", "--vary", f"load.{kind}_amplitude=0.1,0.2,0.3",
                     "--vary", "load.phase=0:315:8", "--set", "output.fields=none", "-o", study.out / f"osc_{kind}",
                     "-q")
            study.rc("plot", study.out / f"osc_{kind}", "-o", study.out / "plots", "--overwrite", capture=True)
            study.figure(study.out / "plots" / f"osc_{kind}_phase.png", f"oscillating_{kind}_phase.png")
    for kind in ("ft", "fn"):
        table = study.out / f"osc_{kind}" / "summary.csv"
        got = {}
        if table.exists():
            for r in read_csv(table):
                got[(float(r["motion.angle"]), round(float(r[f"load.{kind}_amplitude"]), 6),
                     round(float(r["load.phase"])))] = r
        rows = []
        for angle, setting in SETTINGS.items():
            for amp in (0.1, 0.2, 0.3):
                cells = []
                for phase in PHASES:
                    r = got.get((angle, amp, phase))
                    cells.append(SKIPPED if r is None else
                                 f"{STATE.get(r['state'], r['state'])} "
                                 f"{float(r['dissipation_per_period']) / mu_Fn_U0:.3g}")
                rows.append([setting, f"{amp:g}", *cells])
        study.table(f"{kind}_map", ["setting", f"{kind}_amplitude", *(f"{p}°" for p in PHASES)], rows)


def limits(study):
    rows = []
    for kind, amp, folder in (("ft", 0.2, "osc_lim"), ("fn", 0.3, "osc_fn_lim")):
        got = {}
        if not study.quick:
            study.rc("limit-search", "--vary", "motion.w=0.23", "--vary", "motion.angle=0,90", "--vary",
                     "load.phase=0:270:4", "--set", f"load.{kind}_amplitude={amp}", "--set", "output.fields=none",
                     "-o", study.out / folder, "-q")
            study.rc("plot", study.out / folder, "-o", study.out / "plots", "--overwrite", capture=True)
            study.figure(study.out / "plots" / f"{folder}_phase_limits.png", f"oscillating_{kind}_limits.png")
            for r in read_csv(study.out / folder / "limits.csv"):
                got[(float(r["motion.angle"]), round(float(r["load.phase"])))] = r
        for angle, setting in SETTINGS.items():
            cells = []
            for phase in (0, 90, 180, 270):
                r = got.get((angle, phase))
                cells.append(SKIPPED if r is None else f"[{float(r['lower']):.4f}, {float(r['upper']):.4f}]")
            rows.append([setting, f"{kind}_amplitude = {amp}", *cells])
    study.table("limits", ["setting", "oscillation", "0°", "90°", "180°", "270°"], rows)


def main(argv=None) -> int:
    study = Study.from_command_line("oscillating_loads", __doc__, argv)
    import rollcontact
    scene = rollcontact.load_scene()
    mu_Fn_U0 = scene.load.mu * scene.load.Fn * scene.tangential_reference.U0
    accuracy(study)
    steps_table(study)
    if not study.quick:
        md = study.out / "md06.h5"
        if not md.exists():
            study.rc("run", "--set", "motion.w=0", "--set", "load.ft=0", "--set", "load.ft_amplitude=0.6",
                     "--set", "motion.periods=3", "-o", md, "-q")
        study.rc("plot", md, "-o", study.out / "plots", "--overwrite", capture=True)
        study.figure(study.out / "plots" / "md06_loads.png", "oscillating_md_loads.png")
    maps(study, mu_Fn_U0)
    limits(study)
    return study.finish()


if __name__ == "__main__":
    sys.exit(main())

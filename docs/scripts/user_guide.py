"""The figures and tables of docs/user_guide.md: the README's walkthrough, run into a folder the user chooses.

    .venv/bin/python docs/scripts/user_guide.py [-o results/user_guide] [--figures DIR] [--quick]

    rollcontact run -o OUT/perp.h5                                    (the paper's scene, W ⊥ Ft)
    rollcontact run --set motion.angle=0 -o OUT/par.h5                (W ∥ Ft)
    rollcontact run --set load.ft=0.77 -o OUT/perp_rat.h5             (ratcheting)
    rollcontact plot OUT/perp.h5; rollcontact compare OUT/par.h5 OUT/perp.h5
    rollcontact sweep --vary motion.angle=0,90 --vary motion.w=0.1,0.23,0.4 --vary load.ft=0.2,0.4,0.6,0.8 \\
        --set motion.periods=8 -o OUT/sweep;  rollcontact plot OUT/sweep
    rollcontact stresses OUT/perp_rat.h5; rollcontact plot OUT/perp_rat.h5

Tables: the three runs, and kappa of the sweep per alignment. --quick: the parallel run only.
"""
from __future__ import annotations

import csv
from pathlib import Path
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _study import SKIPPED, Study  # noqa: E402

RUNS = {"par": ("W ∥ Ft, f_t = 0.46", ["--set", "motion.angle=0"]),
        "perp": ("W ⊥ Ft, f_t = 0.46", []),
        "perp_rat": ("W ⊥ Ft, f_t = 0.77", ["--set", "load.ft=0.77"])}


def main(argv=None) -> int:
    study = Study.from_command_line("user_guide", __doc__, argv)
    import rollcontact
    out, plots = study.out, study.out / "plots"
    rows = []
    for name, (label, sets) in RUNS.items():
        path = out / f"{name}.h5"
        if study.quick and name != "par":
            rows.append([label, SKIPPED, SKIPPED, SKIPPED])
            continue
        if not path.exists():
            study.rc("run", *sets, "-o", path, "-q")
        s = rollcontact.read_run(path).summary
        value = (f"u_sd = {s['u_sd']:.5f}" if s["state"] == "shakedown" else
                 f"Δu = {s['du']:.4f} per period" if s["state"] == "ratcheting" else "-")
        rows.append([label, s["state"], value, str(s["periods_to_shakedown"] if s["periods_to_shakedown"] is not None
                                                    else "-")])
    study.table("runs", ["run (the paper's grid, 10 periods)", "state", "result", "periods to shakedown"], rows)
    kappa = [["W ∥ Ft (0°)", SKIPPED, SKIPPED, "1"], ["W ⊥ Ft (90°)", SKIPPED, SKIPPED, "1.1"]]
    if not study.quick:
        study.rc("plot", out / "perp.h5", "-o", plots, "--overwrite", capture=True)
        study.figure(sorted(plots.glob("perp_maps_step*.png"))[-1], "perpendicular_maps.png")
        study.rc("compare", out / "par.h5", out / "perp.h5", "-o", plots, "--overwrite", capture=True)
        study.figure(plots / "compare_par_vs_perp_centrelines.png", "compare_centrelines.png")
        study.rc("sweep", "--vary", "motion.angle=0,90", "--vary", "motion.w=0.1,0.23,0.4",
                 "--vary", "load.ft=0.2,0.4,0.6,0.8", "--set", "motion.periods=8", "-o", out / "sweep", "-q")
        study.rc("plot", out / "sweep", "-o", plots, "--overwrite", capture=True)
        study.figure(plots / "sweep_usd.png", "sweep_usd.png")
        study.rc("stresses", out / "perp_rat.h5", "-q")
        study.rc("plot", out / "perp_rat.h5", "-o", plots, "--overwrite", capture=True)
        study.figure(sorted(plots.glob("perp_rat_subsurface_step*.png"))[-1], "perpendicular_subsurface.png")
        from rollcontact.solver.mdr.limits import fit_kappa
        with open(out / "sweep" / "summary.csv", newline="") as fh:
            table = list(csv.DictReader(fh))
        for row, angle in zip(kappa, (0.0, 90.0)):
            sd = [r for r in table if float(r["angle"]) == angle and r["state"] == "shakedown"]
            fit = fit_kappa([float(r["f_t"]) for r in sd], [float(r["w"]) for r in sd], [float(r["u_sd"]) for r in sd])
            row[1:3] = [f"{fit.kappa:.3f} ± {fit.stderr:.3f}", str(fit.n)]
    study.table("kappa", ["alignment", "κ of Eq. 13", "shaken-down runs", "the paper's κ"], kappa)
    return study.finish()


if __name__ == "__main__":
    sys.exit(main())

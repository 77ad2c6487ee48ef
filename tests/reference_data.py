"""Regression data: values taken from rollcontact's own converged runs, not from an independent reference.

Where no closed form or published table exists (the 3-D kappa of seed Eq. 13, the pure-MDR ratcheting increment),
the tests compare with the program's own result on a much finer discretisation. Those values live in one file,
tests/data/reference_data.json, and the tests that use them are marked `regression` (run them alone with
`pytest -m regression`, leave them out with `-m "not regression"`); every other test checks against a closed
form, a conservation law or a published reference. A change of the model that moves a value (for the better or
the worse) fails its regression tests: regenerate the file, check the change, commit both.

    .venv/bin/python tests/reference_data.py [NAME ...] [-o DIR]      # DIR/reference_data.json (default
                                                                      # results/reference_data); 25 min of CPU
    .venv/bin/python tests/reference_data.py -o tests/data --overwrite  # refresh the committed file

NAME is one of the entries below (all by default; mdr_ratchet_ratio takes about half the time, kappa_3d_fig8 and
kappa_3d_ft03 a third); the command prints each value (and the committed one beside it when they differ). An
entry records what it is, the scene and discretisation it comes from, and its values:

* kappa_3d_fig8: seed Fig. 8's points (w = 0.23, f_t = 0.2 / 0.4 / 0.6, parallel and perpendicular) on the paper
  scene at half the paper's spacing (dx = dy = dW = 0.1 mm; 10 periods, 20 at f_t = 0.6): u_sd and the kappa that
  puts seed Eq. 13 through it (fit_kappa of one point). Used by tests/cases/test_rolling_paper.py.
* kappa_3d_ft03: the same for the coarse sweep's shaken-down points (paper parallel scene, f_t = 0.3,
  w = 0.15 / 0.3, angle 0 / 90, dx = dy = dW = 0.1 mm, 10 periods). Used by tests/cases/test_sweep.py.
* mdr_ratchet_ratio: the pure-MDR ratcheting increment per period over sqrt(u_stat) (w - w_lim,MDR) at three
  (w, f_t), 16001 springs, nq = W/dW = 400 and 1600, extrapolated to dW -> 0 with order 1. Used by
  tests/solver/test_mdr.py.
* fig4_periods_to_shakedown: periods until shakedown of seed Fig. 4's runs (paper scenes, f_t = 0.46, paper grid).
  Used by tests/cases/test_rolling_paper.py.
Units: dimensionless (u = U/U0, f_t = Ft/(mu Fn), w = W/a, seed Eq. 9).
"""
from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
import sys
import tempfile

DATA = Path(__file__).resolve().parent / "data" / "reference_data.json"


def load() -> dict:
    """The committed reference data (tests/data/reference_data.json)."""
    return json.loads(DATA.read_text())


_REF = load()
#: (setting, f_t) -> kappa of seed Eq. 13 through the converged 3-D u_sd at w = 0.23
KAPPA_3D = {(r["setting"], r["f_t"]): r["kappa"] for r in _REF["kappa_3d_fig8"]["values"]}
#: (w, angle) -> the same at f_t = 0.3 on the paper parallel scene
KAPPA_3D_FT03 = {(r["w"], r["angle"]): r["kappa"] for r in _REF["kappa_3d_ft03"]["values"]}
#: (w, f_t) -> pure-MDR du per period / (sqrt(u_stat) (w - w_lim,MDR)), extrapolated to dW -> 0
RATCHET_RATIO = {(r["w"], r["f_t"]): r["ratio"] for r in _REF["mdr_ratchet_ratio"]["values"]}
#: setting -> periods to shakedown of the paper scene at f_t = 0.46 on the paper grid
FIG4_PERIODS_TO_SHAKEDOWN = {r["setting"]: r["periods_to_shakedown"]
                             for r in _REF["fig4_periods_to_shakedown"]["values"]}

SETTINGS = {"parallel": 0.0, "perpendicular": 90.0}


# ------------------------------------------------------------------------------------------ derivations
def _paper_summary(overrides, tmp):
    from rollcontact.cases.run.scene_run import run_scene
    from rollcontact.cases.scene.scene import default_scene
    scene = default_scene().with_overrides(overrides)
    return run_scene(scene, Path(tmp) / f"run{len(list(Path(tmp).iterdir()))}.h5").summary


def derive_kappa_3d_fig8(tmp):
    from rollcontact.solver.mdr.limits import fit_kappa
    values = []
    for setting, angle in SETTINGS.items():
        for f_t in (0.2, 0.4, 0.6):
            s = _paper_summary([f"motion.angle={angle}", f"load.ft={f_t}", f"motion.periods={20 if f_t == 0.6 else 10}",
                                'output.fields="none"', "grid.dx=0.1", "motion.dW=0.1"], tmp)
            values.append(dict(setting=setting, f_t=f_t, u_sd=round(s["u_sd"], 7),
                               kappa=round(fit_kappa(f_t, 0.23, s["u_sd"]).kappa, 6)))
    return dict(what="seed Fig. 8 points: u_sd and kappa of seed Eq. 13 through it, w = 0.23",
                scene="paper scene (cases/paper_perpendicular.toml) with motion.angle = 0 / 90, load.ft, "
                      "grid.dx = motion.dW = 0.1 mm, motion.periods = 10 (20 at f_t = 0.6), output.fields = none",
                values=values)


def derive_kappa_3d_ft03(tmp):
    from rollcontact.cases.run.scene_run import run_scene
    from rollcontact.cases.scene.scene import Scene, shipped_scene_path
    from rollcontact.solver.mdr.limits import fit_kappa
    base = Scene.from_toml(shipped_scene_path("paper_parallel.toml"))
    values = []
    for angle in (0, 90):
        for w in (0.15, 0.3):
            scene = base.with_overrides(["grid.dx=0.1", "grid.dy=0.1", "motion.dW=0.1", "load.ft=0.3",
                                         f"motion.w={w}", f"motion.angle={angle}", 'output.fields="none"'])
            s = run_scene(scene, Path(tmp) / f"ft03_{w}_{angle}.h5").summary
            values.append(dict(w=w, angle=angle, u_sd=round(s["u_sd"], 7),
                               kappa=round(fit_kappa(0.3, w, s["u_sd"]).kappa, 6)))
    return dict(what="u_sd and kappa of seed Eq. 13 through it at f_t = 0.3",
                scene="cases/paper_parallel.toml with grid.dx = grid.dy = motion.dW = 0.1 mm, load.ft = 0.3, "
                      "motion.w, motion.angle, output.fields = none (10 periods, margin 0.6, shakedown_tol 1e-4)",
                values=values)


def derive_mdr_ratchet_ratio(tmp):
    from rollcontact.bem.materials import MaterialPair
    from rollcontact.solver.analytic import HertzSphere
    from rollcontact.solver.mdr import limits as L
    from rollcontact.solver.mdr.simulate import simulate_mdr
    pair = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
    a = HertzSphere(40.0, pair.E_star, 21.19).a
    values = []
    for w, f_t in ((0.3, 0.7), (0.5, 0.5), (0.7, 0.3)):
        scale = math.sqrt(L.u_stat(f_t)) * (w - L.w_lim(f_t, L.KAPPA_MDR))
        ratio = {}
        for nq in (400, 1600):
            r = simulate_mdr(R=40.0, E_star=pair.E_star, G_star=pair.G_star, Fn=21.19, mu=0.93,
                             Ft=f_t * 0.93 * 21.19, W=w * a, dW=w * a / nq, periods=10, n_springs=16001)
            ratio[nq] = r.classification.du / scale
        values.append(dict(w=w, f_t=f_t, ratio=round(ratio[1600] + (ratio[1600] - ratio[400]) / 3, 5)))
    return dict(what="pure-MDR ratcheting increment per period / (sqrt(u_stat) (w - w_lim,MDR)), dW -> 0",
                scene="seed scene (R = 40 mm, steel on rubber, Fn = 21.19 N, mu = 0.93), simulate_mdr with 16001 "
                      "springs, 10 periods, nq = W/dW = 400 and 1600, extrapolated with order 1",
                values=values)


def derive_fig4_periods_to_shakedown(tmp):
    values = []
    for setting, angle in SETTINGS.items():
        s = _paper_summary([f"motion.angle={angle}", "load.ft=0.46"], tmp)
        values.append(dict(setting=setting, periods_to_shakedown=int(s["periods_to_shakedown"])))
    return dict(what="periods until shakedown, seed Fig. 4 (f_t = 0.46, w = 0.23)",
                scene="paper scene with motion.angle = 0 / 90 on the paper grid (dx = dW = 0.2 mm, 10 periods)",
                values=values)


DERIVATIONS = {name[len("derive_"):]: f for name, f in list(globals().items()) if name.startswith("derive_")}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description="Regenerate the regression data of the tests from rollcontact's own "
                                            "converged runs.")
    p.add_argument("names", nargs="*", metavar="NAME",
                   help=f"entries to regenerate ({', '.join(DERIVATIONS)}; default all)")
    p.add_argument("-o", "--output", default="results/reference_data",
                   help="folder of reference_data.json (default results/reference_data)")
    p.add_argument("--overwrite", action="store_true", help="replace an existing reference_data.json")
    args = p.parse_args(argv)
    unknown = [n for n in args.names if n not in DERIVATIONS]
    if unknown:
        p.error(f"unknown entries {', '.join(unknown)}; known: {', '.join(DERIVATIONS)}")
    out = Path(args.output) / "reference_data.json"
    if out.exists() and not args.overwrite:
        print(f"{out}: exists; add --overwrite to replace it", file=sys.stderr)
        return 2
    data = load()
    for name in args.names or list(DERIVATIONS):
        with tempfile.TemporaryDirectory() as tmp:
            entry = DERIVATIONS[name](tmp)
        for new, old in zip(entry["values"], data.get(name, {}).get("values", [])):
            print(f"{name}: {new}" + ("" if new == old else f"   (committed: {old})"))
        data[name] = entry
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(data, indent=1) + "\n")
    print(out.resolve())
    return 0


if __name__ == "__main__":
    sys.exit(main())

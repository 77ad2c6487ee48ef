"""Benchmark of the MDR fidelity level (solver.mdr, solver.mdr.bisection, solver.mdr.limits; docs/theory.md §8).

Run:  .venv/bin/python benchmarks/mdr.py [-o DIR]
Writes DIR/mdr.json (default results/benchmarks/) and prints the Markdown tables of benchmarks/README.md "## MDR model".

* time per 10-period run (median of 7 warm runs; the first call of the process is reported separately:
  it loads the numba on-disk cache, or compiles if there is none), for 1001 and 4001 springs,
  dW = W/50 (2002 steps), scene of the seed (Table 1), w = 0.23, f_t = 0.46;
* closed forms for w in {0.1, 0.23, 0.4}: f_t,lim and u_lim for kappa = 1, 1.1, 1.5 and u_sd(f_t);
* the simulator's u_sd (4001 springs, dW = W/50, 20 periods) next to seed Eq. 12 (kappa = 3/2);
* the simulated shakedown limit (bisection in f_t, 801 springs) next to f_t,lim(kappa = 3/2).
"""
from __future__ import annotations

import os
import statistics
import sys
import time


HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

import _record  # noqa: E402
from rollcontact.bem.materials import MaterialPair  # noqa: E402
from rollcontact.solver.mdr import limits as L  # noqa: E402
from rollcontact.solver.analytic import HertzSphere  # noqa: E402
from rollcontact.solver.mdr.simulate import simulate_mdr  # noqa: E402
from rollcontact.solver.mdr.bisection import shakedown_limit_ft  # noqa: E402

PAIR = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
SCENE = dict(R=40.0, E_star=PAIR.E_star, G_star=PAIR.G_star, Fn=21.19, mu=0.93)
MU_FN = SCENE["mu"] * SCENE["Fn"]
A = HertzSphere(SCENE["R"], PAIR.E_star, SCENE["Fn"]).a
W_VALUES = (0.1, 0.23, 0.4)
KAPPAS = {"parallel": L.KAPPA_PARALLEL, "perpendicular": L.KAPPA_PERPENDICULAR, "mdr": L.KAPPA_MDR}
FT_VALUES = (0.2, 0.3, 0.46, 0.6)


def run(f_t, w, *, nq=50, periods=10, n_springs=4001):
    W = w * A
    return simulate_mdr(**SCENE, Ft=f_t * MU_FN, W=W, dW=W / nq, periods=periods, n_springs=n_springs)


def timing():
    out = {}
    for n in (1001, 4001):
        t = time.perf_counter()
        r = run(0.46, 0.23, n_springs=n)
        first = time.perf_counter() - t
        times = []
        for _ in range(7):
            t = time.perf_counter()
            run(0.46, 0.23, n_springs=n)
            times.append(time.perf_counter() - t)
        steps = len(r.history["U"])
        med = statistics.median(times)
        out[str(n)] = dict(first_call_s=first, median_s=med, min_s=min(times), steps=steps,
                           us_per_step=med / steps * 1e6)
    return out


def closed_forms():
    rows = []
    for w in W_VALUES:
        row = dict(w=w, u_lim=L.u_lim(w))
        for name, k in KAPPAS.items():
            row[f"f_t_lim_{name}"] = L.f_t_lim(w, k)
            row[f"u_sd_{name}"] = {str(f): (L.u_shakedown(f, w, k) if f <= L.f_t_lim(w, k) else None)
                                   for f in FT_VALUES}
        rows.append(row)
    return rows


def simulator_vs_eq12():
    rows = []
    for w in W_VALUES:
        for f in FT_VALUES:
            if f > L.f_t_lim(w, L.KAPPA_MDR):
                continue
            r = run(f, w, periods=20)
            c = r.classification
            ref = L.u_shakedown(f, w, L.KAPPA_MDR)
            rows.append(dict(w=w, f_t=f, u_stat=L.u_stat(f), eq12=ref, state=c.state, u_sim=c.u_sd,
                             error=None if c.u_sd is None else c.u_sd - ref,
                             periods_to_shakedown=c.periods_to_shakedown, last_du=c.du))
    return rows


def limits():
    rows = []
    for w in W_VALUES:
        t = time.perf_counter()
        b = shakedown_limit_ft(**SCENE, W=w * A, dW=w * A / 20, periods=40, f_t_lo=0.2, f_t_hi=0.95,
                               f_t_tol=2e-4, n_springs=801)
        rows.append(dict(w=w, f_t_shakedown=b.f_t_shakedown, f_t_ratcheting=b.f_t_ratcheting,
                         closed_form=L.f_t_lim(w, L.KAPPA_MDR), runs=b.runs,
                         undecided_retries=b.undecided_retries, seconds=time.perf_counter() - t))
    return rows


def fmt(x, spec=".6f"):
    return "ratch." if x is None else format(x, spec)


def main():
    args = _record.parser(__doc__).parse_args()
    res = dict(scene=dict(SCENE, a=A), timing=timing(), closed_forms=closed_forms(),
               simulator_vs_eq12=simulator_vs_eq12(), limits=limits())
    _record.write("mdr", res, args.output)

    print("Time per 10-period run (w = 0.23, f_t = 0.46, dW = W/50):\n")
    print("| springs | steps | first call (s) | median warm (s) | us/step |\n|---|---|---|---|---|")
    for n, t in res["timing"].items():
        print(f"| {n} | {t['steps']} | {t['first_call_s']:.3f} | {t['median_s']:.4f} | {t['us_per_step']:.0f} |")
    print("\nClosed forms (f_t,lim for kappa = 1 / 1.1 / 1.5; u_sd at f_t for kappa = 1 / 1.1 / 1.5):\n")
    print("| w | u_lim | f_t,lim par | f_t,lim perp | f_t,lim MDR | " +
          " | ".join(f"u_sd(f_t={f})" for f in FT_VALUES) + " |")
    print("|---" * (5 + len(FT_VALUES)) + "|")
    for r in res["closed_forms"]:
        cells = [" / ".join(fmt(r[f"u_sd_{k}"][str(f)], ".4f") for k in KAPPAS) for f in FT_VALUES]
        print(f"| {r['w']} | {r['u_lim']:.4f} | {r['f_t_lim_parallel']:.4f} | {r['f_t_lim_perpendicular']:.4f}"
              f" | {r['f_t_lim_mdr']:.4f} | " + " | ".join(cells) + " |")
    print("\nSimulator (4001 springs, dW = W/50, 20 periods) vs seed Eq. 12:\n")
    print("| w | f_t | u_stat | Eq. 12 | simulated | error | periods to shakedown | last du |")
    print("|---|---|---|---|---|---|---|---|")
    for r in res["simulator_vs_eq12"]:
        print(f"| {r['w']} | {r['f_t']} | {r['u_stat']:.6f} | {r['eq12']:.6f} | {fmt(r['u_sim'])} | "
              f"{r['error']:.1e} | {r['periods_to_shakedown']} | {r['last_du']:.1e} |")
    print("\nShakedown limit by bisection (801 springs, dW = W/20, 40 periods) vs 1 - 1.5 w + 0.5 w^3:\n")
    print("| w | simulated bracket | closed form | runs | time (s) |\n|---|---|---|---|---|")
    for r in res["limits"]:
        print(f"| {r['w']} | [{r['f_t_shakedown']:.5f}, {r['f_t_ratcheting']:.5f}] | {r['closed_form']:.5f} | "
              f"{r['runs']} | {r['seconds']:.2f} |")


if __name__ == "__main__":
    main()

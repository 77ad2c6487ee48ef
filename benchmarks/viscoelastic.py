"""Speed of viscoelastic runs against elastic ones on the same grid (docs/viscoelastic.md; issue targets: the paper
scene with a viscoelastic substrate within 1.5 x the elastic run's time, a steady viscoelastic case within 2 x an
elastic one).

    .venv/bin/python benchmarks/viscoelastic.py [--quick] [-o DIR]

Paper scene (cases/paper_perpendicular.toml: 65 x 55 cells, dx = dW = 0.2 mm, 10 periods, 242 steps) with the
substrate a Standard Linear Solid (E_r = 4.35 MPa the seed's modulus, E_g = 2 E_r, tau_c = 0.1 s), against the
elastic run with E_r: (a) rolled at 1e-9 mm/s, where the viscoelastic run is the elastic one step by step (same
iterations: the cost of the element states alone), (b) at V tau/a = 1 (47.9 mm/s), a different contact (more
iterations; the time per FFT product is given beside). Steady rolling (cases/creep_steady.toml's grid, 57 x 43 cells,
steel-like bodies both SLS with E_g = 10 E_r so that they stay uncoupled), elastic with E_r against viscoelastic at
V tau/a = 0.1, 1, 10: the whole run (kernels, normal and tangential problems, viscous power). Process CPU time (the
machine is shared), the median of --repeats runs after a warm-up run (numba and FFTW plans cached). JSON to
DIR/viscoelastic.json (default results/benchmarks).
"""
import argparse
import json
import platform
import statistics
import time
from pathlib import Path

import rollcontact
from rollcontact.cases.scene.scene import Scene, shipped_scene_path

SLS2 = ['materials.visco2="sls"', "materials.E2=8.7", "materials.E2_relaxed=4.35", "materials.tau2=0.1"]
A_PAPER = 4.786            # relaxed Hertz radius of the paper scene (mm)
BOTH = ['materials.visco1="sls"', "materials.E1=2100e3", "materials.E1_relaxed=210e3", "materials.tau1=1.0",
        'materials.visco2="sls"', "materials.E2=2100e3", "materials.E2_relaxed=210e3", "materials.tau2=1.0"]


def timed(scene, repeats):
    times, result = [], None
    for _ in range(repeats):
        c0 = time.process_time()
        result = rollcontact.run(scene)
        times.append(time.process_time() - c0)
    return statistics.median(times), result


def products(result):
    return int(sum(result.history["iterations"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="3 periods, one repeat")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("-o", "--output", default="results/benchmarks")
    args = ap.parse_args()
    repeats = 1 if args.quick else args.repeats
    paper = Scene.from_toml(shipped_scene_path("paper_perpendicular.toml"))
    if args.quick:
        paper = paper.with_overrides(["motion.periods=3"])
    paper = paper.with_overrides(['output.fields="none"'])
    rollcontact.run(paper)                                                     # warm-up
    rows = {}
    t_el, r_el = timed(paper, repeats)
    for label, speed in (("paper_slow", 1e-9), ("paper_De1", A_PAPER / 0.1)):
        scene = paper.with_overrides(SLS2 + [f"motion.speed={speed}"])
        rollcontact.run(scene)
        t, r = timed(scene, repeats)
        rows[label] = dict(elastic_cpu=t_el, visco_cpu=t, ratio=t / t_el, elastic_products=products(r_el),
                           visco_products=products(r), ratio_per_product=(t / products(r)) / (t_el / products(r_el)),
                           state=r.state, elastic_state=r_el.state)
        print(f"{label}: elastic {t_el:.2f} s ({products(r_el)} products), viscoelastic {t:.2f} s ({products(r)}), "
              f"ratio {t / t_el:.2f}, per product {rows[label]['ratio_per_product']:.2f}")
    steady = Scene.from_toml(shipped_scene_path("creep_steady.toml")).with_overrides(['output.fields="none"'])
    a = steady.rolling_half_length
    rollcontact.run(steady)
    t_el, r_el = timed(steady, repeats)
    for de in (0.1, 1.0, 10.0):
        scene = steady.with_overrides(BOTH + [f"rolling.speed={de * a}"])
        rollcontact.run(scene)
        t, r = timed(scene, repeats)
        rows[f"steady_De{de:g}"] = dict(elastic_cpu=t_el, visco_cpu=t, ratio=t / t_el,
                                        normal_products=int(r.history["normal_iterations"][0]),
                                        sweeps=int(r.history["tangential_iterations"][0]),
                                        elastic_normal_products=int(r_el.history["normal_iterations"][0]),
                                        elastic_sweeps=int(r_el.history["tangential_iterations"][0]))
        print(f"steady V tau/a = {de:g}: elastic {t_el:.3f} s, viscoelastic {t:.3f} s, ratio {t / t_el:.2f} "
              f"(normal products {rows[f'steady_De{de:g}']['normal_products']}, sweeps "
              f"{rows[f'steady_De{de:g}']['sweeps']})")
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    report = dict(machine=platform.processor() or platform.machine(), python=platform.python_version(),
                  date=time.strftime("%Y-%m-%d"), quick=args.quick, repeats=repeats, rows=rows)
    try:
        import os
        report["load"] = os.getloadavg()
    except OSError:
        pass
    (out / "viscoelastic.json").write_text(json.dumps(report, indent=1))
    print(f"written {out / 'viscoelastic.json'}")


if __name__ == "__main__":
    main()

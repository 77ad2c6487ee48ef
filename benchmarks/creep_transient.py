"""Transient rolling on the world-fixed grid (solver.creep.world) against the steady state: forces against the
rolled distance, and the time per step (docs/theory.md §6, §11.5; docs/creep_rolling.md, "Transient on the world grid").

    .venv/bin/python benchmarks/creep_transient.py [--quick] [--n 41 61] [--lengths 8] [--initial rest cattaneo] [-o DIR]

Steel on steel (E = 210 GPa, nu = 0.28), a sphere R = 40 mm under Fn = 1000 N (Hertz a = 0.641 mm), mu = 0.3,
xi = 5e-4, eta = 2e-4, phi = 1e-3 1/mm (partial slip, |F| = 0.29 mu Fn), n elements across the contact diameter
(dx = 2a/n), the step dx, rolled `lengths` contact lengths (2a) on a world grid with two free cells around the
contact's path. The steady reference: solve_steady on a contact-fixed grid of the same cells (tol 1e-9) with its
own normal solve. Per contact length rolled: Fx, Fy, Mz relative to the steady ones; the time per step (wall, and
CPU by time.process_time: the machine is shared) after a warm-up of two steps (numba compiled or loaded from its
cache), and the total; products (FFT convolution pairs) per step, normal and tangential. JSON to
DIR/creep_transient.json (default results/benchmarks/).
"""
import math
import time

import numpy as np

import _record
from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.solver.creep import SteadyParams, SteadyRolling, roll_world, solve_steady
from rollcontact.solver.normal import solve_normal
from rollcontact.solver.rolling import QuadricProfile

R, FN, MU, NU = 40.0, 1000.0, 0.3, 0.28
MATS = MaterialPair.from_moduli(210e3, NU, 210e3, NU)
A = (3 * FN * R * 2 * (1 - NU ** 2) / (4 * 210e3)) ** (1 / 3)
CREEP = (5e-4, 2e-4, 1e-3)
PROFILE = QuadricProfile(R, R)


def run(n, lengths, initial):
    dx = 2 * A / n
    m = 2 * dx
    world = Grid.covering(-A - m, 2 * A * lengths + A + m, -A - m, A + m, dx, dx)
    fixed = Grid.covering(-A - m, A + m, -A - m, A + m, dx, dx)
    w0, c0 = time.perf_counter(), time.process_time()
    normal = solve_normal(HalfSpaceOperator(fixed, MATS), PROFILE(*fixed.mesh()), force=FN)
    steady = solve_steady(SteadyRolling(fixed, MATS), normal.pressure, MU, *CREEP, params=SteadyParams(tol=1e-9))
    t_steady, c_steady = time.perf_counter() - w0, time.process_time() - c0
    op = HalfSpaceOperator(world, MATS, threads=1)
    list(roll_world(op, PROFILE, Fn=FN, mu=MU, distance=2 * dx, step=dx, xi=CREEP[0], eta=CREEP[1], phi=CREEP[2],
                    initial=initial))                                          # warm-up
    w0, c0 = time.perf_counter(), time.process_time()
    steps = list(roll_world(op, PROFILE, Fn=FN, mu=MU, distance=2 * A * lengths, step=dx, xi=CREEP[0], eta=CREEP[1],
                            phi=CREEP[2], initial=initial))
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    scale = math.hypot(*steady.force)
    rows = []
    for k in range(0, lengths + 1):
        s = steps[min(round(k * 2 * A / dx), len(steps) - 1)]
        rows.append(dict(lengths=k, distance=s.centre, Fx=float(s.force[0]), Fy=float(s.force[1]), Mz=s.moment,
                         dFx=float(s.force[0] - steady.force[0]) / scale, dFy=float(s.force[1] - steady.force[1]) / scale,
                         dMz=(s.moment - steady.moment) / abs(steady.moment)))
    rolling = steps[1:]
    return dict(n=n, initial=initial, dx=dx, world_grid=list(world.shape), contact_cells=int(normal.contact.sum()),
                steps=len(rolling), wall=wall, cpu=cpu, wall_per_step=wall / len(rolling),
                cpu_per_step=cpu / len(rolling), steady_wall=t_steady, steady_cpu=c_steady,
                steady_force=list(steady.force), steady_moment=steady.moment,
                normal_products=float(np.mean([s.normal.iterations for s in rolling])),
                tangential_products=float(np.mean([s.tangential.iterations for s in rolling])), rows=rows)


def main():
    ap = _record.parser(__doc__)
    ap.add_argument("--n", type=int, nargs="+", default=[41, 61])
    ap.add_argument("--lengths", type=int, default=8)
    ap.add_argument("--initial", nargs="+", default=["rest"])
    ap.add_argument("--quick", action="store_true", help="n = 41 from rest over one contact length")
    args = ap.parse_args()
    if args.quick:
        args.n, args.lengths, args.initial = [41], 1, ["rest"]
    results = []
    for n in args.n:
        for initial in args.initial:
            r = run(n, args.lengths, initial)
            results.append(r)
            print(f"n = {n} ({r['contact_cells']} cells in contact), world grid {r['world_grid'][1]} x "
                  f"{r['world_grid'][0]}, {r['steps']} steps from {initial}: {r['wall']:.2f} s wall, {r['cpu']:.2f} s "
                  f"CPU; per step {1e3 * r['wall_per_step']:.1f} ms wall, {1e3 * r['cpu_per_step']:.1f} ms CPU, "
                  f"{r['normal_products']:.1f} normal + {r['tangential_products']:.1f} tangential products; steady "
                  f"{r['steady_wall']:.2f} s wall")
            for row in r["rows"]:
                print(f"  {row['lengths']} lengths ({row['distance']:.4f} mm): Fx {100 * row['dFx']:+.4f} %, Fy "
                      f"{100 * row['dFy']:+.4f} % of |F|, Mz {100 * row['dMz']:+.4f} %")
    _record.write("creep_transient", dict(creep=CREEP, results=results), args.output)


if __name__ == "__main__":
    main()

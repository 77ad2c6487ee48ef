"""Seeded robustness campaign of the tangential solver (the stability map's random counterpart).

    .venv/bin/python benchmarks/tangential_fuzz.py [--dx 0.2 0.1] [--cases 300] [--seed 2024]

On the Cattaneo scene of `tangential_cattaneo.py` (the seed's sphere on rubber; grids 55^2, 109^2, ...), each case
draws a bound (g; the contact moved by one cell; g scaled by 0.9-1.1; g rolled by 1-3 cells in x or y), a previous
state (zero traction, or a converged solve at another force, possibly from its own previous state) and a step of
one of the categories

  cold        from zero traction, f_t in [0, 0.995] (15 % in [0.95, 0.995], 5 % below 0.1), any direction
  warm        from the previous traction (the default start)
  region      the same with previous_region = the previous division
  initial     a random feasible initial traction, with or without a random previous_region
  shift       a prescribed shift: 0.5-1.5 x the shift of a converged solve, turned by up to 0.5 rad
  reversal    the previous force reversed or turned by +-90 degrees
  near_bound  previous state at f_t 0.7-0.99, new f_t 0.95-0.995 turned by any angle

The step is a strictly convex program, so every start must reach one solution. Checked per case: convergence (any
exception but GrossSlidingError is a finding); the invariants of tests/solver/tangential_helpers.py (force balance,
|tau| <= g (1 + 1e-9), zero slip in stick to 10 tol a_self max g, slip within acos(0.999) of -tau where resolved);
displacement = A tau on the whole grid; the traction and shift against a solve from the plain start with the
product memo cleared (flag above 1e-5 max g / 1e-5 relative); for a prescribed shift, the force-mode solve at the
returned force must give back the traction, and the shift unless it ends with no stick element (then it reports
the sub-element stick point's shift, `solver.tangential.shift._stick_point_shift`; such results are also held to the
stick point's 8 degrees of slip alignment instead of acos(0.999)). Products: median / 90th percentile / max per
category.
Writes DIR/tangential_fuzz.json (-o DIR, default results/benchmarks/).
"""
import argparse
import math
import statistics
import time

import numpy as np

from tangential_cattaneo import cattaneo_scene
import _record
from rollcontact.solver.tangential import shift as T
from rollcontact.solver.tangential.shift import TangentialParams, solve_tangential, traction_capacity

CATEGORIES = ("cold", "warm", "region", "initial", "shift", "reversal", "near_bound")
TOL = TangentialParams().tol


class Scene:
    def __init__(self, dx):
        self.grid, self.op, _, _, self.g, self.g2 = cattaneo_scene(dx)
        self.zero = np.zeros((2,) + self.grid.shape)
        self.a_self = max(self.op.self_coefficients["xx"], self.op.self_coefficients["yy"])

    def bound(self, rng):
        k = int(rng.integers(0, 5))
        if k == 0:
            return self.g, "g"
        if k == 1:
            return self.g2, "moved one cell"
        if k == 2:
            s = float(rng.uniform(0.9, 1.1))
            return s * self.g, f"g x {s:.3f}"
        cells = int(rng.integers(1, 4)) * int(rng.choice([-1, 1]))
        return np.roll(self.g, cells, axis=1 if k == 3 else 0), f"rolled {cells} in {'x' if k == 3 else 'y'}"

    def force(self, g, f_t, angle):
        cap = traction_capacity(g, self.grid)
        return (f_t * cap * math.cos(angle), f_t * cap * math.sin(angle))


def random_f_t(rng):
    u = rng.random()
    if u < 0.15:
        return float(rng.uniform(0.95, 0.995))
    if u < 0.2:
        return float(10 ** rng.uniform(-5, -1))
    return float(rng.uniform(0, 0.995))


def make_case(sc, cat, rng):
    """Returns (bound, previous traction, keyword arguments, description)."""
    g, gdesc = sc.bound(rng)
    prev, prev_region, desc = sc.zero, None, [cat, gdesc]
    if cat != "cold":
        gp, _ = sc.bound(rng)
        f_p = float(rng.uniform(0.7, 0.99)) if cat == "near_bound" else random_f_t(rng)
        a_p = float(rng.uniform(0, 2 * math.pi))
        p = solve_tangential(sc.op, gp, sc.zero, force=sc.force(gp, f_p, a_p))
        prev, prev_region = p.traction, p.region
        desc.append(f"previous f_t {f_p:.4f} at {a_p:.3f} rad")
    kw = {}
    if cat == "shift":
        ref = solve_tangential(sc.op, g, prev, force=sc.force(g, random_f_t(rng), float(rng.uniform(0, 2 * math.pi))))
        turn, scale = float(rng.uniform(-0.5, 0.5)), float(rng.uniform(0.5, 1.5))
        c, s = math.cos(turn), math.sin(turn)
        dU = ref.shift_increment
        kw["shift"] = (scale * (c * dU[0] - s * dU[1]), scale * (s * dU[0] + c * dU[1]))
        desc.append(f"shift {scale:.3f} x turned {turn:.3f} rad")
        return g, prev, kw, desc
    if cat == "reversal":
        F_p = np.asarray(p.force)
        turn = float(rng.choice([math.pi, math.pi / 2, -math.pi / 2]))
        c, s = math.cos(turn), math.sin(turn)
        F = (c * F_p[0] - s * F_p[1], s * F_p[0] + c * F_p[1])
        cap = traction_capacity(g, sc.grid)
        if math.hypot(*F) >= 0.995 * cap:
            F = tuple(np.asarray(F) * 0.995 * cap / math.hypot(*F))
        kw["force"] = F
        desc.append(f"previous force turned {turn:.3f} rad")
        return g, prev, kw, desc
    f_t = float(rng.uniform(0.95, 0.995)) if cat == "near_bound" else random_f_t(rng)
    angle = float(rng.uniform(0, 2 * math.pi))
    kw["force"] = sc.force(g, f_t, angle)
    desc.append(f"f_t {f_t:.4f} at {angle:.3f} rad")
    if cat == "region" or (cat == "near_bound" and rng.random() < 0.3):
        kw["previous_region"] = prev_region
        desc.append("previous_region")
    if cat == "initial":
        th = rng.uniform(0, 2 * math.pi, g.shape)
        m = rng.uniform(0, 1, g.shape) * g
        kw["initial"] = np.array([m * np.cos(th), m * np.sin(th)])
        if rng.random() < 0.5:
            reg = rng.integers(1, 3, g.shape).astype(np.int8)
            reg[g <= 0] = 0
            kw["previous_region"] = reg
            desc.append("random previous_region")
    return g, prev, kw, desc


def violations(sc, r, g, force):
    tau, slip, region = r.traction, r.slip, r.region
    out = []
    cap = traction_capacity(g, sc.grid)
    total = tau.sum(axis=(1, 2)) * sc.grid.cell_area
    if force is not None and np.abs(total - np.asarray(force)).max() > 1e-10 * cap:
        out.append("force balance")
    mag = np.hypot(*tau)
    if np.any(mag > g * (1 + 1e-9)) or np.any(region[g == 0] != 0):
        out.append("Coulomb bound")
    slip_tol = 10 * TOL * sc.a_self * g.max()
    smag = np.hypot(*slip)
    if np.any(smag[region == 1] > slip_tol):
        out.append("slip in stick")
    big = (region == 2) & (smag > 100 * slip_tol)
    align = 0.999
    if np.count_nonzero(region == 1) <= 1:
        # the shift may be the sub-element stick point's (solver.tangential.shift._stick_point_shift), which keeps the
        # resolved slips (above STICK_POINT_RESOLVED of the largest) within acos(STICK_POINT_ALIGN) of -tau
        big &= smag > T.STICK_POINT_RESOLVED * smag[region == 2].max(initial=0.0)
        align = T.STICK_POINT_ALIGN
    if np.any(big) and np.max((tau[0] * slip[0] + tau[1] * slip[1])[big] / (mag * smag)[big]) > -align:
        out.append("slip not opposite traction")
    exact = sc.op.tangential(tau[0], tau[1])
    if np.abs(r.displacement - exact).max() > 1e-9 * sc.a_self * g.max():
        out.append("displacement != A tau")
    return out


def run_case(sc, cat, seed):
    rng = np.random.default_rng(seed)
    g, prev, kw, desc = make_case(sc, cat, rng)
    row = dict(category=cat, seed=seed, case="; ".join(desc))
    t0 = time.perf_counter()
    try:
        r = solve_tangential(sc.op, g, prev, **kw)
    except Exception as exc:  # noqa: BLE001 - classified below
        row.update(status=type(exc).__name__, error=str(exc)[:300])
        if type(exc).__name__ != "GrossSlidingError":
            row["flags"] = [f"exception {type(exc).__name__}"]
        return row
    row.update(status="converged", time_s=time.perf_counter() - t0, products=r.iterations, steps=r.steps,
               stick=int((r.region == 1).sum()))
    flags = violations(sc, r, g, kw.get("force"))
    if r.iterations > 100:
        flags.append(f"{r.iterations} products")
    T._memo.clear()
    plain = {k: v for k, v in kw.items() if k in ("force", "shift")}
    ref = solve_tangential(sc.op, g, prev, **plain)
    row["dtau"] = float(np.abs(r.traction - ref.traction).max() / g.max())
    row["dshift"] = float(np.hypot(*(r.shift_increment - ref.shift_increment))
                          / max(np.hypot(*ref.shift_increment), 1e-300))
    if row["dtau"] > 1e-5 or (row["dshift"] > 1e-5 and np.hypot(*(r.shift_increment - ref.shift_increment)) > 1e-9):
        flags.append("differs from the plain start")
    if "shift" in kw:
        back = solve_tangential(sc.op, g, prev, force=tuple(r.force))
        if np.abs(back.traction - r.traction).max() > 1e-5 * g.max():
            flags.append("force mode at the returned force misses the traction")
        elif np.count_nonzero(back.region == 1) <= 1:
            row["stick_point"] = True  # no stick element: the force mode reports the stick point's shift
        elif np.hypot(*(back.shift_increment - np.asarray(kw["shift"]))) > 1e-5 * max(np.hypot(*kw["shift"]), 1e-12):
            flags.append("force mode at the returned force misses the shift")
    if flags:
        row["flags"] = flags
    return row


def summary(rows):
    out = {}
    for cat in CATEGORIES:
        rs = [r for r in rows if r["category"] == cat]
        prods = sorted(r["products"] for r in rs if r["status"] == "converged")
        if not rs:
            continue
        out[cat] = dict(cases=len(rs), converged=len(prods),
                        gross_sliding=sum(r["status"] == "GrossSlidingError" for r in rs),
                        flagged=sum(bool(r.get("flags")) for r in rs),
                        stick_point=sum(bool(r.get("stick_point")) for r in rs),
                        median=statistics.median(prods) if prods else None,
                        p90=prods[int(0.9 * (len(prods) - 1))] if prods else None, max=max(prods) if prods else None)
    return out


def main():
    ap = _record.parser(__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dx", type=float, nargs="+", default=[0.2, 0.1])
    ap.add_argument("--cases", type=int, default=280, help="cases per grid (spread over the categories)")
    ap.add_argument("--seed", type=int, default=2024)
    args = ap.parse_args()
    results = {}
    for dx in args.dx:
        sc = Scene(dx)
        rows = []
        t0 = time.perf_counter()
        for i in range(args.cases):
            rows.append(run_case(sc, CATEGORIES[i % len(CATEGORIES)], args.seed * 100000 + i))
            if rows[-1].get("flags"):
                print(f"  FLAG dx {dx} seed {rows[-1]['seed']}: {rows[-1]['flags']} ({rows[-1]['case']})", flush=True)
            if (i + 1) % 50 == 0:
                print(f"dx {dx}: {i + 1}/{args.cases} cases, {time.perf_counter() - t0:.0f} s", flush=True)
        results[str(dx)] = dict(grid=list(sc.grid.shape), summary=summary(rows), rows=rows)
        print(f"\ndx = {dx} mm ({sc.grid.shape[1]} x {sc.grid.shape[0]}), {args.cases} cases, seed {args.seed}")
        print("| category | cases | converged | gross sliding | flagged | stick-point shift "
              "| products median / p90 / max |")
        print("|---|---|---|---|---|---|---|")
        for cat, s in results[str(dx)]["summary"].items():
            print(f"| {cat} | {s['cases']} | {s['converged']} | {s['gross_sliding']} | {s['flagged']} "
                  f"| {s['stick_point']} | "
                  f"{s['median']} / {s['p90']} / {s['max']} |")
    _record.write("tangential_fuzz", results, args.output)


if __name__ == "__main__":
    main()

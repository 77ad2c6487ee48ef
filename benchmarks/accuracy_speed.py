"""Accuracy against wall time: grid spacing, rolling step and solver tolerance (issue #7).

    .venv/bin/python benchmarks/accuracy_speed.py [--quick] [--repeats 3] [--no-peers] [-o DIR]

Three problems, each swept over the discretisation and the tolerance, error plotted against wall time:

(a) Hertz normal contact of the seed sphere (R = 40 mm, Fn = 21.19 N, E* = 5.79985 MPa), square grid over
    +-1.25 a, a/dx = 6 ... 96, tol 1e-4 ... 1e-10. Error: relative error of the approach d against Hertz
    (docs/theory.md §7.1), and of the centre pressure against p0. Time: one cold `solve_normal` (median of
    --repeats, after a warm-up solve: FFTW planning and numba compilation excluded; operator set-up time is
    reported separately). Peers, if importable (the optional `bench` extra): tamaas (PolonskyKeerRey with its
    non-periodic "dcfft" operator) and ContactMechanics (FreeFFTElasticHalfSpace + constrained CG, pentol =
    tol d), on the same grids, the same tolerance number and in the same process, their approach taken from
    the pressure they return (d = mean over the contact of h + A p, our operator) resp. their offset.
(b) Cattaneo-Mindlin, f_t = 0.5, same geometry but two identical bodies with nu = 0 (E1 = E2 = 2 E*): beta = 0
    and nu = 0, the case in which Mindlin's shift is exact (docs/theory.md §7.2, P10), so that the error against the
    closed form goes to zero with dx. Error: relative error of the rigid shift U. Time: the cold
    `solve_tangential` (pressure from `solve_normal` on the same grid, tol 1e-10).
(c) The shakedown displacement u_sd of the paper scene (f_t = 0.46, w = 0.23, 10 periods), perpendicular and
    parallel: `run_scene` over dx x dW and over the tolerance. No closed form: the reference is Richardson-
    extrapolated, u* = u(dx1, dW1) - A dx1^p - B dW1^q, with p from three grids at the finest dW and q from
    three steps at dx = 0.2 (additive error model, checked by the table). Time: the whole run.

Order of convergence: slope of log error vs log dx between successive grids. Pareto front: the settings
not beaten in both error and time. Recommended default for (c): the cheapest setting whose u_sd is within
1 % of u* in both alignments.

JSON and PNG to DIR/accuracy_speed.{json,png} (default results/benchmarks/; the committed chart:
-o benchmarks/results). The 2 cores are shared with other jobs:
times are medians and noisy by ~20 %.
"""
from __future__ import annotations

import json
import math
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from accuracy_speed_chart import chart, pareto
import _record
from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.bem.errors import RollcontactError
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import default_scene
from peers import contactmechanics_solver, tamaas_solver
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere
from rollcontact.solver.normal.normcg import NormalParams, solve_normal
from rollcontact.solver.tangential.shift import TangentialParams, solve_tangential

R, FN, MU = 40.0, 21.19, 0.93
SCENE_PAIR = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
HERTZ = HertzSphere(R, SCENE_PAIR.E_star, FN)
E_ID = 2.0 * SCENE_PAIR.E_star                       # identical nu = 0 bodies: E* = E/2, beta = 0
MINDLIN_PAIR = MaterialPair.from_moduli(E_ID, 0.0, E_ID, 0.0)


def median_time(fn, repeats):
    out, times = None, []
    for _ in range(max(1, repeats)):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return out, statistics.median(times)


def square_grid(a, dx):
    return Grid.covering(-1.25 * a, 1.25 * a, -1.25 * a, 1.25 * a, dx, dx)


def orders(rows, key_h, key_err):
    """Observed orders log(e_i/e_{i+1}) / log(h_i/h_{i+1}) between successive rows (sorted by h desc)."""
    rows = sorted(rows, key=lambda r: -r[key_h])
    out = []
    for r0, r1 in zip(rows, rows[1:]):
        e0, e1 = abs(r0[key_err]), abs(r1[key_err])
        out.append(math.log(e0 / e1) / math.log(r0[key_h] / r1[key_h]) if e0 > 0 and e1 > 0 else float("nan"))
    return out


def fitted_order(rows, key_h, key_err):
    """Least-squares slope of log|error| against log h over all rows (robust to the non-monotone errors
    caused by the contact edge moving across cells)."""
    pts = [(math.log(r[key_h]), math.log(abs(r[key_err]))) for r in rows if r.get(key_err)]
    if len(pts) < 2:
        return float("nan")
    x, y = np.array(pts).T
    return float(np.polyfit(x, y, 1)[0])


# --- (a) Hertz -------------------------------------------------------------------------------------

def hertz_sweep(ratios, tols, repeats, peers):
    a = HERTZ.a
    rows = []
    for ratio in ratios:
        dx = a / ratio
        grid = square_grid(a, dx)
        X, Y = grid.mesh()
        h = (X ** 2 + Y ** 2) / (2 * R)
        t0 = time.perf_counter()
        op = HalfSpaceOperator(grid, SCENE_PAIR)
        setup = time.perf_counter() - t0
        centre = grid.index_of(0.0, 0.0)
        reps = repeats if grid.size < 40000 else 1
        for tol in tols:
            params = NormalParams(tol=tol, max_iter=2000)
            solve_normal(op, h, force=FN, params=params)                     # warm-up
            r, t = median_time(lambda: solve_normal(op, h, force=FN, params=params), reps)
            rows.append(dict(code="rollcontact", a_over_dx=ratio, dx=dx, elements=grid.size, tol=tol, time_s=t,
                             setup_s=setup, iterations=r.iterations,
                             d_err=r.approach / HERTZ.approach - 1, p0_err=r.pressure[centre] / HERTZ.p0 - 1))
            for name, solve in peers.items():
                try:
                    solve(grid, h, tol)                                       # warm-up (plans, imports)
                    (p, d), t = median_time(lambda: solve(grid, h, tol), reps)
                    if d is None:
                        u = op.normal(p)
                        c = p > 0
                        d = float(np.mean((h + u)[c]))
                    rows.append(dict(code=name, a_over_dx=ratio, dx=dx, elements=grid.size, tol=tol, time_s=t,
                                     d_err=d / HERTZ.approach - 1, p0_err=p[centre] / HERTZ.p0 - 1,
                                     force_err=float(p.sum()) * grid.cell_area / FN - 1))
                except Exception as exc:   # a peer failing is a result, not a crash
                    rows.append(dict(code=name, a_over_dx=ratio, dx=dx, tol=tol,
                                     error=f"{type(exc).__name__}: {exc}"))
            print(f"(a) a/dx={ratio:5.1f} tol={tol:.0e}: " + "  ".join(
                f"{x['code']} {x.get('time_s', float('nan')) * 1e3:8.2f} ms d_err {x.get('d_err', float('nan')):+.2e}"
                for x in rows if x["a_over_dx"] == ratio and x["tol"] == tol), flush=True)
    return rows


# --- (b) Cattaneo-Mindlin --------------------------------------------------------------------------

def cattaneo_sweep(ratios, tols, repeats, f_t=0.5):
    hertz = HertzSphere(R, MINDLIN_PAIR.E_star, FN)
    mindlin = CattaneoMindlin(hertz, MU, MINDLIN_PAIR.G_star)
    a = hertz.a
    rows = []
    for ratio in ratios:
        dx = a / ratio
        grid = Grid.covering(-a - max(0.6, 2 * dx), a + max(0.6, 2 * dx), -a - max(0.6, 2 * dx),
                             a + max(0.6, 2 * dx), dx, dx)
        X, Y = grid.mesh()
        op = HalfSpaceOperator(grid, MINDLIN_PAIR)
        assert not op.coupled
        t0 = time.perf_counter()
        nr = solve_normal(op, (X ** 2 + Y ** 2) / (2 * R), force=FN, params=NormalParams(tol=1e-10, max_iter=2000))
        t_normal = time.perf_counter() - t0
        g = MU * nr.pressure
        zero = np.zeros((2,) + grid.shape)
        force = (f_t * MU * FN, 0.0)
        reps = repeats if grid.size < 40000 else 1
        for tol in tols:
            params = TangentialParams(tol=tol, max_iter=5000)
            try:
                solve_tangential(op, g, zero, force=force, params=params)   # warm-up
                r, t = median_time(lambda: solve_tangential(op, g, zero, force=force, params=params), reps)
            except RollcontactError as exc:
                rows.append(dict(a_over_dx=ratio, dx=dx, tol=tol, error=f"{type(exc).__name__}: {exc}"))
                print(f"(b) a/dx={ratio:5.1f} tol={tol:.0e}: {type(exc).__name__}", flush=True)
                continue
            rows.append(dict(a_over_dx=ratio, dx=dx, elements=grid.size, tol=tol, time_s=t, normal_time_s=t_normal,
                             iterations=r.iterations, U_err=r.shift_increment[0] / mindlin.shift(f_t) - 1,
                             Uy_over_Ux=r.shift_increment[1] / r.shift_increment[0]))
            print(f"(b) a/dx={ratio:5.1f} tol={tol:.0e}: {t * 1e3:8.2f} ms, {r.iterations} it, "
                  f"U_err {rows[-1]['U_err']:+.3e}", flush=True)
    return rows


# --- (c) shakedown displacement of the paper scene -------------------------------------------------

def run_usd(angle, dx, dW, tol, repeats):
    """u at the end of the last period (u_sd if the state is shakedown), the state, du, and the run time."""
    scene = default_scene().with_overrides([
        f"motion.angle={angle}", f"grid.dx={dx}", f"grid.dy={dx}", f"motion.dW={dW}", f"solver.tol={tol}",
        f"grid.margin={max(0.6, 2 * dx)}", "output.fields=none", "solver.max_iter=5000"])
    times, out = [], None
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(max(1, repeats)):
            out = run_scene(scene, Path(tmp) / "run.h5", overwrite=True)
            times.append(out.wall_time)
    d = out
    s, h = d.summary, d.history
    row = dict(angle=angle, dx=dx, dW=dW, dW_used=s.get("dW_used"), tol=tol, a_over_dx=s["a"] / dx,
               elements=s.get("elements"), steps=s.get("steps"), iterations=s.get("iterations"),
               time_s=statistics.median(times), times_s=times, state=s.get("state"), du=s.get("du"),
               status=d.status, error=d.error)
    if d.status == "complete" and len(h["U_x"]):
        # u at the last period end (U along Ft = +x), whether or not classified as shakedown
        row["u_end"] = float(h["U_x"][-1] / s["U0"])
        row["u_sd"] = s.get("u_sd")
        row["u_stat"] = s.get("u_stat")
    return row


def richardson(values, h):
    """(limit, order) from three values at h, h/2, h/4 (any fixed ratio): u = u* + C h^p."""
    (u0, u1, u2), r = values, h[0] / h[1]
    d0, d1 = u0 - u1, u1 - u2
    if d1 == 0 or d0 / d1 <= 0:
        return u2, float("nan")           # not monotone: no order, keep the finest value
    p = math.log(d0 / d1) / math.log(r)
    return u2 - d1 / (r ** p - 1), p


def usd_sweep(angles, dxs, dWs, tols, repeats, dW_ref_dx=0.2):
    rows = []
    default_tol = 1e-8
    for angle in angles:
        combos = [(dx, dW, default_tol) for dx in dxs for dW in dWs]
        combos += [(dW_ref_dx, dW, default_tol) for dW in (min(dWs) / 2,) if dW_ref_dx in dxs]
        combos += [(dx, dW, t) for t in tols if t != default_tol
                   for (dx, dW) in ((0.2, 0.2), (0.4, 0.4), (0.8, 0.4), (0.8, 0.8)) if dx in dxs and dW in dWs]
        for dx, dW, tol in combos:
            cost = (0.2 / dx) ** 2 * (0.2 / dW)
            row = run_usd(angle, dx, dW, tol, repeats if cost <= 2.5 else 1)
            rows.append(row)
            print(f"(c) angle={angle:3.0f} dx={dx:.3g} dW={dW:.3g} tol={tol:.0e}: {row['time_s']:7.2f} s "
                  f"u_end={row.get('u_end', float('nan')):.6f} state={row['state']} du={row['du']} "
                  f"{row['status']} {row['error']}", flush=True)
    return rows


def usd_reference(rows, angle, dxs, dWs, dW_ref_dx=0.2):
    """Richardson reference of u_sd for one alignment (see the module docstring)."""
    tol = 1e-8
    def u(dx, dW):
        for r in rows:
            if r["angle"] == angle and r["tol"] == tol and math.isclose(r["dx"], dx) and math.isclose(r["dW"], dW):
                return r.get("u_end")
        return None
    fine_dW = min(dWs)
    three_dx = sorted(dxs)[:3][::-1]                 # coarse -> fine
    vals_dx = [u(dx, fine_dW) for dx in three_dx]
    dW_list = sorted(set(dWs) | {fine_dW / 2})[:3][::-1]
    vals_dW = [u(dW_ref_dx, dW) for dW in dW_list]
    if None in vals_dx or None in vals_dW:
        return None
    lim_dx, p = richardson(vals_dx, three_dx)
    lim_dW, q = richardson(vals_dW, dW_list)
    # u(dx -> 0, fine_dW) + [u(dx_ref, dW -> 0) - u(dx_ref, fine_dW)]: the dW correction taken at dx_ref
    corr_fine = lim_dW - u(dW_ref_dx, fine_dW)
    ref = lim_dx + corr_fine
    return dict(angle=angle, reference=ref, order_dx=p, order_dW=q, dx_values=dict(zip(map(str, three_dx), vals_dx)),
                dW_values_at_dx=dict(zip(map(str, dW_list), vals_dW)), limit_dx=lim_dx, limit_dW_at_dx=lim_dW,
                dW_correction=corr_fine, uncertainty=abs(lim_dx - vals_dx[-1]) * 0.5 + abs(corr_fine) * 0.5)


def main():
    ap = _record.parser(__doc__)
    ap.add_argument("--quick", action="store_true", help="coarse grids only (a/dx <= 24; dx >= 0.2 for u_sd)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--no-peers", action="store_true")
    ap.add_argument("--skip", default="", help="comma list of parts to skip: a,b,c")
    args = ap.parse_args()
    skip = set(args.skip.split(",")) - {""}
    if args.quick:
        ratios, tols = (6, 12, 24), (1e-4, 1e-6, 1e-8)
        dxs, dWs = (0.8, 0.4, 0.2), (0.4, 0.2)
    else:
        ratios, tols = (6, 12, 24, 48, 96), (1e-4, 1e-6, 1e-8, 1e-10)
        dxs, dWs = (0.8, 0.4, 0.2, 0.1), (0.8, 0.4, 0.2, 0.1)
    peers = {}
    if not args.no_peers:
        for name, make in (("tamaas", lambda: tamaas_solver(HERTZ.E_star, FN)),
                           ("contactmechanics", lambda: contactmechanics_solver(HERTZ.E_star, FN, HERTZ.approach))):
            s = make()
            if s is not None:
                peers[name] = s
    print(f"peers: {sorted(peers) or 'none importable'}", flush=True)
    name = "accuracy_speed_quick" if args.quick else "accuracy_speed"
    out = args.output / f"{name}.json"
    old = json.loads(out.read_text()) if out.exists() and skip else {}
    hertz = old.get("hertz", []) if "a" in skip else hertz_sweep(ratios, tols, args.repeats, peers)
    catt = old.get("cattaneo", []) if "b" in skip else cattaneo_sweep(ratios, tols, args.repeats)
    usd = old.get("u_sd", []) if "c" in skip else usd_sweep((90, 0), dxs, dWs, tols, args.repeats)
    refs = {}
    for angle in (90, 0):
        ref = usd_reference(usd, angle, dxs, dWs)
        if ref:
            refs[str(angle)] = ref
            for r in usd:
                if r["angle"] == angle and "u_end" in r:
                    r["err_vs_ref"] = r["u_end"] / ref["reference"] - 1
    # recommended default: the cheapest (dx, dW, tol) within 1 % in both alignments (time summed)
    cands = {}
    for r in usd:
        if "err_vs_ref" in r:
            cands.setdefault((r["dx"], r["dW"], r["tol"]), []).append(r)
    recommended = {}
    for bound in (0.01, 0.001):
        ok = [(sum(x["time_s"] for x in v), k, v) for k, v in cands.items()
              if len(v) == len(refs) and all(abs(x["err_vs_ref"]) <= bound for x in v)]
        if ok:
            t, k, v = min(ok)
            recommended[str(bound)] = dict(dx=k[0], dW=k[1], tol=k[2], time_s_both=t,
                                           per_angle={str(x["angle"]): dict(time_s=x["time_s"], err=x["err_vs_ref"],
                                                                            u=x["u_end"]) for x in v})
    today = cands.get((0.2, 0.2, 1e-8))
    summary = dict(
        hertz_orders={code: {str(tol): orders([r for r in hertz if r["code"] == code and r["tol"] == tol
                                                and "d_err" in r], "dx", "d_err") for tol in tols}
                      for code in ["rollcontact"] + sorted(peers)},
        hertz_fitted_order={code: {str(tol): fitted_order([r for r in hertz if r["code"] == code and r["tol"] == tol
                                                            and "d_err" in r], "dx", "d_err") for tol in tols}
                            for code in ["rollcontact"] + sorted(peers)},
        hertz_p0_fitted_order={str(tol): fitted_order([r for r in hertz if r["code"] == "rollcontact"
                                                       and r["tol"] == tol], "dx", "p0_err") for tol in tols},
        cattaneo_fitted_order={str(tol): fitted_order([r for r in catt if r["tol"] == tol and "U_err" in r], "dx",
                                                      "U_err") for tol in tols},
        cattaneo_orders={str(tol): orders([r for r in catt if r["tol"] == tol and "U_err" in r], "dx", "U_err")
                         for tol in tols},
        usd_references=refs, recommended=recommended,
        today_default=[dict(angle=x["angle"], time_s=x["time_s"], err=x["err_vs_ref"]) for x in today] if today else None,
        pareto_usd={a: [dict(dx=p["dx"], dW=p["dW"], tol=p["tol"], time_s=p["time_s"], err=p["err_vs_ref"])
                        for p in (lambda pts: [pts[i] for i in pareto([(q["time_s"], abs(q["err_vs_ref"])) for q in pts])])(
                            [r for r in usd if str(r["angle"]) == a and "err_vs_ref" in r])]
                    for a in refs})
    _record.write(name, dict(benchmark="accuracy_speed", quick=args.quick, peers=sorted(peers),
                             note="wall times: medians on a shared 2-core machine, noisy by ~20 %",
                             hertz=hertz, cattaneo=catt, u_sd=usd, summary=summary), args.output)
    png = out.with_suffix(".png")
    chart(hertz, catt, usd, refs, png)
    print(json.dumps(summary, indent=1, default=float))
    print(f"wrote {out} and {png} ({png.stat().st_size / 1e3:.0f} kB)")


if __name__ == "__main__":
    sys.exit(main())

"""Stability map over the hard regimes of the contact solvers (issue #7).

    .venv/bin/python benchmarks/stability.py [--quick] [--only GROUP[,GROUP]] [-o DIR]

Every case is run once and classified: 'converged' (to its stated tolerance, with the physics invariants
checked: force balance, |tau| <= mu p (1 + 1e-9), p >= 0, no NaN), 'ConvergenceError' (with its message, which
must name the regime), 'gross_sliding', or another error (a bug). Recorded: iterations (normal + tangential
products; for runs the largest per step and the total), the residual, and the error where a reference exists
(Hertz, HertzEllipse, Mindlin, seed Eq. 13 with the seed's kappa).

Groups (the seed scene unless stated: R = 40 mm, rubber E2 = 4.35 MPa nu2 = 0.5, steel sphere, Fn = 21.19 N,
mu = 0.93, tol = 1e-8):
  ft_static   static Cattaneo, f_t = 0.5, 0.9, 0.99, 0.999 at a/dx = 12, 24, 48, 96 (dx 0.4 ... 0.05)
  ft_rolling  rolling (w = 0.23, 4 periods, both alignments) at f_t = 0.9, 0.99, 0.999 (ratcheting), dx = 0.4, 0.2
  w_limit     rolling at f_t = 0.46, w = 0.9 and 1.1 x w_lim(f_t; seed kappa), both alignments, 10 periods
  mu          static Cattaneo f_t = 0.5 with mu = 0.05, 0.2, 0.93, 2 (U/U0 must not depend on mu)
  a_dx        static Hertz + Cattaneo f_t = 0.5 at a/dx = 3, 6, 12, 24, 48, 100, 200
  dW_dx       rolling, W = 1.2 mm, dx = 0.2, dW/dx = 0.1, 0.5, 1, 3, 6 (10 periods, perpendicular)
  coupled     E1 = 210e3 nu1 = 0.3 on E2 = 70e3 / 20e3, nu2 = 0.0 / 0.3 (beta -0.14 ... -0.32), a/dx = 12:
              static Cattaneo f_t = 0.5 and rolling w = 0.23 (4 periods)
  ellipse     Rx/Ry = 1, 2, 5, 10 (sqrt(Rx Ry) = 40 mm), static Hertz + Cattaneo f_t = 0.5, b/dx = 12
  edge        tiny pressures at the contact edge: dx chosen so that the outermost elements sit just inside
              r = a (p/p0 down to ~1e-3), and a tiny load Fn = 1e-4 N (p0 ~ 0.03 MPa, a/dx = 12)
  near_limit  u_sd for f_t -> f_t,lim(w = 0.23): f_t = 0.6, 0.7, 0.73 (parallel f_t,lim = 0.77, perpendicular
              0.748 by the seed's kappa), dx = 0.4 -> 0.2 -> 0.1, dW = 0.2, 15 periods: convergence under
              refinement (Richardson order), against seed Eq. 13.

JSON + PNG to DIR/stability.{json,png} (default results/benchmarks/; the committed chart: -o benchmarks/results).
Wall times are single runs on a shared 2-core machine.
"""
from __future__ import annotations

import json
import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import _record
from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.bem.errors import ConvergenceError, GrossSlidingError, RollcontactError
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import default_scene
from rollcontact.solver.mdr import limits as lim
from rollcontact.solver.analytic import CattaneoMindlin, HertzEllipse, HertzSphere
from rollcontact.solver.rolling.coupled import solve_coupled_step
from rollcontact.solver.normal.normcg import NormalParams, solve_normal
from rollcontact.solver.tangential.shift import TangentialParams, solve_tangential

R, FN, MU, TOL = 40.0, 21.19, 0.93, 1e-8
SCENE_PAIR = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)


def invariants(pressure, traction, mu, force_t, dA, Fn):
    """Physics checks of one solution: NaN, p >= 0, |tau| <= mu p (1 + 1e-9), force balance (relative)."""
    tau_mag = np.hypot(traction[0], traction[1])
    bound = mu * pressure
    excess = tau_mag - bound * (1 + 1e-9)
    return dict(
        finite=bool(np.all(np.isfinite(pressure)) and np.all(np.isfinite(traction))),
        min_p=float(pressure.min()),
        coulomb_excess=float(excess.max() / max(bound.max(), 1e-300)),     # > 0 is a violation
        normal_force_err=float(pressure.sum() * dA / Fn - 1),
        tangential_force_err=float(np.hypot(traction[0].sum() * dA - force_t[0], traction[1].sum() * dA - force_t[1])
                                   / max(np.hypot(*force_t), 1e-300)))


def invariants_ok(inv):
    return (inv["finite"] and inv["min_p"] >= 0 and inv["coulomb_excess"] <= 0
            and abs(inv["normal_force_err"]) < 1e-6 and inv["tangential_force_err"] < 1e-6)


def static_case(group, label, pair, rx, ry, Fn, mu, f_t, dx, tol=TOL, max_iter=500, margin_cells=3, shift=0.0):
    """Static Hertz + Cattaneo (loading phase in one step) on a grid covering the Hertz ellipse + margin."""
    row = dict(group=group, label=label, kind="static", f_t=f_t, mu=mu, dx=dx, beta=pair.beta, Rx=rx, Ry=ry, Fn=Fn)
    if rx == ry:
        hz = HertzSphere(rx, pair.E_star, Fn)
        sa = sb = hz.a
        ref_d, ref_p0 = hz.approach, hz.p0
    else:
        hz = HertzEllipse(rx, ry, pair.E_star, Fn)
        sa, sb = hz.a, hz.b
        ref_d, ref_p0 = hz.approach, hz.p0
    m = margin_cells * dx
    grid = Grid.covering(-sa - m + shift, sa + m + shift, -sb - m, sb + m, dx, dx)
    X, Y = grid.mesh()
    row.update(elements=grid.size, a_over_dx=math.sqrt(sa * sb) / dx)
    t0 = time.perf_counter()
    try:
        op = HalfSpaceOperator(grid, pair)
        profile = (X - shift) ** 2 / (2 * rx) + Y ** 2 / (2 * ry)
        nparams, tparams = NormalParams(tol=tol, max_iter=max_iter), TangentialParams(tol=tol, max_iter=max_iter)
        F = (f_t * mu * Fn, 0.0)
        zero = np.zeros((2,) + grid.shape)
        if op.coupled:
            nr, tr, outer = solve_coupled_step(op, profile, Fn=Fn, F=F, mu=mu, previous_pressure=None,
                                               previous_traction=zero, normal_params=nparams,
                                               tangential_params=tparams)
            row["outer_iterations"] = outer
        else:
            nr = solve_normal(op, profile, force=Fn, params=nparams)
            tr = solve_tangential(op, mu * nr.pressure, zero, force=F, params=tparams) if f_t > 0 else None
        row.update(status="converged", normal_iterations=nr.iterations, normal_residual=nr.residual,
                   d_err=nr.approach / ref_d - 1, p0_err=float(nr.pressure.max()) / ref_p0 - 1,
                   min_positive_p_over_p0=float(nr.pressure[nr.pressure > 0].min() / ref_p0))
        if tr is not None:
            cm = CattaneoMindlin(HertzSphere(math.sqrt(rx * ry), pair.E_star, Fn), mu, pair.G_star)
            row.update(tangential_iterations=tr.iterations, tangential_residual=tr.residual,
                       stick_elements=int((tr.region == 1).sum()),
                       U_err=tr.shift_increment[0] / cm.shift(f_t) - 1 if rx == ry else None,
                       U_over_U0=tr.shift_increment[0] / cm.U0,
                       iterations=nr.iterations + tr.iterations, residual=max(nr.residual, tr.residual))
            row["invariants"] = invariants(nr.pressure, tr.traction, mu, F, grid.cell_area, Fn)
        else:
            row.update(iterations=nr.iterations, residual=nr.residual)
            row["invariants"] = invariants(nr.pressure, np.zeros((2,) + grid.shape), mu, (0.0, 0.0),
                                           grid.cell_area, Fn)
            row["invariants"]["tangential_force_err"] = 0.0
        row["max_iter"] = max_iter
        if not invariants_ok(row["invariants"]):
            row["status"] = "INVARIANT VIOLATION"
    except ConvergenceError as exc:
        row.update(status="ConvergenceError", error=str(exc), iterations=exc.iterations, residual=exc.residual)
    except GrossSlidingError as exc:
        row.update(status="gross_sliding", error=str(exc))
    except Exception as exc:  # noqa: BLE001 - anything else is a finding
        row.update(status=f"BUG {type(exc).__name__}", error=str(exc))
    row["time_s"] = time.perf_counter() - t0
    return row


def rolling_case(group, label, overrides, kappa=None, periods=None):
    """A run_scene run; iterations per step, residuals, state, and the invariants at the stored steps."""
    overrides = list(overrides)
    for item in list(overrides):    # the shipped scene sets dy = 0.2 explicitly: square cells unless stated
        if item.startswith("grid.dx=") and not any(o.startswith("grid.dy=") for o in overrides):
            overrides.append("grid.dy=" + item.split("=", 1)[1])
    scene = default_scene().with_overrides(overrides + ["output.fields=reversals"]
                                           + ([f"motion.periods={periods}"] if periods else []),
                                           replaces=("motion.W",))   # the amplitude in mm, over the scene's w
    row = dict(group=group, label=label, kind="rolling", overrides=list(overrides), f_t=scene.f_t,
               w=scene.amplitude / scene.contact_radius, angle=scene.motion.angle, dx=scene.grid.dx,
               dW=scene.rolling_step, beta=scene.material_pair.beta, mu=scene.load.mu)
    with tempfile.TemporaryDirectory() as tmp:
        try:
            out = run_scene(scene, Path(tmp) / "run.h5")
        except Exception as exc:  # noqa: BLE001 - run_scene should not raise: a finding
            row.update(status=f"BUG {type(exc).__name__}", error=str(exc))
            return row
    d, s, h = out, out.summary, out.history
    row.update(time_s=out.wall_time, elements=s.get("elements"), steps=s.get("steps"),
               steps_planned=s.get("steps_planned"), state=s.get("state"), u_sd=s.get("u_sd"), du=s.get("du"),
               u_stat=s.get("u_stat"), iterations=int(np.max(h["iterations"])) if len(h["iterations"]) else None,
               iterations_total=s.get("iterations"),
               max_tangential_iterations=int(np.max(h["tangential_iterations"])) if len(h["iterations"]) else None,
               residual=float(np.max(h["residual"])) if len(h["residual"]) else None)
    if len(h.get("U_x", [])):
        row["u_end"] = float(h["U_x"][-1] / s["U0"])
    if d.status == "complete":
        row["status"] = "gross_sliding" if s.get("state") == "gross_sliding" else "converged"
    else:
        row["status"] = d.error.split(":")[0] if d.error else "failed"
        row["error"] = d.error
    worst = None
    dA = (d.x[1] - d.x[0]) * (d.y[1] - d.y[0]) if len(d.x) > 1 else 0
    for i, step in enumerate(d.field_steps):
        inv = invariants(d.fields["p"][i], np.stack([d.fields["tau_x"][i], d.fields["tau_y"][i]]), scene.load.mu,
                         (scene.Ft * scene.load_direction[0], scene.Ft * scene.load_direction[1]), dA,
                         scene.load.Fn)
        if worst is None or inv["coulomb_excess"] > worst["coulomb_excess"] or not invariants_ok(inv):
            worst = inv
    row["invariants"] = worst
    if worst is not None and not invariants_ok(worst) and row["status"] == "converged":
        row["status"] = "INVARIANT VIOLATION"
    if kappa is not None:
        try:
            row["u_sd_eq13"] = float(lim.u_shakedown(row["f_t"], row["w"], kappa))
        except RollcontactError:
            row["u_sd_eq13"] = None
    return row


def show(row):
    keys = ("u_end", "u_sd_eq13", "U_err", "d_err", "p0_err", "state", "du")
    extra = " ".join(f"{k}={row[k]:.4g}" if isinstance(row.get(k), float) else f"{k}={row[k]}"
                     for k in keys if row.get(k) is not None)
    inv = row.get("invariants") or {}
    print(f"[{row['group']}] {row['label']}: {row['status']} it={row.get('iterations')} res={row.get('residual')} "
          f"t={row.get('time_s', 0):.2f}s {extra} coul={inv.get('coulomb_excess')} "
          f"{(row.get('error') or '')[:160]}", flush=True)
    return row


# --- groups -----------------------------------------------------------------------------------------

def g_ft_static(quick):
    a = HertzSphere(R, SCENE_PAIR.E_star, FN).a
    ratios = (12, 24) if quick else (12, 24, 48, 96)
    return [show(static_case("ft_static", f"f_t={f} a/dx={k}", SCENE_PAIR, R, R, FN, MU, f, a / k))
            for k in ratios for f in (0.5, 0.9, 0.99, 0.999)]


def g_ft_rolling(quick):
    rows = []
    for dx in ((0.4,) if quick else (0.4, 0.2)):
        for angle in (90, 0):
            for f in (0.9, 0.99, 0.999):
                rows.append(show(rolling_case("ft_rolling", f"f_t={f} angle={angle} dx={dx}",
                                              [f"load.ft={f}", f"motion.angle={angle}", f"grid.dx={dx}",
                                               f"motion.dW={dx}"], periods=4)))
    return rows


def g_w_limit(quick):
    rows = []
    for angle, kappa in ((90, lim.KAPPA_PERPENDICULAR), (0, lim.KAPPA_PARALLEL)):
        wl = lim.w_lim(0.46, kappa)
        for fac in (0.9, 1.1):
            rows.append(show(rolling_case("w_limit", f"w={fac}w_lim={fac * wl:.3f} angle={angle}",
                                          [f"motion.w={fac * wl}", f"motion.angle={angle}"]
                                          + (["grid.dx=0.4", "motion.dW=0.4"] if quick else []),
                                          kappa=kappa)))
    return rows


def g_mu(quick):
    a = HertzSphere(R, SCENE_PAIR.E_star, FN).a
    return [show(static_case("mu", f"mu={mu}", SCENE_PAIR, R, R, FN, mu, 0.5, a / 24)) for mu in (0.05, 0.2, 0.93, 2.0)]


def g_a_dx(quick):
    a = HertzSphere(R, SCENE_PAIR.E_star, FN).a
    ratios = (3, 6, 12, 24) if quick else (3, 6, 12, 24, 48, 100, 200)
    return [show(static_case("a_dx", f"a/dx={k}", SCENE_PAIR, R, R, FN, MU, 0.5, a / k, max_iter=2000))
            for k in ratios]


def g_dW_dx(quick):
    ratios = (0.5, 1, 3, 6) if quick else (0.1, 0.5, 1, 3, 6)
    return [show(rolling_case("dW_dx", f"dW/dx={r}", ["motion.W=1.2", f"motion.dW={0.2 * r}", "grid.dx=0.2"],
                              kappa=lim.KAPPA_PERPENDICULAR)) for r in ratios]


def g_coupled(quick):
    rows = []
    for E2, nu2 in ((70e3, 0.3), (20e3, 0.3), (70e3, 0.0)):
        pair = MaterialPair.from_moduli(210e3, 0.3, E2, nu2)
        a = HertzSphere(R, pair.E_star, FN).a
        rows.append(show(static_case("coupled", f"E2={E2:g} nu2={nu2} beta={pair.beta:.3f} static", pair, R, R,
                                     FN, MU, 0.5, a / 12)))
        ov = ["materials.E1=210e3", "materials.nu1=0.3", f"materials.E2={E2}", f"materials.nu2={nu2}",
              f"grid.dx={a / 12}", f"motion.dW={a / 12}", f"grid.margin={3 * a / 12}"]
        rows.append(show(rolling_case("coupled", f"E2={E2:g} nu2={nu2} beta={pair.beta:.3f} rolling", ov,
                                      periods=2 if quick else 4)))
    return rows


def g_ellipse(quick):
    rows = []
    for k in (1, 2, 5, 10):
        rx, ry = R * math.sqrt(k), R / math.sqrt(k)
        b = HertzEllipse(rx, ry, SCENE_PAIR.E_star, FN).b if k > 1 else HertzSphere(R, SCENE_PAIR.E_star, FN).a
        rows.append(show(static_case("ellipse", f"Rx/Ry={k}", SCENE_PAIR, rx, ry, FN, MU, 0.5, b / 12)))
    return rows


def g_edge(quick):
    rows = []
    a = HertzSphere(R, SCENE_PAIR.E_star, FN).a
    for k, eps in ((12, 1e-3), (12, 1e-5), (24, 1e-5)):
        dx = a * (1 - eps) / k            # element centre k dx = a (1 - eps): p/p0 ~ sqrt(2 eps)
        rows.append(show(static_case("edge", f"edge element at r=a(1-{eps:g}) a/dx~{k}", SCENE_PAIR, R, R, FN, MU,
                                     0.5, dx)))
    for f in (0.5, 0.99):
        a_small = HertzSphere(R, SCENE_PAIR.E_star, 1e-4).a
        rows.append(show(static_case("edge", f"Fn=1e-4 N f_t={f}", SCENE_PAIR, R, R, 1e-4, MU, f, a_small / 12)))
    return rows


def g_near_limit(quick):
    rows = []
    dxs = (0.4, 0.2) if quick else (0.4, 0.2, 0.1)
    for angle, kappa in ((90, lim.KAPPA_PERPENDICULAR), (0, lim.KAPPA_PARALLEL)):
        for f in (0.6, 0.7, 0.73):
            for dx in dxs:
                rows.append(show(rolling_case("near_limit", f"f_t={f} angle={angle} dx={dx}",
                                              [f"load.ft={f}", f"motion.angle={angle}", f"grid.dx={dx}",
                                               "motion.dW=0.2", f"grid.margin={max(0.6, 2 * dx)}"],
                                              kappa=kappa, periods=15)))
    return rows


GROUPS = dict(ft_static=g_ft_static, mu=g_mu, a_dx=g_a_dx, ellipse=g_ellipse, edge=g_edge, coupled=g_coupled,
              w_limit=g_w_limit, dW_dx=g_dW_dx, ft_rolling=g_ft_rolling, near_limit=g_near_limit)


def near_limit_summary(rows):
    out = []
    for angle in (90, 0):
        for f in (0.6, 0.7, 0.73):
            pts = sorted([r for r in rows if r["group"] == "near_limit" and r["angle"] == angle
                          and math.isclose(r["f_t"], f) and r.get("u_end") is not None], key=lambda r: -r["dx"])
            item = dict(angle=angle, f_t=f, u_by_dx={str(r["dx"]): r["u_end"] for r in pts},
                        states={str(r["dx"]): r["state"] for r in pts}, du={str(r["dx"]): r["du"] for r in pts},
                        u_sd_eq13=pts[0].get("u_sd_eq13") if pts else None)
            if len(pts) == 3:
                u0, u1, u2 = (r["u_end"] for r in pts)
                d0, d1 = u0 - u1, u1 - u2
                item["changes"] = [d0, d1]
                if d1 != 0 and d0 / d1 > 0:
                    p = math.log(d0 / d1) / math.log(2)
                    item.update(order=p, extrapolated=u2 - d1 / (2 ** p - 1))
            out.append(item)
    return out


def chart(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    height = max(5.5, 0.16 * len(rows) + 1.2)  # one readable label line per case
    fig, axes = plt.subplots(1, 2, figsize=(15, height), gridspec_kw=dict(width_ratios=[1.4, 1]))
    ax = axes[0]
    colours = {"converged": "tab:green", "ConvergenceError": "tab:red", "gross_sliding": "tab:orange"}
    labels = [f"{r['group']}: {r['label']}" for r in rows]
    its = [r.get("iterations") or 0 for r in rows]
    col = [colours.get(r["status"], "black") for r in rows]
    y = np.arange(len(rows))
    ax.barh(y, its, color=col)
    ax.set_yticks(y, labels, fontsize=7)
    ax.set_ylim(len(rows) - 0.5, -0.5)
    ax.set_xscale("log")
    ax.set_xlabel("iterations (static: normal + tangential products; rolling: largest per step)")
    ax.set_title("stability map: green converged, red ConvergenceError,\norange gross sliding, black other", fontsize=10)
    ax = axes[1]
    for angle, mk in ((90, "o-"), (0, "s--")):
        for f in (0.6, 0.7, 0.73):
            pts = sorted([r for r in rows if r["group"] == "near_limit" and r["angle"] == angle
                          and math.isclose(r["f_t"], f) and r.get("u_end") is not None], key=lambda r: r["dx"])
            if pts:
                ax.plot([r["dx"] for r in pts], [r["u_end"] for r in pts], mk,
                        label=f"{'perp' if angle == 90 else 'par'} f_t={f}")
                if pts[0].get("u_sd_eq13"):
                    ax.plot([0], [pts[0]["u_sd_eq13"]], "k" + mk[0], mfc="none")
    ax.set(xlabel="dx (mm)", ylabel="u after 15 periods", xlim=(-0.02, 0.45),
           title="near the limit (w = 0.23): u vs dx (open black: seed Eq. 13)")
    ax.legend(fontsize=7)
    axes[1].set_box_aspect(0.8)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def main():
    ap = _record.parser(__doc__)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--only", default="", help="comma list of groups (default all): " + ",".join(GROUPS))
    ap.add_argument("--replot", action="store_true", help="redraw the PNG from the stored JSON, run nothing")
    args = ap.parse_args()
    if args.replot:
        out = args.output / ("stability_quick.json" if args.quick else "stability.json")
        chart(json.loads(out.read_text())["rows"], out.with_suffix(".png"))
        print(f"wrote {out.with_suffix('.png')}")
        return 0
    only = [g for g in args.only.split(",") if g] or list(GROUPS)
    name = "stability_quick" if args.quick else "stability"
    out = args.output / f"{name}.json"
    old = json.loads(out.read_text())["rows"] if out.exists() and args.only else []
    rows = [r for r in old if r["group"] not in only]
    for g in only:
        rows += GROUPS[g](args.quick)
    order = list(GROUPS)
    rows.sort(key=lambda r: order.index(r["group"]))
    counts = {}
    for r in rows:
        counts[r["status"]] = counts.get(r["status"], 0) + 1
    summary = dict(counts=counts, near_limit=near_limit_summary(rows),
                   failures=[dict(group=r["group"], label=r["label"], status=r["status"], error=r.get("error"))
                             for r in rows if r["status"] not in ("converged",)])
    _record.write(name, dict(benchmark="stability", quick=args.quick, rows=rows, summary=summary,
                             note="single runs on a shared 2-core machine"), args.output)
    png = out.with_suffix(".png")
    chart(rows, png)
    print(json.dumps(summary, indent=1, default=float))
    print(f"wrote {out} and {png} ({png.stat().st_size / 1e3:.0f} kB)")


if __name__ == "__main__":
    sys.exit(main())

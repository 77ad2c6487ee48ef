"""The study of docs/viscoelastic.md: the seed's scene with a Standard Linear Solid substrate, against the Deborah
number De = V tau_c / a_r (a_r the quasi-static, relaxed Hertz radius), from quasi-static to fast; both alignments.

    .venv/bin/python benchmarks/viscoelastic_study.py -o DIR [--quick] [--ratio 2] [--jobs 2]

Writes DIR/viscoelastic_study.json (every number), DIR/viscoelastic_study.md (the tables of the page) and the
figures DIR/viscoelastic_*.png. Material: the seed's steel sphere (R = 40 mm, Fn = 21.19 N, mu = 0.93) on a silicone
substrate with the seed's modulus as the relaxed one, E_r = 4.35 MPa, E_g = ratio E_r (default 2), tau_c = 0.1 s,
nu = 0.5 (docs/viscoelastic.md says why these values). Parts:

  steady    rolling resistance (pressure centroid, M = Fn x_c, viscous power) of the sphere in free steady rolling
            against De, for E_g/E_r = ratio and 10, beside Hunter's cylinder; the pressure along the rolling direction
  cylinder  the mid-length of a steel cylinder rolled steadily across its axis, against Hunter's plane strain (how
            long a cylinder must be for its mid-length to be plane strain)
  cyclic    u_sd (f_t = 0.3) and the ratchet increment (f_t = 0.77) of the oscillating paper scene (W = 0.23 a_r, 30
            periods), both alignments, against De, with the elastic runs with E_r and E_g (at the same W; every u is
            U / U0 of the relaxed modulus); the viscous work per period
  limits    the shakedown limit f_t,lim(W = 0.23 a_r) against De, both alignments (rollcontact limit_search)

--quick: a coarse grid and a few De (checks that the script runs; its numbers are not the page's). The full study
takes about 20 minutes on 2 quiet cores (dx = dW = a/12 for the cyclic runs and limits; measured in the JSON).
"""
import argparse
import json
import math
import os
import time
from pathlib import Path

import numpy as np

import rollcontact
from rollcontact.cases.scene.scene import Scene, default_scene
from rollcontact.solver.visco.hunter import hunter_cylinder

E_R, TAU, R_SPHERE, FN, MU = 4.35, 0.1, 40.0, 21.19, 0.93
A_R = 4.786                      # relaxed Hertz radius of the seed scene (mm)


def sls(ratio, body=2):
    return [f'materials.visco{body}="sls"', f"materials.E{body}={ratio * E_R}", f"materials.E{body}_relaxed={E_R}",
            f"materials.tau{body}={TAU}"]


def speed(de):
    return de * A_R / TAU


STEADY = """
[materials]
E1 = 206000.0
nu1 = 0.3
E2 = {E2}
nu2 = 0.5
{visco}
[geometry]
{geometry}
[load]
Fn = {Fn}
mu = 0.93
[rolling]
mode = "steady"
xi = 0.0
speed = {speed}
[grid]
dx = {dx}
{dy}
[output]
fields = "{fields}"
"""


def steady_scene(ratio, de, dx, geometry=f"R = {R_SPHERE}", fn=FN, dy="", fields="last"):
    visco = "" if ratio is None else f'visco2 = "sls"\nE2_relaxed = {E_R}\ntau2 = {TAU}'
    E2 = E_R if ratio is None else ratio * E_R
    return Scene.from_toml_text(STEADY.format(E2=E2, visco=visco, geometry=geometry, Fn=fn, speed=speed(de), dx=dx,
                                              dy=dy, fields=fields))


def part_steady(ratios, des, dx):
    """Free steady rolling of the sphere: x_c / a_r, mu_r = M / (Fn R), viscous power against De; Hunter beside."""
    out = {}
    for ratio in ratios:
        rows = []
        for de in des:
            r = rollcontact.run(steady_scene(ratio, de, dx))
            s = r.summary
            rows.append(dict(De=de, xc_over_a=s["pressure_centroid_x"] / A_R,
                             mu_r=s["rolling_resistance_moment"] / (FN * R_SPHERE), viscous_power=s["viscous_power"],
                             work_per_mm=s["viscous_power"] * 1e3 / speed(de),
                             p_max=s["p0"], contact_area=float(r.history["contact_area"][0]),
                             approach=float(r.history["approach"][0]), wall_time=s["wall_time"]))
        # Hunter's cylinder at the same moduli: x_c / w_r against V tau / w_r
        P, R = 1.0, R_SPHERE
        w_r = math.sqrt(2 * (2 * 0.75 / math.pi) * R * P / E_R)
        hunter, guess = [], None
        for de in np.geomspace(min(des), max(des), 40):
            h = hunter_cylinder(P, R, ratio * E_R, E_R, 0.5, de * w_r, guess=guess)
            guess = (h.c, h.w)
            hunter.append(dict(De=float(de), xc_over_a=h.centroid / w_r, mu_r=h.resistance_coefficient * R / w_r))
        out[str(ratio)] = dict(sphere=rows, hunter=hunter)
    return out


def part_profiles(ratio, des, dx):
    """The pressure along the rolling direction through the sphere's lowest point, steady, for a few De."""
    out = {}
    for de in list(des) + [None]:
        scene = steady_scene(ratio if de is not None else None, de if de is not None else 1.0, dx)
        r = rollcontact.run(scene)
        j = int(np.argmin(np.abs(r.y)))
        out["elastic E_r" if de is None else f"{de:g}"] = dict(x=list(map(float, r.x)),
                                                                  p=list(map(float, r.field("p")[j])))
    return out


def part_cylinder(ratio, de, lengths, dx):
    """A steel cylinder (R = 40 mm) rolled steadily across its axis on the SLS substrate at De (the relaxed
    half-width of the line contact): the pressure centroid of its mid-length row against Hunter's plane strain at
    the mid-length's line load."""
    rows = []
    P = 1.0                                         # N/mm along the axis
    k = 2 * 0.75 / math.pi
    w_r = math.sqrt(2 * k * R_SPHERE * P / E_R)
    for L in lengths:
        geometry = f'shape = "cylinder"\nR = {R_SPHERE}\nlength = {L * w_r}\nedge_R = {R_SPHERE / 4}\naxis = "y"'
        scene = steady_scene(ratio, de * w_r / A_R, w_r / 12, geometry=geometry, fn=P * L * w_r,
                             dy=f"dy = {w_r / 3}")
        r = rollcontact.run(scene)
        p = r.field("p")
        j = int(np.argmin(np.abs(r.y)))
        line = float(p[j].sum() * (r.x[1] - r.x[0]))
        xc = float((r.x * p[j]).sum() / p[j].sum())
        h = hunter_cylinder(line, R_SPHERE, ratio * E_R, E_R, 0.5, de * w_r)
        rows.append(dict(length_over_a=L, line_load=line, line_load_nominal=P, xc=xc, xc_hunter=h.centroid,
                         difference=xc / h.centroid - 1.0, De=de, dx=w_r / 12))
    return dict(w_r=w_r, rows=rows)


#: the loads of the cyclic part: below the shakedown limit at every De (u_sd), above it at every De (ratchet rate)
FT_SD, FT_RATCHET = 0.3, 0.77
#: periods of the cyclic part: the memory's creep after the ramp settles over several periods at De ~ 0.1
CYCLIC_PERIODS = 30

#: U0 of the seed scene with the relaxed modulus (mm): every u below is U / U0_R, so that the elastic run with E_g
#: (whose own U0 is smaller) is compared at the same W = 0.23 a_r and in the same unit
U0_R = 0.79873


def part_hunter(ns=(20, 40, 80), des=(0.3, 1.0, 3.0, 10.0)):
    """The steady boundary elements in plane strain (one strip of 1e5 mm) against Hunter's closed form: a rigid
    cylinder (R = 50 mm, 10 N/mm) on E_g/E_r = 10, n cells per relaxed half-width: the centroid's relative difference
    and the largest pressure difference at abs(t) <= 0.9 relative to the peak."""
    from rollcontact.bem.grid import Grid
    from rollcontact.bem.materials import Material
    from rollcontact.solver.visco.sls import StandardLinearSolid
    from rollcontact.solver.visco.steady import SteadyVisco, pressure_centroid
    P, R, Eg, Er = 10.0, 50.0, 40.0, 4.0
    w_r = math.sqrt(2 * (2 * 0.75 / math.pi) * R * P / Er)
    rows = []
    for n in ns:
        grid = Grid.covering(-1.3 * w_r, 1.3 * w_r, -0.1, 0.1, w_r / n, 1e5)
        X, _ = grid.mesh()
        for de in des:
            h = hunter_cylinder(P, R, Eg, Er, 0.5, de * w_r)
            sv = SteadyVisco(grid, Material(math.inf, 0.3), StandardLinearSolid(Eg, Er, 1.0, 0.5), de * w_r)
            res = sv.solve_normal(X ** 2 / (2 * R), P * grid.dy)
            exact = h.pressure(grid.x)
            inner = np.abs((grid.x - h.c) / h.w) <= 0.9
            rows.append(dict(n=n, De=de, centroid=pressure_centroid(grid, res.pressure) / h.centroid - 1.0,
                             interior=float(np.max(np.abs(res.pressure[0] - exact)[inner]) / exact.max()),
                             peak=float(res.pressure.max() / exact.max() - 1.0)))
    return rows


def part_contact():
    """CONTACT's examples/visc_cylindr (eve70a/CONTACT) posed as in tests/solver/test_visco_contact_example.py."""
    from rollcontact.bem.grid import Grid
    from rollcontact.bem.materials import Material, MaterialPair
    from rollcontact.bem.operator import HalfSpaceOperator
    from rollcontact.solver.creep.prescribed import solve_for_forces
    from rollcontact.solver.creep.steady import SteadyRolling
    from rollcontact.solver.normal import solve_normal
    from rollcontact.solver.visco.sls import StandardLinearSolid
    from rollcontact.solver.visco.steady import SteadyVisco
    G, nu = 1143.0, 0.4
    Eg = 2 * G * (1 + nu)
    reference = {0.0: (1.378e-2, 2.50845, 60.32, 80, 51), 0.009: (1.365e-2, 2.36736, 78.74, 62, 37),
                 0.045: (1.152e-2, 2.06321, 84.72, 57, 36), 2.0: (9.932e-3, 1.45462, 85.31, 56, 35)}
    grid = Grid(99, 1, 0.16, 1000.0, -49, 0)
    X, _ = grid.mesh()
    h = 0.01 * (X - 0.08) ** 2
    rows = []
    for tau, (xi, d, pmax, ncon, nadh) in reference.items():
        if tau == 0.0:
            pair = MaterialPair(Material(Eg / 2, nu), Material(Eg / 2, nu))
            op = HalfSpaceOperator(grid, pair)
            normal, problem = solve_normal(op, h, force=6e5), SteadyRolling(grid, pair, operator=op)
        else:
            body = StandardLinearSolid(Eg, Eg / 2, tau, nu)
            sv = SteadyVisco(grid, body, body, 1000.0)
            normal, problem = sv.solve_normal(h, 6e5), sv.tangential_problem
        found = solve_for_forces(problem, normal.pressure, 0.3, -0.6 * 0.3 * 6e5, 0.0, 0.0)
        rows.append(dict(tau=tau, xi=found.xi, xi_contact=xi, approach=normal.approach, approach_contact=d,
                         p_max=float(normal.pressure.max()), p_max_contact=pmax, contact=int(normal.contact.sum()),
                         contact_contact=ncon, adhesion=int(found.steady.stick.sum()), adhesion_contact=nadh))
    return rows


def part_energy(des=(0.3, 1.0, 3.0), n=12):
    """Steady free rolling of a rigid sphere (R = 20 mm, 2 N) on E_g/E_r = 10: the rolling resistance's work per unit
    distance Fn x_c / R against the viscous power of the element states over V."""
    from rollcontact.bem.grid import Grid
    from rollcontact.bem.materials import Material
    from rollcontact.solver.visco.sls import StandardLinearSolid
    from rollcontact.solver.visco.steady import SteadyVisco, pressure_centroid
    R, F = 20.0, 2.0
    body = StandardLinearSolid(40.0, 4.0, 1.0, 0.5)
    a = (3 * F * R / (4 * 4.0 / 0.75)) ** (1 / 3)
    grid = Grid.covering(-1.5 * a, 1.5 * a, -1.3 * a, 1.3 * a, a / n, a / n)
    X, Y = grid.mesh()
    rows = []
    for de in des:
        sv = SteadyVisco(grid, Material(math.inf, 0.3), body, de * a)
        res = sv.solve_normal((X ** 2 + Y ** 2) / (2 * R), F)
        t = np.concatenate([res.pressure[None], np.zeros((2,) + grid.shape)])
        dissipated = sv.viscous_power(t) * 1e3 / (de * a)
        work = F * pressure_centroid(grid, res.pressure) / R
        rows.append(dict(De=de, work_per_mm=work, dissipated_per_mm=dissipated, ratio=dissipated / work))
    return rows


def part_transient(de=1.0, lengths=12.0, n=8):
    """A rigid sphere rolled from rest at V tau/a = de (E_g/E_r = 10, xi = 0.002) over `lengths` relaxed radii on the
    world-fixed grid (step = dx = a/n) against the steady state of the same scene (tests/cases/test_viscoelastic.py)."""
    a = 1.7784
    text = f"""
[materials]
E1 = inf
E2 = 40.0
nu2 = 0.5
visco2 = "sls"
E2_relaxed = 4.0
tau2 = 1.0
[geometry]
R = 20.0
[load]
Fn = 2.0
mu = 0.5
[rolling]
mode = "transient"
xi = 0.002
speed = {de * a}
distance = {lengths * a}
[grid]
dx = {a / n}
"""
    s = rollcontact.run(Scene.from_toml_text(text)).summary
    return dict(De=de, F_x=s["F_x"] / s["F_x_steady"] - 1.0,
                pressure_centroid_x=s["pressure_centroid_x"] / s["pressure_centroid_x_steady"] - 1.0,
                viscous_power=s["viscous_power"] / s["viscous_power_steady"] - 1.0, steps=s["steps"])


def cyclic_sweep(overrides, out, jobs, grid):
    scene = default_scene().with_overrides(grid + overrides + ['output.fields="none"', f"motion.W={0.23 * A_R}"],
                                           replaces=("motion.W",))
    report = rollcontact.sweep(scene, {"motion.angle": [0, 90], "load.ft": [FT_SD, FT_RATCHET]}, out, jobs=jobs)
    rows = []
    for r in report.rows:
        row = {k: r.get(k) for k in ("motion.angle", "load.ft", "state", "U_sd", "dU_per_period",
                                     "periods_to_shakedown", "pressure_centroid_x", "viscous_dissipation_per_period",
                                     "dissipation_per_period", "wall_time")}
        row["u_sd"] = None if r.get("U_sd") is None else r["U_sd"] / U0_R
        row["du"] = None if r.get("dU_per_period") is None else r["dU_per_period"] / U0_R
        rows.append(row)
    return rows


def part_cyclic(ratio, des, out, jobs, grid):
    """u_sd and the ratchet increment against De, both alignments, with the elastic E_r and E_g runs."""
    res = {"elastic E_r": cyclic_sweep([], out / "cyclic_Er", jobs, grid),
           "elastic E_g": cyclic_sweep([f"materials.E2={ratio * E_R}"], out / "cyclic_Eg", jobs, grid)}
    for de in des:
        res[f"{de:g}"] = cyclic_sweep(sls(ratio) + [f"motion.speed={speed(de)}"], out / f"cyclic_De{de:g}", jobs, grid)
    return res


def part_limits(ratio, des, out, jobs, grid, tol):
    """f_t,lim(w = 0.23) against De, both alignments."""
    res = {}
    cases = [("elastic E_r", [], 0.23), ("elastic E_g", [f"materials.E2={ratio * E_R}"], 0.23 * ratio ** (1 / 3))] + \
        [(f"{de:g}", sls(ratio) + [f"motion.speed={speed(de)}"], 0.23) for de in des]
    for label, over, w in cases:            # E_g: the same W = 0.23 a_r, w = W / a_g
        scene = default_scene().with_overrides(grid + over + ['output.fields="none"'])
        rep = rollcontact.limit_search(scene, {"motion.w": [w], "motion.angle": [0, 90]},
                                       out / f"limits_{label.replace(' ', '_')}", tol=tol, jobs=jobs)
        res[label] = [{k: r.get(k) for k in ("motion.angle", "lower", "upper", "midpoint", "status", "probes")}
                      for r in rep.rows]
    return res


def figures(data, out, ratio):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    paths = []
    # rolling resistance against De
    fig, ax = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    for key, col in zip(data["steady"], ("C0", "C3")):
        s, h = data["steady"][key]["sphere"], data["steady"][key]["hunter"]
        ax[0].semilogx([r["De"] for r in s], [r["xc_over_a"] for r in s], "o-", color=col,
                       label=f"sphere, E_g/E_r = {key}")
        ax[0].semilogx([r["De"] for r in h], [r["xc_over_a"] for r in h], "--", color=col,
                       label=f"Hunter's cylinder, E_g/E_r = {key}")
    ax[0].set_xlabel("De = V tau_c / a_r")
    ax[0].set_ylabel("pressure centroid x_c / a_r  (M = Fn x_c)")
    ax[0].legend(fontsize=8)
    ax[0].set_title("rolling resistance, steady free rolling", fontsize=10)
    prof = data["profiles"]
    for key in prof:
        x = np.array(prof[key]["x"]) / A_R
        p = np.array(prof[key]["p"])
        ax[1].plot(x, p, "-" if key != "elastic E_r" else "k:", label=f"De = {key}" if key[0].isdigit() else key)
    ax[1].set_xlabel("x / a_r (rolling direction)")
    ax[1].set_ylabel("p (MPa) through the lowest point")
    ax[1].legend(fontsize=8)
    ax[1].set_title(f"pressure along the rolling direction, E_g/E_r = {ratio:g}", fontsize=10)
    paths.append(out / "viscoelastic_rolling_resistance.png")
    fig.savefig(paths[-1], dpi=120)
    plt.close(fig)
    # cyclic results
    cyc = data["cyclic"]
    des = [k for k in cyc if k[0].isdigit()]
    x = [float(k) for k in des]
    fig, ax = plt.subplots(1, 3, figsize=(15, 4), layout="constrained")
    for angle, col, mark in ((0, "C0", "o"), (90, "C3", "^")):
        def pick(rows, ft, key):
            for r in rows:
                if r["motion.angle"] == angle and abs(r["load.ft"] - ft) < 1e-9:
                    return r.get(key)
        for k, (ft, key, axis) in enumerate(((FT_SD, "u_sd", ax[0]), (FT_RATCHET, "du", ax[1]))):
            y = [pick(cyc[d], ft, key) for d in des]
            axis.semilogx(x, [np.nan if v is None else v for v in y], mark + "-", color=col,
                          label=f"{'W || Ft' if angle == 0 else 'W perp Ft'}")
            for label, ls in (("elastic E_r", ":"), ("elastic E_g", "--")):
                v = pick(cyc[label], ft, key)
                if v is not None:
                    axis.axhline(v, color=col, ls=ls, lw=0.8)
        y = [pick(cyc[d], FT_SD, "viscous_dissipation_per_period") for d in des]
        ax[2].semilogx(x, [np.nan if v is None else v for v in y], mark + "-", color=col,
                       label=f"{'W || Ft' if angle == 0 else 'W perp Ft'}")
    ax[0].set_ylabel(f"u_sd = U_sd / U0(E_r)  (f_t = {FT_SD})")
    ax[1].set_ylabel(f"du = dU / U0(E_r) per period  (f_t = {FT_RATCHET})")
    ax[2].set_ylabel(f"viscous work per period (N mm, f_t = {FT_SD})")
    for a_ in ax:
        a_.set_xlabel("De = V tau_c / a_r")
        a_.legend(fontsize=8)
    ax[0].set_title("dotted: elastic E_r, dashed: elastic E_g", fontsize=9)
    paths.append(out / "viscoelastic_cyclic.png")
    fig.savefig(paths[-1], dpi=120)
    plt.close(fig)
    if data.get("limits"):
        lim = data["limits"]
        fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
        des = [k for k in lim if k[0].isdigit()]
        for angle, col, mark in ((0, "C0", "o"), (90, "C3", "^")):
            mids = [next((r["midpoint"] for r in lim[d] if r["motion.angle"] == angle), np.nan) for d in des]
            ax.semilogx([float(d) for d in des], mids, mark + "-", color=col,
                        label=f"{'W || Ft' if angle == 0 else 'W perp Ft'}")
        for label, ls in (("elastic E_r", ":"), ("elastic E_g", "--")):
            v = lim[label][0]["midpoint"]
            ax.axhline(v, color="k", ls=ls, lw=0.8, label=label)
        ax.set_xlabel("De = V tau_c / a_r")
        ax.set_ylabel("f_t,lim (W = 0.23 a_r)")
        ax.legend(fontsize=8)
        paths.append(out / "viscoelastic_limits.png")
        fig.savefig(paths[-1], dpi=120)
        plt.close(fig)
    return paths


def tables(data, ratio):
    lines = ["Hunter's cylinder against the steady boundary elements (plane strain, E_g/E_r = 10):", "",
             "| n per a_r | V tau/a_r | centroid | interior pressure | peak |", "|---|---|---|---|---|"]
    for r in data["hunter"]:
        lines.append(f"| {r['n']} | {r['De']:g} | {100 * r['centroid']:+.3f} % | {100 * r['interior']:.2f} % | "
                     f"{100 * r['peak']:+.2f} % |")
    lines += ["", "CONTACT's visc_cylindr (reference output in parentheses):", "",
              "| tau_c (s) | xi | approach (mm) | p_max (MPa) | contact / adhesion cells |", "|---|---|---|---|---|"]
    for r in data["contact"]:
        lines.append(f"| {r['tau']:g} | {r['xi']:.4e} ({r['xi_contact']:.4e}, {100 * (r['xi'] / r['xi_contact'] - 1):+.2f} %)"
                     f" | {r['approach']:.5f} ({r['approach_contact']:.5f}) | {r['p_max']:.2f} ({r['p_max_contact']:.2f}) |"
                     f" {r['contact']} / {r['adhesion']} ({r['contact_contact']} / {r['adhesion_contact']}) |")
    lines += ["", "Energy, steady free rolling (rigid sphere, E_g/E_r = 10, a/dx = 12):", "",
              "| V tau/a | Fn x_c / R (N) | viscous work per mm (N) | ratio |", "|---|---|---|---|"]
    for r in data["energy"]:
        lines.append(f"| {r['De']:g} | {r['work_per_mm']:.6g} | {r['dissipated_per_mm']:.6g} | {r['ratio']:.5f} |")
    t = data["transient"]
    lines += ["", f"Transient from rest against steady (V tau/a = {t['De']:g}, {t['steps']} steps): F_x "
              f"{100 * t['F_x']:+.3f} %, pressure_centroid_x {100 * t['pressure_centroid_x']:+.2e} %, viscous power "
              f"{100 * t['viscous_power']:+.2e} %", ""]
    lines += [f"E_g/E_r = {ratio:g}, tau_c = {TAU} s, E_r = {E_R} MPa; De = V tau_c / a_r, a_r = {A_R} mm", ""]
    lines += ["Steady free rolling of the sphere:", "", "| De | x_c/a_r | mu_r = M/(Fn R) | viscous power (W) |",
              "|---|---|---|---|"]
    for r in data["steady"][str(ratio)]["sphere"]:
        lines.append(f"| {r['De']:.3g} | {r['xc_over_a']:.4f} | {r['mu_r']:.3e} | {r['viscous_power']:.3e} |")
    lines += ["", f"Oscillating paper scene (W = 0.23 a_r, {CYCLIC_PERIODS} periods; u = U / U0(E_r)):", "",
              f"| case | angle | u_sd (f_t {FT_SD}) | state | du (f_t {FT_RATCHET}) | state | viscous work/period (N mm) |",
              "|---|---|---|---|---|---|---|"]
    for key, rows in data["cyclic"].items():
        for angle in (0, 90):
            a = next(r for r in rows if r["motion.angle"] == angle and abs(r["load.ft"] - FT_SD) < 1e-9)
            b = next(r for r in rows if r["motion.angle"] == angle and abs(r["load.ft"] - FT_RATCHET) < 1e-9)
            fmt = (lambda v: "-" if v is None else f"{v:.4g}")
            lines.append(f"| {key} | {angle} | {fmt(a['u_sd'])} | {a['state']} | {fmt(b['du'])} | {b['state']} | "
                         f"{fmt(a['viscous_dissipation_per_period'])} |")
    if data.get("limits"):
        lines += ["", "Shakedown limit f_t,lim(W = 0.23 a_r):", "", "| case | angle | bracket |", "|---|---|---|"]
        for key, rows in data["limits"].items():
            for r in rows:
                lines.append(f"| {key} | {r['motion.angle']} | [{r['lower']:.4f}, {r['upper']:.4f}] |"
                             if r.get("lower") is not None else f"| {key} | {r['motion.angle']} | {r['status']} |")
    if data.get("cylinder"):
        lines += ["", "Mid-length of a long cylinder against Hunter's plane strain (De at the line contact):", "",
                  "| length / a | line load at mid-length / nominal | x_c (mm) | Hunter x_c (mm) | difference |",
                  "|---|---|---|---|---|"]
        for r in data["cylinder"]["rows"]:
            lines.append(f"| {r['length_over_a']:g} | {r['line_load'] / r['line_load_nominal']:.4f} | {r['xc']:.5f} | "
                         f"{r['xc_hunter']:.5f} | {100 * r['difference']:+.2f} % |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("-o", "--output", default="results/viscoelastic_study")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--ratio", type=float, default=2.0, help="E_g / E_r of the substrate (default 2)")
    ap.add_argument("--jobs", type=int, default=2)
    args = ap.parse_args()
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    work = out / "runs"
    t0, c0 = time.time(), time.process_time()
    quick = args.quick
    grid = ["grid.dx=0.8", "grid.dy=0.8", "motion.dW=0.8", "motion.periods=6"] if quick else \
        ["grid.dx=0.4", "grid.dy=0.4", "motion.dW=0.4"]
    des_steady = [0.1, 1.0, 10.0] if quick else list(np.geomspace(0.01, 100, 13))
    data = {"ratio": args.ratio, "tau": TAU, "E_r": E_R, "a_r": A_R}
    data["hunter"] = part_hunter((20,) if quick else (20, 40, 80))
    data["contact"] = part_contact()
    data["energy"] = part_energy()
    data["transient"] = part_transient()
    print("validation done", time.time() - t0, flush=True)
    data["steady"] = part_steady([args.ratio] if quick else [args.ratio, 10.0], des_steady, 0.8 if quick else 0.4)
    print("steady done", time.time() - t0, flush=True)
    data["profiles"] = part_profiles(args.ratio, [0.1, 1.0] if quick else [0.1, 0.3, 1.0, 3.0, 10.0], 0.4)
    data["cylinder"] = part_cylinder(args.ratio, 1.0, [4] if quick else [4, 8, 16], None)
    print("cylinder done", time.time() - t0, flush=True)
    des = [0.1, 1.0, 10.0] if quick else [0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0]
    data["cyclic"] = part_cyclic(args.ratio, des, work, args.jobs,
                                 grid + ([] if quick else [f"motion.periods={CYCLIC_PERIODS}"]))
    print("cyclic done", time.time() - t0, flush=True)
    data["limits"] = part_limits(args.ratio, [1.0] if quick else [0.1, 0.3, 1.0, 3.0, 10.0], work, args.jobs, grid,
                                 0.05 if quick else 0.01)
    data["wall_time"], data["cpu_time_main"] = time.time() - t0, time.process_time() - c0
    data["load"] = os.getloadavg()
    (out / "viscoelastic_study.json").write_text(json.dumps(data, indent=1, default=float))
    (out / "viscoelastic_study.md").write_text(tables(data, args.ratio))
    for p in figures(data, out, args.ratio):
        print("written", p)
    print(f"written {out / 'viscoelastic_study.json'}, {out / 'viscoelastic_study.md'} in {data['wall_time']:.0f} s")


if __name__ == "__main__":
    main()

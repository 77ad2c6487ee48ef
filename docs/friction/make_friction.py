"""The tables and figures of docs/friction.md: one command.

    .venv/bin/python docs/friction/make_friction.py [-o DIR] [--quick] [--part validation contact study] [--jobs N]

Writes into DIR (default results/friction/; the committed figures: -o docs/friction/figures) and prints the tables:

* validation: the friction laws and the memory relaxation (laws.png); the moving square heat source against the
  classical solution at Peclet numbers 0.1-100 and the blend of its limits in the form of Tian & Kennedy
  (jaeger_square.csv); the heat balance of steady full sliding (heat_balance.csv).
* contact: the reference program's examples ertz_temperature (cases 1-4) and veldep_fric (the steady state, then
  rolled from rest) posed in rollcontact (docs/friction/*.toml) against the figures of their ref_out files
  (contact_examples.csv, veldep_transient.png).
* study: the seed's scene (perpendicular rolling, 10 periods, dW = 0.2 mm) on a coarse grid, dx = 0.4 mm (12
  elements per contact radius against the page's default 0.2 mm: the study compares laws on one grid), at
  motion.speed = V = 10 mm/s with mu_static = 0.93 and the exponential law mu_kin = 0.62, mu_1 = 0.31 (mu(s) = 0.62 +
  0.31 2^(-s/s_1)): the shakedown limit f_t,lim(w) = Ft,lim/(mu_static Fn) at w = 0.1, 0.23, 0.35, 0.5, 0.7 by
  bisection to 0.02, for s_1 / V = 1, 0.1, 0.03, 0.01, with friction memory (d_c = 0.02 and 0.2 mm at s_1 / V
  = 0.01), and with Coulomb's law at mu_static and at mu_kin (limits.csv, study_limits.png; the probe runs under
  --runs). About 25 min on 2 loaded cores at --jobs 2; --quick: one w, tol 0.05, 3 periods (the docs test).
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
V = 10.0                                   # mm/s, the study's rolling speed
STUDY_GRID = {"grid.dx": 0.4}              # the study's coarse grid (module docstring)
MU_STATIC, MU_KIN = 0.93, 0.62


# ------------------------------------------------------------------------------------------------ validation
def validation(out: Path, quick: bool) -> dict:
    from rollcontact.solver.friction import FrictionLaw, FrictionMemory
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    s = np.linspace(0.0, 60.0, 601)
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
    for kind, style in (("linear", "-"), ("rational", "--"), ("exponential", "-.")):
        law = FrictionLaw(kind, mu_kin=0.62, mu_1=0.31, s_1=10.0)
        axes[0].plot(s, law.coefficient(s), style, label=kind)
    axes[0].set(xlabel="slip velocity s (mm/s)", ylabel="mu(s)", title="laws: mu_kin 0.62, mu_1 0.31, s_1 10 mm/s")
    axes[0].legend()
    law = FrictionLaw("exponential", mu_kin=0.62, mu_1=0.31, s_1=10.0)
    memory = FrictionMemory(distance=0.2)
    dt, mu, t, trace = 0.01, MU_STATIC, [0.0], [MU_STATIC]
    for k in range(200):
        v = 2.0 if k < 100 else 40.0
        mu = float(memory.step(mu, law.coefficient(v), v, dt))
        t.append((k + 1) * dt)
        trace.append(mu)
    axes[1].plot(t, trace, label="memory d_c = 0.2 mm")
    axes[1].plot(t, [float(law.coefficient(2.0 if x <= 1.0 else 40.0)) for x in t], ":", label="instantaneous")
    axes[1].set(xlabel="t (s)", ylabel="local mu", title="slip velocity 2 then 40 mm/s")
    axes[1].legend()
    fig.savefig(out / "laws.png", dpi=110)
    plt.close(fig)
    rows = jaeger_square(quick)
    _write_csv(out / "jaeger_square.csv", rows)
    balance = heat_balance(quick)
    _write_csv(out / "heat_balance.csv", balance)
    curves = creep_curves(out, quick)
    against = steady_against_transient(quick)
    _write_csv(out / "steady_transient.csv", against)
    return {"jaeger_square": rows, "heat_balance": balance, "creep_curves": curves, "steady_transient": against}


def creep_curves(out: Path, quick: bool) -> dict:
    """Steady creep-force curves on the Hertzian ellipse of tests/solver/test_friction_steady.py (41 elements
    across, V = 30 m/s): Coulomb at mu = 0.3, the exponential law 0.15 + 0.15 2^(-s/100 mm/s) without and with memory
    (d_c = 0.05 mm); the figure falling_creep_curve.png."""
    from rollcontact.bem import MaterialPair
    from rollcontact.solver.creep import (SteadyParams, SteadyRolling, creep_curve, ellipse_grid, hertz_pressure,
                                          kalker_coefficients, saturation_creepage)
    from rollcontact.solver.friction import (FrictionLaw, FrictionMemory, FrictionParams, LocalFriction,
                                             solve_steady_friction)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    a, b, fn, nu, speed = 6.0, 4.0, 50e3, 0.28, 30000.0
    pair = MaterialPair.from_moduli(210e3, nu, 210e3, nu)
    grid = ellipse_grid(a, b, 31 if quick else 41)
    p, problem = hertz_pressure(grid, a, b, fn), SteadyRolling(grid, pair)
    xs = saturation_creepage(pair.G, math.sqrt(a * b), kalker_coefficients(a / b, nu)[0], 0.3, fn)
    fractions = np.geomspace(0.02, 8.0, 12 if quick else 24)
    creep = np.zeros((len(fractions), 3))
    creep[:, 0] = fractions * xs
    params = SteadyParams(tol=1e-8)
    law = FrictionLaw("exponential", mu_kin=0.15, mu_1=0.15, s_1=100.0)
    out_curves = {"fractions": fractions.tolist(),
                  "coulomb": (-creep_curve(problem, p, 0.3, creep, params=params).force[:, 0] / (0.3 * fn)).tolist()}
    for name, memory in (("law", FrictionMemory()), ("law, d_c = 0.05 mm", FrictionMemory(0.05))):
        friction = LocalFriction(law, memory, speed=speed, params=FrictionParams(tol=1e-8))
        states = []

        def solve(problem, pressure, mu, xi, eta, phi, *, initial=None, params=None):
            res = solve_steady_friction(problem, pressure, friction, xi, eta, phi, initial=initial, params=params,
                                        mu_initial=states[-1] if states else None)
            states.append(res.friction.mu)
            return res
        out_curves[name] = (-creep_curve(problem, p, 0.3, creep, params=params, solve=solve).force[:, 0]
                            / (0.3 * fn)).tolist()
    fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
    for name, style in (("coulomb", "k-"), ("law", "o-"), ("law, d_c = 0.05 mm", "s-")):
        ax.plot(fractions, out_curves[name], style, ms=3, label={"coulomb": "Coulomb, mu = 0.3"}.get(name, name))
    ax.axhline(0.5, color="C3", ls="-.", lw=0.8, label="mu_kin Fn")
    ax.set(xscale="log", xlabel="xi / xi* (xi* = mu_static Fn / (G c^2 C11))", ylabel="F_x / (mu_static Fn)",
           title="steady creep-force curves, exponential law 0.15 + 0.15 2^(-s/100 mm/s), V = 30 m/s")
    ax.title.set_fontsize(9)
    ax.legend(fontsize=8)
    fig.savefig(out / "falling_creep_curve.png", dpi=110)
    plt.close(fig)
    k = int(np.argmax(out_curves["law"]))
    out_curves.update(peak_fraction=float(fractions[k]), peak=float(out_curves["law"][k]))
    return out_curves


def steady_against_transient(quick: bool) -> list:
    """A sphere (R = 300 mm, steel, Fn = 20 kN, dx = 0.4 mm) rolled at V = 30 m/s from rest over 4 contact lengths
    (mode 'transient', step dx) against its steady state, with the exponential law of creep_curves: in partial slip
    with memory, in full sliding beyond the peak without, and in partial slip without memory (where the transient
    does not settle)."""
    import rollcontact
    base = {"materials.E1": 210e3, "materials.nu1": 0.28, "materials.E2": 210e3, "materials.nu2": 0.28,
            "load.Fn": 20e3, "rolling.speed": 30000.0, "grid.dx": 0.4, "friction.law": "exponential",
            "friction.mu_kin": 0.15, "friction.mu_1": 0.15, "friction.s_1": 100.0}
    cases = [("partial slip, d_c = 5 um", {"rolling.xi": 0.003, "friction.memory_distance": 0.005}),
             ("full sliding, instantaneous", {"rolling.xi": 0.01})]
    if not quick:
        cases.append(("partial slip, instantaneous", {"rolling.xi": 0.003}))
    rows = []
    for name, over in cases:
        scene = rollcontact.Scene.from_toml_text('[geometry]\nR = 300.0\n[rolling]\nmode = "steady"\n',
                                                 name="sphere").with_overrides({**base, **over})
        steady = rollcontact.run(scene)
        transient = rollcontact.run(scene.with_overrides({"rolling.mode": "transient"}))
        fx = np.asarray(transient.history["F_x"])
        last = fx[-20:]                   # the force on the substrate: -F_x on the sphere
        rows.append(dict(case=name, xi=over["rolling.xi"], F_x_steady=-steady.summary["F_x"],
                         F_x_transient=-transient.summary["F_x"],
                         relative_difference=transient.summary["F_x"] / steady.summary["F_x"] - 1,
                         last_20_steps_min=float(last.min()), last_20_steps_max=float(last.max()),
                         solves_per_step=float(np.mean(transient.history["friction_iterations"])),
                         friction_feedback=steady.summary.get("friction_feedback")))
    return rows


def jaeger_square(quick: bool) -> list:
    """Max and mean rise (q a / k) of a uniform flux on the square |x|, |y| <= a moving at Peclet number Pe = V a/(2
    kappa): Jaeger's time integral (bem.heat.element_response of the square), the grid (n x n elements across), and
    the blend 2/sqrt(pi (c0 + Pe)) (max), 4/(3 sqrt(pi (c1 + Pe))) (mean) of the two exact limits in the form of Tian
    & Kennedy (c0, c1 fitted to the stationary values 1.1222 and 0.9464)."""
    from scipy.optimize import minimize_scalar
    from rollcontact.bem import Grid
    from rollcontact.bem.heat import MovingHeatSource, ThermalBody, element_response
    n = 21 if quick else 41
    stat_max = 4 * math.log(1 + math.sqrt(2)) / math.pi
    t, w = np.polynomial.legendre.leggauss(64)
    t, w = 0.5 * (t + 1), 0.5 * w
    xg, wx = 1 - 2 * t ** 2, 4 * t * w
    yg, wy = np.polynomial.legendre.leggauss(64)
    stat_mean = float(np.sum(wy[:, None] * wx[None, :] * element_response(xg[None, :], yg[:, None], 1, 1, 0.0))) / 4
    c0 = (2 / stat_max) ** 2 / math.pi
    c1 = ((4 / 3) / stat_mean) ** 2 / math.pi
    rows = []
    for pe in (0.1, 1.0, 10.0, 100.0):
        res = minimize_scalar(lambda x: -float(element_response(x, 0.0, 1.0, 1.0, pe)), bounds=(-1 + 1e-9, 1 - 1e-9),
                              method="bounded", options={"xatol": 1e-10})
        peak = -res.fun
        mean = float(np.sum(wy[:, None] * wx[None, :] * element_response(xg[None, :], yg[:, None], 1, 1, pe))) / 4
        dx = 2.0 / n
        grid = Grid(n + 12, n + 12, dx, dx, -(n + 11) // 2, -(n + 11) // 2)
        X, Y = grid.mesh()
        inside = (np.abs(X) < 1 - dx / 4) & (np.abs(Y) < 1 - dx / 4)
        T = MovingHeatSource(grid, ThermalBody(1.0, 1.0), 2.0 * pe).temperature(np.where(inside, 1.0, 0.0))
        blend_max, blend_mean = 2 / math.sqrt(math.pi * (c0 + pe)), 4 / (3 * math.sqrt(math.pi * (c1 + pe)))
        rows.append(dict(Pe=pe, max_exact=peak, mean_exact=mean, max_grid=float(T[inside].max()),
                         mean_grid=float(T[inside].mean()), grid_max_error=float(T[inside].max()) / peak - 1,
                         grid_mean_error=float(T[inside].mean()) / mean - 1, blend_max=blend_max,
                         blend_mean=blend_mean, blend_max_error=blend_max / peak - 1,
                         blend_mean_error=blend_mean / mean - 1, elements_across=n, c0=c0, c1=c1))
    return rows


def heat_balance(quick: bool) -> list:
    """Steady full sliding of a steel wheel on a bronze-like roller (solver.friction.thermal): heat entering the two
    bodies against the power of the creep force -V F_x xi, at 6 and 20 times the saturation creepage."""
    from rollcontact.bem import MaterialPair
    from rollcontact.bem.heat import ThermalBody
    from rollcontact.solver.creep import (SteadyParams, SteadyRolling, ellipse_grid, hertz_pressure,
                                          kalker_coefficients, saturation_creepage)
    from rollcontact.solver.friction import ContactTemperature, FrictionLaw, LocalFriction, solve_steady_friction
    a, b, fn, nu, speed = 6.0, 4.0, 50e3, 0.28, 30000.0
    pair = MaterialPair.from_moduli(210e3, nu, 210e3, nu)
    rows = []
    for n in ((31,) if quick else (31, 61)):
        grid = ellipse_grid(a, b, n)
        problem, p = SteadyRolling(grid, pair), hertz_pressure(grid, a, b, fn)
        thermal = ContactTemperature(grid, ThermalBody.from_si(50, 7850, 450), ThermalBody.from_si(120, 8800, 380),
                                     speed, 20.0, 20.0)
        friction = LocalFriction(FrictionLaw("coulomb", mu=0.3), speed=speed, thermal=thermal)
        for factor in (6.0, 20.0):
            xi = factor * saturation_creepage(pair.G, math.sqrt(a * b), kalker_coefficients(a / b, nu)[0], 0.3, fn)
            res = solve_steady_friction(problem, p, friction, xi, params=SteadyParams(tol=1e-9))
            temps = res.friction.temperatures
            heat = float((temps.q1 + temps.q2).sum()) * grid.cell_area
            creep_power = -speed * res.force[0] * xi * 1e-3
            rows.append(dict(elements_across=n, creepage_over_saturation=factor, heat_into_bodies_W=heat,
                             frictional_power_W=res.friction.power, creep_force_power_W=creep_power,
                             relative_difference=heat / creep_power - 1,
                             share_body1=float(temps.q1.sum() / (temps.q1 + temps.q2).sum()),
                             blok_share_body1=thermal.blok_share, T_max=float(temps.T1.max())))
    return rows


# ------------------------------------------------------------------------------------------------ CONTACT
#: The reference program's printed figures (examples/ertz_temperature.ref_out, veldep_fric.ref_out).
ERTZ_REF = {1: dict(Fx_over_muFn=1.0, fric_power_W=2.994e4, T_max=166.8, p_max=770.6, contact_elements=1969),
            2: dict(Fx_over_muFn=0.0, fric_power_W=0.0, T_max=75.00),
            3: dict(Fx_over_muFn=1.0, fric_power_W=2.994e4, T_max=241.8),
            4: dict(Fx_over_muFn=0.7274, Fy_over_muFn=-0.1492, M_z=-4.626e4, fric_power_W=1672.0, T_max=90.85, stick=770,
                    slip=1199)}
VELDEP_REF = dict(steady_Fx_over_muFn=0.5941, steady_stick=45, steady_slip=36, p_max=495.3,
                  transient_range=(0.5702, 0.5882))


def contact(out: Path, quick: bool) -> dict:
    import rollcontact
    rows = []
    ertz = rollcontact.load_scene(HERE / "ertz_temperature.toml")
    cases = {1: {}, 2: {"rolling.xi": 0.0, "thermal.T_bulk2": 150.0}, 3: {"thermal.T_bulk2": 150.0},
             4: {"rolling.xi": 0.002, "rolling.eta": -0.001, "rolling.phi": 0.0002, "thermal.T_bulk2": 150.0}}
    for case, over in cases.items():
        if quick and case in (3, 4):
            continue
        res = rollcontact.run(ertz.with_overrides(over) if over else ertz)
        s, f = res.summary, res.fields
        p, T1, T2 = f["p"][0], f["T1"][0], f["T2"][0]
        contact_max = float(max(T1[p > 0].max(), T2[p > 0].max()))
        ref = ERTZ_REF[case]
        rows.append(dict(example="ertz_temperature", case=case, F_over_muFn=math.hypot(s["F_x"], s["F_y"]) / s["mu_Fn"],
                         # in the example's frame (rolling along -x): -F
                         Fx_over_muFn=-s["F_x"] / s["mu_Fn"], Fy_over_muFn=-s["F_y"] / s["mu_Fn"], M_z=s["M_z"],
                         frictional_power_W=s["frictional_power"], T_max_contact=contact_max,
                         T_max_ref=ref["T_max"], T_difference=contact_max - ref["T_max"],
                         stick_cells=int((f["region"][0] == 1).sum()), slip_cells=int((f["region"][0] == 2).sum()),
                         p_max=float(p.max()), contact_cells=int((p > 0).sum()), ref=json.dumps(ref),
                         **ertz_one_dimensional(res) if case == 1 else {}))
    steady, transient = veldep(quick)
    x, fx = transient.pop("distance"), transient.pop("history")
    rows += [steady, transient]
    _write_csv(out / "contact_examples.csv", rows)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 3.6), layout="constrained")
    ax.plot(x, fx, ".-", ms=3, label="rollcontact, transient from rest (instantaneous law)")
    ax.axhline(steady["Fx_over_muFn"], color="C1", label="rollcontact, steady state")
    ax.axhline(VELDEP_REF["steady_Fx_over_muFn"], color="C2", ls="--", label="CONTACT steady (ref_out)")
    ax.axhspan(*VELDEP_REF["transient_range"], color="C2", alpha=0.15, label="CONTACT time steps (ref_out)")
    ax.set(xlabel="rolled distance (mm)", ylabel="F_x / (mu_static Fn)", title="veldep_fric: 2-D rolling, 45 m/s")
    ax.legend(fontsize=8)
    fig.savefig(out / "veldep_transient.png", dpi=110)
    plt.close(fig)
    return {"contact_examples": rows}


def ertz_one_dimensional(res) -> dict:
    """Case 1 by Jaeger's 1-D solution along each row (Ertz & Knothe's high-speed model, the reference program's):
    T = T_bulk + 1/(e sqrt(pi V)) sum_j q_j/2 int 1/sqrt(x' - x) dx' over the cells upstream (e = sqrt(k rho c_p), q/2
    into each of the equal bodies), with the cell of the point itself counted once (its own half, 2 sqrt(dx/2)) and
    counted twice: the largest temperatures of the two sums."""
    f = res.fields
    q = np.hypot(f["tau_x"][0], f["tau_y"][0]) * f["slip_velocity"][0] * 1e-3           # W/mm^2
    dx = float(res.x[1] - res.x[0])
    h, k, kappa, speed = dx / 2, 50e-3, 50.0 / (7850.0 * 450.0) * 1e6, 30000.0
    fact = 0.5 / (k / math.sqrt(kappa) * math.sqrt(math.pi * speed))
    d = np.arange(1, q.shape[1]) * dx
    weights = 2 * (np.sqrt(d + h) - np.sqrt(d - h))                       # upstream cell j at distance d
    out = {}
    for name, own in (("T_max_1d_own_once", 1.0), ("T_max_1d_own_twice", 2.0)):
        best = 0.0
        for row in q:
            T = own * 2 * math.sqrt(h) * row
            for i in range(len(row) - 1):
                T[i] += np.dot(weights[: len(row) - 1 - i], row[i + 1:])
            best = max(best, float(T.max()) * fact)
        out[name] = best
    return out


def veldep(quick: bool):
    """veldep_fric at the solver level: CONTACT's own grid, one row of elements 0.1 x 200 mm (the scene's resolution
    rule asks for 3 elements per semi-axis, which the row does not have), the profile x^2/(2 R) on it and no contact
    in the rows beside it; the steady state (solver.friction.solve_steady_friction) and the transient rolled from
    rest on the world-fixed grid (solver.creep.roll_world), both with the instantaneous exponential law."""
    from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
    from rollcontact.solver.creep import SteadyParams, SteadyRolling, roll_world
    from rollcontact.solver.friction import FrictionLaw, FrictionParams, LocalFriction, solve_steady_friction
    from rollcontact.solver.normal import NormalParams, solve_normal
    from rollcontact.solver.rolling import FunctionProfile, StepParams
    from rollcontact.solver.tangential import TangentialParams
    R, FN, XI, SPEED, MU = 460.0, 622216.0, -0.0009999, 45000.0, 0.3
    pair = MaterialPair.from_moduli(209920.0, 0.28, 209920.0, 0.28)
    friction = LocalFriction(FrictionLaw("exponential", mu_kin=0.18, mu_1=0.12, s_1=100.0), speed=SPEED,
                             params=FrictionParams(tol=1e-9))
    profile = FunctionProfile(lambda x, y: x ** 2 / (2 * R) + np.where(np.abs(y) > 100.0, 10.0, 0.0))
    grid = Grid.covering(-4.7, 4.7, -300.0, 300.0, 0.1, 200.0)
    op = HalfSpaceOperator(grid, pair)
    X, Y = grid.mesh()
    p = solve_normal(op, profile(X, Y, (0.0, 0.0)), force=FN, params=NormalParams(tol=1e-9)).pressure
    res = solve_steady_friction(SteadyRolling(grid, pair, operator=op), p, friction, XI, params=SteadyParams(tol=1e-9))
    steady = dict(example="veldep_fric", case="steady", Fx_over_muFn=res.force[0] / (MU * FN),
                  stick_cells=int(res.stick.sum()), slip_cells=int((res.contact & ~res.stick).sum()),
                  p_max=float(p.max()), contact_cells=int((p > 0).sum()), friction_feedback=res.friction.feedback,
                  ref=json.dumps(VELDEP_REF))
    distance = 16.0 if quick else 120.0
    world = Grid.covering(-4.9, distance + 4.9, -300.0, 300.0, 0.1, 200.0)
    fx, x, solves = [], [], []
    for rec in roll_world(HalfSpaceOperator(world, pair), profile, Fn=FN, mu=MU, distance=distance, step=0.1, xi=XI,
                          params=StepParams(tangential=TangentialParams(tol=1e-9)), friction=friction):
        fx.append(rec.force[0] / (MU * FN))
        x.append(rec.centre)
        solves.append(rec.friction.iterations)
    fx = np.array(fx)
    tail = fx[int(0.75 * len(fx)):]
    drops = np.nonzero(np.diff(tail) < -0.5 * (tail.max() - tail.min()))[0]     # the sawtooth's falls
    period = float(np.median(np.diff(drops))) if len(drops) > 2 else None
    transient = dict(example="veldep_fric", case="transient from rest", Fx_over_muFn=float(tail.mean()),
                     Fx_min=float(tail.min()), Fx_max=float(tail.max()), steps=len(fx) - 1,
                     sawtooth_period_steps=period,
                     shift_of_mean=float(tail.mean()) - 0.5 * sum(VELDEP_REF["transient_range"]),
                     solves_per_step=float(np.mean(solves)), ref=json.dumps(VELDEP_REF), distance=np.array(x),
                     history=fx)
    return steady, transient


# ------------------------------------------------------------------------------------------------ study
def study_configurations(quick: bool) -> dict:
    """name -> (overrides of the paper scene, factor converting its f_t into units of mu_static Fn)."""
    law = {**STUDY_GRID, "motion.speed": V, "friction.law": "exponential", "friction.mu_kin": MU_KIN, "friction.mu_1": MU_STATIC - MU_KIN}
    configs = {"coulomb mu_static": ({**STUDY_GRID}, 1.0),
               "coulomb mu_kin": ({**STUDY_GRID, "load.mu": MU_KIN}, MU_KIN / MU_STATIC)}
    ratios = (1.0, 0.01) if quick else (1.0, 0.1, 0.03, 0.01)
    for r in ratios:
        configs[f"law s_1/V = {r:g}"] = ({**law, "friction.s_1": r * V}, 1.0)
    if not quick:
        for d in (0.02, 0.2):
            configs[f"law s_1/V = 0.01, d_c = {d:g} mm"] = ({**law, "friction.s_1": 0.01 * V,
                                                            "friction.memory_distance": d}, 1.0)
    return configs


def study(out: Path, quick: bool, jobs: int, runs: Path, only=None) -> dict:
    import rollcontact
    ws = [0.23] if quick else [0.1, 0.23, 0.35, 0.5, 0.7]
    tol = 0.05 if quick else 0.02
    rows = []
    for name, (over, factor) in study_configurations(quick).items():
        if only and not any(part in name for part in only):
            continue
        over = dict(over)
        if quick:
            over["motion.periods"] = 3
        scene = rollcontact.load_scene(overrides=over or None)
        folder = runs / name.replace(" ", "_").replace("/", "").replace(",", "").replace("=", "")
        t0 = time.time()
        report = rollcontact.limit_search(scene, {"motion.w": ws}, folder, tol=tol, jobs=jobs)   # resumes a rerun
        for row in report.rows:
            lo, hi = row.get("lower"), row.get("upper")
            rows.append(dict(configuration=name, w=row["w"], lower=None if lo is None else lo * factor,
                             upper=None if hi is None else hi * factor,
                             f_t_lim=None if row.get("midpoint") is None else row["midpoint"] * factor,
                             status=row["status"], error=row.get("error", ""), probes=row.get("probes"),
                             wall_s=time.time() - t0, mdr_kappa_1=row.get("mdr_kappa=1")))
        print(f"  {name}: {[(r['w'], r['f_t_lim'], r['status']) for r in rows if r['configuration'] == name]}",
              flush=True)
    _write_csv(out / "limits.csv", rows)
    study_figure(out, rows)
    return {"limits": rows}


def study_figure(out: Path, rows: list):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.2), layout="constrained")
    names = list(dict.fromkeys(r["configuration"] for r in rows))
    for k, name in enumerate(names):
        pts = [(r["w"], r["f_t_lim"]) for r in rows if r["configuration"] == name and r["f_t_lim"] is not None]
        if pts:
            w, f = zip(*pts)
            style = "k-" if name == "coulomb mu_static" else ("k--" if name == "coulomb mu_kin" else "o-")
            ax.plot(w, f, style, label=name, ms=4)
    ax.set(xlabel="w = W/a", ylabel="f_t,lim = Ft,lim / (mu_static Fn)",
           title=f"shakedown limit (dx = 0.4 mm), exponential law mu(s) = {MU_KIN} + {MU_STATIC - MU_KIN:.2f} "
                 f"2^(-s/s_1), V = {V:g} mm/s")
    ax.title.set_fontsize(9)
    ax.legend(fontsize=7)
    fig.savefig(out / "study_limits.png", dpi=110)
    plt.close(fig)


STUDY_COLUMNS = [("coulomb mu_static", "Coulomb mu_static"), ("coulomb mu_kin", "Coulomb mu_kin"),
                 ("law s_1/V = 1", "1"), ("law s_1/V = 0.1", "0.1"), ("law s_1/V = 0.03", "0.03"),
                 ("law s_1/V = 0.01", "0.01"),
                 ("law s_1/V = 0.01, d_c = 0.02 mm", "0.01, d_c 0.02 mm"),
                 ("law s_1/V = 0.01, d_c = 0.2 mm", "0.01, d_c 0.2 mm")]


def page_tables(out: Path) -> str:
    """The tables and numbers of docs/friction.md from the files the parts wrote into `out` (those present), as
    Markdown; written to out/tables.md."""
    text = []
    v = out / "friction_validation.json"
    if v.exists():
        val = json.loads(v.read_text())
        c = val["creep_curves"]
        text.append(f"falling creep curve: peak {c['peak']:.3f} mu_static Fn at {c['peak_fraction']:.2f} xi*; "
                    f"last point ({c['fractions'][-1]:.3g} xi*) {c['law'][-1]:.3f}, with memory "
                    f"{c['law, d_c = 0.05 mm'][-1]:.3f}; Coulomb's there {c['coulomb'][-1]:.3f}\n")
    c = out / "contact_examples.csv"
    if c.exists():
        with open(c) as fh:
            rows = {(r["example"], r["case"]): r for r in csv.DictReader(fh)}
        st, tr = rows[("veldep_fric", "steady")], rows[("veldep_fric", "transient from rest")]
        ref = VELDEP_REF
        text += ["| veldep_fric | F_x / (mu_static Fn) | stick / slip elements | p_max MPa |", "|---|---|---|---|",
                 f"| steady, reference program | {ref['steady_Fx_over_muFn']:.4f} | {ref['steady_stick']} / "
                 f"{ref['steady_slip']} | {ref['p_max']} |",
                 f"| steady, rollcontact | {float(st['Fx_over_muFn']):.4f} | {st['stick_cells']} / {st['slip_cells']} | "
                 f"{float(st['p_max']):.1f} |",
                 f"| time steps from the steady state, reference program | {ref['transient_range'][0]:.4f} to "
                 f"{ref['transient_range'][1]:.4f} | | |",
                 f"| rolled from rest, rollcontact (last quarter of {tr['steps']} steps) | {float(tr['Fx_min']):.4f} "
                 f"to {float(tr['Fx_max']):.4f} (mean {float(tr['Fx_over_muFn']):.4f}) | | |", "",
                 f"sawtooth period {tr.get('sawtooth_period_steps') or '-'} steps; mean minus the reference program's "
                 f"mid-range {float(tr['shift_of_mean']):+.4f}; solves per step {float(tr['solves_per_step']):.1f}; "
                 f"feedback {float(st['friction_feedback']):.3f}\n"]
    lim = out / "limits.csv"
    if lim.exists():
        with open(lim) as fh:
            rows = list(csv.DictReader(fh))
        ws = sorted({float(r["w"]) for r in rows})
        have = [(k, h) for k, h in STUDY_COLUMNS if any(r["configuration"] == k for r in rows)]
        text += ["| w | " + " | ".join(h for _, h in have) + " |", "|---" * (len(have) + 1) + "|"]
        for w in ws:
            cells = []
            for k, _ in have:
                r = next((r for r in rows if r["configuration"] == k and float(r["w"]) == w), None)
                cells.append("-" if r is None else (f"{float(r['f_t_lim']):.3f}" if r["f_t_lim"] else r["status"])
                             + (" (u)" if r is not None and r["status"] == "widened" else ""))
            text.append(f"| {w:g} | " + " | ".join(cells) + " |")
    md = "\n".join(text) + "\n"
    (out / "tables.md").write_text(md)
    return md


def _write_csv(path: Path, rows: list):
    keys = list(dict.fromkeys(k for r in rows for k in r))
    with open(path, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=keys)
        writer.writeheader()
        for r in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--out", type=Path, default=Path("results") / "friction")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--part", nargs="+", default=["validation", "contact", "study"],
                    choices=["validation", "contact", "study"])
    ap.add_argument("--jobs", type=int, default=1, help="processes of the limit searches")
    ap.add_argument("--runs", type=Path, default=Path("results") / "friction_runs",
                    help="folder of the limit searches' probe runs (default results/friction_runs)")
    ap.add_argument("--configs", nargs="+", default=None,
                    help="only the study configurations whose names contain one of these (e.g. 'd_c')")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    for part in args.part:
        t0, c0, load = time.time(), time.process_time(), os.getloadavg()
        print(f"{part} ...", flush=True)
        result = {"validation": lambda: validation(args.out, args.quick),
                  "contact": lambda: contact(args.out, args.quick),
                  "study": lambda: study(args.out, args.quick, args.jobs, args.runs, args.configs)}[part]()
        result.update(wall_s=time.time() - t0, cpu_s=time.process_time() - c0, load_before=load,
                      load_after=os.getloadavg(), date=time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()))
        name = f"friction_{part}{'_quick' if args.quick else ''}.json"
        (args.out / name).write_text(json.dumps(result, indent=1, default=str))
    print(page_tables(args.out))
    print(f"written to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

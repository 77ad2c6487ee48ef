"""Module 3 mapped onto a scene, one small function per capability: materials, friction, the Hertzian or quadric
geometry, the grid, the normal load, subsurface points, and the digits rollcontact has no counterpart for. Each
function writes the keys it can into the Draft and refuses (Draft.refuse: name, value, what rollcontact would need)
what it cannot, so that nothing is dropped silently. The kinds of problem (frictionless compression, shift
histories, steady and transient rolling) are in cases.decks.problems.

Conventions: CONTACT's body 1 (the upper body) is rollcontact's body 1 (E1, nu1, the 'sphere'), body 2 the
substrate; E = 2 G (1 + nu). The undeformed distance h = A x^2 + B y^2 is an ellipsoid with Rx = 1/(2A),
Ry = 1/(2B) (mm). Units: mm, N, MPa, rad in the deck, degrees in the scene.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

from rollcontact.cases.decks import hertz
from rollcontact.cases.decks.case import Case
from rollcontact.cases.decks.draft import Draft
from rollcontact.cases.decks.digits import NAMES, NAMES_MODULE1

#: |K| below which CONTACT treats the materials as quasi-identical (its MAXOUT rule)
QUASI_IDENTICAL = 1e-4


def digit(case: Case, name: str) -> str:
    names = NAMES_MODULE1 if case.module == 1 else NAMES
    return f"control digit {name} ({names.get(name, name)})"


def where(case: Case, *names: str) -> str:
    """'GG1 = 200, POISS1 = 0.42 (line 12)': the deck values a key comes from."""
    parts, lines = [], []
    for n in names:
        item = case.values.get(n)
        if item is not None:
            parts.append(f"{n} = {item.value:.6g}" if isinstance(item.value, float) else f"{n} = {item.value}")
            lines.append(item.line)
    ls = sorted(set(lines))
    return ", ".join(parts) + (f" (line{'s' if len(ls) > 1 else ''} {', '.join(map(str, ls))})" if ls else "")


# --- digits ------------------------------------------------------------------------------------------------------
def map_digits(case: Case, d: Draft):
    """The digits that change the problem and have no counterpart (B, E, V, M2, C = 4, 9, gap weighting); the
    digits and values that only steer the reference program's solvers and output, listed as ignored."""
    dg, line = case.digits, case.digit_lines
    needs = {1: "a compressible interfacial sheet (FLXZ)",
             2: "a prescribed elliptic traction bound (rollcontact's solver.traction_bound = 'ellipsoid' applies to its "
                "fast models only)",
             3: "a prescribed parabolic traction bound (rollcontact's solver.traction_bound = 'parabolic' applies to its "
                "fast models only)", 4: "the SDEC double half-ellipse",
             5: "the KPEC approximation of the normal problem", 6: "the ANALYN approximation of the normal problem"}
    if dg["B"] != 0:
        d.refuse(digit(case, "B"), dg["B"], f"needs {needs[dg['B']]}; rollcontact solves the full elastic normal "
                                             "problem (B = 0)", line["B"])
    if case.module == 3 and (dg["E"] in (2, 3) or (dg["E"] in (1, 9) and "EXRHS" in case.values)):
        d.refuse(digit(case, "E"), dg["E"], "needs an extra term in the rigid slip of each element (EXRHS) or a "
                                            "spin term discarded in one direction", line["E"])
    eff_c = case.effective.get("C", dg["C"])
    if eff_c in (4, 9):
        d.refuse(digit(case, "C"), eff_c, "needs influence coefficients for conformal contact (C = 4) or read "
                                          "from a file (C = 9); rollcontact has the half-space's", line["C"])
    if eff_c == 3:
        d.note("C = 3: the reference program uses bilinear traction elements; rollcontact's are piecewise constant "
               "(a difference of discretisation)")
    if case.effective.get("M2", 0) == 2:
        d.refuse(digit(case, "M2"), 2, "needs force-proportional damping (CDAMPN, CDAMPT)", line.get("M2"))
    if dg.get("gap weighting", 0):
        d.refuse("gap weighting (tens of M2)", dg["gap weighting"], "needs gap weighting", line.get("M2"))
    solver = [n for n in ("MAXGS", "MAXIN", "MAXNR", "MAXOUT", "EPS", "OMEGAH", "OMEGAS", "INISLP", "OMGSLP")
              if n in case.values]
    d.ignore(f"G = {dg['G']}, I = {dg['I']}" + (f" and {', '.join(solver)}" if solver else "") +
             ": the reference program's solver settings (rollcontact's solvers and [solver] tol apply)")
    d.ignore(f"A = {dg['A']}, O = {dg['O']}, W = {dg['W']}, X = {dg['X']}, R = {dg['R']}: output and flow of the "
             "reference program")


# --- materials and friction ----------------------------------------------------------------------------------------
def youngs(case: Case, body: int) -> float:
    return 2.0 * case.value(f"GG{body}") * (1.0 + case.value(f"POISS{body}"))


def difference_parameter(case: Case) -> float:
    """Kalker's K of the pair (CONTACT's AK; 0 for quasi-identical materials)."""
    g1, g2, n1, n2 = (case.value(n) for n in ("GG1", "GG2", "POISS1", "POISS2"))
    G = 2.0 / (1.0 / g1 + 1.0 / g2)
    return G / 4.0 * ((1.0 - 2.0 * n1) / g1 - (1.0 - 2.0 * n2) / g2)


def plane_strain_modulus(case: Case) -> float:
    """E* (MPa): 1/E* = (1 - nu1)/(2 G1) + (1 - nu2)/(2 G2)."""
    return 1.0 / sum((1.0 - case.value(f"POISS{i}")) / (2.0 * case.value(f"GG{i}")) for i in (1, 2))


def map_materials(case: Case, d: Draft):
    """Elastic bodies (M = 0); the other material models go through `map_material_model`."""
    for body in (1, 2):
        d.set("materials", f"E{body}", youngs(case, body), f"2 GG{body} (1 + POISS{body}); "
                                                           + where(case, f"GG{body}", f"POISS{body}"))
        d.set("materials", f"nu{body}", case.value(f"POISS{body}"), where(case, f"POISS{body}"))
    map_material_model(case, d)


def map_material_model(case: Case, d: Draft):
    """M = 0: elastic; M = 1: viscoelastic (`map_viscoelastic`); M = 2, 3, 5-7: the reference program's simplified
    theories (`map_fast_model`); M = 4 (an interfacial layer) is refused, with what it would need."""
    m = case.effective.get("M", case.digits["M"])
    if m == 1:
        map_viscoelastic(case, d)
    elif m in (2, 3, 5, 6, 7):
        map_fast_model(case, d, m)
    elif m == 4:
        d.refuse(digit(case, "M"), m, "needs an interfacial layer with plasticity (GG3, LAYTHK, TAU_C0, K_TAU)",
                 case.digit_lines["M"])


def map_fast_model(case: Case, d: Draft, m: int):
    """The reference program's simplified theories are other models than rollcontact's fast ones (solver.fidelity
    'fastsim': Kalker's FASTSIM with one flexibility weighted by the creepages; 'fastrip': its FaStrip;
    docs/creep_fidelity.md): its M = 2 takes a given flexibility FLX, M = 3 three blended flexibilities, M = 5-7 its
    own FaStrip variants, each with the slope reduction K0_MF, ALFAMF, BETAMF. Posed with rollcontact's models they
    would run with another meaning, so they are refused, naming the model rollcontact has instead."""
    flx = case.value("FLX")
    what = {2: (f"FASTSIM with the given flexibility FLX = {flx:.6g} mm^3/N" if flx is not None else "", "fastsim"),
            3: ("Modified FASTSIM with three blended flexibilities", "fastsim"),
            5: ("Modified FaStrip", "fastrip"), 6: ("original FaStrip (Sichani)", "fastrip"),
            7: ("FaStrip with its full sliding correction", "fastrip")}[m]
    reduction = ""
    if case.value("K0_MF") is not None and (case.value("K0_MF"), case.value("ALFAMF")) != (1.0, 1.0):
        reduction = (f" and the slope reduction K0_MF = {case.value('K0_MF'):.6g}, ALFAMF = "
                     f"{case.value('ALFAMF'):.6g}, BETAMF = {case.value('BETAMF'):.6g}")
    d.refuse(digit(case, "M"), m, f"needs the reference program's {what[0]}{reduction}; rollcontact's "
                                  f"solver.fidelity = '{what[1]}' is another variant (docs/creep_fidelity.md): set it "
                                  "by hand to compare", case.digit_lines["M"])


def map_viscoelastic(case: Case, d: Draft):
    """M = 1: each body a Standard Linear Solid (docs/viscoelastic.md): GG the glassy shear modulus, so E<i> = 2 GG
    (1 + nu) glassy, FG = E_g/E_r - 1, so E<i>_relaxed = E<i> / (1 + FG), TC the creep relaxation time tau<i> (s).
    FG = 0 is an elastic body; TC = 0 relaxes at once: an elastic body of the relaxed modulus."""
    for body in (1, 2):
        fg, tc = case.value(f"FG{body}"), case.value(f"TC{body}")
        if fg is None or fg == 0:
            continue
        relaxed = youngs(case, body) / (1.0 + fg)
        if tc == 0:
            d.set("materials", f"E{body}", relaxed, f"relaxed at once (TC{body} = 0): 2 GG{body} (1 + POISS{body}) / "
                                                    f"(1 + FG{body}); " + where(case, f"GG{body}", f"FG{body}"))
            continue
        d.set("materials", f"visco{body}", "sls", f"M = 1 (line {case.digit_lines['M']}): a standard linear solid")
        d.set("materials", f"E{body}_relaxed", relaxed, f"E{body} / (1 + FG{body}); " + where(case, f"FG{body}"))
        d.set("materials", f"tau{body}", tc, "creep relaxation time; " + where(case, f"TC{body}"))


def map_friction(case: Case, d: Draft, kind: str = "rolling"):
    """L = 0 (Coulomb, FSTAT = FKIN) as load.mu; L = 2, 3, 4 (the linear, rational and exponential slip-velocity laws)
    and L = 6 (temperature dependent friction) as a [friction] law with its memory (MEMDST, MEM_S0) where the problem
    rolls (`kind` 'rolling': steady or transient, T = 2, 3); in a frictionless compression ('normal') the law's static
    coefficient as load.mu; refused in shifts ('shift': the reference program takes a shift's slip velocity as the
    slip over 1 s) and on a wheel ('wheelrail'), and so is friction per grid row or varying along the track."""
    law = case.effective.get("L", case.digits["L"])
    vary = case.effective.get("V", case.digits["V"])
    if vary:
        what = {1: "across the rail profile", 2: "along the track", 3: "from grid row to grid row"}[vary]
        d.refuse(digit(case, "V"), vary, f"needs a friction coefficient varying {what}", case.digit_lines["V"])
        return
    if law == 0:
        mu = case.value("FKIN")
        if not 1e-6 <= mu <= 10:
            d.refuse("FKIN", mu, "is outside rollcontact's range of load.mu, [1e-6, 10]", case.line_of("FKIN"))
        d.set("load", "mu", mu, "FSTAT = FKIN; " + where(case, "FKIN"))
        return
    names = {2: "FLIN", 3: "FRAT", 4: "FEXP"}
    if kind == "normal":          # T = 0: the tangential problem is not solved; the law's mu(0) for the record
        mu = (case.value("FREF") if law == 6 else
              case.value("FKIN") + sum(case.value(f"{names[law]}{k}") or 0.0 for k in (1, 2)))
        d.set("load", "mu", mu, f"the static coefficient of friction law L = {law} (frictionless compression, T = 0)")
        return
    if kind != "rolling":
        why = {"shift": "in a shift (T = 1), whose slip velocity the reference program takes as the slip over 1 s; "
                        "rollcontact's laws are for rolling",
               "wheelrail": "on a wheel (module 1); rollcontact's [friction] is for module 3's rolling"}[kind]
        d.refuse(digit(case, "L"), law, f"needs a friction law {why}", case.digit_lines["L"])
        return
    if law == 6:
        d.set("friction", "law", "temperature", f"L = 6 (line {case.digit_lines['L']})")
        for key, name in (("mu_ref", "FREF"), ("T_ref", "TREF"), ("dmu_heat", "DFHEAT"), ("dT_heat", "DTHEAT")):
            d.set("friction", key, case.value(name), where(case, name))
        return
    name = {2: "linear", 3: "rational", 4: "exponential"}[law]
    d.set("friction", "law", name, f"L = {law} (line {case.digit_lines['L']})")
    d.set("friction", "mu_kin", case.value("FKIN"), where(case, "FKIN"))
    for k in (1, 2):
        size, half = case.value(f"{names[law]}{k}") or 0.0, case.value(f"SABSH{k}")
        if k == 1 or size > 0:
            d.set("friction", f"mu_{k}", size, where(case, f"{names[law]}{k}"))
            d.set("friction", f"s_{k}", half, where(case, f"SABSH{k}") + " (mm/s)")
    dc, s0 = case.value("MEMDST") or 0.0, case.value("MEM_S0") or 0.0
    if dc > 0:
        d.set("friction", "memory_distance", dc, where(case, "MEMDST") + " (mm)")
        if s0 > 0:
            d.set("friction", "memory_s0", s0, where(case, "MEM_S0") + " (mm/s)")


#: the reference program's thermal units in rollcontact's: LAMBDA W/(mm K) -> W/(m K), DENS kg/mm^3 -> kg/m^3
_THERMAL = (("T_bulk", "BKTEMP", 1.0), ("heat_capacity", "HEATCP", 1.0), ("conductivity", "LAMBDA", 1e3),
            ("density", "DENS", 1e9))


def map_heat(case: Case, d: Draft, kind: str = "rolling"):
    """H = 1, 3 (surface temperatures) as [thermal] in steady rolling (T = 3; the inputs converted to W/(m K) and
    kg/m^3); refused in the other problems and on a wheel ('wheelrail'), with what they would need."""
    if not case.digits["H"]:
        return
    if kind == "wheelrail" or case.digits.get("T") != 3:
        d.refuse(digit(case, "H"), case.digits["H"], "needs the surface temperatures " +
                 ("on a wheel (module 1)" if kind == "wheelrail" else "of a shift or a transient") +
                 "; rollcontact's [thermal] is for module 3's steady rolling (T = 3)", case.digit_lines["H"])
        return
    for key, name, factor in _THERMAL:
        for body in (1, 2):
            unit = {"LAMBDA": " (W/(mm K), x 1000)", "DENS": " (kg/mm^3, x 1e9)"}.get(name, "")
            d.set("thermal", f"{key}{body}", case.value(f"{name}{body}") * factor, where(case, f"{name}{body}") + unit)


# --- geometry and grid ---------------------------------------------------------------------------------------------
@dataclass
class Geometry:
    """The contact's geometry as the grid and the kinematics need it: curvatures A, B (1/mm), the centre (x0, y0)
    of the undeformed distance and its minimum h_min (mm), the potential contact [xl, xh] x [yl, yh] and its
    element sizes dx, dy (mm); `symmetric_y` when h(x, -y) = h(x, y) about the centre."""
    A: float
    B: float
    x0: float = 0.0
    y0: float = 0.0
    h_min: float = 0.0
    xl: float = 0.0
    xh: float = 0.0
    yl: float = 0.0
    yh: float = 0.0
    dx: float = 0.0
    dy: float = 0.0
    mx: int = 0
    my: int = 0
    symmetric_y: bool = True
    profile: tuple | None = None


def map_geometry(case: Case, d: Draft) -> Geometry | None:
    """The undeformed distance as a sphere or an ellipsoid: Hertzian IPOTCN = -1, -2, -3 (the curvatures, or from
    a/b or the semi-axes under FN) or IPOTCN > 0 with the quadratic IBASE = 1 without the cross term; a constant
    and linear terms shift the contact (its centre and minimum are kept for the kinematics and the figures)."""
    ipotcn = case.value("IPOTCN")
    line = case.line_of("IPOTCN")
    if ipotcn in (-4, -5):
        d.refuse("IPOTCN", ipotcn, "needs a 2D (line) contact with a prescribed pressure in each strip; rollcontact's "
                                   "contacts are 3D", line)
        return None
    if ipotcn == -6:
        d.refuse("IPOTCN", ipotcn, "needs the SDEC double half-ellipse", line)
        return None
    if ipotcn < 0:
        geo = _hertzian(case, d)
    else:
        geo = _quadric(case, d)
    if geo is None:
        return None
    if geo.profile is not None:
        d.set("geometry", "shape", "file", f"IBASE = {case.value('IBASE')} (line {case.line_of('IBASE')}), sampled")
        d.set("geometry", "path", "", "the undeformed distance at the deck's element centres")
        return geo
    if not (geo.A > 0 and geo.B > 0):
        d.refuse("undeformed distance", f"A = {geo.A:g}, B = {geo.B:g} 1/mm",
                 "needs a line contact on a grid of one strip (2D), which rollcontact's scene keys do not take, or a "
                 "concave body; rollcontact's ellipsoid has A, B > 0", line)
        return None
    if geo.A == geo.B:
        d.set("geometry", "R", 0.5 / geo.A, "1/(2 A) with A = B = " + _curvature_origin(case))
    else:
        d.set("geometry", "Rx", 0.5 / geo.A, "1/(2 A); " + _curvature_origin(case))
        d.set("geometry", "Ry", 0.5 / geo.B, "1/(2 B)")
    return geo


def _curvature_origin(case: Case) -> str:
    ipotcn = case.value("IPOTCN")
    names = {-1: ("A1", "B1"), -2: ("A1", "AOB", "FN"), -3: ("AA", "BB", "FN", "GG1", "GG2")}.get(ipotcn, ("B",))
    return where(case, *names) if ipotcn < 0 else f"B(1), B(3) of IBASE = 1 (line {case.line_of('B')})"


def _hertzian(case: Case, d: Draft) -> Geometry | None:
    ipotcn, fn, es = case.value("IPOTCN"), case.value("FN"), plane_strain_modulus(case)
    if fn is None:
        return None        # the approach is prescribed: refused by map_normal_load
    if ipotcn == -1:
        A, B = case.value("A1"), case.value("B1")
    elif ipotcn == -2:
        A = case.value("A1")
        B = hertz.b_curvature(A, case.value("AOB"))
    else:
        A, B = hertz.curvatures(case.value("AA"), case.value("BB"), fn, es)
    aa, bb = hertz.semi_axes(A, B, fn, es) if ipotcn != -3 else (case.value("AA"), case.value("BB"))
    s, mx, my = case.value("SCALE"), case.value("MX"), case.value("MY")
    return Geometry(A=A, B=B, xl=-aa * s, xh=aa * s, yl=-bb * s, yh=bb * s, dx=2 * aa * s / mx, dy=2 * bb * s / my,
                    mx=mx, my=my)


def _quadric(case: Case, d: Draft) -> Geometry | None:
    from rollcontact.cases.decks.module3 import explicit_grid
    ibase, iplan = case.value("IBASE"), case.value("IPLAN")
    if iplan != 1:
        d.refuse("IPLAN", iplan, "needs a planform that keeps elements out of contact", case.line_of("IPLAN"))
    if ibase != 1:
        return _sampled(case, d)
    b1, b2, b3, b4, b5, b6 = case.value("B")
    if b2 != 0:
        d.refuse("B(2)", b2, "needs an ellipsoid turned in the plane (an x y term); rollcontact's axes are x and y",
                 case.line_of("B"))
        return None
    if not (b1 > 0 and b3 > 0):
        return Geometry(A=b1, B=b3)
    x0, y0 = -b4 / (2 * b1), -b5 / (2 * b3)
    h_min = b6 - b4 ** 2 / (4 * b1) - b5 ** 2 / (4 * b3)
    if b4 or b5:
        d.note(f"the linear terms B(4), B(5) put the contact's centre at ({x0:.6g}, {y0:.6g}) mm: the scene is "
               "centred there (creepages, spin centre and MZ are carried over)")
    xl, yl, dx, dy, mx, my = explicit_grid({k: case.values[k] for k in ("IPOTCN", "MX", "MY", "XL", "YL", "DX", "DY",
                                                                         "XH", "YH", "XC1", "YC1", "XCM", "YCM")
                                            if k in case.values})
    return Geometry(A=b1, B=b3, x0=x0, y0=y0, h_min=h_min, xl=xl, xh=xl + mx * dx, yl=yl, yh=yl + my * dy, dx=dx,
                    dy=dy, mx=mx, my=my, symmetric_y=(b5 == 0))


def _sampled(case: Case, d: Draft) -> Geometry | None:
    """IBASE = 2, 3, 9 as a sampled profile (cases.decks.profiles) about the element of least h."""
    import numpy as np
    from rollcontact.cases.decks.module3 import explicit_grid
    from rollcontact.cases.decks.profiles import sampled_profile
    xl, yl, dx, dy, mx, my = explicit_grid({k: case.values[k] for k in ("IPOTCN", "MX", "MY", "XL", "YL", "DX", "DY",
                                                                         "XH", "YH", "XC1", "YC1", "XCM", "YCM")
                                            if k in case.values})
    got = sampled_profile(case, d, xl, yl, dx, dy, mx, my)
    if got is None:
        return None
    x, y, h, (x0, y0) = got
    return Geometry(A=0.0, B=0.0, x0=x0, y0=y0, h_min=0.0, xl=xl, xh=xl + mx * dx, yl=yl, yh=yl + my * dy, dx=dx,
                    dy=dy, mx=mx, my=my, symmetric_y=bool(np.allclose(h, h[::-1, :], rtol=1e-12, atol=0.0)),
                    profile=(x, y, h))


def map_grid(case: Case, d: Draft, geo: Geometry):
    """[grid] dx, dy = the deck's element sizes (the margin follows with `grid_margin`)."""
    d.set("grid", "dx", geo.dx, "element size of the potential contact" + _grid_origin(case))
    d.set("grid", "dy", geo.dy, "")
    for name, low, step, centre in (("x", geo.xl, geo.dx, geo.x0), ("y", geo.yl, geo.dy, geo.y0)):
        offset = ((low + step / 2 - centre) / step) % 1.0
        if 1e-3 < offset < 1 - 1e-3:
            d.note(f"the deck's element centres lie {offset:.3g} of an element off the contact's centre in {name}; "
                   "rollcontact has an element centred on it (a difference of discretisation)")


def grid_margin(d: Draft, geo: Geometry, extent: tuple[float, float]):
    """[grid] margin: beyond rollcontact's estimate of the contact (`extent`, its half-widths in mm), as far as the
    deck's potential contact reaches about the contact's centre, but at least 2 and at most 10 elements (the grid
    only has to hold the contact: rollcontact stops with ContactEdgeError if a contact reaches its edge)."""
    half_x = max(abs(geo.xl - geo.x0), abs(geo.xh - geo.x0))
    half_y = max(abs(geo.yl - geo.y0), abs(geo.yh - geo.y0))
    h = max(geo.dx, geo.dy)
    margin = min(max(half_x - extent[0], half_y - extent[1], 2 * h), 10 * h)
    d.set("grid", "margin", float(f"{margin:.6g}"), "2-10 elements, towards the deck's potential contact "
                                                    f"[{geo.xl:.6g}, {geo.xh:.6g}] x [{geo.yl:.6g}, {geo.yh:.6g}] mm")


def _grid_origin(case: Case) -> str:
    ipotcn = case.value("IPOTCN")
    if ipotcn < 0:
        return f", 2 AA SCALE / MX and 2 BB SCALE / MY; {where(case, 'MX', 'MY', 'SCALE')}"
    return f"; {where(case, 'DX', 'DY', 'XH', 'YH', 'XCM', 'YCM')}"


# --- loads and output ----------------------------------------------------------------------------------------------
def map_normal_load(case: Case, d: Draft):
    """N = 1: load.Fn; N = 0 (a prescribed approach PEN) refused."""
    if case.digits["N"] == 0:
        d.refuse(digit(case, "N"), 0, f"needs a prescribed approach (PEN = {case.value('PEN'):.6g} mm); rollcontact "
                                      "prescribes the normal force", case.digit_lines["N"])
        return
    d.set("load", "Fn", case.value("FN"), where(case, "FN"))


def map_subsurface(case: Case, d: Draft):
    """S >= 1: the blocks' depths become the run's --depths (rollcontact computes at its own element centres)."""
    if not case.digits["S"] or not case.subsurface:
        return
    depths = sorted({round(z, 12) for block in case.subsurface for z in block["Z"]})
    if any(z < 0 for z in depths):
        d.refuse("subsurface Z", min(depths), "needs points above the surface (z < 0)", case.subsurface[0]["line"])
        return
    d.run_options["stresses"] = True
    d.run_options["depths"] = depths
    kinds = {b["ISUBS"] for b in case.subsurface}
    if kinds & {2, 3, 6, 7}:
        d.note("subsurface: the deck selects some elements (ISUBS = 2, 3, 6, 7); rollcontact computes the stresses "
               "below every element at those depths")
    if 9 in kinds:
        d.note("subsurface: the deck's points (ISUBS = 9) at given x, y; rollcontact computes at its element centres "
               "at the same depths")


def rotate(vx: float, vy: float, angle: float) -> tuple[float, float]:
    """(vx, vy) in the frame turned by `angle` (rad): the components along and to the left of that direction."""
    c, s = math.cos(angle), math.sin(angle)
    return vx * c + vy * s, -vx * s + vy * c

"""One case of module 3 (basic Hertzian and non-Hertzian contact) read in the order of the reference program's input
file: control words, solver settings, kinematics (PEN or FN, CKSI or FX, CETA or FY, CPHI), friction, rolling
step (CHI, DQ, VELOC), materials, damping and temperatures, potential contact (IPOTCN and its grid), undeformed
distance (IBASE, IPLAN), friction per grid row, extra rigid slip (EXRHS) and subsurface points, with the checks the
reference program makes on each and on the digits of consecutive cases (DeckError naming the line and the field).
Units as in the deck: mm, N, N/mm^2 (MPa), rad, s.
"""
from __future__ import annotations

from rollcontact.cases.decks import groups
from rollcontact.cases.decks.case import Case, ElementState
from rollcontact.cases.decks.reader import DeckText, Item

KINEMATIC_NAMES = ("PEN", "FN", "CKSI", "CETA", "FXREL", "FYREL", "CPHI", "SPINXO", "SPINYO")
ROLLING_NAMES = ("CHI", "DQ", "VELOC", "FACPHI")
#: the grid values of each IPOTCN
POTCON_SPEC = {-1: "MX:i MY:i A1:d B1:d SCALE:d", -2: "MX:i MY:i A1:d AOB:d SCALE:d",
               -3: "MX:i MY:i AA:d BB:d SCALE:d", -4: "MX:i MY:i A1:d BB:d SCALE:d",
               -5: "MX:i MY:i AA:d BB:d SCALE:d", -6: "MX:i MY:i AA:d BNEG:d BPOS:d SCALE:d",
               1: "MX:i MY:i XL:d YL:d DX:d DY:d", 2: "MX:i MY:i XL:d YL:d XH:d YH:d",
               3: "MX:i MY:i XC1:d YC1:d DX:d DY:d", 4: "MX:i MY:i XC1:d YC1:d XCM:d YCM:d"}
POTCON_NAMES = ("IPOTCN", "MX", "MY", "A1", "B1", "AOB", "AA", "BB", "BNEG", "BPOS", "SCALE", "XL", "YL", "DX", "DY",
                "XH", "YH", "XC1", "YC1", "XCM", "YCM")
GEOMETRY_NAMES = ("IBASE", "IPLAN", "B", "NN", "XM", "RM", "Y1", "DY1", "H", "PL", "PLAN", "NPATCH", "XYLIM", "FAC")


def explicit_grid(values: dict) -> tuple[float, float, float, float, int, int]:
    """(xl, yl, dx, dy, mx, my) of a potential contact given directly (IPOTCN = 1-4): the lower-left corner and the
    element sizes (mm), from whichever pair of corner, centre and step the IPOTCN gives."""
    v = {k: it.value for k, it in values.items()}
    ipotcn, mx, my = v["IPOTCN"], v["MX"], v["MY"]
    if ipotcn == 1:
        return v["XL"], v["YL"], v["DX"], v["DY"], mx, my
    if ipotcn == 2:
        return v["XL"], v["YL"], (v["XH"] - v["XL"]) / mx, (v["YH"] - v["YL"]) / my, mx, my
    if ipotcn == 3:
        return v["XC1"] - v["DX"] / 2, v["YC1"] - v["DY"] / 2, v["DX"], v["DY"], mx, my
    dx, dy = (v["XCM"] - v["XC1"]) / (mx - 1), (v["YCM"] - v["YC1"]) / (my - 1)
    return v["XC1"] - dx / 2, v["YC1"] - dy / 2, dx, dy, mx, my


def read_case(text: DeckText, case: Case, state: ElementState):
    """Read one module-3 case into `case` (its digits, read and effective values), updating the element's state."""
    groups.read_control_words(text, 3, case)
    _check_digits(text, case, state)
    dg = case.digits
    groups.read_solver(text, case, state)
    _read_kinematics(text, case, state)
    if dg["V"] == 0:
        groups.read_friction(text, case, state)
    new_influence = dg["C"] in (2, 3, 4, 9)
    rolling = dg["T"] in (2, 3)
    if new_influence and rolling:
        got = text.read("rolling direction, step and velocity", "CHI:a DQ:d VELOC:d FACPHI:D")
        eps = state.values.get("EPS", Item(1e-4, 0)).value
        groups.in_range(text, got["DQ"], "DQ", eps, 1e20)
        groups.in_range(text, got["VELOC"], "VELOC", eps, 1e20)
        if dg["M"] == 1 and abs(got["CHI"].value) > 0.01:
            raise text.error(got["CHI"].line, "CHI", f"{got['CHI'].value!r} rad: viscoelastic materials (M = 1) "
                                                     "roll in +x only (CHI = 0)")
        state.drop(*ROLLING_NAMES)
        state.keep(case, got)
    elif rolling and "DQ" not in state.values:
        raise text.error(case.digit_lines["C"], "control digit C (INFLCF)",
                         f"{dg['C']} keeps the rolling step of an earlier case, but no case has given CHI, DQ, VELOC")
    if new_influence:
        groups.read_materials(text, 3, case, state)
    groups.read_damping_and_heat(text, case, state)
    if dg["D"] == 2:
        _read_potcon(text, case, state)
    _check_potcon(text, case, state)
    if dg["Z"] == 2:
        _read_geometry(text, case, state)
    if dg["V"] == 3 and dg["L"] != 1:
        groups.read_friction(text, case, state, rows=state.values["MY"].value)
    if dg["E"] == 9:
        npot = state.values["MX"].value * state.values["MY"].value
        state.keep(case, {"EXRHS": text.read_array("extra term of the rigid slip", "EXRHS", "d", 2 * npot)})
    elif dg["E"] != 1:
        state.drop("EXRHS")
    groups.read_subsurface(text, case, state)
    if dg["C"] in (2, 3, 4, 9) and "MX" in state.values:
        state.effective["influence_grid"] = (state.values["MX"].value, state.values["MY"].value)
    state.last_tang = dg["T"]


def _check_digits(text: DeckText, case: Case, state: ElementState):
    """The reference program's checks of the digits, for the first case of an element and against the previous."""
    dg, ln = case.digits, case.digit_lines
    first = state.cases == 1

    def bad(digit, message):
        return text.error(ln[digit], f"control digit {digit}", f"{dg[digit]}: {message}")
    if first:
        if dg["P"] != 2:
            case.notes.append(f"P = {dg['P']} in the first case: set to 2 (the contact is initiated), as the "
                              "reference program does")
            dg["P"] = 2
        if dg["I"] != 0:
            case.notes.append(f"I = {dg['I']} in the first case: set to 0, as the reference program does")
            dg["I"] = 0
        if dg["L"] == 1:
            raise bad("L", "the first case has no earlier friction law to keep (L = 1)")
        if dg["D"] == 0:
            raise bad("D", "the first case has no earlier potential contact to keep (D = 0)")
        if dg["C"] in (0, 1):
            raise bad("C", "the first case has no earlier materials to keep (C = 0, 1): give C = 2")
        if dg["G"] == 1:
            case.notes.append("G = 1 in the first case: the reference program's default solver settings")
    if dg["L"] == 1 and dg["V"] != state.effective.get("V", dg["V"]):
        raise bad("V", f"changes from {state.effective['V']} with L = 1: new friction parameters are needed")
    if dg["D"] != 0 and dg["Z"] == 0:
        raise bad("Z", f"a new discretisation (D = {dg['D']}) needs a new undeformed distance (Z = 1, 2)")
    rolling, was_rolling = dg["T"] in (2, 3), state.last_tang in (2, 3)
    if dg["C"] == 0 and rolling and not was_rolling:
        raise bad("C", f"the first rolling case (T = {dg['T']}) needs new influence coefficients (C = 2, 3)")
    if dg["C"] == 0 and not rolling and was_rolling:
        raise bad("C", f"from rolling to T = {dg['T']} needs new influence coefficients (C = 2, 3)")
    if dg["M"] == 1 and dg["T"] != 3:
        raise bad("M", f"viscoelastic materials need steady rolling (T = 3, here T = {dg['T']})")
    if dg["H"] >= 1 and dg["T"] != 3:
        raise bad("H", f"temperatures need steady rolling (T = 3, here T = {dg['T']})")
    if dg["L"] == 6 and dg["H"] == 0:
        raise bad("L", "temperature dependent friction needs the temperature (H = 1, 3)")
    if dg["L"] == 6 and dg["M"] in (2, 3, 5, 6, 7):
        raise bad("L", f"temperature dependent friction is not available with the simplified theory (M = {dg['M']})")


def _read_kinematics(text: DeckText, case: Case, state: ElementState):
    dg = case.digits
    first = "PEN" if dg["N"] == 0 else "FN"
    second, third = {0: ("CKSI", "CETA"), 1: ("FXREL", "CETA"), 2: ("FXREL", "FYREL")}[dg["F"]]
    got = text.read("kinematics", f"{first}:d {second}:d {third}:d CPHI:d SPINXO:D SPINYO:D")
    if dg["N"] == 1 and got["FN"].value <= 0:
        raise text.error(got["FN"].line, "FN", f"{got['FN'].value!r} N: the normal force must be > 0")
    if dg["F"] >= 1:
        groups.in_range(text, got["FXREL"], "FX", -1.0, 1.0, " (FX / (FSTAT FN))")
    if dg["F"] == 2 and got["FXREL"].value ** 2 + got["FYREL"].value ** 2 > 1.0:
        raise text.error(got["FYREL"].line, "FY", f"FX, FY = {got['FXREL'].value!r}, {got['FYREL'].value!r}: the "
                                                  "tangential force exceeds FSTAT FN (FX^2 + FY^2 > 1)")
    if "SPINXO" in got and "SPINYO" not in got:
        case.notes.append("SPINXO without SPINYO: the spin centre is set to (0, 0), as the reference program does")
        got.pop("SPINXO")
    state.drop(*KINEMATIC_NAMES)
    state.keep(case, got)


def _read_potcon(text: DeckText, case: Case, state: ElementState):
    item = text.read("potential contact", "IPOTCN:i")["IPOTCN"]
    if item.value not in POTCON_SPEC:
        raise text.error(item.line, "IPOTCN", f"{item.value} is not allowed: -6 to -1 (Hertzian) or 1 to 4")
    got = {"IPOTCN": item, **text.read(f"potential contact (IPOTCN = {item.value})", POTCON_SPEC[item.value])}
    for name in ("MX", "MY"):
        groups.in_range(text, got[name], name, 1, 10 ** 8)
    for name in ("A1", "B1", "AOB", "AA", "BB", "SCALE"):
        if name in got and got[name].value <= 0:
            raise text.error(got[name].line, name, f"{got[name].value!r} must be > 0")
    for name in ("BNEG", "BPOS", "DX", "DY"):
        if name in got:
            groups.in_range(text, got[name], name, 1e-8, 1e20)
    for low, high in (("XL", "XH"), ("YL", "YH"), ("XC1", "XCM"), ("YC1", "YCM")):
        if high in got and not got[low].value < got[high].value:
            raise text.error(got[high].line, high, f"{got[high].value!r} must exceed {low} = {got[low].value!r}")
    if item.value == 4 and 1 in (got["MX"].value, got["MY"].value):
        raise text.error(got["MX"].line, "MX, MY", "IPOTCN = 4 needs MX, MY > 1 (the step follows from the first "
                                                   "and last element centres)")
    if item.value > 0 and (case.digits["P"] != 2 or case.digits["I"] != 0) and "IPOTCN" in state.values \
            and state.values["IPOTCN"].value > 0:
        _check_aligned(text, case, state.values, got)
    state.drop(*POTCON_NAMES)
    state.keep(case, got)


def _check_aligned(text, case, old, new):
    """In a sequence (P != 2 or I != 0) the new grid keeps the element size and lies on the old one's lattice."""
    xl0, yl0, dx0, dy0, _, _ = explicit_grid(old)
    xl1, yl1, dx1, dy1, _, _ = explicit_grid(new)
    line = new["IPOTCN"].line
    if abs(dx1 - dx0) >= 1e-6 * min(dx0, dx1) or abs(dy1 - dy0) >= 1e-6 * min(dy0, dy1):
        raise text.error(line, "DX, DY", f"{dx1:g}, {dy1:g} differ from the previous case's {dx0:g}, {dy0:g}: a "
                                         f"sequence (P = {case.digits['P']}, I = {case.digits['I']}) keeps the "
                                         "element size")
    for shift, step, name in ((xl1 - xl0, dx1, "x"), (yl1 - yl0, dy1, "y")):
        if abs(shift - round(shift / step) * step) >= 1e-6 * step:
            raise text.error(line, "XL, YL", f"the grid moves by {shift:g} mm in {name}, not a whole number of "
                                             f"elements ({step:g} mm): a sequence keeps the grid's lattice")


def _check_potcon(text: DeckText, case: Case, state: ElementState):
    """The combinations of IPOTCN with the B and N digits that the reference program refuses."""
    dg = case.digits
    ipotcn = state.values["IPOTCN"].value
    line = state.values["IPOTCN"].line

    def bad(message):
        return text.error(line, "IPOTCN", f"{ipotcn}: {message}")
    if ipotcn >= 1 and dg["B"] in (2, 3):
        raise bad(f"a prescribed traction bound (B = {dg['B']}) needs a Hertzian potential contact (IPOTCN < 0)")
    if ipotcn == -6 and dg["B"] != 4:
        raise bad(f"the SDEC contact needs B = 4 (here B = {dg['B']})")
    if dg["B"] == 4 and ipotcn != -6:
        raise bad("B = 4 (SDEC) needs IPOTCN = -6")
    if ipotcn in (-5, -4) and dg["N"] != 1:
        raise bad("a rectangular (2D) Hertzian contact needs the normal force (N = 1)")
    if -5 <= ipotcn <= -1 and dg["N"] == 0 and state.values["PEN"].value < 0:
        raise text.error(state.values["PEN"].line, "PEN", f"{state.values['PEN'].value!r}: a Hertzian contact "
                                                          "needs PEN >= 0")
    if dg["B"] == 4 and dg["N"] != 1:
        raise bad("SDEC (B = 4) needs the normal force (N = 1)")
    if dg["B"] in (5, 6) and dg["N"] != 0:
        raise bad(f"KPEC and ANALYN (B = {dg['B']}) need the approach (N = 0)")
    if dg["D"] != 0 and dg["C"] == 0 and ipotcn > 0 and "influence_grid" in state.effective:
        mx, my = state.effective["influence_grid"]
        if state.values["MX"].value > mx or state.values["MY"].value > my:
            raise bad(f"a larger potential contact ({state.values['MX'].value} x {state.values['MY'].value} > "
                      f"{mx} x {my}) needs new influence coefficients (C = 2, 3)")


def _read_geometry(text: DeckText, case: Case, state: ElementState):
    """IBASE, IPLAN and their parameters (IPOTCN > 0); a Hertzian potential contact has its own quadratic
    undeformed distance and reads nothing here."""
    state.drop(*GEOMETRY_NAMES)
    if state.values["IPOTCN"].value < 0:
        return
    got = text.read("undeformed distance IBASE, IPLAN", "IBASE:i IPLAN:i")
    ibase, iplan = got["IBASE"], got["IPLAN"]
    if ibase.value not in (1, 2, 3, 9):
        raise text.error(ibase.line, "IBASE", f"{ibase.value} is not allowed: 1, 2, 3 or 9")
    if iplan.value not in (1, 2, 3, 4):
        raise text.error(iplan.line, "IPLAN", f"{iplan.value} is not allowed: 1 to 4")
    if ibase.value == 1:
        got["B"] = text.read_array("quadratic undeformed distance", "B", "d", 6)
    elif ibase.value == 2:
        got.update(text.read("body of revolution", "NN:i XM:d RM:d Y1:d DY1:d"))
        groups.in_range(text, got["NN"], "NN", 2, 999999)
        groups.in_range(text, got["DY1"], "DY1", 1e-8, 1e20)
        got["B"] = text.read_array("profile heights", "B", "d", got["NN"].value)
    elif ibase.value == 3:
        got["B"] = text.read_array("quadratic plus sines", "B", "d", 8)
    else:
        npot = state.values["MX"].value * state.values["MY"].value
        got["H"] = text.read_array("undeformed distance of every element", "H", "d", npot)
    if iplan.value == 2:
        got["PL"] = text.read_array("quadratic planform", "PL", "d", 6)
    elif iplan.value == 3:
        got["PLAN"] = text.read_array("planform of two rectangles", "PLAN", "d", 8)
        lo_hi = got["PLAN"].value
        if any(lo_hi[k + 1] <= lo_hi[k] for k in (0, 2, 4, 6)):
            raise text.error(got["PLAN"].line, "PLAN", f"{lo_hi}: each rectangle needs XL < XH and YL < YH")
    elif iplan.value == 4:
        npatch = text.read("number of patches", "NPATCH:i")["NPATCH"]
        n = max(1, min(100, npatch.value))
        got["NPATCH"] = npatch
        got["XYLIM"] = text.read_array("patch rectangles", "XYLIM", "d", 4 * n)
        got["FAC"] = text.read_array("patch interaction factors", "FAC", "d", n * (n - 1) // 2)
    state.keep(case, got)

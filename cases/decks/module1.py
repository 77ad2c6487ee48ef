"""One case of module 1 (wheel on rail) read in the order of the reference program's input file: control words,
solver settings, friction, materials, damping and temperatures, discretisation (DX, DS, DQREL, A_SEP, D_SEP,
D_COMB), track and rail profile with its deviations, wheelset dimensions and wheel profile, wheelset position and
velocity (or shift) and its flexible deviations, subsurface points; with the reference program's checks (DeckError
naming the line and the field). Units as in the deck: mm, N, rad, mm/s, rad/s.
"""
from __future__ import annotations

from rollcontact.cases.decks import groups
from rollcontact.cases.decks.case import Case, ElementState
from rollcontact.cases.decks.reader import DeckText

PROFILE_SPEC = "FNAME:s MIRRORY:i SCALEYZ:d SMOOTH:d MIRRORZ:I PRFOPT:I"


def read_case(text: DeckText, case: Case, state: ElementState):
    """Read one module-1 case into `case`, updating the element's state."""
    groups.read_control_words(text, 1, case)
    _check_digits(text, case, state)
    dg = case.digits
    groups.read_solver(text, case, state)
    groups.read_friction(text, case, state)
    if dg["C"] in (2, 3, 4):
        groups.read_materials(text, 1, case, state)
    groups.read_damping_and_heat(text, case, state)
    if 2 <= dg["D"] <= 9:
        got = text.read("discretisation", "DX:d DS:d DQREL:d A_SEP:a D_SEP:d D_COMB:d D_TURN:D G_MISS:D")
        for name, lo, hi in (("DX", 1e-8, 1e20), ("DS", 1e-8, 1e20), ("DQREL", 5e-7, 10.0)):
            groups.in_range(text, got[name], name, lo, hi)
        if got["D_SEP"].value < got["D_COMB"].value:
            raise text.error(got["D_SEP"].line, "D_SEP", f"{got['D_SEP'].value!r} is below D_COMB = "
                                                         f"{got['D_COMB'].value!r}: D_SEP >= D_COMB is needed")
        state.drop("DX", "DS", "DQREL", "A_SEP", "D_SEP", "D_COMB", "D_TURN", "G_MISS")
        state.keep(case, got)
        state.effective["D"] = dg["D"]
    _read_track(text, case, state)
    _read_wheelset(text, case, state)
    groups.read_subsurface(text, case, state)
    state.last_tang = dg["T"]


def _check_digits(text: DeckText, case: Case, state: ElementState):
    dg, ln = case.digits, case.digit_lines

    def bad(digit, message):
        return text.error(ln[digit], f"control digit {digit}", f"{dg[digit]}: {message}")
    if state.cases == 1:
        if dg["P"] != 2:
            case.notes.append(f"P = {dg['P']} in the first case: set to 2, as the reference program does")
            dg["P"] = 2
        if dg["I"] != 0:
            case.notes.append(f"I = {dg['I']} in the first case: set to 0, as the reference program does")
            dg["I"] = 0
        for digit, what in (("L", "friction law"), ("D", "discretisation")):
            if dg[digit] in ((1,) if digit == "L" else (0, 1)):
                raise bad(digit, f"the first case has no earlier {what} to keep")
        if dg["C"] in (0, 1):
            raise bad("C", "the first case has no earlier materials to keep: give C = 2")
        if dg["Z"] in (0, 1, 2):
            raise bad("Z", "the first case reads no rail profile (Z = 3 reads the track and the profile)")
        if dg["E"] not in (3, 5):
            raise bad("E", "the first case reads no wheel profile (E = 3, 5 read the wheelset and the profile)")
    if dg["C"] == 0:
        case.notes.append("C = 0 in module 1: set to 1 (keep the materials), as the reference program does")
        dg["C"] = 1
    if dg["L"] == 1 and dg["V"] != state.effective.get("V", dg["V"]):
        raise bad("V", f"changes from {state.effective['V']} with L = 1: new friction parameters are needed")
    last_n = state.effective.get("N")
    if dg["E"] == 0 and last_n is not None and dg["N"] != last_n:
        raise bad("N", "switching between position and total force needs a new wheelset position (E >= 1)")
    if dg["F"] == 1 and dg["N"] != 1:
        raise bad("F", "a prescribed total force FX needs the vertical force (N = 1)")
    if dg["M"] == 1 and dg["T"] != 3:
        raise bad("M", f"viscoelastic materials need steady rolling (T = 3, here T = {dg['T']})")
    if dg["H"] >= 1 and dg["T"] != 3:
        raise bad("H", f"temperatures need steady rolling (T = 3, here T = {dg['T']})")
    if dg["L"] == 6 and dg["H"] == 0:
        raise bad("L", "temperature dependent friction needs the temperature (H = 1, 3)")
    if dg["E"] >= 1:
        state.effective["N"] = dg["N"]


def _read_profile(text: DeckText, body: str, case: Case, state: ElementState):
    """The profile line of the rail or the wheel and its optional extra lines (PRFOPT >= 1, 2)."""
    got = text.read(f"{body} profile", PROFILE_SPEC)
    for name, lo, hi in (("MIRRORY", -1, 1), ("MIRRORZ", -1, 1), ("PRFOPT", 0, 2)):
        if name in got:
            groups.in_range(text, got[name], name, lo, hi, f" ({body} profile)")
    prfopt = got["PRFOPT"].value if "PRFOPT" in got else 0
    if prfopt >= 1:
        got.update(text.read(f"{body} profile options", "ISMOOTH:i ZIGTHRS:a KINKHIGH:a KINKLOW:a KINKWID:d"))
    if prfopt >= 2:
        got.update(text.read(f"{body} profile error handling", "ERRHND:i MAXOMIT:d"))
    names = [f"{k}({body})" for k in ("FNAME", "MIRRORY", "SCALEYZ", "SMOOTH", "MIRRORZ", "PRFOPT", "ISMOOTH",
                                      "ZIGTHRS", "KINKHIGH", "KINKLOW", "KINKWID", "ERRHND", "MAXOMIT")]
    state.drop(*names)
    state.keep(case, {f"{k}({body})": v for k, v in got.items()})


def _read_track(text: DeckText, case: Case, state: ElementState):
    dg = case.digits
    if dg["Z"] in (1, 3):
        roller = dg["C1"] >= 4
        spec = "GAUGHT:d SECOND:d THIRD:d " + ("NOMRADR:d" if roller else "CANT:a") + " CURV:D"
        got = text.read("roller rig dimensions" if roller else "track dimensions", spec)
        positioned = got["GAUGHT"].value > 0
        got["GAUGSQ" if positioned else "RAILY0"] = got.pop("SECOND")
        got["GAUGWD" if positioned else "RAILZ0"] = got.pop("THIRD")
        state.drop("GAUGHT", "GAUGSQ", "GAUGWD", "RAILY0", "RAILZ0", "CANT", "NOMRADR", "CURV")
        state.keep(case, got)
    if dg["Z"] == 3:
        _read_profile(text, "rail", case, state)
    if dg["Z"] in (2, 3):
        got = text.read("rail deviations", "DYRAIL:d DZRAIL:d DROLLR:a VYRAIL:d VZRAIL:d VROLLR:a")
        state.keep(case, got)
        if dg["F"] == 3:
            state.keep(case, text.read("rail deflection", "KYRAIL:d FYRAIL:d KZRAIL:d FZRAIL:d DYSTEP0:D"))


def _read_wheelset(text: DeckText, case: Case, state: ElementState):
    dg = case.digits
    if dg["E"] in (3, 5):
        got = text.read("wheelset dimensions", "FBDIST:d FBPOS:d NOMRADW:d YTAPE:D")
        groups.in_range(text, got["NOMRADW"], "NOMRAD", 1e-3, 1e20)
        state.drop("YTAPE")
        state.keep(case, got)
        _read_profile(text, "wheel", case, state)
    roller = dg["C1"] >= 4
    if 1 <= dg["E"] <= 5:
        z = "Z_WS" if dg["N"] == 0 else "FZ_WS"
        got = text.read("wheelset position", f"{'X_WS' if roller else 'S_WS'}:d Y_WS:d {z}:d ROLL:a YAW:a PITCH:a")
        state.drop("S_WS", "X_WS", "Y_WS", "Z_WS", "FZ_WS", "ROLL", "YAW", "PITCH")
        state.keep(case, got)
    if 2 <= dg["E"] <= 5:
        shift = dg["T"] == 1
        last = "VPITCH" if dg["F"] in (0, 3) else ("FX_WS" if dg["F"] == 1 else "MY_WS")
        names = (["RPITCH" if roller else "VS_WS", "VY_WS", "VZ_WS", "VROLL", "VYAW", last] if not shift else
                 ["SHFT_RPIT" if roller else "SHFT_SWS", "SHFT_YWS", "SHFT_ZWS", "SHFT_ROL", "SHFT_YAW", "SHFT_WPIT"])
        kinds = ["a" if roller else "d", "d", "d", "a", "a", "a" if dg["F"] in (0, 3) else "d"]
        got = text.read("wheelset shift" if shift else "wheelset velocity",
                        " ".join(f"{n}:{k}" for n, k in zip(names, kinds)))
        state.drop("VS_WS", "RPITCH", "VY_WS", "VZ_WS", "VROLL", "VYAW", "VPITCH", "FX_WS", "MY_WS", "SHFT_SWS",
                   "SHFT_RPIT", "SHFT_YWS", "SHFT_ZWS", "SHFT_ROL", "SHFT_YAW", "SHFT_WPIT")
        state.keep(case, got)
    if dg["E"] in (4, 5):
        state.keep(case, text.read("wheel position deviations", "DXWHL:d DYWHL:d DZWHL:d DROLLW:a DYAWW:a DPITCHW:a"))
        state.keep(case, text.read("wheel velocity deviations", "VXWHL:d VYWHL:d VZWHL:d VROLLW:a VYAWW:a VPITCHW:a"))

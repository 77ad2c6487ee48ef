"""Module 1 (a wheel on its rail) mapped onto a [wheelrail] scene (docs/wheelrail.md).

Conventions (CONTACT's user guide, "Wheelset geometry & state", and docs/wheelrail.md): CONTACT's body 1 is the
rail, body 2 the wheel (rollcontact's E1, nu1 are the wheel's); its track frame has y to the right and z down, so
the right wheel's y is Y_WS and the left wheel's -Y_WS, yaw is -YAW, omega is -VPITCH, roll is ROLL; its CANT is the
rail's inclination towards the track centre (rail_inclination). Forces are on the rail in CONTACT, on the wheel in
rollcontact. Units: mm, N, rad, mm/s, rad/s.
"""
from __future__ import annotations

from pathlib import Path

from rollcontact.cases.decks import mapping as M
from rollcontact.cases.decks.case import Case
from rollcontact.cases.decks.draft import Draft
from rollcontact.cases.decks.problems import Problem

#: rollcontact's distance (mm) below which contact regions form one patch (docs/wheelrail.md)
PATCH_JOIN = 4.0


def map_wheelrail(problem: Problem, folder: Path | None) -> Problem:
    """Fill problem.draft with the [wheelrail] scene of one module-1 case."""
    case = problem.cases[0]
    d = problem.draft = Draft()
    dg, ln = case.digits, case.digit_lines
    M.map_digits(case, d)
    M.map_heat(case, d, "wheelrail")
    M.map_material_model(case, d)
    if dg["C1"] not in (0, 1):
        d.refuse(M.digit(case, "C1"), dg["C1"], "needs a wheel on a roller (roller rig)", ln["C1"])
    if dg["T"] != 3:
        d.refuse(M.digit(case, "T"), dg["T"], "needs a wheel-rail shift or transient of the reference program's kind; "
                                              "rollcontact's [wheelrail] solves steady rolling (T = 3)", ln["T"])
    if dg["N"] != 1:
        d.refuse(M.digit(case, "N"), dg["N"], "needs a prescribed vertical position Z_WS; rollcontact prescribes the "
                                              "load Fz", ln["N"])
    if dg["F"] != 0:
        d.refuse(M.digit(case, "F"), dg["F"], "needs a prescribed total force FX_WS or a massless rail model",
                 ln["F"])
    _materials(case, d)
    M.map_friction(case, d, "wheelrail")
    _discretisation(case, d)
    _track(case, d, folder)
    _wheelset(case, d, folder)
    M.map_subsurface(case, d)
    problem.steps = {case.number: 0}
    problem.frame = {"side": "left" if dg["C1"] == 0 else "right"}
    return problem


def _materials(case: Case, d: Draft):
    for body, contact_body in ((1, 2), (2, 1)):
        d.set("materials", f"E{body}", M.youngs(case, contact_body),
              f"{'wheel' if body == 1 else 'rail'}: 2 GG{contact_body} (1 + POISS{contact_body}); "
              + M.where(case, f"GG{contact_body}", f"POISS{contact_body}"))
        d.set("materials", f"nu{body}", case.value(f"POISS{contact_body}"), "")
    if abs(M.difference_parameter(case)) >= M.QUASI_IDENTICAL:
        d.refuse("materials", f"K = {M.difference_parameter(case):.3g}", "needs coupled normal and tangential "
                                                                         "problems of dissimilar wheel and rail")


def _discretisation(case: Case, d: Draft):
    v = case.value
    d.set("grid", "dx", v("DX"), M.where(case, "DX"))
    d.set("grid", "dy", v("DS"), M.where(case, "DS"))
    if v("DQREL") != 1.0:
        d.note(f"DQREL = {v('DQREL'):.6g}: the reference program's rolling step is DQREL DX; rollcontact's steady "
               "state uses DX")
    d.note(f"patches: the deck separates and joins contact regions with A_SEP = {v('A_SEP'):.4g} rad, D_SEP = "
           f"{v('D_SEP'):.4g} mm, D_COMB = {v('D_COMB'):.4g} mm; rollcontact joins regions closer than {PATCH_JOIN:g} "
           "mm into one patch (the totals differ where a patch lies between)")
    dd = case.effective.get("D", case.digits["D"])
    if dd not in (2, 5):
        what = {3: "the rigid slip on the actual curved surfaces", 4: "conformal contact on a curved surface",
                6: "a larger grid for steep slopes", 7: "the initial contact point's local angle",
                8: "an oblique view direction", 9: "an oblique view direction"}[dd]
        d.refuse(M.digit(case, "D"), dd, f"needs {what}; rollcontact's patches are planar (D = 2, 5)",
                 case.digit_lines["D"])


def _profile(case: Case, d: Draft, body: str, folder: Path | None) -> str | None:
    v = case.value
    name = v(f"FNAME({body})")
    for key, want, what in (("MIRRORY", 0, "a mirrored profile"), ("MIRRORZ", 0, "a mirrored profile"),
                            ("SCALEYZ", 1.0, "a scaled profile"), ("SMOOTH", 0.0, "a smoothed profile"),
                            ("PRFOPT", 0, "the profile options (kinks, zig-zags)")):
        value = v(f"{key}({body})")
        if value is not None and value != want:
            d.refuse(f"{key} ({body} profile)", value, f"needs {what}", case.line_of(f"{key}({body})"))
    path = (folder / name) if folder is not None else Path(name)
    if path.suffix.lower() in (".slcs", ".slcw") or not path.suffix:
        d.refuse(f"{body} profile", name, "needs a profile that varies along the track (slices)",
                 case.line_of(f"FNAME({body})"))
        return None
    if not path.is_file():
        d.refuse(f"{body} profile", name, f"is not found in the deck's folder ({path})", case.line_of(f"FNAME({body})"))
        return None
    d.files[f"{body}_profile"] = path
    return path.name


def _track(case: Case, d: Draft, folder: Path | None):
    v = case.value
    name = _profile(case, d, "rail", folder)
    if name:
        d.set("wheelrail", "rail_profile", name, M.where(case, "FNAME(rail)").replace("FNAME(rail)", "RFNAME"))
    if v("GAUGHT") is not None and v("GAUGHT") > 0:
        d.set("wheelrail", "gauge_height", v("GAUGHT"), M.where(case, "GAUGHT"))
        d.set("wheelrail", "gauge", v("GAUGWD"), M.where(case, "GAUGWD"))
        if v("GAUGSQ"):
            d.refuse("GAUGSQ", v("GAUGSQ"), "needs a gauge face other than the first", case.line_of("GAUGSQ"))
    else:
        d.refuse("GAUGHT", v("GAUGHT"), "needs the rail placed at absolute coordinates RAILY0, RAILZ0",
                 case.line_of("GAUGHT"))
    d.set("wheelrail", "rail_inclination", v("CANT"), M.where(case, "CANT") + " (towards the track centre)")
    if v("CURV"):
        d.refuse("CURV", v("CURV"), "needs a curved track", case.line_of("CURV"))
    for name in ("DYRAIL", "DZRAIL", "DROLLR", "VYRAIL", "VZRAIL", "VROLLR"):
        if v(name):
            d.refuse(name, v(name), "needs rail deviations from the design position", case.line_of(name))


def _wheelset(case: Case, d: Draft, folder: Path | None):
    v = case.value
    left = case.digits["C1"] == 0
    name = _profile(case, d, "wheel", folder)
    if name:
        d.set("wheelrail", "wheel_profile", name, M.where(case, "FNAME(wheel)").replace("FNAME(wheel)", "WFNAME"))
    d.set("wheelrail", "wheel_radius", v("NOMRADW"), M.where(case, "NOMRADW"))
    d.set("wheelrail", "side", "left" if left else "right", f"C1 = {case.digits['C1']} (line "
                                                             f"{case.digit_lines['C1']})")
    d.set("wheelrail", "back_to_back", v("FBDIST"), M.where(case, "FBDIST"))
    d.set("wheelrail", "flange_back", v("FBPOS"), M.where(case, "FBPOS"))
    if v("YTAPE") is not None:
        d.ignore(f"YTAPE = {v('YTAPE'):.6g}: the tape circle's position (a report convention)")
    d.set("wheelrail", "y", -v("Y_WS") if left else v("Y_WS"), ("-" if left else "") + "Y_WS; " + M.where(case, "Y_WS"))
    d.set("wheelrail", "yaw", -v("YAW"), "-YAW; " + M.where(case, "YAW"))
    d.set("wheelrail", "roll", v("ROLL"), M.where(case, "ROLL"))
    if v("FZ_WS") is not None:
        d.set("wheelrail", "Fz", v("FZ_WS"), M.where(case, "FZ_WS"))
    if v("PITCH"):
        d.ignore(f"PITCH = {v('PITCH'):.6g} rad: a wheel is a body of revolution (its pitch angle changes nothing)")
    if v("S_WS"):
        d.ignore(f"S_WS = {v('S_WS'):.6g} mm: the track position (the profiles do not vary along the track)")
    d.set("wheelrail", "speed", v("VS_WS"), M.where(case, "VS_WS"))
    if v("VPITCH") is not None:
        d.set("wheelrail", "omega", -v("VPITCH"), "-VPITCH; " + M.where(case, "VPITCH"))
    for name in ("VY_WS", "VZ_WS", "VROLL", "VYAW"):
        if v(name):
            d.refuse(name, v(name), "needs a lateral, vertical, roll or yaw velocity of the wheelset",
                     case.line_of(name))
    for name in ("DXWHL", "DYWHL", "DZWHL", "DROLLW", "DYAWW", "DPITCHW", "VXWHL", "VYWHL", "VZWHL", "VROLLW",
                 "VYAWW", "VPITCHW"):
        if v(name):
            d.refuse(name, v(name), "needs flexible wheelset deviations", case.line_of(name))

"""The cases of a deck grouped into problems rollcontact can run as one, and each problem mapped onto a scene.

A case with T = 1 or 2 and P = 0 continues the tangential history of the previous computed case of its result
element (its 'previous time instance'); the cases so linked form one history: a shift history (T = 1: compression,
then shifts with prescribed forces, one case per step, as load.ft and load.levels with ramp_steps = 1) or a
transient rolling history (T = 2: from rest or from a Cattaneo shift, one case per rolling step DQ, as
[rolling] mode = "transient"). Every other computed case stands alone: frictionless compression (T = 0), one shift
from zero tractions (T = 1, P = 1, 2), steady rolling (T = 3), a wheel on its rail (module 1). Cases the reference
program only prepares (R = 2, 3) compute nothing and are skipped.

Conventions (rollcontact's README and docs/contact_decks.md): CONTACT's forces FX, FY act on body 1 (the upper
body) in the contact's x, y; in a shift the load on body 1 is their opposite, rollcontact's load.Ft along
load.load_angle; in rolling [rolling] Fx, Fy and xi, eta are along and to the left of the rolling direction CHI.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import math

from rollcontact.cases.decks import mapping as M
from rollcontact.cases.decks.case import Case
from rollcontact.cases.decks.draft import Draft, show

#: the values that must stay the same along one history (besides the digits L, M, C of the effective input)
STATIC = ("FN", "POISS1", "POISS2", "GG1", "GG2", "FSTAT", "FKIN", "IPOTCN", "A1", "B1", "AOB", "AA", "BB", "B",
          "IBASE", "IPLAN")


@dataclass
class Problem:
    """One problem: its cases (the head first), its kind and, once mapped, the draft scene, the scene's name and
    the step of the run that answers each case ({case number: step}) with what the figures need (`frame`)."""
    deck: str
    cases: list[Case]
    kind: str
    draft: Draft | None = None
    name: str = ""
    steps: dict = field(default_factory=dict)
    frame: dict = field(default_factory=dict)
    reason: str = ""
    geometry: object = None

    @property
    def numbers(self) -> list[int]:
        return [c.number for c in self.cases]

    @property
    def converted(self) -> bool:
        return self.draft is not None and self.draft.ok and self.kind not in ("skipped",)


def group(cases: list[Case]) -> list[Problem]:
    """The deck's cases as problems, in the order of the file (a history at the place of its head)."""
    problems: list[Problem] = []
    last: dict[tuple, Problem] = {}
    for case in cases:
        key = (case.module, case.element)
        if case.skipped:
            problems.append(Problem("", [case], "skipped", reason="R = %d: the reference program only prepares this "
                                                                  "case (nothing is computed)" % case.digits["R"]))
            continue
        dg = case.digits
        previous = last.get(key)
        if case.module == 3 and dg["T"] in (1, 2) and dg["P"] in (0, 3) and previous is not None:
            previous.cases.append(case)
            previous.kind = "history"
            continue
        kind = "wheelrail" if case.module == 1 else {0: "normal", 1: "single shift", 2: "single transient",
                                                     3: "steady"}[dg["T"]]
        problem = Problem("", [case], kind)
        problems.append(problem)
        last[key] = problem
    return problems


def map_problem(problem: Problem) -> Problem:
    """Fill problem.draft (and steps, frame) for a module-3 problem; the refusals are in draft.unsupported."""
    d = problem.draft = Draft()
    head = problem.cases[0]
    rolls = problem.kind in ("steady", "single transient") or any(c.digits["T"] == 2 for c in problem.cases)
    kind = "rolling" if rolls else ("normal" if problem.kind == "normal" else "shift")
    for case in problem.cases:
        M.map_digits(case, d)
        M.map_heat(case, d, kind)
    M.map_materials(head, d)
    M.map_friction(head, d, kind)
    M.map_normal_load(head, d)
    geo = M.map_geometry(head, d)
    for case in problem.cases[1:]:
        _same_static(head, case, d)
    if geo is None:
        return problem
    M.map_grid(head, d, geo)
    problem.geometry = geo
    problem.frame = {"x0": geo.x0, "y0": geo.y0, "spin_centre": (head.value("SPINXO", 0.0), head.value("SPINYO", 0.0)), "h_min": geo.h_min, "dx": geo.dx, "dy": geo.dy,
                     "mu_fn": (head.value("FKIN") or 0) * (head.value("FN") or 0), "K": M.difference_parameter(head)}
    kind = problem.kind
    if kind == "normal":
        _normal(problem, d)
    elif kind == "steady":
        _steady(problem, d, geo)
    elif kind in ("single shift", "single transient", "history"):
        rest = {c.digits["T"] for c in problem.cases[1:]}
        head_t = head.digits["T"]
        if kind == "single shift" or (rest == {1} and head_t in (0, 1)):
            problem.kind = "shift"
            _shift_history(problem, d, geo)
        elif kind == "single transient" or (rest == {2} and head_t in (0, 1, 2)):
            problem.kind = "transient"
            _transient(problem, d, geo)
        else:
            d.refuse(f"case {problem.cases[1].number}: control digit T (TANG)", sorted(rest),
                     f"continues the history of case {head.number} (T = {head_t}): needs a history that mixes "
                     "shifts and rolling, or one that starts from steady rolling", problem.cases[1].digit_lines["T"])
    for case in problem.cases:
        M.map_subsurface(case, d)
    return problem


def _same_static(head: Case, case: Case, d: Draft):
    """Refuse a history whose normal force, materials, friction or geometry changes from case to case."""
    for dig in ("N", "L", "M", "C"):
        a, b = head.effective.get(dig, head.digits[dig]), case.effective.get(dig, case.digits[dig])
        if dig == "N":
            a, b = head.digits["N"], case.digits["N"]
        if a != b:
            d.refuse(f"case {case.number}: {M.digit(case, dig)}", b, f"differs from case {head.number} ({a}) within "
                                                                      "one history", case.digit_lines[dig])
    for name in STATIC:
        a, b = head.value(name), case.value(name)
        if a != b and a is not None and b is not None:
            d.refuse(f"case {case.number}: {name}", b, f"differs from case {head.number} ({show(a)}) within one "
                                                       "history; rollcontact keeps the normal force, materials, "
                                                       "friction and geometry of a run", case.line_of(name))


def _normal(problem: Problem, d: Draft):
    """T = 0: the normal problem without friction (no tangential traction, also for coupled materials)."""
    head = problem.cases[0]
    if abs(M.difference_parameter(head)) >= M.QUASI_IDENTICAL:
        d.set("solver", "coupling", "off", f"T = 0 (line {head.digit_lines['T']}): frictionless compression")
    problem.steps = {head.number: 0}


# --- kinematics --------------------------------------------------------------------------------------------------
def _forces(case: Case, d: Draft, geo) -> tuple[float, float] | None:
    """(FX, FY) / (FSTAT FN) of a case with prescribed forces (F = 2, or F = 1 with CETA = CPHI = 0 on a contact
    symmetric in y); None, after a refusal, otherwise."""
    f = case.digits["F"]
    if f == 2:
        return case.value("FXREL"), case.value("FYREL")
    if f == 1:
        if case.value("CETA") == 0 and case.value("CPHI") == 0 and geo.symmetric_y:
            d.note(f"case {case.number}: F = 1 with CETA = 0, CPHI = 0 on a contact symmetric in y is posed as FY = 0 "
                   "(by symmetry the same solution)")
            return case.value("FXREL"), 0.0
        d.refuse(f"case {case.number}: {M.digit(case, 'F')}", 1,
                 f"needs a prescribed force FX with a prescribed creepage CETA = {case.value('CETA'):.6g} "
                 f"(CPHI = {case.value('CPHI'):.6g}); rollcontact prescribes both forces or both creepages",
                 case.digit_lines["F"])
        return None
    return None


def _rolling_common(case: Case, d: Draft, geo) -> float:
    """direction and speed of [rolling]; the rolling direction CHI (rad)."""
    chi = case.value("CHI")
    d.set("rolling", "direction", math.degrees(chi), M.where(case, "CHI") + " (rad, in degrees)")
    d.set("rolling", "speed", case.value("VELOC"), M.where(case, "VELOC"))
    dq = case.value("DQ")
    if abs(dq - geo.dx) > 1e-9 * geo.dx:
        d.note(f"DQ = {dq:.6g} mm differs from DX = {geo.dx:.6g} mm: the reference program's time step; rollcontact's "
               "steady state is discretised with one element")
    facphi = case.value("FACPHI")
    if facphi is not None and abs(facphi - 1 / 6) > 1e-9:
        d.note(f"FACPHI = {facphi:.6g}: the reference program's spin offset; rollcontact's is DQ/6")
    return chi


def _creepages(case: Case, geo) -> tuple[float, float, float]:
    """(xi, eta, phi) about the contact's centre (x0, y0), from CKSI, CETA, CPHI about the spin centre."""
    phi = case.value("CPHI")
    xo, yo = case.value("SPINXO", 0.0), case.value("SPINYO", 0.0)
    return case.value("CKSI") - phi * (geo.y0 - yo), case.value("CETA") + phi * (geo.x0 - xo), phi


def _set_kinematics(case: Case, d: Draft, geo, chi: float, origin: str) -> bool:
    """[rolling] xi, eta, phi or Fx, Fy (N) in the rolling frame; False after a refusal."""
    if case.digits["F"] == 0:
        xi, eta, phi = _creepages(case, geo)
        xi, eta = M.rotate(xi, eta, chi)
        d.set("rolling", "xi", xi, origin + M.where(case, "CKSI"))
        d.set("rolling", "eta", eta, M.where(case, "CETA"))
        d.set("rolling", "phi", phi, M.where(case, "CPHI"))
        if math.hypot(geo.x0, geo.y0) > 1e-9 * geo.dx or case.value("SPINXO") or case.value("SPINYO"):
            d.note("creepages turned to the contact's centre: xi = CKSI - CPHI (y0 - SPINYO), eta = CETA + CPHI "
                   "(x0 - SPINXO)")
        return True
    forces = _forces(case, d, geo)
    if forces is None:
        return False
    if case.value("CPHI"):
        d.set("rolling", "phi", case.value("CPHI"), M.where(case, "CPHI"))
    mu_fn = case.value("FKIN") * case.value("FN")
    fx, fy = M.rotate(forces[0] * mu_fn, forces[1] * mu_fn, chi)
    d.set("rolling", "Fx", fx, origin + "FX FSTAT FN; " + M.where(case, "FXREL", "FN"))
    d.set("rolling", "Fy", fy, "FY FSTAT FN" + (f"; {M.where(case, 'FYREL')}" if case.digits["F"] == 2 else ""))
    return True


def _steady(problem: Problem, d: Draft, geo):
    case = problem.cases[0]
    d.set("rolling", "mode", "steady", f"T = 3 (line {case.digit_lines['T']})")
    chi = _rolling_common(case, d, geo)
    _set_kinematics(case, d, geo, chi, "")
    problem.steps = {case.number: 0}
    problem.frame["chi"] = chi


def _tangential_load(case: Case, d: Draft, geo) -> tuple[float, float] | None:
    """The load on body 1 of a shift case, (-FX, -FY) / (FSTAT FN), or None after a refusal. A shift of zero
    (F = 0 with CKSI = CETA = CPHI = 0) on a symmetric contact is the zero load."""
    if case.value("CPHI"):
        d.refuse(f"case {case.number}: CPHI", case.value("CPHI"), "needs a rotation shift about z",
                 case.line_of("CPHI"))
        return None
    if case.digits["F"] == 0:
        if case.value("CKSI") == 0 and case.value("CETA") == 0 and geo.symmetric_y and geo.x0 == 0:
            d.note(f"case {case.number}: the shift CKSI = CETA = 0 on a symmetric contact is posed as zero "
                   "tangential force (by symmetry the same solution)")
            return 0.0, 0.0
        d.refuse(f"case {case.number}: {M.digit(case, 'F')}", 0,
                 f"needs a prescribed rigid shift (CKSI, CETA = {case.value('CKSI'):.6g}, {case.value('CETA'):.6g} "
                 "mm); rollcontact's shifts prescribe the tangential force", case.digit_lines["F"])
        return None
    forces = _forces(case, d, geo)
    return None if forces is None else (-forces[0], -forces[1])


def _shift_history(problem: Problem, d: Draft, geo):
    """Compression then shifts with prescribed forces: load.ft, load_angle and levels, one step per case."""
    head = problem.cases[0]
    coupled = abs(M.difference_parameter(head)) >= M.QUASI_IDENTICAL
    loads, numbers = [], []
    shifts = problem.cases if head.digits["T"] == 1 else problem.cases[1:]
    for case in shifts:
        load = _tangential_load(case, d, geo)
        if load is None:
            return
        loads.append(load)
        numbers.append(case.number)
    steps = {}
    if head.digits["T"] == 0:
        steps[head.number] = 0
        if coupled and shifts:
            d.refuse(M.digit(head, "T"), 0, f"frictionless compression then frictional shifts of coupled materials "
                                            f"(K = {M.difference_parameter(head):.3g}): rollcontact compresses with "
                                            "friction (Spence)", head.digit_lines["T"])
            return
    elif loads[0] == (0.0, 0.0):
        steps[numbers.pop(0)] = 0
        loads.pop(0)
    elif coupled:
        d.refuse("case %d: shift from zero tractions" % head.number, f"FX, FY = {-loads[0][0]:.6g}, {-loads[0][1]:.6g}",
                 f"needs the normal and tangential loads applied in one step to coupled materials (K = "
                 f"{M.difference_parameter(head):.3g}); rollcontact applies Fn first, then Ft", head.digit_lines["T"])
        return
    first = next((v for v in loads if v != (0.0, 0.0)), None)
    problem.frame["angle"] = 0.0
    if first is not None:
        angle = math.atan2(first[1], first[0])
        e = (math.cos(angle), math.sin(angle))
        signed = []
        for number, (lx, ly) in zip(numbers, loads):
            if abs(lx * e[1] - ly * e[0]) > 1e-9 * max(1.0, math.hypot(lx, ly)):
                d.refuse(f"case {number}: FX, FY", f"{-lx:.6g}, {-ly:.6g}", "needs a tangential force that turns "
                                                                             "within the history (rollcontact's "
                                                                             "levels keep one direction)")
                return
            signed.append(lx * e[0] + ly * e[1])
        d.set("load", "load_angle", math.degrees(angle) + 0.0, "direction of the load on body 1, -(FX, FY)")
        problem.frame["angle"] = angle
        d.set("load", "ramp_steps", 1, "one step per case")
        if signed[0] > 0:
            d.set("load", "ft", signed[0], f"-FX/(FSTAT FN) of case {numbers[0]}")
            signed_levels, level_cases = signed[1:], numbers[1:]
        else:
            signed_levels, level_cases = signed, numbers
        if signed_levels:
            d.set("load", "levels", signed_levels, "cases " + ", ".join(map(str, level_cases)))
    elif loads:
        d.set("load", "ramp_steps", 1, "")
        d.set("load", "levels", [0.0] * len(loads), "cases " + ", ".join(map(str, numbers)))
    for k, number in enumerate(numbers, start=1):
        steps[number] = k
    problem.steps = steps


def _transient(problem: Problem, d: Draft, geo):
    """Transient rolling (T = 2) from rest or from a Cattaneo shift: [rolling] mode = 'transient', one step per
    case, constant creepages or forces."""
    head = problem.cases[0]
    rolls = [c for c in problem.cases if c.digits["T"] == 2]
    start = rolls[0]
    coupled = abs(M.difference_parameter(head)) >= M.QUASI_IDENTICAL
    d.set("rolling", "mode", "transient", f"T = 2, cases {rolls[0].number}-{rolls[-1].number}")
    chi = _rolling_common(start, d, geo)
    problem.frame["chi"] = chi
    for case in rolls[1:]:
        for name in ("CHI", "DQ", "VELOC", "CKSI", "CETA", "CPHI", "FXREL", "FYREL", "SPINXO", "SPINYO"):
            if case.value(name) != start.value(name):
                d.refuse(f"case {case.number}: {name}", case.value(name),
                         f"differs from case {start.number}'s {start.value(name)!r}: rollcontact's transient keeps "
                         "its creepages or forces, direction, step and speed", case.line_of(name))
                return
        if case.digits["F"] != start.digits["F"]:
            d.refuse(f"case {case.number}: {M.digit(case, 'F')}", case.digits["F"], "changes within the history")
            return
    if not _set_kinematics(start, d, geo, chi, ""):
        return
    dq = start.value("DQ")
    d.set("rolling", "step", dq, M.where(start, "DQ"))
    d.set("rolling", "distance", dq * len(rolls), f"{len(rolls)} steps of DQ")
    if abs(dq - geo.dx) > 1e-9 * geo.dx:
        d.note("the reference program's T = 2 moves its grid with the contact by DQ per step; rollcontact rolls on a "
               "world-fixed grid (the same problem; the same discretisation when DQ = DX)")
    if coupled:
        d.refuse(M.digit(head, "T"), head.digits["T"], f"a transient of coupled materials (K = "
                                                       f"{M.difference_parameter(head):.3g}) started by a "
                                                       "frictionless or simultaneous loading: rollcontact's starts "
                                                       "from its own normal loading with friction",
                 head.digit_lines["T"])
        return
    if head.digits["T"] == 1:
        if not _cattaneo_matches(head, start, d, geo):
            return
        d.set("rolling", "initial", "cattaneo", f"case {head.number}: T = 1, a shift from zero tractions")
    else:
        d.set("rolling", "initial", "rest", f"case {head.number}" + (": T = 0" if head.digits["T"] == 0 else
                                                                    ": T = 2 from zero tractions"))
    steps = {head.number: 0} if head is not start else {}      # step 0: the initial state
    for k, case in enumerate(rolls):
        steps[case.number] = 1 + k
    problem.steps = steps


def _cattaneo_matches(head: Case, start: Case, d: Draft, geo) -> bool:
    """The Cattaneo state of rollcontact is the load of one rolling step at rest: the head's forces equal the
    rolling forces, or its shift equals DQ times the creepages."""
    if start.digits["F"] != 0:
        load = _tangential_load(head, d, geo)
        forces = _forces(start, d, geo)
        if load is None or forces is None:
            return False
        ok = math.isclose(-load[0], forces[0], abs_tol=1e-12) and math.isclose(-load[1], forces[1], abs_tol=1e-12)
        what = f"FX, FY = {-load[0]:.6g}, {-load[1]:.6g} (the rolling cases' {forces[0]:.6g}, {forces[1]:.6g})"
    else:
        dq = start.value("DQ")
        want = [dq * v for v in _creepages(start, geo)]
        have = [head.value("CKSI"), head.value("CETA"), head.value("CPHI")] if head.digits["F"] == 0 else None
        ok = have is not None and all(math.isclose(h, w, rel_tol=1e-6, abs_tol=1e-15) for h, w in zip(have, want))
        what = f"shift {have} (DQ times the creepages: {want})"
    if not ok:
        d.refuse(f"case {head.number}: initial shift", what, "needs an initial shift other than one rolling step's "
                                                             "load (rollcontact's initial = 'cattaneo')",
                 head.digit_lines["T"])
    return ok

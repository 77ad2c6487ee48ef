"""A converted problem run and its figures set beside the reference output's, case by case, in CONTACT's
conventions: forces FX, FY on body 1 in the contact's x, y (module 1: on the rail), MZ about the contact's origin,
creepages or shifts where the program solves for them, the approach of the undeformed distance as the deck gives
it, the maximum pressure, the areas in contact and in adhesion (elements times dx dy), and the traction where the
output prints it (O = 5).

Differences: forces and MZ relative to mu FN (MZ: mu FN c, c = sqrt(area / pi)), creepages, shifts, approach,
pressure and areas relative to the reference value, the traction as the rms over the elements both grids share, of
the pressure relative to the reference PMAX and of |pt| relative to mu PMAX. All in per cent.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import math
import time

import numpy as np

from rollcontact.cases.decks.refout import CaseOutput


@dataclass
class Comparison:
    """The figures of one problem: `rows` one dict per case and quantity (case, quantity, reference, rollcontact,
    difference in %, the scale it is relative to), the CPU time of the run (s) and its grid."""
    name: str
    kind: str
    rows: list = field(default_factory=list)
    seconds: float = 0.0
    grid: tuple = ()
    status: str = "complete"

    def add(self, case: int, quantity: str, reference, ours, scale: float | None = None):
        if reference is None or ours is None or not np.isfinite(ours):
            return
        scale = abs(reference) if scale is None else scale
        if not scale > 0:
            return
        self.rows.append({"case": case, "quantity": quantity, "reference": float(reference), "rollcontact":
                          float(ours), "difference": 100.0 * (float(ours) - float(reference)) / scale})

    def largest(self) -> dict:
        """{quantity: the largest |difference| (%) over the cases}."""
        out = {}
        for r in self.rows:
            q = r["quantity"]
            out[q] = max(out.get(q, 0.0), abs(r["difference"]))
        return out


def compare_problem(problem, scene, reference: dict[int, CaseOutput]) -> Comparison:
    """Run the problem's scene (all fields stored) and compare each of its cases with `reference`."""
    import rollcontact
    scene = scene.with_overrides({"output.fields": "all"}) if problem.kind != "wheelrail" else scene
    t0 = time.process_time()
    result = rollcontact.run(scene)
    seconds = time.process_time() - t0
    cmp = Comparison(problem.name, problem.kind, seconds=seconds, status=result.status)
    if result.status != "complete":
        return cmp
    if problem.kind == "wheelrail":
        _wheelrail(problem, result, reference, cmp)
        return cmp
    cmp.grid = (len(result.x), len(result.y))
    for number, step in problem.steps.items():
        ref = reference.get(number)
        if ref is not None:
            _case(problem, result, step, ref, number, cmp)
    return cmp


def _case(problem, result, step: int, ref: CaseOutput, number: int, cmp: Comparison):
    f, h = problem.frame, result.history
    mu_fn = f["mu_fn"]
    chi = f.get("chi", 0.0)
    c, s = math.cos(chi), math.sin(chi)
    if problem.kind == "steady":
        sm = result.summary
        fx_r, fy_r = sm["F_x"], sm["F_y"]                     # on body 1, rolling frame
        creep = (sm["xi"], sm["eta"])
    else:
        fx_r, fy_r = -h["F_x"][step], -h["F_y"][step]          # history: on the substrate
        creep = (h["xi"][step], h["eta"][step]) if "xi" in h else None
    fx, fy = fx_r * c - fy_r * s, fx_r * s + fy_r * c
    cmp.add(number, "FX", ref.find("FX"), fx, mu_fn)
    cmp.add(number, "FY", ref.find("FY"), fy, mu_fn)
    area = float(h["contact_area"][step])
    if problem.kind == "steady" and area > 0:
        mz = result.summary["M_z"] + f["x0"] * fy - f["y0"] * fx
        cmp.add(number, "MZ", ref.find("MZ"), mz, mu_fn * math.sqrt(area / math.pi))
    if creep is not None and problem.kind in ("steady", "transient"):
        cx, cy = creep[0] * c - creep[1] * s, creep[0] * s + creep[1] * c
        phi, (xo, yo) = (result.summary.get("phi") or 0.0), f.get("spin_centre", (0.0, 0.0))
        cx, cy = cx + phi * (f["y0"] - yo), cy - phi * (f["x0"] - xo)     # about the deck's spin centre
        for label, ours in (("CREEP_X", cx), ("CREEP_Y", cy)):
            cmp.add(number, label.replace("_", " "), ref.find(label), ours)
    if problem.kind == "shift" and step > 0:
        for label, key in (("SHIFT_X", "U_x"), ("SHIFT_Y", "U_y")):
            cmp.add(number, label.replace("_", " "), ref.find(label), h[key][step] - h[key][step - 1])
    cmp.add(number, "approach", ref.find("APPROACH"), h["approach"][step] + f["h_min"])
    pressure = _field(result, "p", step)
    if pressure is not None:
        cmp.add(number, "PMAX", ref.find("PMAX"), float(pressure.max()))
    da = f["dx"] * f["dy"]
    for label, key in (("NCON", "contact_area"), ("NADH", "stick_area")):
        n = ref.find(label)
        cmp.add(number, "contact area" if label == "NCON" else "adhesion area", None if n is None else n * da,
                float(h[key][step]))
    if ref.traction and pressure is not None:
        _traction(problem, result, step, ref, number, cmp)


def _field(result, name: str, step: int):
    steps = list(result.field_steps) if result.field_steps is not None else []
    if step not in steps:
        return None
    return np.asarray(result.field(name, step))


def _traction(problem, result, step: int, ref: CaseOutput, number: int, cmp: Comparison):
    """rms differences of pn and |pt| over the elements whose centres coincide (rolling frame for rolling)."""
    f = problem.frame
    chi = f.get("chi", 0.0)
    x = np.asarray(ref.traction["x"]) - f["x0"]
    y = np.asarray(ref.traction["y"]) - f["y0"]
    xr, yr = x * math.cos(chi) + y * math.sin(chi), -x * math.sin(chi) + y * math.cos(chi)
    gx, gy = np.asarray(result.x), np.asarray(result.y)
    dx, dy = gx[1] - gx[0], gy[1] - gy[0]
    ix, iy = np.rint((xr - gx[0]) / dx).astype(int), np.rint((yr - gy[0]) / dy).astype(int)
    ok = (ix >= 0) & (ix < len(gx)) & (iy >= 0) & (iy < len(gy))
    ok &= np.abs(gx[np.clip(ix, 0, len(gx) - 1)] - xr) < 1e-3 * dx
    ok &= np.abs(gy[np.clip(iy, 0, len(gy) - 1)] - yr) < 1e-3 * dy
    if ok.sum() < max(1, 0.9 * len(x)):
        return                                   # the grids do not share the elements
    p = _field(result, "p", step)
    tx, ty = _field(result, "tau_x", step), _field(result, "tau_y", step)
    pmax = ref.find("PMAX") or float(np.max(ref.traction["pn"]))
    mu = f["mu_fn"] / max(ref.find("FN") or 1.0, 1e-300)
    pn = np.asarray(ref.traction["pn"])[ok]
    pt = np.asarray(ref.traction["abs_pt"])[ok]
    ours_p = p[iy[ok], ix[ok]]
    ours_t = np.hypot(tx, ty)[iy[ok], ix[ok]]
    rms_p = float(np.sqrt(np.mean((ours_p - pn) ** 2)))
    rms_t = float(np.sqrt(np.mean((ours_t - pt) ** 2)))
    cmp.rows.append({"case": number, "quantity": "traction pn (rms)", "reference": pmax, "rollcontact": rms_p,
                     "difference": 100.0 * rms_p / pmax})
    cmp.rows.append({"case": number, "quantity": "traction |pt| (rms)", "reference": mu * pmax, "rollcontact": rms_t,
                     "difference": 100.0 * rms_t / (mu * pmax)})


def _wheelrail(problem, result, reference: dict[int, CaseOutput], cmp: Comparison):
    """The largest patch and the totals, in rollcontact's conventions turned back (docs/wheelrail.md)."""
    number = problem.numbers[0]
    ref = reference.get(number)
    if ref is None or not ref.patches or not result.patches:
        return
    ours = max(result.patches, key=lambda p: p.values["Fn"]).values
    k = max(range(len(ref.patches)), key=lambda i: ref.find("FN", patch=i) or 0.0)
    mu = problem.draft.sections["load"]["mu"]
    mu_fn = mu * (ref.find("FN", patch=k) or ours["Fn"])
    cmp.grid = (len(ref.patches), int(result.summary["n_patches"]))
    cmp.add(number, "FN", ref.find("FN", patch=k), ours["Fn"])
    cmp.add(number, "FX", ref.find("FX", patch=k), -ours["Fx"], mu_fn)
    cmp.add(number, "FS", ref.find("FS", patch=k), ours["Fy"], mu_fn)
    cmp.add(number, "PMAX", ref.find("PMAX", patch=k), ours["pmax"])
    cmp.add(number, "approach", ref.find("APPROACH", patch=k), ours["penetration"])
    cmp.add(number, "CKSI", ref.find("CKSI", patch=k), -ours["xi"])
    cmp.add(number, "CETA", ref.find("CETA", patch=k), ours["eta"])
    cmp.add(number, "CPHI", ref.find("CPHI", patch=k), ours["phi"])
    n = ref.find("NCON", patch=k)
    dx, ds = problem.draft.sections["grid"]["dx"], problem.draft.sections["grid"]["dy"]
    cmp.add(number, "contact area", None if n is None else n * dx * ds, ours["contact_elements"] * ours["dx"] *
            ours["dy"])
    n = ref.find("NADH", patch=k)
    cmp.add(number, "adhesion area", None if n is None else n * dx * ds, ours["stick_elements"] * ours["dx"] *
            ours["dy"])
    fz = ref.find("FZ(TR)") or 1.0
    s = result.summary
    cmp.add(number, "FX(TR)", ref.find("FX(TR)"), -s["F_track_x"], mu * fz)
    cmp.add(number, "FY(TR)", ref.find("FY(TR)"), s["F_track_y"], mu * fz)

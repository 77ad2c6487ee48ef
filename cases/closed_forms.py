"""The closed-form shakedown limits of oscillating rolling (seed Eqs. 12-21, docs/theory.md §8; solver.mdr.limits) as
one report: what `rollcontact limits` prints and `rollcontact.limits` returns.

Dimensionless (seed Eq. 9): w = W/a, f_t = Ft/(mu Fn), u = U/U0 with U0 = mu E* d/G*. Without `angle` or `kappa` the
three reference kappas are reported side by side: parallel (1.0) and perpendicular (1.1), the seed's fits to CONTACT
and experiments, and 1.5, the pure MDR (seed Eq. 12); `angle` uses solver.mdr.limits.kappa_for_angle (sin^2
interpolation between 0 and 90 deg, an assumption).
"""
from __future__ import annotations

from dataclasses import dataclass, field

from rollcontact.bem.errors import InputError
from rollcontact.cases.arguments import arg

#: table rows: fractions of the largest f_t,lim shown
TABLE_FRACTIONS = (0.0, 0.25, 0.5, 0.75, 0.9, 1.0)


@dataclass
class Limits:
    """The closed forms at `w` and/or `ft` for each of `kappas` [(label, kappa)]: u_lim (seed Eq. 17), f_t,lim
    (Eqs. 18-19) and a table of u_stat and u_sd against f_t (at w), w_lim (at ft), and the state at (ft, w): shakedown
    with u_sd, beyond the limit (with the seed's ratcheting regression Eqs. 20-21 where it applies) or gross sliding.
    Values in `values` (name -> number or {label: number}); `report()` is the text `rollcontact limits` prints."""
    w: float | None
    ft: float | None
    kappas: list
    setting: str | None = None
    values: dict = field(default_factory=dict)
    lines: list = field(default_factory=list)

    def report(self) -> str:
        return "\n".join(self.lines)

    def __repr__(self) -> str:
        return f"Limits(w={self.w}, ft={self.ft}, kappas={[k for _, k in self.kappas]})"


def _kappas(angle, kappa):
    from rollcontact.solver.mdr import limits as lim
    if kappa is not None:
        lim.check_kappa(kappa)
        return [("given", float(kappa))]
    if angle is not None:
        return [(f"angle={angle:g}deg", lim.kappa_for_angle(angle))]
    return [("parallel", lim.KAPPA_PARALLEL), ("perpendicular", lim.KAPPA_PERPENDICULAR),
            ("pure MDR", lim.KAPPA_MDR)]


def _setting(angle, kappa):
    """'parallel'/'perpendicular' when the seed's ratcheting regression (Eqs. 20-21) applies, else None."""
    if kappa is not None or angle is None:
        return None
    return {0.0: "parallel", 180.0: "parallel", 90.0: "perpendicular"}.get(float(angle))


def closed_form_limits(w=None, ft=None, angle=None, kappa=None) -> Limits:
    """The Limits at `w` and/or `ft` (at least one); InputError naming the argument out of its range (w, f_t in
    [0, 1], 0 < kappa <= 1.5, 0 <= angle <= 180)."""
    from rollcontact.solver.mdr import limits as lim
    if w is None and ft is None:
        raise InputError(f"give {arg('w')} (amplitude W/a) and/or {arg('ft')} (load ratio Ft/(mu Fn))")
    if angle is not None and kappa is not None:
        raise InputError(f"give either {arg('angle')} or {arg('kappa')}, not both")
    kappas = _kappas(angle, kappa)
    if w is not None:
        lim.check_w(w)
    if ft is not None:
        lim.check_ft(ft)
    out = Limits(None if w is None else float(w), None if ft is None else float(ft), kappas, _setting(angle, kappa))
    lines, values = out.lines, out.values
    lines.append("kappa (seed Eq. 13): " + ", ".join(f"{label} {k:g}" for label, k in kappas))
    if w is not None:
        w = float(w)
        lines.append(f"w = W/a = {w:g}")
        values["u_lim"] = lim.u_lim(w)
        lines.append(f"  u_lim = 1 - w^2 = {values['u_lim']:.6f}   (seed Eq. 17, independent of kappa)")
        limits = [lim.f_t_lim(w, k) for _, k in kappas]
        values["f_t_lim"] = {label: f for (label, _), f in zip(kappas, limits)}
        for (label, k), f in zip(kappas, limits):
            lines.append(f"  f_t,lim = {f:.6f}   ({label}, kappa = {k:g})")
        head = "  f_t        u_stat   " + "".join(f"  u_sd[{label}]".ljust(22) for label, _ in kappas)
        lines.append(head.rstrip())
        for frac in TABLE_FRACTIONS:
            f = frac * max(limits)
            row = f"  {f:<9.6f}  {lim.u_stat(f):.6f} "
            for (_, k), fl in zip(kappas, limits):
                cell = f"{lim.u_shakedown(f, w, k):.6f}" if f <= fl else "ratcheting"
                row += f"  {cell:<20}"
            lines.append(row.rstrip())
    if ft is not None:
        f = float(ft)
        values["u_stat"] = lim.u_stat(f)
        lines.append(f"f_t = Ft/(mu Fn) = {f:g}   (u_stat = {values['u_stat']:.6f}, seed Eq. 4)")
        values["w_lim"] = {label: lim.w_lim(f, k) for label, k in kappas}
        for label, k in kappas:
            lines.append(f"  w_lim = {values['w_lim'][label]:.6f}   ({label}, kappa = {k:g})")
    if w is not None and ft is not None:
        _state_lines(out, lim, float(ft), float(w))
    return out


def _state_lines(out: Limits, lim, f: float, w: float):
    """The state at (f_t, w) for each kappa."""
    if f >= 1.0:  # Ft >= mu Fn: no static equilibrium, not a ratchet (a run reports gross_sliding)
        out.values["state"] = "gross_sliding"
        out.lines.append(f"  at (f_t, w) = ({f:g}, {w:g}): gross sliding (Ft >= mu Fn: the contact slides as a "
                         "whole, no shakedown and no ratchet rate)")
        return
    out.values["state"] = {}
    for label, k in out.kappas:
        if f <= lim.f_t_lim(w, k):
            out.values["state"][label] = "shakedown"
            out.lines.append(f"  at (f_t, w) = ({f:g}, {w:g}): shakedown, u_sd = {lim.u_shakedown(f, w, k):.6f}"
                             f"   ({label})")
        else:
            out.values["state"][label] = "ratcheting"
            msg = f"  at (f_t, w) = ({f:g}, {w:g}): beyond the limit, ratcheting ({label})"
            if out.setting is not None or label in ("parallel", "perpendicular"):
                s = out.setting or label
                msg += (f"; seed regression Eq. {20 if s == 'parallel' else 21}: du per period ~ "
                        f"{lim.ratcheting_increment(f, w, s):.4f} (empirical fit)")
            out.lines.append(msg)

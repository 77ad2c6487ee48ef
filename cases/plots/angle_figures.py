"""The alignment study of a sweep folder (`rollcontact plot OUTDIR` on a sweep over motion.angle): how the
shakedown behaviour depends on the angle theta between Ft and the rolling direction (the seed's open question I).

`<folder>_angles`, six panels against theta (folded to 0..90 deg: theta, -theta and 180 - theta are mirror
images of one another, docs/theory.md §11.1):
* kappa of seed Eq. 13 fitted per angle over its shaken-down runs (least squares, +- its standard error), with
  the interpolation kappa(theta) = kappa_par cos^2(theta) + kappa_perp sin^2(theta) between the fits at 0 and 90;
* u_sd = U_sd/U0 per (f_t, w) of the shaken-down runs;
* du = dU/U0 per period of the ratcheting runs, and their sideways walk du_perp = dU_perp/U0 per period;
* the sideways offset U_perp/U0 at which the shaken-down runs come to rest;
* f_t,lim from limits.csv (a limit search with motion.angle varied), bracket as error bar, against the
  angle-free bound 1 - 1.5 w + 0.5 w^3 (kappa = 3/2, docs/theory.md §8.4) and the seed's Eqs. 18-19 at 0 and 90 deg.
`angle_fit_text` gives the same numbers as text, with the largest error of both closed forms.
Units: f_t = Ft/(mu Fn), w = W/a, u = U/U0 (seed Eq. 9), theta in degrees.
"""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from rollcontact.solver.mdr import limits as lim

from rollcontact.cases.plots.common import MDR_COLOUR, PARALLEL_COLOUR, PERPENDICULAR_COLOUR


def _study(points):
    """The 3-D runs with rolling (w > 0): the runs of the alignment study."""
    return [p for p in points if not p.mdr and p.w > 0]


def study_angles(points) -> list[float]:
    """The alignments (deg, folded to 0..90) of the study's runs."""
    return sorted({round(p.angle, 6) for p in _study(points)})


def kappa_by(points, key) -> dict:
    """key(point) -> fit_kappa (seed Eq. 13) over the runs with w > 0 that share that key and that Eq. 13 describes
    (shaken down under constant loads, `cases.plots.sweep_figures.Point.on_eq13`)."""
    fits = {}
    for g in sorted({key(p) for p in points}):
        sel = [p for p in points if key(p) == g and p.on_eq13 and p.w > 0]
        if sel:
            try:
                fits[g] = lim.fit_kappa([p.f_t for p in sel], [p.w for p in sel], [p.u_sd for p in sel])
            except ValueError:
                pass
    return fits


def angle_kappas(points) -> dict:
    """angle -> fit_kappa over the angle's shaken-down runs (limit-search probes excluded when the folder has sweep
    runs, as for the other figures)."""
    pts = [p for p in _study(points) if not p.probe] or _study(points)
    return kappa_by(pts, lambda p: round(p.angle, 6))


def kappa_interpolation(fits):
    """kappa(theta) = kappa(0) cos^2 + kappa(90) sin^2 from the fits at 0 and 90 deg; None without both."""
    if 0.0 not in fits or 90.0 not in fits:
        return None
    k0, k90 = fits[0.0].kappa, fits[90.0].kappa
    return lambda theta: k0 * np.cos(np.radians(theta)) ** 2 + k90 * np.sin(np.radians(theta)) ** 2


def lens_bound(w):
    """The angle-free closed form proposed for f_t,lim: 1 - 1.5 w + 0.5 w^3 (kappa = 3/2, docs/theory.md §8.4)."""
    w = np.asarray(w, dtype=float)
    return 1.0 - 1.5 * w + 0.5 * w ** 3


def _limit_rows(limits):
    """limits.csv rows of f_t,lim searches (w fixed): (angle, w, f_t midpoint, lower, upper)."""
    return [(round(r["angle"], 6), round(r["w"], 6), r["f_t"], r["f_t"] - r["f_err"][0][0],
             r["f_t"] + r["f_err"][1][0]) for r in limits if r.get("f_err") is not None]


def angle_fit_text(points, limits) -> str:
    """kappa per angle, the largest error of the cos^2/sin^2 interpolation, and of the lens bound against the
    limit-search brackets."""
    fits = angle_kappas(points)
    lines = ["alignment study (theta folded to 0..90 deg):"]
    for a, f in fits.items():
        err = f"+- {f.stderr:.3f}" if f.stderr is not None else "(one run)"
        lines.append(f"  theta = {a:g} deg: kappa = {f.kappa:.3f} {err} (n = {f.n})")
    interp = kappa_interpolation(fits)
    if interp is not None:
        worst = max(fits, key=lambda a: abs(fits[a].kappa - interp(a)))
        lines.append(f"  kappa(theta) = {fits[0.0].kappa:.3f} cos^2 + {fits[90.0].kappa:.3f} sin^2: largest error "
                     f"{fits[worst].kappa - interp(worst):+.3f} at {worst:g} deg")
    rows = _limit_rows(limits)
    if rows:
        errs = [(mid - float(lens_bound(w)), a, w, lo <= lens_bound(w) <= hi) for a, w, mid, lo, hi in rows]
        e, a, w, _ = max(errs, key=lambda t: abs(t[0]))
        inside = sum(t[3] for t in errs)
        lines.append(f"  f_t,lim = 1 - 1.5 w + 0.5 w^3: largest error {e:+.4f} (bracket midpoint minus formula) at "
                     f"theta = {a:g} deg, w = {w:g}; inside {inside} of {len(errs)} brackets")
    return "\n".join(lines)


def _by(points, key):
    groups = {}
    for p in points:
        groups.setdefault(key(p), []).append(p)
    return {k: sorted(v, key=lambda p: p.angle) for k, v in sorted(groups.items())}


def angle_figure(points, limits, title):
    """The six panels of the module docstring."""
    fig, axes = plt.subplots(2, 3, figsize=(15, 8.5), layout="constrained")
    theta = np.linspace(0, 90, 181)
    study = [p for p in _study(points) if not p.probe] or _study(points)
    ws = sorted({round(p.w, 6) for p in study})
    cmap = plt.get_cmap("viridis")

    fts = sorted({round(p.f_t, 6) for p in study})

    def colour(w):
        k = ws.index(w) if w in ws else 0
        return cmap(0.15 + 0.7 * k / max(len(ws) - 1, 1))

    def line(f_t):     # colour: w; line style: f_t
        return ("-", "--", ":", "-.")[fts.index(f_t) % 4 if f_t in fts else 0]

    ax = axes[0, 0]
    fits = angle_kappas(points)
    if fits:
        a = np.array(list(fits))
        ax.errorbar(a, [fits[x].kappa for x in a], yerr=[fits[x].stderr or 0.0 for x in a], fmt="o", color="k",
                    capsize=3, label="fitted per angle (Eq. 13), ± standard error")
    interp = kappa_interpolation(fits)
    if interp is not None:
        ax.plot(theta, interp(theta), "-", color="0.4", lw=1, label="κ(0°) cos²θ + κ(90°) sin²θ")
    ax.axhline(lim.KAPPA_PARALLEL, ls=":", color=PARALLEL_COLOUR, lw=1, label="seed κ = 1 (W ∥ Ft)")
    ax.axhline(lim.KAPPA_PERPENDICULAR, ls="-", color=PERPENDICULAR_COLOUR, lw=1, label="seed κ = 1.1 (W ⊥ Ft)")
    ax.axhline(lim.KAPPA_MDR, ls="-.", color=MDR_COLOUR, lw=0.8, label="pure MDR κ = 3/2")
    ax.set_ylabel("κ (seed Eq. 13)")
    ax.legend(fontsize=7)

    ax = axes[0, 1]
    for (f_t, w), sel in _by([p for p in study if p.on_eq13], lambda p: (round(p.f_t, 6), round(p.w, 6))).items():
        ax.plot([p.angle for p in sel], [p.u_sd for p in sel], "o", ls=line(f_t), color=colour(w), ms=4, lw=1,
                label=f"f_t={f_t:g}, w={w:g}")
    ax.set_ylabel("$u_{sd} = U_{sd}/U_0$ (shakedown runs)")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=6, ncol=2)

    ratcheting = _by([p for p in study if p.state == "ratcheting" and p.du is not None],
                     lambda p: (round(p.f_t, 6), round(p.w, 6)))
    panels = ((axes[1, 0], lambda p: p.du, "Δu = ΔU/U₀ per period along Ft (ratcheting runs)"),
              (axes[1, 1], lambda p: p.du_perp, "Δu⊥ = ΔU⊥/U₀ per period across Ft (ratcheting runs)"))
    for ax, value, label in panels:
        for (f_t, w), sel in ratcheting.items():
            pts = [(p.angle, value(p)) for p in sel if value(p) is not None]
            if pts:
                ax.plot(*zip(*pts), "o", ls=line(f_t), color=colour(w), ms=4, lw=1, label=f"f_t={f_t:g}, w={w:g}")
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_ylabel(label)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)

    ax = axes[1, 2]
    for (f_t, w), sel in _by([p for p in study if p.on_eq13 and p.u_perp is not None],
                             lambda p: (round(p.f_t, 6), round(p.w, 6))).items():
        ax.plot([p.angle for p in sel], [p.u_perp for p in sel], "o", ls=line(f_t), color=colour(w), ms=4, lw=1,
                label=f"f_t={f_t:g}, w={w:g}")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_ylabel("u⊥ = U⊥/U₀ where the shaken-down runs rest")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=6, ncol=2)

    ax = axes[0, 2]
    rows = _limit_rows(limits)
    for w in sorted({r[1] for r in rows}):
        sel = sorted(r for r in rows if r[1] == w)
        c = colour(w)
        ax.errorbar([r[0] for r in sel], [r[2] for r in sel], yerr=[[r[2] - r[3] for r in sel],
                    [r[4] - r[2] for r in sel]], fmt="o", color=c, capsize=3, label=f"3-D bracket, w = {w:g}")
        ax.axhline(float(lens_bound(w)), color=c, lw=1, ls="-.")
        ax.plot([0, 90], [lim.f_t_lim(w, lim.KAPPA_PARALLEL), lim.f_t_lim(w, lim.KAPPA_PERPENDICULAR)], "x",
                color=c, ms=8, mew=1.5)
    if rows:
        ax.plot([], [], "k-.", lw=1, label="1 - 1.5w + 0.5w³ (κ = 3/2)")
        ax.plot([], [], "kx", label="seed Eqs. 18 (0°), 19 (90°)")
        ax.legend(fontsize=7)
    else:
        ax.text(0.5, 0.5, "no limits.csv with f_t,lim brackets in the folder\n(rollcontact limit-search --vary "
                "motion.w=... --vary motion.angle=...)", ha="center", va="center", fontsize=8,
                transform=ax.transAxes)
    ax.set_ylabel("$f_{t,lim}$")
    for ax in axes.ravel():
        ax.set_xlabel("θ: rolling direction against Ft (deg)")
        ax.set_xlim(-3, 93)
        ax.set_xticks(range(0, 91, 15))
        ax.grid(alpha=0.3)
    fig.suptitle(f"Alignment study: {title} ({len(study)} runs, {len(study_angles(points))} angles; colour: w, "
                 "line style: f_t)", fontsize=10)
    return fig

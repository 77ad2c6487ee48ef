"""Sweep figure of a folder whose runs are not of a sphere (`rollcontact plot OUTDIR` on a cone, power-law or
rounded-flat-punch sweep; issue #27): the seed's closed forms (kappa curves, Eqs. 12-21) hold for the sphere only,
so the runs are compared with the MDR of their own profile (docs/theory.md §8.3 for any profile, solver.mdr.exact).

* <folder>_usd: u_sd versus f_t of the shaken-down runs (o parallel, ^ perpendicular, s the 1-D MDR model) with
  the profile's MDR u_sd(f_t) at each w and its end point (f_t,lim, u_lim), the profile's u_stat (w = 0) and, when
  the folder holds limits.csv (rollcontact limit-search), the 3-D limit brackets as shaded bands. The table of the
  points goes to the terminal.

Normalisations as everywhere (seed Eq. 9): u = U/U0, U0 = mu E* d/G* with d the profile's MDR approach,
f_t = Ft/(mu Fn), w = W/a with a the profile's MDR contact radius.
"""
from __future__ import annotations

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.lines import Line2D

from rollcontact.cases.plots.common import FIGSIZE, MDR_COLOUR, save_figure, setting_colour, setting_of

MARKERS = {"parallel": "o", "perpendicular": "^"}


def shape_usd_figure(points, scene, limits, title):
    """u_sd versus f_t against the MDR of the runs' own profile (module docstring)."""
    tg = scene.tangential_reference
    a = scene.contact_radius
    fig, ax = plt.subplots(figsize=FIGSIZE["usd"], layout="constrained")
    f = np.linspace(0, 0.999, 300)
    ax.plot(f, [tg.shift(x) / tg.U0 for x in f], "-", color="k", lw=1.0, label="MDR $u_{stat}$ (w = 0)")
    for w in sorted({round(p.w, 6) for p in points if p.w > 0}):
        f_lim, u_lim = tg.limit(w * a)
        ff = np.linspace(0, f_lim, 200)
        ax.plot(ff, [tg.shakedown_shift(x, w * a) for x in ff], "-.", color=MDR_COLOUR, lw=1.2,
                label=f"MDR $u_{{sd}}$ of the profile, w = {w:g} (docs/theory.md §8.3)")
        ax.plot(f_lim, u_lim, "o", color=MDR_COLOUR, ms=5)
        ax.annotate(f"MDR limit {f_lim:.3f}", (f_lim, u_lim), xytext=(6, -10), textcoords="offset points", fontsize=8)
    for r in limits:                       # f_err = [[below], [above]] of read_limits
        if r["f_err"] is not None:
            ax.axvspan(r["f_t"] - r["f_err"][0][0], r["f_t"] + r["f_err"][1][0], color=setting_colour(r["angle"]),
                       alpha=0.25)
    handles = ax.get_legend_handles_labels()[0]
    for group in sorted({p.group for p in points}):
        sel = [p for p in points if p.group == group and p.on_eq13]
        for p in sel:
            colour = MDR_COLOUR if p.mdr else setting_colour(p.angle)
            ax.plot(p.f_t, p.u_sd, "s" if p.mdr else MARKERS.get(p.setting, "D"), color=colour, mec="k", ms=7)
        if sel:
            p = sel[0]
            handles.append(Line2D([], [], ls="none", marker="s" if p.mdr else MARKERS.get(p.setting, "D"),
                                  color=MDR_COLOUR if p.mdr else setting_colour(p.angle), mec="k",
                                  label=f"simulated, {group}"))
    if limits:
        handles.append(Line2D([], [], lw=8, color="0.6", alpha=0.4, label="3-D limit bracket (limits.csv)"))
    ax.legend(handles=handles, fontsize=8, loc="upper left")
    ax.set_xlabel("$f_t = F_t/(\\mu F_n)$")
    ax.set_ylabel("$u_{sd} = U_{sd}/U_0$")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.02)
    ax.grid(alpha=0.3)
    n_rat = sum(not p.on_eq13 for p in points)
    ax.set_title(f"Shakedown displacement, {scene.shape} profile: {title}\n{len(points)} runs, {n_rat} not in "
                 "shakedown (not shown); curves: the MDR of this profile", fontsize=10)
    return fig


def plot_shape_folder(points, scene, limits, out_dir, stem, title, out=print, overwrite=False) -> list:
    """The u_sd figure of a non-sphere sweep folder, and its points as a table on `out`."""
    tg = scene.tangential_reference
    a = scene.contact_radius
    out(f"{scene.shape} profile: MDR contact radius a = {a:.4g} mm, U0 = {tg.U0:.4g} mm")
    out(f"{'setting':24s} f_t     w       state        u_sd     MDR u_sd")
    for p in sorted(points, key=lambda q: (q.group, q.w, q.f_t)):
        mdr = tg.shakedown_shift(p.f_t, p.w * a) if p.w > 0 else tg.shift(p.f_t) / tg.U0
        out(f"{p.group:24s} {p.f_t:5.3f}  {p.w:6.3f}  {p.state:11s}  "
            f"{'-' if p.u_sd is None else f'{p.u_sd:.4f}':7s}  {'ratchets' if mdr is None else f'{mdr:.4f}'}")
    for w in sorted({round(p.w, 6) for p in points if p.w > 0}):
        f_lim, u_lim = tg.limit(w * a)
        out(f"MDR limit at w = {w:g}: f_t,lim = {f_lim:.4f}, u_lim = {u_lim:.4f}")
    for r in limits:
        if r["f_err"] is not None:
            out(f"3-D limit (limits.csv), {setting_of(r['angle'])}, w = {r['w']:g}: f_t,lim in "
                f"[{r['f_t'] - r['f_err'][0][0]:.4f}, {r['f_t'] + r['f_err'][1][0]:.4f}]")
    return save_figure(shape_usd_figure(points, scene, limits, title), out_dir, f"{stem}_usd", overwrite)

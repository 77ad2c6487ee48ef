"""Figures of one run, or of two runs side by side (`rollcontact plot RUN.h5`, `rollcontact compare A B`).

* history: u = U/U0 along Ft versus periods with u_stat, u_sd and the MDR closed forms (seed Fig. 4);
  below it the stick fraction of the contact area, which goes to 1 at shakedown.
* maps at one stored step (seed Figs. 5-6): p (MPa), tau_x/mu p0, tau_y/mu p0, u_x/U0, the seed regions
  (I stick, II at mu p_min, III released during the period, slip) and the traction use |tau|/(mu p).
* centre lines through the sphere centre, along and across the rolling direction (seed Figs. 5, 7):
  tau_x/mu p0 with the Coulomb bound mu p/(mu p0) = p/p0 and, when a full period is stored, the bound at the
  minimum pressure of the period, mu p_min/(mu p0); u_x/U0 with u_sd.
* compare: the same maps on shared colour scales plus B - A (diverging), centre lines and histories overlaid.
Units mm, N, MPa; normalisations as in cases/plots/common.py.
"""
from __future__ import annotations

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from rollcontact.solver.rolling.shakedown import SETTLED_STATES
from rollcontact.solver.mdr import limits as lim

from rollcontact.cases.plots.common import (
    FIGSIZE, MDR_COLOUR, PARALLEL_COLOUR, PERPENDICULAR_COLOUR, REGION_COLOURS, REGION_NAMES, PlotError, RunView,
    centre_line, save_figure)

KAPPAS = ((lim.KAPPA_PARALLEL, "κ = 1 (Eq. 15)", PARALLEL_COLOUR),
          (lim.KAPPA_PERPENDICULAR, "κ = 1.1 (Eq. 16)", PERPENDICULAR_COLOUR),
          (lim.KAPPA_MDR, "κ = 3/2 (MDR, Eq. 12)", MDR_COLOUR))
MASKED = "#e6e6e6"           # background of the masked (out-of-contact) part of the maps
REGION_CMAP = ListedColormap(REGION_COLOURS)
REGION_NORM = BoundaryNorm(np.arange(-0.5, len(REGION_COLOURS)), len(REGION_COLOURS))


# ------------------------------------------------------------------------------------------ history
def _outcome(v: RunView) -> str:
    """The run's outcome for its legend entry: u_sd when U settled, else the state and du per period."""
    if v.state in SETTLED_STATES and v.u_sd is not None:
        return f"$u_{{sd}}$ = {v.u_sd:.3f}" + (" (cyclic slip)" if v.state == "cyclic_slip" else "")
    if v.du is not None:
        return f"{v.state}, Δu = {v.du:.3g} per period"
    return v.state.replace("_", " ")


def history_figure(views: list[RunView]):
    """u = U/U0 (along Ft) versus periods for one or more runs, with u_stat, u_sd, MDR u_sd (seed Fig. 4).

    The values (u_sd or du per period, u_stat) are given in the legend, beside the curve they belong to, and the
    settled u_sd is marked by a dot at the end of its curve: labels on the curves would cross the other runs'."""
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=FIGSIZE["history"], sharex=True, height_ratios=(3, 1.2),
                                  layout="constrained")
    extra = []
    done = set()
    stats = []
    for v in views:
        t, u = v.periods(), v.u()
        ls = "--" if v.is_mdr else "-"
        ax.plot(t, u, ls, color=v.colour, lw=1.6, label=f"{v.label}: $f_t$ = {v.f_t:.3g}, $w$ = {v.w:.3g}; "
                                                            f"{_outcome(v)}")
        if v.u_stat is not None and round(v.u_stat, 4) not in [round(x, 4) for x in stats]:
            stats.append(v.u_stat)
            ax.axhline(v.u_stat, color="k", ls=(0, (4, 3)), lw=0.8)
        if v.state in SETTLED_STATES and v.u_sd is not None:
            ax.plot(t[-1], v.u_sd, "o", color=v.colour, ms=6)
        ax2.plot(t, np.divide(v.data.history["stick_area"], v.data.history["contact_area"]), ls,
                 color=v.colour, lw=1.2)
        # MDR closed forms (seed Eqs. 12, 15, 16) at this (f_t, w), drawn once per (f_t, w). They hold for a
        # monotonic ramp to f_t under constant loads: not after further force levels (load.levels) nor for loads
        # oscillating within the period.
        key = (round(v.f_t, 6), round(v.w, 6))
        if (v.w <= 0 or key in done or not 0 <= v.f_t <= 1 or v.scene.load.levels or v.scene.oscillating):
            continue
        done.add(key)
        beyond = []
        for kappa, label, colour in KAPPAS:
            if v.w <= 1 and v.f_t <= lim.f_t_lim(v.w, kappa):
                usd = lim.u_shakedown(v.f_t, v.w, kappa)
                ax.plot([0, t[-1]], [usd, usd], ":", color=colour, lw=1.1)
                extra.append(Line2D([], [], ls=":", color=colour, lw=1.1,
                                    label=f"MDR $u_{{sd}}$ = {usd:.3f}, {label}" + (f" at $w$ = {v.w:.3g}"
                                                                                   if len(views) > 1 else "")))
            else:
                beyond.append(f"{kappa:g}")
        if beyond:
            extra.append(Line2D([], [], ls="none", label=f"beyond the shakedown limit for κ = {', '.join(beyond)}"
                                + f" ($f_t$ = {v.f_t:.3g}, $w$ = {v.w:.3g})"))
    handles, _ = ax.get_legend_handles_labels()
    if stats:
        handles += [Line2D([], [], ls=(0, (4, 3)), color="k", lw=0.8, label="$u_{stat}$ (Mindlin, seed Eq. 4) = "
                           + ", ".join(f"{x:.3f}" for x in stats))]
    # above the axes: inside, the legend of a run whose u swings over the whole axis would hide part of it
    fig.legend(handles=handles + extra, fontsize=8, loc="outside upper center", ncol=2 if len(handles + extra) > 3
               else 1)
    ax.set_ylabel("$u = U/U_0$ (along $F_t$)")
    ax.grid(alpha=0.3)
    if min(float(np.min(v.u(), initial=0.0)) for v in views) >= 0.0:
        ax.set_ylim(bottom=0)  # else (reversed loads) the negative part would be cut off
    ax2.set_ylabel("stick area /\ncontact area")
    ax2.set_title("stick fraction per step (elements at the traction bound count as slip)", fontsize=8)
    oscillating = any(v.steps_per_period() for v in views)
    ax2.set_xlabel("periods of the oscillation (0 = end of loading)" if oscillating
                   else "steps (0 = end of loading)")
    ax2.set_ylim(0, 1.05)
    ax2.grid(alpha=0.3)
    ax.set_title(views[0].title if len(views) == 1 else "Rigid shift along $F_t$ (seed Fig. 4)")
    return fig


# ------------------------------------------------------------------------------------------ maps
def _imshow(ax, view_x, view_y, values, mask=None, **kw):
    dx, dy = view_x[1] - view_x[0], view_y[1] - view_y[0]
    ext = (view_x[0] - dx / 2, view_x[-1] + dx / 2, view_y[0] - dy / 2, view_y[-1] + dy / 2)
    data = np.ma.masked_where(~mask, values) if mask is not None else values
    ax.set_facecolor(MASKED)
    im = ax.imshow(data, origin="lower", extent=ext, interpolation="nearest", **kw)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    return im


def _outline(ax, x, y, contact, colour="k"):
    if contact.any() and not contact.all():
        ax.contour(x, y, contact.astype(float), levels=[0.5], colors=colour, linewidths=0.8)


def _map_limits(views, steps):
    """Shared colour scales: p 0..max, tau symmetric >= 1, u_x over the contact of every run."""
    pmax, tmax, ulo, uhi = 0.0, 1.0, np.inf, -np.inf
    for v, s in zip(views, steps):
        f = v.normalised_fields(s)
        c = f["contact"]
        pmax = max(pmax, float(f["p"].max()))
        tmax = max(tmax, float(np.abs(f["tau_x"]).max()), float(np.abs(f["tau_y"]).max()))
        if c.any():
            ulo, uhi = min(ulo, float(f["u_x"][c].min())), max(uhi, float(f["u_x"][c].max()))
    if not np.isfinite(ulo):
        ulo, uhi = 0.0, 1.0
    if uhi - ulo < 1e-6:
        ulo, uhi = ulo - 0.01, uhi + 0.01
    return dict(p=(0.0, pmax or 1.0), tau=(-tmax, tmax), u=(ulo, uhi))


def _map_panels(axes, view, step, lims, colorbars=True, fig=None, extent=None):
    """Draw p, tau_x, tau_y, u_x, regions, traction use of one run into six axes (extent: x0, x1, y0, y1)."""
    f = view.normalised_fields(step)
    x, y, c = view.data.x, view.data.y, f["contact"]
    x0, x1, y0, y1 = extent or (x[0], x[-1], y[0], y[-1])
    centre = view.centre(step)
    ims = []
    ims.append(_imshow(axes[0], x, y, f["p"], c, cmap="viridis", vmin=lims["p"][0], vmax=lims["p"][1]))
    ims.append(_imshow(axes[1], x, y, f["tau_x"], c, cmap="RdBu_r", vmin=lims["tau"][0], vmax=lims["tau"][1]))
    ims.append(_imshow(axes[2], x, y, f["tau_y"], c, cmap="RdBu_r", vmin=lims["tau"][0], vmax=lims["tau"][1]))
    ims.append(_imshow(axes[3], x, y, f["u_x"], c, cmap="plasma", vmin=lims["u"][0], vmax=lims["u"][1]))
    if c.sum() > 4:
        levels = np.linspace(lims["u"][0], lims["u"][1], 9)[1:-1]
        axes[3].contour(x, y, np.where(c, f["u_x"], np.nan), levels=levels, colors="w", linewidths=0.5,
                        alpha=0.8)
    codes, seed = view.regions(step)
    ims.append(_imshow(axes[4], x, y, codes, None, cmap=REGION_CMAP, norm=REGION_NORM))
    use = np.where(c, np.hypot(view.field("tau_x", step), view.field("tau_y", step))
                   / np.maximum(view.mu * f["p"], 1e-300), 0.0)
    ims.append(_imshow(axes[5], x, y, use, c, cmap="YlOrRd", vmin=0.0, vmax=1.0))
    # sphere centre and the two centre lines (dashed: along the rolling direction, solid: across it)
    e_r = view.e_r
    half = 0.5 * max(x[-1] - x[0], y[-1] - y[0])
    for ax in axes[:6]:
        _outline(ax, x, y, c)
        ax.plot(*centre, "+", color="k", ms=7, mew=1.0)
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
    for d, ls in ((e_r, "--"), (np.array([-e_r[1], e_r[0]]), "-")):
        axes[3].plot([centre[0] - half * d[0], centre[0] + half * d[0]],
                     [centre[1] - half * d[1], centre[1] + half * d[1]], ls, color="k", lw=0.8)
        axes[3].set_xlim(x0, x1)
        axes[3].set_ylim(y0, y1)
    titles = ["pressure p (MPa)", "$\\tau_x/\\mu p_0$", "$\\tau_y/\\mu p_0$", "$u_x/U_0$",
              "regions" + ("" if seed else " (no full period stored)"), "traction use $|\\tau|/\\mu p$"]
    for ax, t in zip(axes, titles):
        ax.set_title(t, fontsize=10)
    if colorbars and fig is not None:
        for k, (ax, im) in enumerate(zip(axes, ims)):
            cb = fig.colorbar(im, ax=ax, shrink=0.85)
            if k == 3 and view.state in SETTLED_STATES and view.u_sd is not None:
                cb.ax.axhline(view.u_sd, color="k", lw=1.5)
                cb.set_label(f"black line: $u_{{sd}}$ = {view.u_sd:.3f}", fontsize=8)
            if k == 4:
                cb.set_ticks(range(len(REGION_NAMES)))
                cb.set_ticklabels(REGION_NAMES, fontsize=7)
    return ims


def _step_label(view, step):
    t = view.periods()[list(np.asarray(view.data.history["step"])).index(step)]
    if view.w == 0:
        return f"step {step} (period {t:.2f})"
    c = view.centre(step) @ view.e_r
    return f"step {step} (period {t:.2f}, centre at {c / view.a:+.2f} a along the rolling direction)"


def maps_figure(view: RunView, step: int):
    """Maps of one run at a stored step (seed Figs. 5-6)."""
    fig, axes = plt.subplots(2, 3, figsize=FIGSIZE["maps"], layout="constrained")
    lims = _map_limits([view], [step])
    _map_panels(axes.ravel(), view, step, lims, fig=fig)
    fig.suptitle(f"{view.title}\n{_step_label(view, step)}", fontsize=11)
    return fig


# ------------------------------------------------------------------------------------------ centre lines
def _shade_regions(ax, s, codes):
    """Light background spans for the seed regions along a centre line."""
    if len(s) < 2:
        return
    edges = np.concatenate([[s[0] - (s[1] - s[0]) / 2], (s[1:] + s[:-1]) / 2, [s[-1] + (s[-1] - s[-2]) / 2]])
    starts = np.flatnonzero(np.diff(codes, prepend=-1))        # one span per run of equal codes
    ends = np.append(starts[1:], len(codes))
    for i, j in zip(starts, ends):
        if codes[i] > 0:
            ax.axvspan(edges[i], edges[j], color=REGION_COLOURS[codes[i]], alpha=0.18, lw=0)


def _profile_axes(fig, axes, a):
    for ax in axes.ravel():
        ax.grid(alpha=0.3)
        ax.axhline(0, color="k", lw=0.5)
    for ax in axes[0]:
        sec = ax.secondary_xaxis("top", functions=(lambda s: s / a, lambda r: r * a))
        sec.set_xlabel("s / a", fontsize=8)
        sec.tick_params(labelsize=8)


def profiles_figure(views: list[RunView], steps: list[int]):
    """tau_x/mu p0 and u_x/U0 along and across the rolling direction through the sphere centre."""
    fig, axes = plt.subplots(2, 2, figsize=FIGSIZE["centrelines"], sharex="col", layout="constrained")
    single = len(views) == 1
    for v, step in zip(views, steps):
        f = v.normalised_fields(step)
        codes, seed = v.regions(step)
        p_min = v.p_min(step)
        e_r = v.e_r
        for j, d in enumerate((e_r, np.array([-e_r[1], e_r[0]]))):
            s, tau = centre_line(v, f["tau_x"], step, d)
            _, bound = centre_line(v, f["p"] / v.p0, step, d)
            _, ux = centre_line(v, np.where(f["contact"], f["u_x"], np.nan), step, d, order=0)
            if single:
                _, cl = centre_line(v, codes, step, d, order=0)
                _shade_regions(axes[0, j], s, cl.astype(int))
                _shade_regions(axes[1, j], s, cl.astype(int))
            axes[0, j].plot(s, tau, "-", color=v.colour, lw=1.6, label=f"$\\tau_x/\\mu p_0$, {v.label}")
            axes[0, j].plot(s, bound, "--", color=v.colour, lw=0.9, alpha=0.8,
                            label=f"Coulomb bound $p/p_0$, {v.label}")
            if p_min is not None:
                _, bmin = centre_line(v, p_min / v.p0, step, d)
                axes[0, j].plot(s, bmin, ":", color=v.colour, lw=1.2,
                                label=f"$\\mu p_{{min}}/\\mu p_0$ over the last period, {v.label}")
            axes[1, j].plot(s, ux, "-", color=v.colour, lw=1.6, drawstyle="steps-mid",
                            label=f"$u_x/U_0$ (in contact), {v.label}")
            if v.state in SETTLED_STATES and v.u_sd is not None:
                axes[1, j].axhline(v.u_sd, color=v.colour, ls="-.", lw=0.9,
                                   label=f"$u_{{sd}}$ = {v.u_sd:.3f}, {v.label}")
    names = ("along the rolling direction (dashed line in the maps)",
             "across the rolling direction (solid line in the maps)")
    for j in range(2):
        axes[0, j].set_title(f"centre line {names[j]}", fontsize=10)
        axes[1, j].set_xlabel("s, distance from the sphere centre (mm)")
    axes[0, 0].set_ylabel("$\\tau_x / \\mu p_0$")
    axes[1, 0].set_ylabel("$u_x / U_0$")
    _profile_axes(fig, axes, views[0].a)
    axes[0, 0].legend(fontsize=7, loc="lower center")
    axes[1, 0].legend(fontsize=7, loc="lower center")
    if single:
        handles = [Patch(color=REGION_COLOURS[k], alpha=0.35, label=REGION_NAMES[k])
                   for k in range(1, len(REGION_COLOURS))]
        axes[0, 1].legend(handles=handles, fontsize=7, loc="lower center", title="regions", title_fontsize=7)
        fig.suptitle(f"{views[0].title}\n{_step_label(views[0], steps[0])}", fontsize=11)
    else:
        fig.suptitle("Centre lines (seed Figs. 5, 7): " + "  vs  ".join(
            f"{v.label} $f_t$ = {v.f_t:.3g}, $w$ = {v.w:.3g}, step {s}" for v, s in zip(views, steps)),
            fontsize=10)
    return fig


# ------------------------------------------------------------------------------------------ compare
def _common_grid(views):
    """Union of the world-fixed grids (same spacing): x, y and index offsets of each run; None otherwise."""
    dxs = {(round(v.data.x[1] - v.data.x[0], 9), round(v.data.y[1] - v.data.y[0], 9)) for v in views}
    if len(dxs) != 1:
        return None
    dx, dy = dxs.pop()
    i0 = [int(round(v.data.x[0] / dx)) for v in views]
    j0 = [int(round(v.data.y[0] / dy)) for v in views]
    i1 = [a + len(v.data.x) for a, v in zip(i0, views)]
    j1 = [b + len(v.data.y) for b, v in zip(j0, views)]
    lo_i, hi_i, lo_j, hi_j = min(i0), max(i1), min(j0), max(j1)
    x, y = dx * np.arange(lo_i, hi_i), dy * np.arange(lo_j, hi_j)
    return x, y, [(b - lo_j, a - lo_i) for a, b in zip(i0, j0)]


def _embed(values, shape, offset, fill):
    out = np.full(shape, fill, dtype=float)
    j, i = offset
    out[j:j + values.shape[0], i:i + values.shape[1]] = values
    return out


def compare_maps_figure(va: RunView, sa: int, vb: RunView, sb: int):
    """Maps of A and B on shared colour scales and B - A with a diverging map (common world-fixed grid)."""
    fig, axes = plt.subplots(3, 6, figsize=FIGSIZE["compare_maps"], layout="constrained")
    lims = _map_limits([va, vb], [sa, sb])
    extent = (min(va.data.x[0], vb.data.x[0]), max(va.data.x[-1], vb.data.x[-1]),
              min(va.data.y[0], vb.data.y[0]), max(va.data.y[-1], vb.data.y[-1]))
    for row, (v, s, tag) in enumerate(((va, sa, "A"), (vb, sb, "B"))):
        _map_panels(axes[row], v, s, lims, colorbars=True, fig=fig, extent=extent)
        axes[row, 0].set_title(f"{tag}: {v.label}, $f_t$ = {v.f_t:.3g}, $w$ = {v.w:.3g}, step {s}\n"
                               "pressure p (MPa)", fontsize=9)
    common = _common_grid([va, vb])
    if common is None:
        for ax in axes[2]:
            ax.axis("off")
        axes[2, 0].text(0, 0.5, "B - A not drawn: the grids have different spacings", fontsize=11)
        return fig
    x, y, offs = common
    shape = (len(y), len(x))
    fa, fb = va.normalised_fields(sa), vb.normalised_fields(sb)
    ca = _embed(fa["contact"].astype(float), shape, offs[0], 0.0) > 0
    cb = _embed(fb["contact"].astype(float), shape, offs[1], 0.0) > 0
    either = ca | cb
    diffs = []
    for name, title in (("p", "B − A: p (MPa)"), ("tau_x", "B − A: $\\tau_x/\\mu p_0$"),
                        ("tau_y", "B − A: $\\tau_y/\\mu p_0$"), ("u_x", "B − A: $u_x/U_0$")):
        fill = 0.0 if name != "u_x" else np.nan
        a_, b_ = _embed(fa[name], shape, offs[0], fill), _embed(fb[name], shape, offs[1], fill)
        if name == "u_x":     # displacement differences only where both are in contact
            a_ = np.where(ca, a_, np.nan)
            b_ = np.where(cb, b_, np.nan)
        diffs.append((b_ - a_, title))
    for k, (d, title) in enumerate(diffs):
        m = either & np.isfinite(d)
        amp = float(np.nanmax(np.abs(d[m]))) if m.any() else 1.0
        im = _imshow(axes[2, k], x, y, np.nan_to_num(d), m, cmap="RdBu_r", vmin=-amp or -1, vmax=amp or 1)
        _outline(axes[2, k], x, y, ca)
        _outline(axes[2, k], x, y, cb, "0.55")
        fig.colorbar(im, ax=axes[2, k], shrink=0.85)
        axes[2, k].set_title(title + f"  (max |Δ| = {amp:.3g})", fontsize=10)
    ra = _embed(va.regions(sa)[0], shape, offs[0], 0)
    rb = _embed(vb.regions(sb)[0], shape, offs[1], 0)
    changed = np.where(ra != rb, 1.0, 0.0)
    im = _imshow(axes[2, 4], x, y, changed, either, cmap=ListedColormap(["#ffffff", "#7a3fb0"]), vmin=0, vmax=1)
    _outline(axes[2, 4], x, y, ca)
    _outline(axes[2, 4], x, y, cb, "0.55")
    axes[2, 4].set_title(f"regions differ ({int(changed.sum())} elements, purple)", fontsize=10)
    axes[2, 5].axis("off")
    axes[2, 5].text(0.0, 0.55, "A outline: black\nB outline: grey\nsame world-fixed grid;\n"
                    "u_x difference only where\nboth are in contact", fontsize=10, va="center")
    fig.suptitle("Compare: A = " + va.path.name + ",  B = " + vb.path.name, fontsize=12)
    return fig


def plot_run(view: RunView, out_dir, step: int | None = None, notes=None, overwrite=False) -> list:
    """All figures of one run into out_dir: <stem>_history, _maps, _centrelines (PNG + PDF), <stem>_loads for a run
    with oscillating loads (cases.plots.load_figures), <stem>_friction_step<N> for a run with a friction law
    (cases.plots.friction_figures), and when the file holds subsurface stresses
    _subsurface_step<N> and _subsurface_maxima (cases.plots.subsurface_figures)."""
    stem = view.path.stem
    if not view.has_fields and step is not None:     # refused before any figure is drawn
        raise PlotError(view.no_fields_note().replace("only the history figure is drawn",
                                                      f"step {step} cannot be drawn"))
    if view.has_fields:
        step = view.resolve_step(step)
    paths = save_figure(history_figure([view]), out_dir, f"{stem}_history", overwrite)
    if view.scene.oscillating:       # loads oscillating within each period: hysteresis loop, work per period
        from rollcontact.cases.plots.load_figures import loads_figure
        paths += save_figure(loads_figure(view), out_dir, f"{stem}_loads", overwrite)
    if not view.has_fields:
        if notes is not None:
            notes.append(view.no_fields_note())
        return paths
    paths += save_figure(maps_figure(view, step), out_dir, f"{stem}_maps_step{step}", overwrite)
    paths += save_figure(profiles_figure([view], [step]), out_dir, f"{stem}_centrelines_step{step}", overwrite)
    if view.scene.viscoelastic:      # the pressure leaning forward and its centroid (docs/viscoelastic.md)
        from rollcontact.cases.plots.visco_figures import plot_pressure
        paths += plot_pressure(view.data, out_dir, f"{stem}_step{step}", step, overwrite)
    from rollcontact.cases.plots.friction_figures import plot_friction
    paths += plot_friction(view.data, out_dir, stem, step, overwrite=overwrite)    # a friction law's mu, slip velocity
    from rollcontact.cases.plots.subsurface_figures import plot_subsurface
    paths += plot_subsurface(view, out_dir, step, notes, overwrite)
    return paths


def compare_runs(va: RunView, vb: RunView, out_dir, step: int | None = None, notes=None,
                 overwrite=False) -> list:
    """History overlay, maps with B - A and overlaid centre lines of two runs."""
    stem = f"compare_{va.path.stem}_vs_{vb.path.stem}"
    missing = [v for v in (va, vb) if not v.has_fields]
    if missing and step is not None:                  # refused before any figure is drawn
        raise PlotError(missing[0].no_fields_note().replace("only the history figure is drawn",
                                                            f"step {step} cannot be drawn"))
    if not missing:
        sa, sb = va.resolve_step(step), vb.resolve_step(step)
    paths = save_figure(history_figure([va, vb]), out_dir, f"{stem}_history", overwrite)
    if missing:
        if notes is not None:
            notes += [v.no_fields_note() for v in missing]
        return paths
    paths += save_figure(compare_maps_figure(va, sa, vb, sb), out_dir, f"{stem}_maps", overwrite)
    paths += save_figure(profiles_figure([va, vb], [sa, sb]), out_dir, f"{stem}_centrelines", overwrite)
    return paths

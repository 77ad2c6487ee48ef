"""The creep-force curve figure (`rollcontact creep-curve`): |F|/(mu Fn) against the creepage over its saturation
value, with Kalker's linear theory and Vermeulen-Johnson's saturation model (cases.run.creep_curve)."""
from __future__ import annotations

import numpy as np

from rollcontact.cases.plots.common import plt, save_figure
from rollcontact.solver.creep import vermeulen_johnson

LABELS = {"xi": ("longitudinal creepage", "F_x"), "eta": ("lateral creepage", "F_y"), "phi": ("spin", "F_y")}
#: How each model's curve is drawn (its name in the legend, marker, colour).
MODEL_STYLES = {"bem": ("exact theory (boundary elements)", "o-", "C0"), "fastsim": ("FASTSIM", "s--", "C3"),
                "fastrip": ("FaStrip", "^-.", "C4")}


def plot_curve(tables, out_dir, stem, overwrite=False):
    """Write stem.png and stem.pdf into out_dir: the curve of each table (one CurveTable, or several of the same
    creepage drawn side by side, one per model) with the linear theory and Vermeulen-Johnson; returns their paths."""
    tables = [tables] if not isinstance(tables, (list, tuple)) else list(tables)
    first = tables[0]
    name, force = LABELS[first.varied]
    fig, ax = plt.subplots(figsize=(6.0, 4.0), layout="constrained")
    top = 0.0
    for table in tables:
        s = np.array([r["creepage_over_saturation"] for r in table.rows])
        f = np.array([r["F_over_muFn"] for r in table.rows])
        label, style, colour = MODEL_STYLES[table.fidelity]
        if len(tables) > 1:
            label += f", {sum(r['cpu_time'] for r in table.rows):.3g} s"
        ax.plot(s, f, style, color=colour, label=label, ms=4)
        top = max(top, s.max())
    fine = np.linspace(0.0, top, 200)
    ax.plot(fine[fine <= 1.2], fine[fine <= 1.2], "--", color="C1", label="Kalker's linear theory")
    ax.plot(fine, vermeulen_johnson(fine), ":", color="C2", label="Vermeulen-Johnson")
    ax.axhline(1.0, color="0.6", lw=0.8)
    if getattr(first, "lowest_ratio", None) is not None and first.lowest_ratio < 1.0:   # a falling friction law
        ax.axhline(first.lowest_ratio, color="C3", lw=0.8, ls="-.", label="mu_kin Fn (the law at high slip velocity)")
    unit = " (1/mm)" if first.varied == "phi" else ""
    ax.set_xlabel(f"{name} / saturation value ({first.saturation:.4g}{unit})")
    ax.set_ylabel(f"-{force} / (mu Fn)")
    law = f"\n{first.law}" if getattr(first, "law", "") else ""
    ax.set_title(f"creep-force curve over {first.varied}; mu Fn = {first.mu_fn:.4g} N{law}", fontsize=10)
    ax.legend(loc="lower right", fontsize=8)
    return save_figure(fig, out_dir, stem, overwrite=overwrite)


def is_creep_run(data) -> bool:
    """True for the result of a [rolling] scene (summary state 'steady', cases.run.creep_run)."""
    return data.summary.get("state") in ("steady", "transient") and "xi" in data.summary


def plot_creep_run(data, out_dir, stem, overwrite=False):
    """Maps of a steady rolling run (stem_maps.png/.pdf): the traction magnitude |tau|/(mu p_max) with the slip
    direction, and stick (at the leading edge) and slip regions; x along the rolling direction (arrow). A transient
    run: its last stored step, around the contact. With a friction law or [thermal], also stem_friction (the local
    mu, slip velocity and temperatures, cases.plots.friction_figures)."""
    s = data.summary
    keep = slice(None)
    if not len(data.field_steps):
        from rollcontact.cases.plots.common import PlotError
        raise PlotError(f"{data.path}: this [rolling] run stored no fields (output.fields = 'none'): no maps to draw")
    mu = data.scene.load.mu
    x, y = np.asarray(data.x), np.asarray(data.y)
    p, tx, ty = data.field("p"), data.field("tau_x"), data.field("tau_y")
    region = data.field("region")
    if s.get("state") == "transient":     # the last stored step on the long world grid: the contact and 3 cells
        cols = np.nonzero((p > 0).any(axis=0))[0]
        keep = slice(max(int(cols[0]) - 3, 0), int(cols[-1]) + 4) if cols.size else slice(None)
        x, p, tx, ty, region = x[keep], p[:, keep], tx[:, keep], ty[:, keep], region[:, keep]
    scale = mu * float(np.max(p))
    extent = (x[0] - 0.5 * (x[1] - x[0]), x[-1] + 0.5 * (x[1] - x[0]), y[0] - 0.5 * (y[1] - y[0]),
              y[-1] + 0.5 * (y[1] - y[0]))
    fig, axes = plt.subplots(1, 2, figsize=(10.0, 4.2), layout="constrained")
    mag = np.where(p > 0, np.hypot(tx, ty) / scale, np.nan)
    im = axes[0].imshow(mag, origin="lower", extent=extent, cmap="viridis", vmin=0, vmax=1)
    fig.colorbar(im, ax=axes[0], label="|tau| / (mu p_max)")
    step = max(1, len(x) // 20)
    X, Y = np.meshgrid(x, y)
    sl = (slice(None, None, step), slice(None, None, step))
    inside = (p > 0)[sl]
    axes[0].quiver(X[sl][inside], Y[sl][inside], tx[sl][inside], ty[sl][inside], color="w", width=0.003)
    axes[0].set_title("traction of the sphere on the substrate", fontsize=10)
    codes = np.where(region == 0, np.nan, region.astype(float))
    axes[1].imshow(codes, origin="lower", extent=extent, cmap=plt.get_cmap("coolwarm", 2), vmin=0.5, vmax=2.5)
    axes[1].set_title(f"stick (blue, {100 * s['stick_fraction']:.0f} %) and slip (red)", fontsize=10)
    for ax in axes:
        ax.set_xlabel("x (mm, rolling direction)")
        ax.set_ylabel("y (mm)")
        ax.set_aspect("equal")
        ax.annotate("", xy=(extent[1], extent[3]), xytext=(extent[1] - 0.2 * (extent[1] - extent[0]), extent[3]),
                    arrowprops=dict(arrowstyle="->", color="k"), annotation_clip=False)
    fig.suptitle(f"{s['mode']} rolling: xi = {s['xi']:.4g}, eta = {s['eta']:.4g}, phi = {s['phi']:.4g} 1/mm; "
                 f"F_x = {s['F_x']:.4g} N, F_y = {s['F_y']:.4g} N (on the sphere)", fontsize=10)
    paths = save_figure(fig, out_dir, f"{stem}_maps", overwrite=overwrite)
    if "pressure_centroid_x" in s:       # viscoelastic bodies: the pressure leaning forward (docs/viscoelastic.md)
        from rollcontact.cases.plots.visco_figures import plot_pressure
        paths += plot_pressure(data, out_dir, stem, overwrite=overwrite)
    from rollcontact.cases.plots.friction_figures import plot_friction      # a law's mu, slip velocity, temperatures
    window = keep if s.get("state") == "transient" else None
    return paths + plot_friction(data, out_dir, stem, window=window, overwrite=overwrite)

"""The creep-force curve figure (`rollcontact creep-curve`): |F|/(mu Fn) against the creepage over its saturation
value, with Kalker's linear theory and Vermeulen-Johnson's saturation model (cases.run.creep_curve)."""
from __future__ import annotations

import numpy as np

from rollcontact.cases.plots.common import plt, save_figure
from rollcontact.solver.creep import vermeulen_johnson

LABELS = {"xi": ("longitudinal creepage", "F_x"), "eta": ("lateral creepage", "F_y"), "phi": ("spin", "F_y")}


def plot_curve(table, out_dir, stem, overwrite=False):
    """Write stem.png and stem.pdf into out_dir; returns their paths."""
    name, force = LABELS[table.varied]
    s = np.array([r["creepage_over_saturation"] for r in table.rows])
    f = np.array([r["F_over_muFn"] for r in table.rows])
    fine = np.linspace(0.0, s.max(), 200)
    fig, ax = plt.subplots(figsize=(6.0, 4.0), layout="constrained")
    ax.plot(s, f, "o-", color="C0", label="rollcontact, steady")
    ax.plot(fine[fine <= 1.2], fine[fine <= 1.2], "--", color="C1", label="Kalker's linear theory")
    ax.plot(fine, vermeulen_johnson(fine), ":", color="C2", label="Vermeulen-Johnson")
    ax.axhline(1.0, color="0.6", lw=0.8)
    unit = " (1/mm)" if table.varied == "phi" else ""
    ax.set_xlabel(f"{name} / saturation value ({table.saturation:.4g}{unit})")
    ax.set_ylabel(f"-{force} / (mu Fn)")
    ax.set_title(f"creep-force curve over {table.varied}; mu Fn = {table.mu_fn:.4g} N", fontsize=10)
    ax.legend(loc="lower right")
    return save_figure(fig, out_dir, stem, overwrite=overwrite)

"""The pressure of a run with viscoelastic bodies (docs/viscoelastic.md): its map with the rolling body's lowest point
and the pressure centroid marked, the profile through the lowest point along the rolling direction, and for a stepped
run the centroid against the step. Units: mm, MPa."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from rollcontact.cases.plots.common import save_figure


def pressure_figure(data, step: int | None = None):
    """The figure of the stored step `step` (default: the last) of a viscoelastic run (a RunResult)."""
    s, scene = data.summary, data.scene
    steps = [int(k) for k in np.asarray(data.field_steps)]
    step = steps[-1] if step is None else int(step)
    p = data.field("p", step)
    x, y = np.asarray(data.x), np.asarray(data.y)
    rolling_run = "xi" in s
    if rolling_run:                        # [rolling]: x is the rolling direction; the contact centre moves along x
        e = (1.0, 0.0)
        k = int(np.flatnonzero(np.asarray(data.history["step"]) == step)[0])
        centre = (float(data.history["W_x"][k]), 0.0)
    else:
        e = scene.rolling_direction
        k = int(np.flatnonzero(np.asarray(data.history["step"]) == step)[0])
        centre = (float(data.history["W_x"][k]), float(data.history["W_y"][k]))
    xc = float(data.history["pressure_centroid_x"][k]) if "pressure_centroid_x" in data.history else \
        float(s["pressure_centroid_x"])
    stepped = "pressure_centroid_x" in data.history and len(data.history["step"]) > 1
    fig, axes = plt.subplots(1, 3 if stepped else 2, figsize=(14.0 if stepped else 10.0, 4.2), layout="constrained")
    on = p > 0
    cols, rows = np.nonzero(on.any(axis=0))[0], np.nonzero(on.any(axis=1))[0]
    if cols.size:
        x0, x1 = cols[0] - 3, cols[-1] + 4
        y0, y1 = rows[0] - 3, rows[-1] + 4
        x0, y0, x1, y1 = max(x0, 0), max(y0, 0), min(x1, len(x)), min(y1, len(y))    # 3 cells beyond, on the grid
    else:
        x0, x1, y0, y1 = 0, len(x), 0, len(y)
    dx = x[1] - x[0] if len(x) > 1 else 1.0
    dy = y[1] - y[0] if len(y) > 1 else 1.0
    sub = p[y0:y1, x0:x1]
    extent = (x[x0] - dx / 2, x[x1 - 1] + dx / 2, y[y0] - dy / 2, y[y1 - 1] + dy / 2)
    im = axes[0].imshow(np.where(sub > 0, sub, np.nan), origin="lower", extent=extent, cmap="magma")
    fig.colorbar(im, ax=axes[0], label="p (MPa)")
    axes[0].plot(*centre, "w+", ms=12, label="lowest point")
    axes[0].plot(centre[0] + xc * e[0], centre[1] + xc * e[1], "co", ms=6, label="pressure centroid")
    axes[0].set_aspect("equal")
    axes[0].set_xlabel("x (mm)")
    axes[0].set_ylabel("y (mm)")
    axes[0].legend(fontsize=8, loc="lower left")
    axes[0].set_title(f"pressure, step {step}", fontsize=10)
    along_x = abs(e[0]) >= abs(e[1])
    if along_x:
        j = int(np.argmin(np.abs(y - centre[1])))
        s_line, p_line = (x - centre[0]) * np.sign(e[0]), p[j]
    else:
        i = int(np.argmin(np.abs(x - centre[0])))
        s_line, p_line = (y - centre[1]) * np.sign(e[1]), p[:, i]
    order = np.argsort(s_line)
    axes[1].plot(s_line[order], p_line[order], "k.-", ms=3)
    axes[1].axvline(0.0, color="0.6", lw=0.8)
    axes[1].axvline(xc, color="c", lw=1.2, label=f"centroid {xc:.4g} mm")
    axes[1].set_xlim(s_line[order][on.any(axis=0 if along_x else 1)[order]].min() - 3 * dx if cols.size else None,
                     s_line[order][on.any(axis=0 if along_x else 1)[order]].max() + 3 * dx if cols.size else None)
    axes[1].set_xlabel("along the rolling direction from the lowest point (mm)")
    axes[1].set_ylabel("p (MPa)")
    axes[1].legend(fontsize=8)
    axes[1].set_title("through the lowest point", fontsize=10)
    if stepped:
        h = data.history
        axes[2].plot(h["step"], h["pressure_centroid_x"], "k-")
        axes[2].set_xlabel("step")
        axes[2].set_ylabel("pressure centroid (mm)")
        axes[2].set_title("pressure centroid along the rolling direction", fontsize=10)
    speed = s.get("speed")
    fig.suptitle(f"viscoelastic: speed {speed:.4g} mm/s; rolling resistance moment "
                 f"{s.get('rolling_resistance_moment', float('nan')):.4g} N mm", fontsize=10)
    return fig


def plot_pressure(data, out_dir, stem, step=None, overwrite=False):
    """Write `stem`_pressure.png/.pdf (`pressure_figure`); returns the paths."""
    return save_figure(pressure_figure(data, step), out_dir, f"{stem}_pressure", overwrite=overwrite)

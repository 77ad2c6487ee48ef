"""Figures of the subsurface stresses of a run (/subsurface, cases.results.subsurface).

* sections: von Mises and the maximum shear stress (Tresca, (sigma_1 - sigma_3)/2) in the x-z and y-z planes through
  the contact centre (the sphere centre of the step) at one computed step; the maximum of each section is marked
  and labelled with its value and place. Stresses in MPa and over p0 (the Hertz peak pressure of the run), depths
  in mm pointing down.
* maxima: the largest von Mises and maximum shear stress of the whole block against the step, with the depth
  where each is found (a maximum at z = 0 lies on the surface).
"""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from rollcontact.cases.plots.common import RunView, save_figure
from rollcontact.cases.results.subsurface import block_maxima, computed_steps, read_sections

TITLES = {"von_mises": "von Mises stress", "tresca": "maximum shear stress (Tresca)"}


def _section_panel(ax, fig, h, z, values, p0, xlabel):
    """One section: values (nz, n) over h (mm, horizontal) and z (mm, down), with its maximum marked."""
    mesh = ax.pcolormesh(h, z, values, shading="nearest", cmap="viridis")
    ax.set_ylim(z[-1], z[0])
    ax.set_xlabel(xlabel)
    ax.set_ylabel("depth z (mm)")
    k = np.unravel_index(int(np.argmax(values)), values.shape)
    vmax = float(values[k])
    ax.plot(h[k[1]], z[k[0]], marker="x", color="red", markersize=10, markeredgewidth=2, clip_on=False)
    ax.text(0.02, 0.04, f"max {vmax:.4g} MPa = {vmax / p0:.3f} p0 at {h[k[1]]:.3g} mm, z = {z[k[0]]:.3g} mm (x)",
            transform=ax.transAxes, color="white", fontsize=9, bbox=dict(boxstyle="round", fc="0.15", alpha=0.7))
    fig.colorbar(mesh, ax=ax, label="MPa")


def sections_figure(view: RunView, step: int):
    """2 x 2 sections (rows: von Mises, maximum shear; columns: x-z at the centre's y, y-z at the centre's x)."""
    s = read_sections(view.path, step, view.centre(step))
    p0 = view.p0
    fig, axes = plt.subplots(2, 2, figsize=(13, 8.5), layout="constrained")
    for row, name in enumerate(("von_mises", "tresca")):
        _section_panel(axes[row, 0], fig, s["x"], s["z"], s["xz"][name], p0, "x (mm)")
        axes[row, 0].set_title(f"{TITLES[name]}, x-z section at y = {s['row_y']:.3g} mm", fontsize=10)
        _section_panel(axes[row, 1], fig, s["y"], s["z"], s["yz"][name], p0, "y (mm)")
        axes[row, 1].set_title(f"{TITLES[name]}, y-z section at x = {s['column_x']:.3g} mm", fontsize=10)
    fig.suptitle(f"{view.title} — subsurface stresses at step {step} (p0 = {p0:.4g} MPa)", fontsize=11)
    return fig


def maxima_figure(view: RunView):
    """The block maxima of von Mises and maximum shear against the step, and the depth of each."""
    m = block_maxima(view.path)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 7), sharex=True, layout="constrained")
    for name, colour in (("von_mises", "C0"), ("tresca", "C3")):
        top.plot(m["step"], m[name]["value"], "o-", color=colour, label=TITLES[name])
        bottom.plot(m["step"], m[name]["z"], "o-", color=colour, label=TITLES[name])
    top.set_ylabel("maximum over the block (MPa)")
    right = top.secondary_yaxis("right", functions=(lambda v: v / view.p0, lambda v: v * view.p0))
    right.set_ylabel("over p0")
    bottom.set_ylabel("depth of the maximum (mm)")
    deepest = max(max(m[name]["z"].max() for name in ("von_mises", "tresca")), 0.05 * float(m["depths"][-1]))
    bottom.set_ylim(-0.05 * deepest, 1.1 * deepest)
    bottom.set_xlabel("step")
    bottom.invert_yaxis()
    top.legend(fontsize=9)
    fig.suptitle(f"{view.title} — maxima of the subsurface stresses per computed step", fontsize=11)
    return fig


def plot_subsurface(view: RunView, out_dir, step: int | None = None, notes=None, overwrite=False) -> list:
    """<stem>_subsurface_step<N> (sections at `step`, default: the last computed one) and <stem>_subsurface_maxima;
    nothing when the file holds no /subsurface. A `step` without stresses gets a note and the last computed step."""
    computed = computed_steps(view.path)
    if not computed:
        return []
    if step is not None and step not in computed:
        if notes is not None:
            notes.append(f"{view.path}: no subsurface stresses at step {step} (computed: "
                         f"{', '.join(map(str, computed))}); the sections show step {computed[-1]}")
        step = None
    step = computed[-1] if step is None else step
    stem = view.path.stem
    paths = save_figure(sections_figure(view, step), out_dir, f"{stem}_subsurface_step{step}", overwrite)
    paths += save_figure(maxima_figure(view), out_dir, f"{stem}_subsurface_maxima", overwrite)
    return paths

"""Maps of the fields a friction law or [thermal] adds to a run file (cases.results.run_result, FRICTION_FIELD_UNITS):
the local coefficient of friction mu, the slip velocity (mm/s) and the surface temperatures T1, T2 (degC), drawn
beside `rollcontact plot`'s other maps as <stem>_friction[_step<N>] (PNG and PDF)."""
from __future__ import annotations

import numpy as np

from rollcontact.cases.plots.common import plt, save_figure


def has_friction_fields(data) -> bool:
    """True when the run file holds the local coefficient (a friction law or [thermal])."""
    return "mu" in data.fields and len(data.field_steps) > 0


def friction_figure(data, step: int, window=None):
    """mu, slip velocity and (when stored) T1, T2 at a stored step; window: (columns slice) to draw (a transient's
    contact on its long world grid), None for the whole grid."""
    x, y = np.asarray(data.x), np.asarray(data.y)
    names = ["mu", "slip_velocity"] + [n for n in ("T1", "T2") if n in data.fields]
    fields = {n: np.asarray(data.field(n, step)) for n in names + ["p"]}
    if window is not None:
        x = x[window]
        fields = {n: v[:, window] for n, v in fields.items()}
    contact = fields["p"] > 0
    dx, dy = (x[1] - x[0]) if len(x) > 1 else 1.0, (y[1] - y[0]) if len(y) > 1 else 1.0
    extent = (x[0] - dx / 2, x[-1] + dx / 2, y[0] - dy / 2, y[-1] + dy / 2)
    nrows = 1 if len(names) <= 2 else 2
    fig, axes = plt.subplots(nrows, 2, figsize=(10.0, 4.2 * nrows), layout="constrained", squeeze=False)
    s = data.summary
    law = s.get("friction_law", "")
    titles = {"mu": "local coefficient of friction $\\mu$", "slip_velocity": "slip velocity (mm/s)",
              "T1": "surface temperature $T_1$ of body 1 (°C)", "T2": "surface temperature $T_2$ of body 2 (°C)"}
    temps = [fields[n] for n in ("T1", "T2") if n in fields]
    t_lo = min(float(t.min()) for t in temps) if temps else 0.0
    t_hi = max(float(t.max()) for t in temps) if temps else 1.0
    for ax, name in zip(axes.ravel(), names):
        values = fields[name]
        if name == "mu":
            lo = min(float(values[contact].min()) if contact.any() else 0.0, s.get("mu_static", 1.0))
            im = ax.imshow(np.where(contact, values, np.nan), origin="lower", extent=extent, cmap="cividis",
                           vmin=lo, vmax=max(s.get("mu_static", values.max()), lo + 1e-12))
        elif name == "slip_velocity":
            im = ax.imshow(np.where(contact, values, np.nan), origin="lower", extent=extent, cmap="magma")
        else:
            im = ax.imshow(values, origin="lower", extent=extent, cmap="inferno", vmin=t_lo,
                           vmax=max(t_hi, t_lo + 1e-9))
            if contact.any():
                ax.contour(x, y, contact.astype(float), levels=[0.5], colors="w", linewidths=0.7)
        fig.colorbar(im, ax=ax, shrink=0.85)
        ax.set_title(titles[name], fontsize=10)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.set_aspect("equal")
    for ax in axes.ravel()[len(names):]:
        ax.set_visible(False)
    extra = (f"; frictional power {s['frictional_power']:.4g} W" if s.get("frictional_power") is not None else "")
    fig.suptitle(f"{law}{extra}\nstep {step}", fontsize=10)
    return fig


def plot_friction(data, out_dir, stem, step=None, window=None, overwrite=False) -> list:
    """The friction maps of a run file (nothing without its fields): stem_friction[_step<N>] PNG and PDF."""
    if not has_friction_fields(data):
        return []
    steps = [int(s) for s in np.asarray(data.field_steps)]
    step = steps[-1] if step is None else int(step)
    suffix = "" if len(steps) == 1 else f"_step{step}"
    return save_figure(friction_figure(data, step, window), out_dir, f"{stem}_friction{suffix}", overwrite=overwrite)

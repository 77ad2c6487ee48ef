"""The figure of a run with loads oscillating within each period (`rollcontact plot RUN.h5`; docs/oscillating_loads.md):

* left: the hysteresis loop, u = U/U0 along Ft against f_t = Ft/(mu Fn) (Fn: the scene's mean normal force), every
  step, the last period drawn bold; for constant Fn, a mean f_t of 0 and no rolling, the Mindlin-Deresiewicz
  branches of the closed cycle (docs/theory.md §11.2) dashed;
* right: the frictional work of each period (N mm, /history/dissipation summed over the period), with the
  Mindlin-Deresiewicz loop area in the same case; a shaken-down run's work falls to zero.

Units mm, N; normalisations as in cases/plots/common.py.
"""
from __future__ import annotations

import numpy as np
import matplotlib.pyplot as plt

from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere

from rollcontact.cases.plots.common import MDR_COLOUR, RunView


def _mindlin_deresiewicz(view: RunView):
    """CattaneoMindlin of the scene and the amplitude x = F*/(mu Fn) when the run is a pure Mindlin-Deresiewicz
    cycle (constant Fn, mean f_t = 0, no rolling, one load cycle per period), else (None, None)."""
    sc = view.scene
    ld = sc.load
    if not (view.w == 0 and sc.f_t == 0 and ld.fn_amplitude == 0 and ld.ft_amplitude > 0
            and ld.cycles_per_period == 1 and sc.radii[0] == sc.radii[1]):
        return None, None
    pair = sc.material_pair
    return CattaneoMindlin(HertzSphere(sc.radii[0], pair.E_star, ld.Fn), ld.mu, pair.G_star), ld.ft_amplitude


def loads_figure(view: RunView):
    """Hysteresis loop u against f_t and the frictional work per period of one run."""
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11.0, 4.4), layout="constrained", width_ratios=(1.3, 1))
    h = view.data.history
    ld = view.scene.load
    f = (np.asarray(h["F_x"]) * view.e_f[0] + np.asarray(h["F_y"]) * view.e_f[1]) / (ld.mu * ld.Fn)
    u, period = view.u(), np.asarray(h["period"])
    last = int(period.max())
    ax.plot(f, u, "-", color=view.colour, lw=0.7, alpha=0.5, label="all steps")
    if last > 0:
        sel = np.flatnonzero(period == last)
        sel = np.concatenate(([sel[0] - 1], sel))        # from the end of the previous period: a closed cycle
        ax.plot(f[sel], u[sel], "o-", color=view.colour, lw=1.8, ms=3, label=f"period {last}")
    cm, x = _mindlin_deresiewicz(view)
    if cm is not None:
        t = np.linspace(-x, x, 201)
        ax.plot(t, [cm.unloading_shift(x, ti) / view.U0 for ti in t], "--", color=MDR_COLOUR, lw=1.2,
                label="Mindlin-Deresiewicz (docs/theory.md §11.2)")
        ax.plot(t, [cm.reloading_shift(x, ti) / view.U0 for ti in t], "--", color=MDR_COLOUR, lw=1.2)
    ax.set_xlabel(r"$f_t = F_t/(\mu F_n)$ (mean $F_n$)")
    ax.set_ylabel(r"$u = U/U_0$ (along $F_t$)")
    ax.set_title("hysteresis loop", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")

    work = np.asarray(h["dissipation"], float)
    k = np.arange(1, last + 1)
    per = np.array([work[period == j].sum() for j in k])
    if per.size:
        ax2.plot(k, per, "o-", color=view.colour, lw=1.6, label="frictional work of the period")
    if cm is not None:
        ax2.axhline(cm.cycle_dissipation(x), color=MDR_COLOUR, ls="--", lw=1.2,
                    label=f"Mindlin-Deresiewicz loop area ({cm.cycle_dissipation(x):.4g} N mm)")
    ax2.set_xlabel("period")
    ax2.xaxis.get_major_locator().set_params(integer=True)
    ax2.set_ylabel("frictional work per period (N mm)")
    ax2.set_title(r"dissipation per period ($-\sum \tau\cdot s\, dA$ over its steps)", fontsize=10)
    ax2.set_ylim(bottom=0)
    ax2.grid(alpha=0.3)
    if per.size or cm is not None:
        ax2.legend(fontsize=8, loc="lower right")
    amp = (f"$f_t$ = {view.scene.f_t:.3g} ± {ld.ft_amplitude:.3g}, $F_n$ = {ld.Fn:.4g} N ± "
           f"{100 * ld.fn_amplitude:.3g} %, phase {ld.phase:g}°, $w$ = {view.w:.3g}")
    fig.suptitle(f"{view.label}: {amp}  ({view.state.replace('_', ' ')})", fontsize=11)
    return fig

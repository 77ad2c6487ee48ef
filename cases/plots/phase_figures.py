"""Figures of sweeps and limit searches over the phase of oscillating loads (`rollcontact plot OUTDIR` when the
folder's runs differ in load.phase; docs/oscillating_loads.md):

* `<folder>_phase`: per rolling setting, the state of each run over (phase, amplitude) (shakedown o, cyclic slip
  (U settled, but slipping in every period) diamond, both coloured and labelled by u_sd; ratcheting x and undecided
  square, labelled with du per period) and the frictional work of the last period over mu Fn U0
  against the phase, one line per amplitude (the physical measure of shakedown: it falls to 0 without slip);
* `<folder>_phase_limits` (a limit search's limits.csv with a load.phase column): f_t,lim against the phase per
  setting and amplitude, the bracket as an error bar.

The amplitude is load.ft_amplitude (units of mu Fn) or, when that does not vary, load.fn_amplitude (relative).
Units: f_t = Ft/(mu Fn), u = U/U0, w = W/a (seed Eq. 9); work in units of mu Fn U0 (mean Fn).
"""
from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np
import matplotlib.pyplot as plt

from rollcontact.solver.rolling.shakedown import SETTLED_STATES
from rollcontact.cases.plots.common import PARALLEL_COLOUR, PERPENDICULAR_COLOUR, save_figure
from rollcontact.cases.results.hdf5 import stored_summary
from rollcontact.cases.scene.scene import Scene


@dataclass
class PhasePoint:
    """One run of a phase sweep: setting (folded rolling angle), amplitudes, phase (deg) and its outcome."""

    angle: float
    ft_amplitude: float
    fn_amplitude: float
    phase: float
    f_t: float
    w: float
    state: str
    u_sd: float | None
    du: float | None
    work: float | None        # frictional work of the last period / (mu Fn U0)


def _fold(angle) -> float:
    t = float(angle) % 180.0
    return 180.0 - t if t > 90.0 else t


def read_phase_points(files) -> list[PhasePoint]:
    """PhasePoints of the complete run files among `files` (others are skipped)."""
    pts = []
    for f in files:
        stored = stored_summary(f)
        if stored is None or stored["status"] != "complete" or not stored["scene"]:
            continue
        s = stored["summary"]
        sc = Scene.from_toml_text(stored["scene"], run_limits=False)
        ld = sc.load
        work = s.get("dissipation_per_period")
        scale = ld.mu * ld.Fn * float(s["U0"])
        pts.append(PhasePoint(_fold(sc.motion.angle), ld.ft_amplitude, ld.fn_amplitude, ld.phase % 360.0, sc.f_t,
                              float(s.get("w") or 0.0), str(s.get("state")), s.get("u_sd"), s.get("du"),
                              None if work is None else float(work) / scale))
    return pts


def varies_phase(points) -> bool:
    """True when the runs differ in phase and no (setting, amplitudes, phase) repeats at another f_t or w (the
    probes of a limit search do: their map would mix loads)."""
    keys = [(p.angle, p.ft_amplitude, p.fn_amplitude, p.phase) for p in points]
    return len({p.phase for p in points}) > 1 and len(set(keys)) == len(keys)


def _amplitude_key(points) -> str:
    return amplitude_key([p.ft_amplitude for p in points], [p.fn_amplitude for p in points])


def amplitude_key(ft_amplitudes, fn_amplitudes) -> str:
    """The amplitude a figure is drawn over: the one that varies (ft_amplitude if both do), else the one that is not
    zero (an Fn oscillation set with --set), else ft_amplitude."""
    ft, fn = set(ft_amplitudes), set(fn_amplitudes)
    if len(ft) > 1 or (len(fn) <= 1 and (ft != {0.0} or fn <= {0.0})):
        return "ft_amplitude"
    return "fn_amplitude"


def _setting(angle) -> tuple[str, str]:
    if angle == 0:
        return "W ∥ Ft", PARALLEL_COLOUR
    if angle == 90:
        return "W ⊥ Ft", PERPENDICULAR_COLOUR
    return f"W at {angle:g}° to Ft", "0.3"


def phase_figure(points, title):
    """State map over (phase, amplitude) and frictional work per period against the phase, per setting."""
    key = _amplitude_key(points)
    settings = sorted({p.angle for p in points})
    fig, axes = plt.subplots(2, len(settings), figsize=(6.0 * len(settings), 8.0), layout="constrained",
                             squeeze=False)
    amps = sorted({getattr(p, key) for p in points})
    shades = plt.cm.viridis(np.linspace(0.1, 0.85, max(len(amps), 1)))
    usd = [p.u_sd for p in points if p.u_sd is not None]
    norm = plt.Normalize(min(usd), max(usd)) if usd else None
    for j, angle in enumerate(settings):
        name, colour = _setting(angle)
        ax, ax2 = axes[0, j], axes[1, j]
        mine = [p for p in points if p.angle == angle]
        for p in mine:
            y = getattr(p, key)
            if p.state in SETTLED_STATES and p.u_sd is not None:
                sc = ax.scatter(p.phase, y, c=[p.u_sd], cmap="viridis", norm=norm, s=90, edgecolors="k",
                                marker="o" if p.state == "shakedown" else "D")
                ax.annotate(f"{p.u_sd:.3f}", (p.phase, y), xytext=(0, 8), textcoords="offset points",
                            ha="center", fontsize=7)
            else:
                ax.plot(p.phase, y, "x" if p.state == "ratcheting" else "s", color="crimson", ms=9, mew=2)
                label = f"Δu {p.du:.2g}" if p.du is not None and p.state in ("ratcheting", "undecided") \
                    else p.state.replace("_", " ")
                ax.annotate(label, (p.phase, y), xytext=(0, 8), textcoords="offset points", ha="center",
                            fontsize=7, color="crimson")
        ax.set_title(f"{name}\no shakedown, ◇ cyclic slip: colour and label $u_{{sd}}$\nx ratcheting, ■ undecided: "
                     "label Δu per period", fontsize=9)
        ax.margins(y=0.2)           # room above the top row for its labels
        ax.set_xlabel("phase of the load oscillation relative to the rolling (deg)")
        ax.set_ylabel(f"load.{key}" + (" (units of μFn)" if key == "ft_amplitude" else " (relative)"))
        ax.set_xticks(np.arange(0, 361, 45))
        ax.set_xlim(-35, 350)      # room for the labels of the first and last phase
        ax.grid(alpha=0.3)
        for amp, shade in zip(amps, shades):
            row = sorted((p for p in mine if getattr(p, key) == amp and p.work is not None), key=lambda p: p.phase)
            if row:
                ax2.semilogy([p.phase for p in row], [max(p.work, 1e-12) for p in row], "o-", color=shade,
                             label=f"{key} = {amp:g}")
        ax2.set_xlabel("phase (deg)")
        ax2.set_ylabel("frictional work of the last period / (μ Fn U0)")
        ax2.set_xticks(np.arange(0, 361, 45))
        ax2.grid(alpha=0.3, which="both")
        ax2.legend(fontsize=8)
    if usd:
        fig.colorbar(sc, ax=axes[0, :].tolist(), label="$u_{sd} = U_{sd}/U_0$ (at the period end)", shrink=0.8)
    f_t = sorted({round(p.f_t, 4) for p in points})
    w = sorted({round(p.w, 4) for p in points})
    fig.suptitle(f"{title}: oscillating loads, $f_t$ = {', '.join(map(str, f_t))}, $w$ = {', '.join(map(str, w))}",
                 fontsize=11)
    return fig


def _search_overrides(path) -> dict:
    """The --set items of the limit search that wrote `path` (limits.csv), from limits.h5 beside it: key -> text."""
    try:
        with h5py.File(Path(path).with_suffix(".h5"), "r") as h5:
            items = [s.decode() if isinstance(s, bytes) else str(s) for s in h5.attrs.get("overrides", [])]
    except OSError:
        return {}
    return dict(item.split("=", 1) for item in items if "=" in item)


def read_phase_limits(path) -> list[dict]:
    """Rows of a limit search's limits.csv with load.phase (deg), the amplitudes (varied, or set with --set),
    motion.angle and the bracket."""
    rows = []
    fixed = _search_overrides(path)
    with open(path, newline="") as fh:
        for row in csv.DictReader(fh):
            row = {**fixed, **{k: v for k, v in row.items() if v not in (None, "")}}
            if row.get("status") not in ("ok", "widened") or "load.phase" not in row:
                continue
            rows.append(dict(phase=float(row["load.phase"]) % 360.0, angle=_fold(row.get("motion.angle") or 90.0),
                             ft_amplitude=float(row.get("load.ft_amplitude") or 0.0),
                             fn_amplitude=float(row.get("load.fn_amplitude") or 0.0),
                             lower=float(row["lower"]), upper=float(row["upper"])))
    return rows


def phase_limits_figure(rows, title, reference=None):
    """f_t,lim against the phase: one line per (setting, amplitude), the bracket as an error bar; `reference`
    {angle: (lower, upper)} draws the limit without oscillation as a band."""
    fig, ax = plt.subplots(figsize=(7.5, 4.8), layout="constrained")
    key = amplitude_key([r["ft_amplitude"] for r in rows], [r["fn_amplitude"] for r in rows])
    for angle in sorted({r["angle"] for r in rows}):
        name, colour = _setting(angle)
        for amp in sorted({r[key] for r in rows if r["angle"] == angle}):
            sel = sorted((r for r in rows if r["angle"] == angle and r[key] == amp), key=lambda r: r["phase"])
            mid = np.array([0.5 * (r["lower"] + r["upper"]) for r in sel])
            err = np.array([0.5 * (r["upper"] - r["lower"]) for r in sel])
            ax.errorbar([r["phase"] for r in sel], mid, yerr=err, fmt="o-" if angle == 0 else "^-", color=colour,
                        capsize=3, label=f"{name}, {key} = {amp:g}")
        if reference and angle in reference:
            lo, hi = reference[angle]
            ax.axhspan(lo, hi, color=colour, alpha=0.15, label=f"{name}, no oscillation [{lo:g}, {hi:g}]")
    ax.set_xlabel("phase of the load oscillation relative to the rolling (deg)")
    ax.set_ylabel("$f_{t,lim}$ (mean $F_t/(\\mu F_n)$ at the shakedown limit)")
    ax.set_xticks(np.arange(0, 361, 45))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=10)
    return fig


def phase_table(points) -> list[str]:
    """Markdown rows: per setting and amplitude, the state (s shakedown, c cyclic slip, R ratcheting, ? otherwise) and the work of
    the last period / (mu Fn U0) at each phase."""
    key = _amplitude_key(points)
    phases = sorted({p.phase for p in points})
    lines = [f"| setting | {key} | " + " | ".join(f"{ph:g}°" for ph in phases) + " |",
             "|---|---|" + "---|" * len(phases)]
    for angle in sorted({p.angle for p in points}):
        for amp in sorted({getattr(p, key) for p in points if p.angle == angle}):
            cells = []
            for ph in phases:
                hit = [p for p in points if p.angle == angle and getattr(p, key) == amp and p.phase == ph]
                if not hit:
                    cells.append("")
                    continue
                p = hit[0]
                mark = {"shakedown": "s", "cyclic_slip": "c", "ratcheting": "R"}.get(p.state, "?")
                cells.append(f"{mark} {p.work:.3g}" if p.work is not None else mark)
            lines.append(f"| {_setting(angle)[0]} | {amp:g} | " + " | ".join(cells) + " |")
    return lines


def plot_phase(folder: Path, points_files, out_dir, overwrite=False, out=print) -> list:
    """The phase figures of a folder whose runs differ in load.phase (none otherwise); prints the table of the
    states and works per period (phase_table)."""
    points = read_phase_points(points_files)
    paths = []
    stem = folder.resolve().name
    if points and varies_phase(points):
        out("state (s shakedown, c cyclic slip: U settled but slipping every period, R ratcheting) and frictional "
            "work of the last period / (mu Fn U0) by phase:")
        for line in phase_table(points):
            out(line)
        paths += save_figure(phase_figure(points, stem), out_dir, f"{stem}_phase", overwrite)
    limits = folder / "limits.csv"
    rows = read_phase_limits(limits) if limits.exists() else []
    if rows and len({r["phase"] for r in rows}) > 1:
        paths += save_figure(phase_limits_figure(rows, stem), out_dir, f"{stem}_phase_limits", overwrite)
    return paths

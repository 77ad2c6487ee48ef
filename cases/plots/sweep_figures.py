"""Figures of a sweep folder (`rollcontact plot OUTDIR`), against the MDR closed forms (solver.mdr.limits).

The runs are read from the run files of the folder (every *.h5 except summary.h5: /summary attributes and the
scene), which works with or without the sweep's summary table; `summary.csv` is used only when the folder
holds no run files. `limits.csv` (from `rollcontact limit-search`) is drawn when present.

* <folder>_usd:        u_sd versus f_t for each w (seed Fig. 8), MDR u_sd for kappa = 1 (Eq. 15), 1.1 (Eq. 16)
                       and 3/2 (Eq. 12), u_stat (Eq. 4) and the end points u_lim = 1 - w_lim^2 (Eq. 17);
                       the fitted kappa of each alignment (fit_kappa over its runs shaken down under constant
                       loads, Point.on_eq13; limit-search probes in runs/ excluded: fit_points) in the legend.
                       Runs in cyclic slip, or with loads oscillating within the period, are outside seed Eq. 13:
                       neither drawn nor fitted (the phase figures show them).
* <folder>_limits:     the (f_t, w) plane (seed Fig. 9 axes: w_lim versus f_t,lim): every run as a marker
                       (filled shakedown, open ratcheting, half undecided, light cyclic slip), Eqs. 18-19 and the
                       MDR limit, limit-search brackets.
* <folder>_ratcheting: du per period versus f_t beyond the limit (seed Fig. 11) with Eqs. 20-21.
* <folder>_angles:     with three or more alignments (a sweep over motion.angle): kappa, u_sd, du, the sideways
                       walk and f_t,lim against the angle (cases.plots.angle_figures).
Colours: the alignment (blue parallel, red perpendicular), darker for larger w; markers: o parallel,
^ perpendicular, D other angles, s the 1-D MDR model.
"""
from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path
import re

import h5py
import numpy as np
import matplotlib.pyplot as plt
from matplotlib.lines import Line2D

from rollcontact.solver.mdr import limits as lim

from rollcontact.cases.results.hdf5 import stored_summary
from rollcontact.cases.plots.common import (
    FIGSIZE, MDR_COLOUR, PARALLEL_COLOUR, PERPENDICULAR_COLOUR, PlotError, save_figure, setting_colour, setting_of)
from rollcontact.cases.scene.scene import Scene
from rollcontact.cases.plots.angle_figures import angle_figure, angle_fit_text, kappa_by, study_angles

MARKERS = {"parallel": "o", "perpendicular": "^"}
CURVES = ((lim.KAPPA_PARALLEL, ":", PARALLEL_COLOUR, "κ = 1, W ∥ Ft (Eq. 15)"),
          (lim.KAPPA_PERPENDICULAR, "-", PERPENDICULAR_COLOUR, "κ = 1.1, W ⊥ Ft (Eq. 16)"),
          (lim.KAPPA_MDR, "-.", MDR_COLOUR, "κ = 3/2, pure MDR (Eq. 12)"))


@dataclass
class Point:
    """One run of a sweep, as the figures need it (normalised, seed Eq. 9)."""

    file: str
    f_t: float
    w: float
    angle: float          # rolling direction relative to Ft, folded to 0..90 deg
    mdr: bool
    state: str
    u_sd: float | None
    du: float | None
    u_stat: float | None
    probe: bool = False   # a limit-search probe (OUTDIR/runs/), not a run of the sweep itself
    du_perp: float | None = None   # change of U_perp over the last period, / U0 (the sideways walk)
    u_perp: float | None = None    # final U_perp / U0 (the sideways offset)
    raw_angle: float | None = None  # motion.angle as given (deg), before folding to 0..90
    oscillating: bool = False      # loads varying within the period (load.ft_amplitude, fn_amplitude)

    @property
    def setting(self) -> str:
        return setting_of(self.angle)

    @property
    def group(self) -> str:
        return self.setting + (" (MDR 1-D)" if self.mdr else "")

    @property
    def on_eq13(self) -> bool:
        """A run seed Eq. 13 describes: shaken down (U settled and no more slip) under constant loads. Cyclic slip
        (U settled, but slipping in every period) and loads oscillating within the period are outside it."""
        return self.state == "shakedown" and not self.oscillating and self.u_sd is not None


def _num(v):
    if v is None:
        return None
    if isinstance(v, bytes):
        v = v.decode()
    if isinstance(v, str):
        if v.strip().lower() in ("", "none", "nan"):
            return None
        try:
            return float(v)
        except ValueError:
            return None
    v = float(v)
    return None if not np.isfinite(v) else v


def _fold(angle: float) -> float:
    t = float(angle) % 180.0
    return 180.0 - t if t > 90.0 else t


def read_point(path) -> Point:
    """Summary attributes and scene of one run file (without reading its fields); OSError if it is not a run
    file with a summary."""
    stored = stored_summary(path)
    if stored is None or not stored["summary"] or not stored["scene"]:
        raise OSError(f"{path}: not a run file with a summary")
    attrs = stored["summary"]
    scene = Scene.from_toml_text(stored["scene"], name=Path(path).stem, run_limits=False)
    f_t = _num(attrs.get("f_t"))
    walk, U0, side = _num(attrs.get("dU_perp_per_period")), _num(attrs.get("U0")), _num(attrs.get("U_perp"))
    return Point(file=Path(path).name, f_t=scene.f_t if f_t is None else f_t, w=_num(attrs.get("w")) or 0.0,
                 angle=_fold(scene.motion.angle),
                 mdr=scene.solver.fidelity == "mdr" or attrs.get("fidelity") == "mdr",
                 state=str(attrs.get("state") or "?"), u_sd=_num(attrs.get("u_sd")), du=_num(attrs.get("du")),
                 u_stat=_num(attrs.get("u_stat")), du_perp=None if walk is None or not U0 else walk / U0,
                 u_perp=None if side is None or not U0 else side / U0,
                 raw_angle=float(scene.motion.angle), oscillating=scene.oscillating)


def _points_from_csv(path) -> list[Point]:
    pts = []
    with open(path, newline="") as fh:
        for row in csv.DictReader(fh):
            key = {_norm(k): v for k, v in row.items() if k}
            f_t, w = _num(key.get("loadft", key.get("ft"))), _num(key.get("motionw", key.get("w")))
            if f_t is None or w is None or key.get("error"):
                continue
            pts.append(Point(file=key.get("file", ""), f_t=f_t, w=w,
                             angle=_fold(_num(key.get("motionangle", key.get("angle"))) or 90.0),
                             mdr=key.get("solverfidelity", "") == "mdr", state=key.get("state", "?"),
                             u_sd=_num(key.get("usd")), du=_num(key.get("du")), u_stat=_num(key.get("ustat"))))
    return pts


def read_folder(folder, notes=None) -> list[Point]:
    """Every run of a sweep folder; PlotError if there is none."""
    folder = Path(folder)
    if not folder.is_dir():
        raise PlotError(f"{folder}: no such folder")
    files = sorted(p for p in list(folder.glob("*.h5")) + list(folder.glob("runs/*.h5"))   # runs/: limit-search
                   if p.name not in ("summary.h5", "limits.h5") and not p.name.startswith("."))
    pts, skipped = [], []
    for f in files:
        try:
            pts.append(read_point(f))
            pts[-1].probe = f.parent != folder
        except (OSError, KeyError, ValueError) as exc:
            skipped.append(f"{f.name} ({type(exc).__name__})")
    if skipped and notes is not None:
        notes.append(f"{folder}: skipped files that are not complete run files: {', '.join(skipped)}")
    if not pts and (folder / "summary.csv").exists():
        pts = _points_from_csv(folder / "summary.csv")
        if notes is not None:
            notes.append(f"{folder}: no run files; read summary.csv")
    if not pts:
        raise PlotError(f"{folder}: no run files (*.h5) and no usable summary.csv; nothing to plot")
    return pts


def _norm(name: str) -> str:
    return re.sub(r"[^a-z0-9]", "", name.lower())


def _base_angle(folder: Path):
    """Rolling angle of limit-search's base scene (limits.h5 attribute base_scene), or None."""
    try:
        with h5py.File(folder / "limits.h5", "r") as h5:
            text = h5.attrs["base_scene"]
        return _fold(Scene.from_toml_text(text.decode() if isinstance(text, bytes) else str(text),
                                           run_limits=False).motion.angle)
    except (OSError, KeyError, ValueError):
        return None


def read_limits(path) -> list[dict]:
    """Rows of limits.csv (cases.sweep.limit_search.LIMIT_COLUMNS): the searched coordinate ('f_t' or 'w') bracketed by
    lower/upper (midpoint), the other one fixed. Returns dicts with f_t, w (midpoints), f_err, w_err
    ([below, above] or None) and angle (deg; from a motion.angle column, else limits.h5's base scene, else 90).
    Failed rows are left out."""
    path = Path(path)
    base_angle = _base_angle(path.parent)
    rows = []
    with open(path, newline="") as fh:
        for row in csv.DictReader(fh):
            key = {_norm(k): v for k, v in row.items() if k}
            if key.get("status", "ok") == "failed":
                continue
            searched = key.get("searched", "f_t")
            lo, hi, mid = _num(key.get("lower")), _num(key.get("upper")), _num(key.get("midpoint"))
            if mid is None and lo is not None and hi is not None:
                mid = 0.5 * (lo + hi)
            if mid is None:
                continue
            err = [[mid - lo], [hi - mid]] if lo is not None and hi is not None else None
            angle = _num(key.get("motionangle", key.get("angle")))
            angle = _fold(angle) if angle is not None else (90.0 if base_angle is None else base_angle)
            if searched == "w":
                f_t = _num(key.get("ft", key.get("loadft")))
                if f_t is not None:
                    rows.append(dict(f_t=f_t, w=mid, f_err=None, w_err=err, angle=angle))
            else:
                w = _num(key.get("w", key.get("motionw")))
                if w is not None:
                    rows.append(dict(f_t=mid, w=w, f_err=err, w_err=None, angle=angle))
    return rows


# ------------------------------------------------------------------------------------------ styling
def _shade(colour, k, n):
    """The alignment colour, lighter for small w (k = rank of w among n values)."""
    c = np.array(plt.matplotlib.colors.to_rgb(colour))
    t = 0.45 + 0.55 * (k + 1) / n if n > 1 else 1.0
    return tuple(1 - t * (1 - c)) if t < 1 else tuple(c)


def _marker(p: Point) -> str:
    return "s" if p.mdr else MARKERS.get(p.setting, "D")


def _w_legend(target, handles, ws, styles, **kwargs):
    """The legend (of an axes or a figure) with an entry per amplitude w: the (line style, colour) of every curve
    family side by side in that w's shade (labels at the curves' ends would cross the other curves)."""
    from matplotlib.legend_handler import HandlerTuple
    handles = handles + [tuple(Line2D([], [], ls=ls, color=_shade(colour, k, len(ws)), lw=1.4)
                               for ls, colour in styles) for k in range(len(ws))]
    labels = [h.get_label() for h in handles[:len(handles) - len(ws)]] + [f"w = {w:g}" for w in ws]
    target.legend(handles, labels, handler_map={tuple: HandlerTuple(ndivide=None, pad=0.3)}, **kwargs)


def fit_points(points) -> list:
    """The runs kappa is fitted to: the sweep's own runs; the limit-search probes (runs/) only when the folder
    has nothing else (of those, kappa_by keeps the ones seed Eq. 13 describes, Point.on_eq13). Probes crowd around the shakedown limit, where u_sd is most sensitive to kappa and to
    the grid, so they would weigh the fit towards the limit instead of over the sweep's range."""
    sweep = [p for p in points if not p.probe]
    return sweep if sweep else list(points)


def fit_scope(points) -> str | None:
    """One line saying what the kappa fit used, when the folder holds limit-search probes; else None."""
    n_probe = sum(p.probe for p in points)
    if not n_probe:
        return None
    n_sweep = len(points) - n_probe
    if n_sweep:
        return (f"kappa fitted to the {n_sweep} sweep runs; {n_probe} limit-search probe(s) (runs/) excluded "
                "(they are drawn in the figures)")
    return f"kappa fitted to the {n_probe} limit-search probe(s) (runs/): the folder holds no sweep runs"


def kappa_fits(points) -> dict:
    """fit_kappa (seed Eq. 13) per alignment group over its runs shaken down under constant loads with w > 0 (see
    fit_points and Point.on_eq13)."""
    return kappa_by(fit_points(points), lambda p: p.group)


def format_fit(fit) -> str:
    err = f" ± {fit.stderr:.2g}" if fit.stderr is not None else " (single point, no error estimate)"
    return f"κ = {fit.kappa:.3f}{err} (n = {fit.n}, rms residual {fit.residual_rms:.2g})"


# ------------------------------------------------------------------------------------------ figures
def usd_figure(points, title):
    """u_sd versus f_t (seed Fig. 8)."""
    fig, ax = plt.subplots(figsize=FIGSIZE["usd"], layout="constrained")
    ws = sorted({round(p.w, 6) for p in points if p.w > 0})
    f = np.linspace(0, 1, 401)
    ax.plot(f, lim.u_stat(f), "-", color="k", lw=1.0)
    ax.annotate("$u_{stat}$ (w = 0, Eq. 4)", (0.8, lim.u_stat(0.8)), xytext=(6, -8), textcoords="offset points",
                ha="left", fontsize=8)
    for k, w in enumerate(ws):
        for kappa, ls, colour, _ in CURVES:
            fl = lim.f_t_lim(w, kappa)
            ff = np.linspace(0, fl, 200)
            u = [lim.u_shakedown(x, w, kappa) for x in ff]
            c = _shade(colour, k, len(ws)) if kappa != lim.KAPPA_MDR else MDR_COLOUR
            ax.plot(ff, u, ls, color=c, lw=1.4 if kappa != lim.KAPPA_MDR else 0.8)
            ax.plot(fl, u[-1], ".", color=c, ms=5)
    wl = np.linspace(0, 1, 200)
    for kappa, colour in ((lim.KAPPA_PARALLEL, PARALLEL_COLOUR), (lim.KAPPA_PERPENDICULAR, PERPENDICULAR_COLOUR)):
        ax.plot(lim.f_t_lim(wl, kappa), lim.u_lim(wl), "--", color=colour, lw=0.8, alpha=0.7)
    fits = kappa_fits(points)
    handles = []
    for g in sorted({p.group for p in points}):
        sel = [p for p in points if p.group == g and p.on_eq13]
        if not sel:
            continue
        for p in sel:
            k = ws.index(round(p.w, 6)) if round(p.w, 6) in ws else 0
            base = MDR_COLOUR if p.mdr else setting_colour(p.angle)
            ax.plot(p.f_t, p.u_sd, _marker(p), color=_shade(base, k, len(ws)), mec="k", mew=0.6, ms=7)
        fit = f": fitted κ = {fits[g].kappa:.3f}" + (f" ± {fits[g].stderr:.2g}" if fits[g].stderr is not None else "") \
            + f" (n = {fits[g].n})" if g in fits else ""
        handles.append(Line2D([], [], ls="none", marker=_marker(sel[0]), mfc="w", mec="k",
                              label=f"simulated, {g}{fit}"))
    handles += [Line2D([], [], ls=ls, color=colour, label=f"MDR $u_{{sd}}$, {label}")
                for _, ls, colour, label in CURVES]
    handles += [Line2D([], [], ls="--", color="0.4", lw=0.8, label="$u_{lim} = 1 - w_{lim}^2$ (Eq. 17)")]
    # below the axes: inside, a legend of this length would hide curves or runs wherever it went
    _w_legend(fig, handles, ws, [(ls, colour) for _, ls, colour, _ in CURVES[:2]], fontsize=8,
              loc="outside lower center", ncol=2)
    n_off = sum(not p.on_eq13 for p in points)
    ax.set_xlabel("$f_t = F_t/(\\mu F_n)$")
    ax.set_ylabel("$u_{sd} = U_{sd}/U_0$")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.02)
    ax.grid(alpha=0.3)
    ax.set_title(f"Shakedown displacement (seed Fig. 8): {title}\n{len(points)} runs, {n_off} not in shakedown "
                 "(not shown); colours darker for larger w", fontsize=10)
    return fig


def limits_figure(points, limits, title):
    """w_lim versus f_t,lim (seed Fig. 9) with every run as a marker in the (f_t, w) plane."""
    fig, ax = plt.subplots(figsize=FIGSIZE["limits"], layout="constrained")
    w = np.linspace(0, 1, 300)
    for kappa, ls, colour, label in CURVES:
        ax.plot(lim.f_t_lim(w, kappa), w, ls, color=colour, lw=1.5 if kappa != lim.KAPPA_MDR else 0.9,
                label=label.replace("(Eq. 15)", "(Eq. 18)").replace("(Eq. 16)", "(Eq. 19)"))
    shown = set()
    for p in points:
        base = MDR_COLOUR if p.mdr else setting_colour(p.angle)
        face = {"shakedown": base, "undecided": base, "cyclic_slip": _shade(base, 0, 4)}.get(p.state, "w")
        lab = f"{p.group}, {p.state.replace('_', ' ')}"
        ax.plot(p.f_t, p.w, _marker(p), color=base, mfc=face, fillstyle="bottom" if p.state == "undecided" else "full",
                mew=1.2, ms=10 if p.setting == "parallel" else 6, label=None if lab in shown else lab)
        shown.add(lab)
    if limits:
        for r in limits:
            ax.errorbar(r["f_t"], r["w"], xerr=r["f_err"], yerr=r["w_err"], fmt="*", color=setting_colour(r["angle"]),
                        mec="k", ms=11, capsize=3, lw=1.2)
        ax.plot([], [], "*", color="0.5", mec="k", ms=11, label="limit-search bracket (limits.csv)")
    ax.set_xlabel("$f_{t,lim} = F_t/(\\mu F_n)$ at the shakedown limit")
    ax.set_ylabel("$w_{lim} = W/a$")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title(f"Shakedown limit (seed Fig. 9): {title}\nfilled: shakedown, open: ratcheting, half: undecided"
                 + (", light: cyclic slip" if any(p.state == "cyclic_slip" for p in points) else "")
                 + ("" if limits else "; no limits.csv in the folder"), fontsize=10)
    return fig


def ratcheting_figure(points, title):
    """du per period versus f_t beyond the limit (seed Fig. 11) with the regressions Eqs. 20-21."""
    fig, ax = plt.subplots(figsize=FIGSIZE["ratcheting"], layout="constrained")
    rat = [p for p in points if p.state in ("ratcheting", "undecided") and p.du is not None]
    ws = sorted({round(p.w, 6) for p in points if p.w > 0})
    f = np.linspace(0, 0.999, 300)
    for k, w in enumerate(ws):
        for setting, ls, colour in (("parallel", ":", PARALLEL_COLOUR), ("perpendicular", "-", PERPENDICULAR_COLOUR)):
            du = np.array([lim.ratcheting_increment(x, min(w, 1.0), setting) for x in f])
            m = du > 0
            if m.any():
                ax.plot(f[m], du[m], ls, color=_shade(colour, k, len(ws)), lw=1.4)
    for p in rat:
        k = ws.index(round(p.w, 6)) if round(p.w, 6) in ws else 0
        base = MDR_COLOUR if p.mdr else setting_colour(p.angle)
        ax.plot(p.f_t, p.du, _marker(p), color=_shade(base, k, len(ws)), mec="k", mew=0.6, ms=7,
                mfc=None if p.state == "ratcheting" else "w")
    handles = [Line2D([], [], ls=":", color=PARALLEL_COLOUR, label="Eq. 20, W ∥ Ft (regression, κ = 1)"),
               Line2D([], [], ls="-", color=PERPENDICULAR_COLOUR, label="Eq. 21, W ⊥ Ft (regression, κ = 1.1)")]
    for g in sorted({p.group for p in rat}):
        p = next(q for q in rat if q.group == g)
        handles.append(Line2D([], [], ls="none", marker=_marker(p), mfc="w", mec="k", label=f"simulated, {g}"))
    _w_legend(ax, handles, ws, [(":", PARALLEL_COLOUR), ("-", PERPENDICULAR_COLOUR)], fontsize=8, loc="upper left")
    ax.set_xlabel("$f_t = F_t/(\\mu F_n)$")
    ax.set_ylabel("$\\Delta u$ per period $= \\Delta U/U_0$")
    ax.set_xlim(0, 1)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.set_title(f"Ratcheting increment (seed Fig. 11): {title}\n"
                 + (f"{len(rat)} runs beyond the limit (open: undecided)" if rat else "no ratcheting runs"),
                 fontsize=10)
    return fig


def plot_folder(folder, out_dir=None, notes=None, out=print, overwrite=False) -> list:
    """The three sweep figures of `folder` into out_dir (default: the folder) from its runs under constant loads,
    and the phase figures of cases.plots.phase_figures when its runs differ in load.phase; prints the fitted
    kappas."""
    folder = Path(folder)
    from rollcontact.cases.plots.wheelrail_figures import is_wheelrail_folder, plot_wheelrail_folder
    if is_wheelrail_folder(folder):                     # a sweep over a [wheelrail] scene
        return plot_wheelrail_folder(folder, Path(out_dir) if out_dir else folder, overwrite, out)
    points = read_folder(folder, notes)
    out_dir = Path(out_dir) if out_dir else folder
    limits_path = folder / "limits.csv"
    limits = read_limits(limits_path) if limits_path.exists() else []
    if limits_path.exists() and not limits and notes is not None:
        notes.append(f"{limits_path}: no rows with recognisable w and f_t columns; not drawn")
    title = folder.resolve().name
    scene = _first_scene(folder)
    if scene is not None and scene.shape in ("cone", "power", "flat_rounded"):
        from rollcontact.cases.plots.shape_figures import plot_shape_folder    # the profile's own MDR
        return plot_shape_folder(points, scene, limits, out_dir, folder.resolve().name, title, out, overwrite)
    stem = folder.resolve().name
    paths = []
    # the seed's figures and closed forms are for constant loads: runs with loads oscillating within the period
    # are drawn in the phase figures instead
    steady = [p for p in points if not p.oscillating]
    if len(steady) < len(points) and notes is not None:
        which = (f"{len(points) - len(steady)} run(s) with loads oscillating within the period are left out of the "
                 "seed's figures" if steady else "its runs have loads oscillating within the period: the seed's "
                 "figures are not drawn")
        notes.append(f"{folder}: {which} (Figs. 8, 9, 11: constant loads); the phase figures show them")
    if steady:
        fits = kappa_fits(steady)
        if fit_scope(steady):
            out(fit_scope(steady))
        for g in sorted({p.group for p in steady}):
            out(f"fitted kappa (seed Eq. 13), {g}: " + (format_fit(fits[g]) if g in fits
                                                       else "no shaken-down run with w > 0, no fit"))
        paths += save_figure(usd_figure(steady, title), out_dir, f"{stem}_usd", overwrite)
        paths += save_figure(limits_figure(steady, limits, title), out_dir, f"{stem}_limits", overwrite)
        paths += save_figure(ratcheting_figure(steady, title), out_dir, f"{stem}_ratcheting", overwrite)
        if len(study_angles(steady)) >= 3:
            out(angle_fit_text(steady, limits))
            paths += save_figure(angle_figure(steady, limits, title), out_dir, f"{stem}_angles", overwrite)
    from rollcontact.cases.plots.phase_figures import plot_phase      # runs differing in load.phase, if any
    paths += plot_phase(folder, sorted(folder.glob("*.h5")) + sorted(folder.glob("runs/*.h5")), out_dir, overwrite,
                        out)
    return paths


def _first_scene(folder: Path):
    """The scene of the first run file of the folder (None without one): its shape selects the figures."""
    for f in sorted(folder.glob("*.h5")) + sorted(folder.glob("runs/*.h5")):
        stored = stored_summary(f) if f.name not in ("summary.h5", "limits.h5") else None
        if stored and stored["scene"]:
            return Scene.from_toml_text(stored["scene"], name=f.stem, run_limits=False)
    return None

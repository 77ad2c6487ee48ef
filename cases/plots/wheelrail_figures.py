"""Figures of [wheelrail] runs (docs/wheelrail.md): `rollcontact plot RUN.h5` draws the wheel and rail around the
contact with the patches' reference points and normals, and each patch's pressure and traction; `rollcontact plot
OUTDIR` of a sweep over wheelrail.y draws the contact-point diagram (the patches' positions on the rail and on the
wheel, their contact angles and the wheel's rolling radius against y: the jumps between tread and flange show) and
the forces against y (the patches' normal forces and the total force on the wheel in the track frame).

Units: mm, N, MPa, rad. Track frame: x along the direction of travel, y to the left, z up; profiles: y towards the
field side, z up.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from rollcontact.cases.plots.common import PlotError, plt, save_figure
from rollcontact.cases.results.hdf5 import stored_summary
from rollcontact.cases.scene.scene import Scene

#: a patch continues a branch of the diagram when its rail position is within this distance (mm) of the branch's
#: last one
BRANCH_GAP = 3.0


def is_wheelrail_run(data) -> bool:
    """True for the result of a [wheelrail] scene (cases.run.wheelrail_run)."""
    return "n_patches" in data.summary


def plot_wheelrail_run(data, out_dir, stem, overwrite=False, notes=None):
    """stem_wheelrail.png/.pdf: the cross-section (when the scene's profile files are still there) and per patch its
    pressure with the contact's outline, and the traction on the rail over mu p with stick / slip."""
    s = data.summary
    n = int(s.get("n_patches") or 0)
    if data.status != "complete" or n == 0:
        raise PlotError(f"{stem}: the run did not complete ({data.status}: {data.error}); nothing to draw")
    scene = data.scene
    fig = plt.figure(figsize=(5.0 + 4.2 * n, 8.0), layout="constrained")
    grid = fig.add_gridspec(2, n + 1, width_ratios=[1.3] + [1.0] * n)
    _cross_section(fig.add_subplot(grid[:, 0]), scene, s, notes)
    mu = scene.load.mu
    for k, patch in enumerate(data.patches):
        v = patch.values
        top, bottom = fig.add_subplot(grid[0, k + 1]), fig.add_subplot(grid[1, k + 1])
        if not patch.fields:
            top.text(0.5, 0.5, "fields not stored\n(output.fields = 'none')", ha="center", va="center")
            top.set_axis_off()
            bottom.set_axis_off()
            continue
        extent = [patch.x[0] - 0.5 * v["dx"], patch.x[-1] + 0.5 * v["dx"], patch.y[0] - 0.5 * v["dy"],
                  patch.y[-1] + 0.5 * v["dy"]]
        p = patch.fields["p"]
        im = top.imshow(p, origin="lower", extent=extent, cmap="viridis", aspect="equal")
        top.contour(patch.x, patch.y, (p > 0).astype(float), levels=[0.5], colors="w", linewidths=0.8)
        fig.colorbar(im, ax=top, label="p (MPa)", shrink=0.8)
        top.set_title(f"patch {k}: rail y {v['y_rail']:.2f} mm, angle {v['contact_angle']:.3f} rad\nFn {v['Fn']:.5g} N, "
                      f"pmax {v['pmax']:.4g} MPa", fontsize=9)
        tau = np.hypot(patch.fields["tau_x"], patch.fields["tau_y"])
        bound = np.where(p > 0, mu * p, np.nan)
        im2 = bottom.imshow(np.where(p > 0, tau / np.maximum(bound, 1e-300), np.nan), origin="lower", extent=extent,
                            cmap="magma", vmin=0.0, vmax=1.0, aspect="equal")
        region = patch.fields["region"]
        bottom.contour(patch.x, patch.y, (region == 1).astype(float), levels=[0.5], colors="c", linewidths=0.9)
        fig.colorbar(im2, ax=bottom, label="|tau| / (mu p) (stick outlined)", shrink=0.8)
        bottom.set_title(f"Fx {v['Fx']:.5g} N, Fy {v['Fy']:.5g} N\nxi {v['xi']:.3g}, eta {v['eta']:.3g}, "
                         f"phi {v['phi']:.3g} 1/mm", fontsize=9)
        for ax in (top, bottom):
            ax.set_xlabel("x (mm, along the track)")
            ax.set_ylabel("s (mm, n x x)")
    wr = scene.wheelrail
    fig.suptitle(f"{stem}: {wr.side} wheel at y = {wr.y:.4g} mm, yaw {wr.yaw:.4g}, roll {wr.roll:.4g} rad, Fz "
                 f"{wr.Fz:.5g} N; F_track = ({s['F_track_x']:.5g}, {s['F_track_y']:.5g}, {s['F_track_z']:.5g}) N",
                 fontsize=10)
    return save_figure(fig, out_dir, f"{stem}_wheelrail", overwrite)


def _cross_section(ax, scene: Scene, s: dict, notes):
    """Rail and wheel (its silhouette along the track at the solved height) in the rail profile's coordinates, with
    each patch's reference point and normal."""
    from rollcontact.bem.errors import RollcontactError
    from rollcontact.cases.scene import wheelrail
    wr = scene.wheelrail
    try:
        found = wheelrail.search(wr)
    except RollcontactError as exc:
        ax.text(0.5, 0.5, "profiles not available:\n" + str(exc)[:80], ha="center", va="center", fontsize=8,
                wrap=True)
        ax.set_axis_off()
        if notes is not None:
            notes.append(f"cross-section not drawn: {exc}")
        return
    rail = found.rail
    wheel = found.wheel(float(s["lowering"]))
    sil = wheel.silhouette(np.linspace(wheel.placement.profile.lo, wheel.placement.profile.hi, 2000))
    ry, rz = rail.to_profile(rail.surface.y, rail.surface.z)
    wy, wz = rail.to_profile(sil.y, sil.z)
    ax.plot(ry, rz, color="0.25", lw=1.2, label="rail")
    ax.plot(wy, wz, color="C0", lw=1.2, label="wheel (silhouette)")
    sign = wheelrail.side_sign(wr)
    span = max(8.0, 0.5 * (ry.max() - ry.min()))
    for k, (y_r, angle) in enumerate(zip(np.atleast_1d(s["patch_y_rail"]), np.atleast_1d(s["patch_contact_angle"]))):
        z_r = float(np.interp(y_r, ry, rz))
        a = sign * angle - rail.inclination          # the normal in the rail profile's axes
        ax.annotate("", xy=(y_r - 4 * math.sin(a), z_r + 4 * math.cos(a)), xytext=(y_r, z_r),
                    arrowprops=dict(arrowstyle="->", color="C3"))
        ax.plot([y_r], [z_r], "o", color="C3", ms=4)
        ax.text(y_r, z_r - 1.5, str(k), color="C3", ha="center", va="top", fontsize=8)
    centre = float(np.mean(np.atleast_1d(s["patch_y_rail"])))
    ax.set_xlim(centre - span, centre + span)
    ax.set_ylim(float(np.interp(centre, ry, rz)) - 0.8 * span, float(np.interp(centre, ry, rz)) + 0.6 * span)
    ax.set_aspect("equal")
    ax.set_xlabel("rail profile y (mm, towards the field side)")
    ax.set_ylabel("rail profile z (mm, up)")
    ax.legend(loc="lower left", fontsize=8)
    ax.set_title("cross-section, patches and normals", fontsize=9)


def is_wheelrail_folder(folder: Path) -> bool:
    """True when the first run file of the folder holds a [wheelrail] scene."""
    for f in sorted(Path(folder).glob("*.h5")):
        stored = stored_summary(f) if f.name != "summary.h5" else None
        if stored and stored["scene"]:
            return "[wheelrail]" in stored["scene"]
    return False


def read_sweep(folder) -> list[dict]:
    """The complete [wheelrail] runs of a folder: per run y (mm), side and its summary (patch arrays, totals), in
    increasing y."""
    runs = []
    for f in sorted(Path(folder).glob("*.h5")):
        stored = stored_summary(f) if f.name != "summary.h5" else None
        if not stored or stored["status"] != "complete" or "n_patches" not in stored["summary"]:
            continue
        scene = Scene.from_toml_text(stored["scene"], name=f.stem, run_limits=False)
        runs.append(dict(y=scene.wheelrail.y, side=scene.wheelrail.side, summary=stored["summary"], file=f.name))
    return sorted(runs, key=lambda r: r["y"])


def branches(runs) -> list[list[tuple]]:
    """The patches of the runs joined into branches: a patch continues the branch whose last rail position (in the run
    before) is nearest, within BRANCH_GAP mm; [(y, index of the patch in its run), ...] per branch."""
    out, last = [], []                 # last: per branch, (y_rail of its last patch, its run's position)
    for i, r in enumerate(runs):
        taken = set()
        for k, y_r in enumerate(np.atleast_1d(r["summary"]["patch_y_rail"])):
            near = [(abs(y_r - last[b][0]), b) for b in range(len(out))
                    if last[b][1] == i - 1 and b not in taken and abs(y_r - last[b][0]) < BRANCH_GAP]
            b = min(near)[1] if near else None
            if b is None:
                out.append([])
                last.append(None)
                b = len(out) - 1
            out[b].append((i, k))
            last[b] = (float(y_r), i)
            taken.add(b)
    return out


def plot_wheelrail_folder(folder, out_dir, overwrite=False, out=print) -> list:
    """<folder>_contact_points and <folder>_forces (PNG + PDF) of a sweep over wheelrail.y."""
    folder = Path(folder)
    runs = read_sweep(folder)
    if not runs:
        raise PlotError(f"{folder}: no complete [wheelrail] run files")
    stem = folder.resolve().name
    side = runs[0]["side"]
    paths = save_figure(_contact_points(runs, stem, side), out_dir, f"{stem}_contact_points", overwrite)
    paths += save_figure(_forces(runs, stem, side), out_dir, f"{stem}_forces", overwrite)
    jumps = [f"{runs[i]['y']:.4g}" for i in range(1, len(runs))
             if runs[i]["summary"]["n_patches"] != runs[i - 1]["summary"]["n_patches"]]
    out(f"{len(runs)} run(s), y = {runs[0]['y']:.4g} to {runs[-1]['y']:.4g} mm; the number of patches changes at y = "
        + (", ".join(jumps) if jumps else "none") + " mm")
    return paths


def _series(runs, branch, name):
    ys = np.array([runs[i]["y"] for i, _ in branch])
    vs = np.array([float(np.atleast_1d(runs[i]["summary"][name])[k]) for i, k in branch])
    return ys, vs


def _contact_points(runs, stem, side):
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), layout="constrained", sharex=True)
    panels = (("patch_y_rail", "on the rail: y (mm)"), ("patch_y_wheel", "on the wheel: y (mm)"),
              ("patch_contact_angle", "contact angle (rad, track frame)"),
              ("patch_rolling_radius", "wheel's rolling radius (mm)"))
    for b, branch in enumerate(branches(runs)):
        for ax, (name, _) in zip(axes.flat, panels):
            ys, vs = _series(runs, branch, name)
            share = _series(runs, branch, "patch_Fn")[1]
            ax.plot(ys, vs, "-", color=f"C{b % 10}", lw=1.0)
            ax.scatter(ys, vs, s=8 + 40 * share / max(1.0, share.max()), color=f"C{b % 10}", zorder=3)
    for ax, (_, label) in zip(axes.flat, panels):
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("wheelset lateral displacement y (mm, towards the field side)")
    fig.suptitle(f"{stem}: contact points of the {side} wheel against its lateral displacement (marker size: the "
                 "patch's normal force; a branch per patch)", fontsize=10)
    return fig


def _forces(runs, stem, side):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), layout="constrained", sharex=True)
    y = np.array([r["y"] for r in runs])
    for name, style in (("F_track_x", "-o"), ("F_track_y", "-s"), ("F_track_z", "-^")):
        axes[0].plot(y, [r["summary"][name] for r in runs], style, ms=3, label=name)
    axes[0].set_ylabel("total force on the wheel (N)")
    axes[0].set_title("track frame: x forward, y left, z up", fontsize=9)
    axes[0].legend(fontsize=8)
    for b, branch in enumerate(branches(runs)):
        ys, fn = _series(runs, branch, "patch_Fn")
        axes[1].plot(ys, fn, "-o", ms=3, color=f"C{b % 10}", label=f"branch {b}")
    axes[1].set_ylabel("patch normal force Fn (N)")
    axes[1].legend(fontsize=8)
    for ax in axes:
        ax.set_xlabel("wheelset lateral displacement y (mm)")
        ax.grid(alpha=0.3)
    fig.suptitle(f"{stem}: forces of the {side} wheel against its lateral displacement", fontsize=10)
    return fig

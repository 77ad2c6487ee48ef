"""Subsurface stresses of a stored run: computed from the stored tractions (bem.subsurface) and added to the run file.

Layout (README, "HDF5 layout"; names and units in cases.results.run_result.SUBSURFACE_UNITS):

    /subsurface         attrs: nu (the substrate's Poisson ratio used), depths ('default' or 'given')
    /subsurface/z       depths below the surface (mm), shape (nz,)
    /subsurface/step    the steps computed, shape (snapshots,); each is a stored step of /fields
    /subsurface/<name>  shape (snapshots, nz, ny, nx) on the run's grid (/grid/x, /grid/y): s_xx, s_yy, s_zz, s_yz,
                        s_xz, s_xy, von_mises, tresca, principal_1 (MPa)

The stresses are in the frame (x, y, z) with z the depth into the substrate, tension positive: at the surface
s_zz = -p, s_xz = -tau_x, s_yz = -tau_y. They depend on the substrate's Poisson ratio nu2 only.

Default depths: DEFAULT_DEPTH_COUNT depths from 0 to DEFAULT_DEPTH_EXTENT * a (a: the Hertz contact radius of the
run's summary), z_k = extent a (k / (count - 1))^DEFAULT_DEPTH_GRADING: spacing 0.013 a under the surface, 0.06 a at
the Hertz maximum of the shear stress (0.48 a), 0.1 a at 2 a.

Writing: the run file is rebuilt in a temporary file beside it (everything but an older /subsurface copied, then
the new group filled depth by depth) and renamed over it, under the run file's lock: a reader sees the old file or
the new one, and a run still writing the file refuses the command. Memory: the stress operator (about 37 padded
arrays) and one depth layer of the nine fields; a 256 x 256 grid at 64 depths needs ~0.2 GB whatever the count of
depths (benchmarks/subsurface.py measures it).
"""
from __future__ import annotations

import math
from pathlib import Path
import time

import h5py
import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.subsurface import COMPONENTS, SubsurfaceStresses, invariants
from rollcontact.cases.results.hdf5 import GZIP_LEVEL, replacing, wait_for_replaced
from rollcontact.cases.results.lock import OutputLock
from rollcontact.cases.results.run_result import SUBSURFACE_NAMES, UNITS
from rollcontact.cases.scene.scene import Scene

DEFAULT_DEPTH_COUNT = 30
DEFAULT_DEPTH_EXTENT = 2.0     # deepest default depth, in contact radii a
DEFAULT_DEPTH_GRADING = 1.5    # z_k ~ k^grading: finer near the surface


def default_depths(a: float, count: int = DEFAULT_DEPTH_COUNT, extent: float = DEFAULT_DEPTH_EXTENT,
                   grading: float = DEFAULT_DEPTH_GRADING) -> np.ndarray:
    """The default depths (mm) for a contact radius a (mm): z_k = extent a (k/(count-1))^grading, k = 0..count-1."""
    if not (a > 0 and math.isfinite(a)):
        raise InputError(f"contact radius a = {a!r} mm: must be > 0 to place the default depths; give --depths")
    k = np.arange(count) / (count - 1)
    return extent * a * k ** grading


def parse_depths(text: str) -> np.ndarray:
    """'z1,z2,...' (mm) -> sorted unique depths; InputError naming --depths for anything but finite values >= 0."""
    try:
        values = [float(v) for v in str(text).split(",") if v.strip()]
    except ValueError:
        raise InputError(f"--depths {text!r}: expected depths in mm separated by commas, e.g. 0,0.5,1.5") from None
    if not values or not all(math.isfinite(v) and v >= 0 for v in values):
        raise InputError(f"--depths {text!r}: each depth must be a finite number >= 0 (mm below the surface)")
    return np.unique(np.array(values))


def grid_of(x, y) -> Grid:
    """The world-fixed `Grid` whose cell centres are the stored /grid/x, /grid/y (mm)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    dx = float(x[1] - x[0]) if len(x) > 1 else 1.0
    dy = float(y[1] - y[0]) if len(y) > 1 else dx
    return Grid(len(x), len(y), dx, dy, int(round(x[0] / dx)), int(round(y[0] / dy)))


def _selected_steps(stored, steps) -> list[int]:
    """The requested steps (default: the last stored), each checked to be stored."""
    stored = [int(s) for s in stored]
    if not stored:
        raise InputError("the run file stores no field snapshots (output.fields = 'none', or an MDR run): "
                         "there are no tractions to compute stresses from")
    if steps is None:
        return stored[-1:]
    if steps == "all":
        return stored
    chosen = sorted({int(s) for s in steps})
    missing = [s for s in chosen if s not in stored]
    if missing:
        raise InputError(f"--step {missing[0]}: not a stored step; stored steps: {_compact(stored)}")
    return chosen


def _compact(steps) -> str:
    return ", ".join(map(str, steps)) if len(steps) <= 12 else f"{steps[0]}, {steps[1]}, ..., {steps[-1]}"


def add_subsurface(path, steps=None, depths=None, progress=None, threads: int = 1) -> dict:
    """Compute the subsurface stresses of the run file `path` and store them in it (layout in the module docstring).

    steps: stored steps (an iterable), 'all', or None for the last stored step. depths: depths in mm (>= 0), or None
    for `default_depths` of the run's contact radius. progress: callable(message) or None. A /subsurface group the
    file holds already is replaced. Returns {'steps', 'z', 'seconds'} (seconds: the computation, without the I/O).
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: no such run file")
    with OutputLock(path, label=str(path)):
        with h5py.File(path, "r") as src:
            if "fields" not in src or "p" not in src["fields"]:
                raise InputError(f"{path}: not a run file with field snapshots (no /fields/p)")
            chosen = _selected_steps(src["fields/step"][()], steps)
            scene = Scene.from_toml_text(_text(src.attrs["scene"]), run_limits=False)
            nu = scene.materials.nu2
            grid = grid_of(src["grid/x"][()], src["grid/y"][()])
            a = float(src["summary"].attrs.get("a", np.nan)) if "summary" in src else np.nan
            z = np.asarray(depths, dtype=float) if depths is not None else default_depths(
                a if a > 0 else scene.contact_radius)
            if z.ndim != 1 or not len(z) or not np.all(np.isfinite(z) & (z >= 0)):
                raise InputError(f"depths {depths!r}: must be finite values >= 0 mm")
            with replacing(path) as tmp:
                with h5py.File(tmp, "w") as dst:
                    for key, value in src.attrs.items():
                        dst.attrs[key] = value
                    for key in src:
                        if key != "subsurface":
                            src.copy(src[key], dst, name=key)
                    seconds = _fill(dst, src, grid, nu, chosen, z, depths is None, progress, threads)
    wait_for_replaced()
    return {"steps": chosen, "z": z, "seconds": seconds}


def _fill(dst, src, grid, nu, steps, z, default, progress, threads) -> float:
    """Create /subsurface in `dst` and fill it step by step, depth by depth (tractions read from `src`)."""
    group = dst.create_group("subsurface")
    group.attrs["nu"] = nu
    group.attrs["depths"] = "default" if default else "given"
    for name, values in (("z", z), ("step", np.asarray(steps, dtype=np.int64))):
        group.create_dataset(name, data=values).attrs["units"] = UNITS[name]
    ny, nx = grid.shape
    shape = (len(steps), len(z), ny, nx)
    out = {}
    for name in SUBSURFACE_NAMES:
        out[name] = group.create_dataset(name, shape=shape, dtype=np.float64, chunks=(1, 1, ny, nx),
                                         compression="gzip", compression_opts=GZIP_LEVEL)
        out[name].attrs["units"] = UNITS[name]
    stored = [int(s) for s in src["fields/step"][()]]
    op = SubsurfaceStresses(grid, nu, threads=threads)
    layer = np.empty((6, ny, nx))
    seconds = 0.0
    for i, step in enumerate(steps):
        k = stored.index(step)
        p, tx, ty = (src[f"fields/{n}"][k] for n in ("p", "tau_x", "tau_y"))
        t0 = time.perf_counter()
        op.set_tractions(p, tx, ty)
        seconds += time.perf_counter() - t0
        for j, depth in enumerate(z):
            t0 = time.perf_counter()
            op.layer(float(depth), out=layer)
            derived = invariants(layer)
            seconds += time.perf_counter() - t0
            for m, name in enumerate(COMPONENTS):
                out[name][i, j] = layer[m]
            for name, values in derived.items():
                out[name][i, j] = values
        if progress:
            progress(f"subsurface stresses: step {step} ({i + 1}/{len(steps)}), {len(z)} depths, max von Mises "
                     f"{max(out['von_mises'][i, j].max() for j in range(len(z))):.4g} MPa")
    return seconds


def read_subsurface(path) -> dict:
    """The /subsurface group of a run file as numpy arrays ({'z', 'step', name: (snapshots, nz, ny, nx)}), with
    'x', 'y' (the grid, mm) and 'nu'; InputError when the file holds none."""
    with h5py.File(path, "r") as h5:
        if "subsurface" not in h5:
            raise InputError(f"{path}: holds no subsurface stresses; compute them with: rollcontact stresses {path}")
        g = h5["subsurface"]
        out = {name: g[name][()] for name in g}
        out["nu"] = float(g.attrs["nu"])
        out["x"], out["y"] = h5["grid/x"][()], h5["grid/y"][()]
    return out


def computed_steps(path) -> list[int]:
    """The steps whose subsurface stresses the run file holds ([] when it holds none)."""
    try:
        with h5py.File(path, "r") as h5:
            return [int(v) for v in h5["subsurface/step"][()]] if "subsurface" in h5 else []
    except OSError:
        return []


def read_sections(path, step: int, point, names=("von_mises", "tresca")) -> dict:
    """Sections through `point` (x, y in mm; the nearest grid row and column) at a computed `step`:
    {'x', 'y', 'z', 'xz': {name: (nz, nx)}, 'yz': {name: (nz, ny)}, 'row_y', 'column_x'} (mm, MPa). Reads only the
    two sections (one hyperslab per dataset), whatever the size of the block."""
    with h5py.File(path, "r") as h5:
        g = h5["subsurface"]
        steps = [int(v) for v in g["step"][()]]
        if int(step) not in steps:
            raise InputError(f"step {step}: no subsurface stresses stored; computed steps: {_compact(steps)}")
        k = steps.index(int(step))
        x, y = h5["grid/x"][()], h5["grid/y"][()]
        j, i = int(np.argmin(np.abs(y - point[1]))), int(np.argmin(np.abs(x - point[0])))
        return {"x": x, "y": y, "z": g["z"][()], "row_y": float(y[j]), "column_x": float(x[i]),
                "xz": {n: g[n][k, :, j, :] for n in names}, "yz": {n: g[n][k, :, :, i] for n in names}}


def block_maxima(path, names=("von_mises", "tresca")) -> dict:
    """Per computed step, the maximum over the whole block of each name and where it is: {'step': (n,), name:
    {'value', 'x', 'y', 'z'} of arrays (n,)} (MPa, mm). Read one depth layer at a time (bounded memory)."""
    with h5py.File(path, "r") as h5:
        g = h5["subsurface"]
        x, y, z, steps = h5["grid/x"][()], h5["grid/y"][()], g["z"][()], g["step"][()]
        out = {"step": steps}
        for name in names:
            ds = g[name]
            res = {key: np.empty(len(steps)) for key in ("value", "x", "y", "z")}
            for k in range(len(steps)):
                best = (-np.inf, 0, 0, 0)
                for d in range(len(z)):
                    layer = ds[k, d]
                    flat = int(np.argmax(layer))
                    if layer.flat[flat] > best[0]:
                        best = (float(layer.flat[flat]), d) + np.unravel_index(flat, layer.shape)
                res["value"][k], res["z"][k], res["y"][k], res["x"][k] = best[0], z[best[1]], y[best[2]], x[best[3]]
            out[name] = res
    return out


def _text(value) -> str:
    return value.decode() if isinstance(value, bytes) else str(value)

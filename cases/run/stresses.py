"""Subsurface stresses of a stored run: computed from the stored tractions (bem.subsurface) and added to the run file
as /subsurface (layout: cases.results.subsurface; docs/hdf5_schema.md).

Default depths: DEFAULT_DEPTH_COUNT depths from 0 to DEFAULT_DEPTH_EXTENT * a (a: the Hertz contact radius of the
run's summary), z_k = extent a (k / (count - 1))^DEFAULT_DEPTH_GRADING: spacing 0.013 a under the surface, 0.06 a at
the Hertz maximum of the shear stress (0.48 a), 0.1 a at 2 a.

Writing: the run file is rebuilt in a temporary file beside it (everything but an older /subsurface copied, then
the new group filled step by step, depth by depth) and renamed over it, under the run file's lock: a reader sees the
old file or the new one, and a run still writing the file refuses the command. Each layer of a field is one chunk,
stored with HDF5's standard shuffle and deflate filters (LAYER_FILTERS: level 1, which on these dense fields of
doubles compresses better and about twice as fast as deflate alone at level 4), compressed here and written as it is
(`write_layer`). Memory: the stress operator (48 padded arrays' worth, 100 MB at 256 x 256), one depth layer of the
nine fields and the tractions of the chosen steps (read once), whatever the count of depths
(benchmarks/subsurface.py measures a 256 x 256 x 64 block).
"""
from __future__ import annotations

import math
from pathlib import Path
import time
import zlib

import h5py
import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.subsurface import COMPONENTS, SubsurfaceStresses, invariants
from rollcontact.cases.arguments import arg
from rollcontact.cases.results.writing import new_hdf5, wait_for_replaced
from rollcontact.cases.results.lock import OutputLock
from rollcontact.cases.results.run_result import SUBSURFACE_NAMES, UNITS
from rollcontact.cases.scene.scene import Scene

#: HDF5 filters of every /subsurface layer (one chunk each), here and in the step files of cases.run.step_stresses:
#: chunks are copied between them as they are, so both use these (`same_filters` checks a file written elsewhere)
LAYER_FILTERS = dict(shuffle=True, compression="gzip", compression_opts=1)
#: the tractions of the chosen steps are read once when they take at most this many bytes (else once per depth)
TRACTION_BYTES = 64 * 2 ** 20

DEFAULT_DEPTH_COUNT = 30
DEFAULT_DEPTH_EXTENT = 2.0     # deepest default depth, in contact radii a
DEFAULT_DEPTH_GRADING = 1.5    # z_k ~ k^grading: finer near the surface


def default_depths(a: float, count: int = DEFAULT_DEPTH_COUNT, extent: float = DEFAULT_DEPTH_EXTENT,
                   grading: float = DEFAULT_DEPTH_GRADING) -> np.ndarray:
    """The default depths (mm) for a contact radius a (mm): z_k = extent a (k/(count-1))^grading, k = 0..count-1."""
    if not (a > 0 and math.isfinite(a)):
        raise InputError(f"contact radius a = {a!r} mm: must be > 0 to place the default depths; give {arg('depths')}")
    k = np.arange(count) / (count - 1)
    return extent * a * k ** grading


def parse_depths(text: str) -> np.ndarray:
    """'z1,z2,...' (mm) -> the depths, checked (`check_depths`); InputError naming --depths for anything but finite
    values >= 0 in increasing order."""
    try:
        values = [float(v) for v in str(text).split(",") if v.strip()]
    except ValueError:
        raise InputError(f"{arg('depths')} {text!r}: expected depths in mm separated by commas, e.g. 0,0.5,1.5") from None
    return check_depths(values, text)


def check_depths(depths, label=None) -> np.ndarray:
    """The depths (mm) as a 1-D array: finite, >= 0, strictly increasing (none sorted or dropped unannounced);
    InputError naming the depths (as `label`, default their value) otherwise."""
    label = depths if label is None else label
    try:
        z = np.asarray(depths, dtype=float)
    except (TypeError, ValueError):
        z = np.zeros(0)
    if z.ndim != 1 or not len(z) or not np.all(np.isfinite(z) & (z >= 0)):
        raise InputError(f"{arg('depths')} {label!r}: each depth must be a finite number >= 0 (mm below the "
                         "surface), at least one")
    if np.any(np.diff(z) <= 0):
        k = int(np.flatnonzero(np.diff(z) <= 0)[0])
        raise InputError(f"{arg('depths')} {label!r}: depths must increase, each given once (mm below the surface); "
                         f"{z[k + 1]:g} follows {z[k]:g}")
    return z


def run_depths(scene: Scene, a: float, depths=None) -> np.ndarray:
    """The depths (mm) of a run's stresses: `depths` checked (`check_depths`), or, when None, the default depths of
    the contact radius a (mm; the run summary's) or, when a is not > 0, of the scene's."""
    if depths is None:
        return default_depths(a if a > 0 else scene.contact_radius)
    return check_depths(depths)


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
    if isinstance(steps, str):
        if steps != "all":
            raise InputError(f"{arg('steps')} {steps!r}: expected stored steps, 'all' or None (the last stored step)")
        return stored
    if isinstance(steps, (int, np.integer)):
        steps = [steps]
    try:
        chosen = sorted({int(s) for s in steps})
    except (TypeError, ValueError):
        raise InputError(f"{arg('steps')} {steps!r}: expected stored steps (integers), 'all' or None") from None
    missing = [s for s in chosen if s not in stored]
    if missing:
        raise InputError(f"{arg('step')} {missing[0]}: not a stored step; stored steps: {_compact(stored)}")
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
        raise InputError(f"{path}: " + ("is a folder; expected a run file (.h5)" if path.is_dir() else "no such file"))
    if not h5py.is_hdf5(path):
        raise InputError(f"{path}: not an HDF5 file; expected a run file written by rollcontact run")
    with OutputLock(path, label=str(path)):
        try:
            src = h5py.File(path, "r")
        except OSError:
            raise InputError(f"{path}: cannot be read as HDF5 (a truncated or damaged file); expected a run file "
                             "written by rollcontact run") from None
        with src:
            missing = [k for k in ("fields/p", "fields/tau_x", "fields/tau_y", "fields/step", "grid/x", "grid/y")
                       if k not in src] + [k for k in ("scene",) if k not in src.attrs]
            if missing:
                raise InputError(f"{path}: not a run file with field snapshots (no {missing[0]})")
            chosen = _selected_steps(src["fields/step"][()], steps)
            scene = Scene.from_toml_text(_text(src.attrs["scene"]), run_limits=False)
            nu = scene.materials.nu2
            grid = grid_of(src["grid/x"][()], src["grid/y"][()])
            a = float(src["summary"].attrs.get("a", np.nan)) if "summary" in src else np.nan
            z = run_depths(scene, a, depths)
            try:
                with new_hdf5(path, "run file") as (dst, check):
                    for key, value in src.attrs.items():
                        dst.attrs[key] = value
                    for key in src:
                        if key != "subsurface":
                            src.copy(src[key], dst, name=key)
                    check()
                    seconds = _fill(dst, src, grid, nu, chosen, z, depths is None, progress, threads, check)
            except OSError:      # reading the run file failed part-way (a failed write is an OutputWriteError)
                raise InputError(f"{path}: cannot be read as HDF5 (a truncated or damaged file); expected a run "
                                 "file written by rollcontact run") from None
    wait_for_replaced()
    return {"steps": chosen, "z": z, "seconds": seconds}


def subsurface_in_memory(result, steps=None, depths=None, progress=None, threads: int = 1):
    """The subsurface stresses of a RunResult held in memory (no file): the same values `add_subsurface` stores, for
    `steps` (stored steps, 'all', or None for the last) at `depths` (mm; None: the default depths of the run's
    contact radius), as a cases.results.subsurface.Subsurface of arrays (snapshots, nz, ny, nx) in MPa."""
    from rollcontact.cases.results.subsurface import Subsurface
    chosen = _selected_steps(result.field_steps, steps)
    scene = result.scene
    grid = grid_of(result.x, result.y)
    a = result.summary.get("a")
    z = run_depths(scene, float(a) if a is not None else np.nan, depths)
    op = SubsurfaceStresses(grid, scene.materials.nu2, threads=threads)
    stored = [int(s) for s in np.asarray(result.field_steps)]
    arrays = {name: np.empty((len(chosen), len(z)) + grid.shape) for name in SUBSURFACE_NAMES}
    layer = np.empty((6,) + grid.shape)
    t0 = time.perf_counter()
    for i, step in enumerate(chosen):
        k = stored.index(step)
        op.set_tractions(*(result.fields[n][k] for n in ("p", "tau_x", "tau_y")))
        for j, depth in enumerate(z):
            for name, v in layer_fields(op, float(depth), layer).items():
                arrays[name][i, j] = v
        if progress:
            progress(f"subsurface stresses of step {step}: {len(z)} depths")
    return Subsurface(None, z=z, steps=chosen, x=np.asarray(result.x), y=np.asarray(result.y),
                      nu=float(scene.materials.nu2), depths="default" if depths is None else "given", arrays=arrays,
                      seconds=time.perf_counter() - t0, computed=chosen)


def _fill(dst, src, grid, nu, steps, z, default, progress, threads, check) -> float:
    """Create /subsurface in `dst` and fill it depth by depth, step by step (tractions read from `src`); check()
    after each depth stops at the first failed write."""
    out = create_group(dst, nu, z, steps, default, grid.shape)
    stored = [int(s) for s in src["fields/step"][()]]
    op = SubsurfaceStresses(grid, nu, threads=threads)
    layer = np.empty((6,) + grid.shape)

    def tractions(step):
        return tuple(src[f"fields/{n}"][stored.index(step)] for n in ("p", "tau_x", "tau_y"))
    held = None
    if 3 * len(steps) * layer[0].nbytes <= TRACTION_BYTES:
        held = {step: tractions(step) for step in steps}
    seconds = 0.0
    for j, depth in enumerate(z):        # depths outside: each depth's kernels are built once for all the steps
        worst = 0.0
        for i, step in enumerate(steps):
            t0 = time.perf_counter()
            if len(steps) > 1 or j == 0:     # one step: its tractions are transformed once
                op.set_tractions(*(held[step] if held is not None else tractions(step)))
            values = layer_fields(op, float(depth), layer)
            seconds += time.perf_counter() - t0
            for name, v in values.items():
                write_layer(out[name], (i, j), v)
            worst = max(worst, float(values["von_mises"].max()))
        check()
        if progress:
            progress(f"subsurface stresses: depth {j + 1}/{len(z)} (z = {float(depth):.4g} mm), {len(steps)} "
                     f"step(s), max von Mises {worst:.4g} MPa")
    return seconds


def write_layer(dataset, index, values):
    """Write the (ny, nx) layer `values` as the chunk at `index` (the leading indices) of a dataset created with
    LAYER_FILTERS: byte-shuffled (HDF5's shuffle filter: the k-th bytes of all values together) and deflated."""
    values = np.ascontiguousarray(values, dtype=np.float64)
    shuffled = np.ascontiguousarray(values.view(np.uint8).reshape(-1, values.itemsize).T)
    dataset.id.write_direct_chunk(tuple(index) + (0, 0), zlib.compress(shuffled, LAYER_FILTERS["compression_opts"]))


def same_filters(dataset) -> bool:
    """True when `dataset` (a layer dataset of another file) stores its chunks with LAYER_FILTERS, so that they can be
    copied as they are."""
    return (dataset.shuffle == LAYER_FILTERS["shuffle"] and dataset.compression == LAYER_FILTERS["compression"]
            and dataset.compression_opts == LAYER_FILTERS["compression_opts"] and not dataset.fletcher32
            and dataset.scaleoffset is None)


def create_group(h5, nu, z, steps, default, shape) -> dict:
    """The /subsurface group of the open run file `h5` (layout in cases.results.subsurface) for `steps` at the depths
    z (mm) on a grid of `shape` (ny, nx), its nine datasets created (one gzip chunk per layer) and returned by name."""
    group = h5.create_group("subsurface")
    group.attrs["nu"] = nu
    group.attrs["depths"] = "default" if default else "given"
    for name, values in (("z", z), ("step", np.asarray(steps, dtype=np.int64))):
        group.create_dataset(name, data=values).attrs["units"] = UNITS[name]
    ny, nx = shape
    out = {}
    for name in SUBSURFACE_NAMES:
        out[name] = group.create_dataset(name, shape=(len(steps), len(z), ny, nx), dtype=np.float64,
                                         chunks=(1, 1, ny, nx), **LAYER_FILTERS)
        out[name].attrs["units"] = UNITS[name]
    return out


def layer_fields(op: SubsurfaceStresses, depth: float, layer=None) -> dict:
    """The nine stored fields (SUBSURFACE_NAMES, MPa, each (ny, nx)) at `depth` (mm) below the tractions set on `op`:
    the six components (views into `layer`, a (6, ny, nx) work array) and the invariants."""
    layer = op.layer(depth, out=layer)
    return {**{name: layer[m] for m, name in enumerate(COMPONENTS)}, **invariants(layer)}


def _text(value) -> str:
    return value.decode() if isinstance(value, bytes) else str(value)

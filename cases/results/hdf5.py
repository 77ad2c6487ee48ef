"""HDF5 output of a run, written atomically (temporary file in the same folder, then rename).

Layout (public contract; later versions add to it, never rename):

    /                   attrs: rollcontact_version, scene (full scene as TOML text), status
                        ('complete', 'failed', or 'incomplete': a checkpoint of a run going on or killed),
                        error (message, when failed); a restarted run also
                        restarted_from (source file), restart_step, restart_overrides (the --set items)
    /grid/x, /grid/y    cell-centre coordinates (mm)
    /history/<name>     one value per step (names and units: cases.results.run_result.HISTORY_UNITS)
    /fields/<name>      shape (snapshots, ny, nx); /fields/step says which steps were stored (FIELD_UNITS)
    /summary            attrs: run summary (state, u_sd, ...); a value that does not apply (u_sd of a
                        ratcheting run, say) is NaN, or -1 for the counts in SUMMARY_COUNTS, as in a
                        sweep's summary.h5 (readers also accept the text 'none', which the first files of
                        version 0.1.0 wrote)
    /patches/<k>/       a [wheelrail] run's contact patches k = 0, 1, ...: grid/x, grid/y and fields/<name>
                        (1, ny, nx) as at the root, in the patch's tangent plane; attrs: the patch's values
                        (cases.results.run_result.PATCH_UNITS)

A reader that opens a file sees either nothing (no file) or a complete file: the rename is atomic on
POSIX file systems. A run that fails still writes what it computed, with status = 'failed'.
"""
from __future__ import annotations

import functools
import math
from pathlib import Path
import zlib

import h5py
import numpy as np

from rollcontact.cases.results.run_result import UNITS, PatchData, RunResult
from rollcontact.cases.results.snapshots import SnapshotStack
from rollcontact.cases.results.subsurface import Subsurface
# re-exported: the modules that add to a run file write through them
from rollcontact.cases.results.writing import new_hdf5, replacing, wait_for_replaced, write_bytes  # noqa: F401

#: deflate level of the field snapshots: level 1 compresses them as well as h5py's default 4 (within 1 %: they are
#: mostly zeros outside the contact) in three quarters of the time
GZIP_LEVEL = 1
#: chunk length of the growable history datasets of a checkpointed run
HISTORY_CHUNK = 256

#: Summary attributes that are counts: stored as -1 when they do not apply (every other one as NaN).
SUMMARY_COUNTS = ("periods_to_shakedown", "stopped_at_step", "steps", "steps_planned", "iterations", "nx", "ny",
                  "elements", "springs", "checkpoints")


@functools.cache
def version() -> str:
    """The installed rollcontact version (package metadata), written into every file."""
    from rollcontact import __version__
    return __version__


def write_run(path, data: RunResult, chunks: dict | None = None, extend=None, what: str = "run file") -> Path:
    """Write `data` to `path` atomically (a temporary file in the same folder, renamed into place; its folder must
    exist); returns the path. chunks: {field name: [gzip-compressed (ny, nx) snapshots]} already compressed by the
    caller (a run compresses each snapshot once, when it is recorded); the other fields are compressed here. Every
    snapshot is one gzip chunk either way. extend: callable(h5) that adds to the file before it is renamed into place
    (the /subsurface of `run --stresses`). OutputWriteError naming the file when it cannot be written (nothing is
    left under its name; cases.results.writing)."""
    path = Path(path)
    with new_hdf5(path, what) as (h5, _):
        fill_run(h5, data, chunks or {})
        if extend is not None:
            extend(h5)
    return path


def fill_run(h5, data: RunResult, chunks: dict, growable: bool = False):
    """Lay `data` out in the open, empty HDF5 file `h5` (the layout of the module docstring). growable: history
    and fields extendable (cases.results.growing_file)."""
    h5.attrs["rollcontact_version"] = data.version or version()
    h5.attrs["scene"] = data.scene_toml
    root_attrs(h5, data)
    grid = h5.create_group("grid")
    _dataset(grid, "x", data.x)
    _dataset(grid, "y", data.y)
    hist = h5.create_group("history")
    for name, values in data.history.items():
        _dataset(hist, name, np.asarray(values), **(dict(maxshape=(None,), chunks=(HISTORY_CHUNK,)) if growable
                                                    else {}))
    _write_fields(h5.create_group("fields"), data, chunks, growable)
    write_summary_attrs(h5.create_group("summary").attrs, data.summary)
    if data.patches:
        _write_patches(h5.create_group("patches"), data.patches)


def _write_patches(group, patches):
    """/patches/<k>/: grid, fields (one snapshot, gzip) and the patch's values as attributes."""
    for k, patch in enumerate(patches):
        g = group.create_group(str(k))
        grid = g.create_group("grid")
        _dataset(grid, "x", np.asarray(patch.x))
        _dataset(grid, "y", np.asarray(patch.y))
        fields = g.create_group("fields")
        _dataset(fields, "step", np.zeros(1 if patch.fields else 0, dtype=np.int64))
        for name, values in patch.fields.items():
            values = np.asarray(values)[None]
            _dataset(fields, name, values, chunks=values.shape, compression="gzip", compression_opts=GZIP_LEVEL)
        for key, value in patch.values.items():
            g.attrs[key] = _attr_value(key, value)
        if patch.history:
            history = g.create_group("history")
            for name, values in patch.history.items():
                _dataset(history, name, np.asarray(values))


def _read_patches(h5) -> list:
    if "patches" not in h5:
        return []
    out = []
    for k in sorted(h5["patches"], key=int):
        g = h5["patches"][k]
        fields = {n: v[0] for n, v in ((n, g["fields"][n][()]) for n in g["fields"] if n != "step") if len(v)}
        history = {n: v[()] for n, v in g["history"].items()} if "history" in g else {}
        out.append(PatchData(g["grid/x"][()], g["grid/y"][()], fields, summary_from_attrs(g.attrs), history))
    return out


def save_image(path, image: bytes, what: str = "checkpoint") -> Path:
    """Write the bytes of an HDF5 file image to `path` atomically (a temporary file, renamed into place);
    OutputWriteError naming the file when it cannot be written (the file it would replace is kept)."""
    return write_bytes(path, image, what)


def append(dataset, values: np.ndarray, start: int):
    """Extend a growable 1-D dataset to len(values) and write values[start:] (h5py's low-level calls: a third of
    the time of slicing, which matters when a checkpoint appends to 18 history datasets)."""
    n = len(values)
    dataset.set_extent((n,))
    if n > start:
        file_space = dataset.get_space()
        file_space.select_hyperslab((start,), (n - start,))
        block = np.ascontiguousarray(values[start:], dtype=dataset.dtype)
        dataset.write(h5py.h5s.create_simple((n - start,)), file_space, block)


def _same_value(a, b) -> bool:
    try:
        return bool(np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True))
    except TypeError:
        return bool(np.array_equal(np.asarray(a), np.asarray(b)))


def root_attrs(h5, data: RunResult):
    """Status, error and the further root attributes of `data` on the open file `h5` (a list of texts, such as
    restart_overrides, as an array of strings, also when empty)."""
    h5.attrs["status"] = data.status
    h5.attrs["error"] = data.error
    for key, value in data.attrs.items():
        if isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
            value = np.array(list(value), dtype=h5py.string_dtype())
        h5.attrs[key] = value


def write_summary_attrs(attrs, summary: dict, stored: dict | None = None):
    """The summary as attributes (NaN / -1 where a value does not apply); with `stored` (what the attributes hold
    already), only what changed is written and what went is deleted: an attribute write costs 0.1-0.2 ms."""
    for key in [k for k in (stored or {}) if k not in summary]:
        del attrs[key]
    for key, value in summary.items():
        value = _attr_value(key, value)
        if stored is None or key not in stored or not _same_value(_attr_value(key, stored[key]), value):
            attrs[key] = value


def compress_snapshot(values: np.ndarray) -> bytes:
    """One (ny, nx) snapshot as the gzip chunk `write_run` stores (deflate level GZIP_LEVEL)."""
    return zlib.compress(np.ascontiguousarray(values).tobytes(), GZIP_LEVEL)


def _write_fields(group, data: RunResult, chunks: dict, growable: bool):
    steps = np.asarray(data.field_steps, dtype=np.int64)
    _dataset(group, "step", steps, **(dict(maxshape=(None,), chunks=(HISTORY_CHUNK,)) if growable else {}))
    for name, values in data.fields.items():
        compressed = chunks.get(name)
        if isinstance(values, SnapshotStack):      # snapshots held as their chunks: written as they are
            compressed = values.chunks
        elif not isinstance(values, np.ndarray):
            values = np.asarray(values)
        if values.ndim != 3 or (values.shape[0] == 0 and not growable):
            _dataset(group, name, np.asarray(values))
            continue
        shape = (1,) + values.shape[1:]
        options = dict(chunks=shape, compression="gzip", compression_opts=GZIP_LEVEL)
        if growable:
            options["maxshape"] = (None,) + values.shape[1:]
        if compressed is not None and len(compressed) == values.shape[0]:
            ds = _dataset(group, name, None, shape=values.shape, dtype=values.dtype, **options)
            for i, chunk in enumerate(compressed):
                ds.id.write_direct_chunk((i, 0, 0), chunk)
        else:
            _dataset(group, name, np.asarray(values), **options)


def read_run_file(path, error, label) -> RunResult:
    """`read_run` for a file named by the user: error(message) (an exception class) when the path is missing, a
    folder, not HDF5, or HDF5 without the run file layout; label prefixes the message (the option or the path)."""
    p = Path(path)
    if not p.exists():
        raise error(f"{label}: no such file")
    if p.is_dir():
        raise error(f"{label}: is a folder; expected a run file (.h5) written by rollcontact run")
    try:
        return read_run(p)
    except (OSError, KeyError, ValueError, TypeError) as exc:
        why = ("HDF5, but without the run file layout" if not isinstance(exc, OSError) else
               "a truncated or damaged HDF5 file" if _hdf5_signature(p) else "not an HDF5 file")
        raise error(f"{label}: not a run file written by rollcontact run ({why})") from None


def _hdf5_signature(path) -> bool:
    """True when the file starts with HDF5's signature (a truncated run file does)."""
    try:
        with open(path, "rb") as fh:
            return fh.read(8) == b"\x89HDF\r\n\x1a\n"
    except OSError:
        return False


def read_run(path) -> RunResult:
    """Read a run file written by `write_run` (its `path` set to `path`)."""
    with h5py.File(path, "r") as h5:
        return RunResult(
            scene_toml=_str(h5.attrs["scene"]),
            status=_str(h5.attrs["status"]),
            error=_str(h5.attrs.get("error", "")),
            version=_str(h5.attrs.get("rollcontact_version", "")),
            x=h5["grid/x"][()], y=h5["grid/y"][()],
            history={k: v[()] for k, v in h5["history"].items()},
            fields={k: v[()] for k, v in h5["fields"].items() if k != "step"},
            field_steps=h5["fields/step"][()],
            summary=summary_from_attrs(h5["summary"].attrs),
            attrs={k: _py(v) for k, v in h5.attrs.items() if k not in _ROOT_ATTRS},
            path=Path(path),
            subsurface=Subsurface.of_file(path) if "subsurface" in h5 else Subsurface(),
            patches=_read_patches(h5),
        )


_ROOT_ATTRS = ("rollcontact_version", "scene", "status", "error")


def is_complete(path) -> bool:
    """True if `path` is a readable run file with status 'complete' (used to resume sweeps)."""
    try:
        with h5py.File(path, "r") as h5:
            return _str(h5.attrs.get("status", "")) == "complete"
    except (OSError, KeyError):
        return False


def stored_summary(path) -> dict | None:
    """Status, error, scene TOML and summary attributes of a run file, without reading the fields (sweeps and
    limit searches decide from it whether a run is done); None if the file cannot be read."""
    try:
        with h5py.File(path, "r") as h5:
            out = {"status": _str(h5.attrs.get("status", "")), "error": _str(h5.attrs.get("error", "")),
                   "scene": _str(h5.attrs.get("scene", ""))}
            out["summary"] = summary_from_attrs(h5["summary"].attrs) if "summary" in h5 else {}
            return out
    except (OSError, KeyError):
        return None


def stored_history(path, names) -> dict:
    """Some /history datasets of a run file (name -> array), without reading the fields; OSError or KeyError if
    the file or a name is missing."""
    with h5py.File(path, "r") as h5:
        return {name: h5["history"][name][()] for name in names}


def _dataset(group, name, values, **kwargs):
    ds = group.create_dataset(name, data=values, **kwargs)
    if name in UNITS:
        ds.attrs["units"] = UNITS[name]
    return ds


def summary_from_attrs(attrs) -> dict:
    """The /summary attributes as a dict, with None for the values that do not apply (NaN, -1 for a count,
    or the text 'none' of older files)."""
    out = {}
    for key, value in attrs.items():
        value = _py(value)
        if ((isinstance(value, str) and value == "none") or (isinstance(value, float) and math.isnan(value))
                or (key in SUMMARY_COUNTS and value == -1)):
            value = None
        out[key] = value
    return out


def _attr_value(key, value):
    if value is None:
        return -1 if key in SUMMARY_COUNTS else np.nan
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    return value


def _str(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def _py(v):
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, np.ndarray) and v.dtype.kind in "OSU":    # a list of texts (restart_overrides)
        return [x.decode() if isinstance(x, bytes) else str(x) for x in v.tolist()]
    return v

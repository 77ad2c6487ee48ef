"""HDF5 output of a run, written atomically (temporary file in the same folder, then rename).

Layout (public contract; later versions add to it, never rename):

    /                   attrs: rollcontact_version, scene (full scene as TOML text), status
                        ('complete' or 'failed'), error (message, when failed); a restarted run also
                        restarted_from (source file), restart_step, restart_overrides (the --set items)
    /grid/x, /grid/y    cell-centre coordinates (mm)
    /history/<name>     one value per step (names and units: cases.results.run_result.HISTORY_UNITS)
    /fields/<name>      shape (snapshots, ny, nx); /fields/step says which steps were stored (FIELD_UNITS)
    /summary            attrs: run summary (state, u_sd, ...); a value that does not apply (u_sd of a
                        ratcheting run, say) is NaN, or -1 for the counts in SUMMARY_COUNTS, as in a
                        sweep's summary.h5 (files of version 0.1.0 before 2026-11-24 wrote the text 'none')

A reader that opens a file sees either nothing (no file) or a complete file: the rename is atomic on
POSIX file systems. A run that fails still writes what it computed, with status = 'failed'.
"""
from __future__ import annotations

import math
import os
from pathlib import Path

import h5py
import numpy as np

from rollcontact.cases.results.run_result import UNITS, RunResult

#: Summary attributes that are counts: stored as -1 when they do not apply (every other one as NaN).
SUMMARY_COUNTS = ("periods_to_shakedown", "stopped_at_step", "steps", "steps_planned", "iterations", "nx", "ny",
                  "elements", "springs")


def version() -> str:
    """The installed rollcontact version (package metadata), written into every file."""
    from rollcontact import __version__
    return __version__


def write_run(path, data: RunResult) -> Path:
    """Write `data` to `path` atomically; returns the final path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with h5py.File(tmp, "w") as h5:
            h5.attrs["rollcontact_version"] = data.version or version()
            h5.attrs["scene"] = data.scene_toml
            h5.attrs["status"] = data.status
            h5.attrs["error"] = data.error
            for key, value in data.attrs.items():
                h5.attrs[key] = value
            grid = h5.create_group("grid")
            _dataset(grid, "x", data.x)
            _dataset(grid, "y", data.y)
            hist = h5.create_group("history")
            for name, values in data.history.items():
                _dataset(hist, name, np.asarray(values))
            flds = h5.create_group("fields")
            _dataset(flds, "step", np.asarray(data.field_steps, dtype=np.int64))
            for name, values in data.fields.items():
                values = np.asarray(values)
                chunks = (1,) + values.shape[1:] if values.ndim == 3 and values.shape[0] > 0 else None
                _dataset(flds, name, values, compression="gzip" if chunks else None, chunks=chunks)
            summ = h5.create_group("summary")
            for key, value in data.summary.items():
                summ.attrs[key] = _attr_value(key, value)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
    return path


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
        why = "not an HDF5 file" if isinstance(exc, OSError) else "HDF5, but without the run file layout"
        raise error(f"{label}: not a run file written by rollcontact run ({why})") from None


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


def _dataset(group, name, values, **kwargs):
    ds = group.create_dataset(name, data=values, **{k: v for k, v in kwargs.items() if v is not None})
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
    return v

"""The summary tables of sweeps and limit searches: OUTDIR/<stem>.csv and OUTDIR/<stem>.h5, one row per
finished run (or searched combination), written atomically and read back (cases.sweep.runner, cases.sweep.limit_search).

Units per column in `COLUMN_UNITS` (a varied key takes its scene unit); missing values are empty CSV cells,
NaN (floats) or -1 (counts) in HDF5.
"""
import csv
import io
import math
from pathlib import Path

import h5py
import numpy as np

from rollcontact.cases.results.writing import new_hdf5, write_text
from rollcontact.cases.scene.scene import key_unit

SUMMARY_COLUMNS = ("index", "state", "status", "f_t", "w", "angle", "u_sd", "du", "U_sd", "dU_per_period",
                   "U_perp", "dU_perp_per_period", "dissipation_per_period", "u_stat", "periods_to_shakedown", "steps",
                   "iterations", "wall_time", "file", "error")
"""Columns of summary.csv / summary.h5 after the varied keys (one column per varied key, named by the key).

index: position in the plan; state: static/shakedown/cyclic_slip/ratcheting/undecided/gross_sliding ('' if the
run failed before classifying); status: complete/failed; f_t = Ft/(mu Fn); w = W/a; angle: rolling direction
relative to Ft (deg); u_sd, du, u_stat: normalised by U0 (seed Eq. 9); U_sd, dU_per_period: mm; U_perp,
dU_perp_per_period: the final shift across Ft and its change over the last period (mm); dissipation_per_period:
the frictional work of the last period (N mm);
periods_to_shakedown, steps, iterations: counts; wall_time: s of the run itself; file: run file name
(relative to OUTDIR); error: message of a failed run."""

#: Further columns of a sweep over a [rolling] scene (cases.run.creep_run), added only when its runs have them:
#: the creepages xi, eta (dimensionless) and phi (1/mm), the forces F_x, F_y (N) and moment M_z (N mm) on the
#: sphere in Kalker's convention, and the stick fraction of the contact.
CREEP_COLUMNS = ("xi", "eta", "phi", "F_x", "F_y", "M_z", "stick_fraction")
#: Further columns of a sweep over a scene with viscoelastic bodies (docs/viscoelastic.md), added only when its runs
#: have them: the pressure centroid along the rolling direction (mm), the rolling resistance moment (N mm), the viscous
#: work of the last period (N mm) and the viscous power of steady rolling (W).
VISCO_COLUMNS = ("pressure_centroid_x", "rolling_resistance_moment", "viscous_dissipation_per_period",
                 "viscous_power")

#: Further columns of a sweep over a [wheelrail] scene (cases.run.wheelrail_run), added only when its runs have them:
#: the number of contact patches, the total force on the wheel in the track frame (N) and the wheelset centre's height
#: above its nominal position (mm). The patches themselves are in the run files (/summary patch_* arrays).
WHEELRAIL_COLUMNS = ("n_patches", "F_track_x", "F_track_y", "F_track_z", "z_ws")

#: Further columns of a sweep whose scenes ask for solver.fidelity = "auto" (cases.run.fidelity), added only when its
#: runs have them: the model each run chose and its predicted error (docs/creep_fidelity.md).
AUTO_COLUMNS = ("fidelity_used", "predicted_error")

#: `units` attribute of the summary.h5 / limits.h5 columns ('-': dimensionless, a count or text, as in the
#: run files); a varied key takes its scene unit (cases.scene.key_unit).
COLUMN_UNITS = {"angle": "deg", "U_sd": "mm", "dU_per_period": "mm", "U_perp": "mm", "dU_perp_per_period": "mm",
                "dissipation_per_period": "N mm", "wall_time": "s", "phi": "1/mm", "F_x": "N", "F_y": "N", "M_z": "N mm",
                "pressure_centroid_x": "mm", "rolling_resistance_moment": "N mm",
                "viscous_dissipation_per_period": "N mm", "viscous_power": "W",
                "F_track_x": "N", "F_track_y": "N", "F_track_z": "N", "z_ws": "mm"}
_FLOAT_COLUMNS = ("f_t", "w", "angle", "u_sd", "du", "U_sd", "dU_per_period", "U_perp", "dU_perp_per_period",
                  "dissipation_per_period", "u_stat", "wall_time") + VISCO_COLUMNS
_INT_COLUMNS = ("index", "periods_to_shakedown", "steps", "iterations", "n_patches")


def write_summary(outdir, keys, rows, *, stem="summary", columns=SUMMARY_COLUMNS, attrs=None):
    """Write OUTDIR/<stem>.csv and OUTDIR/<stem>.h5 atomically (temporary file + rename), rows by index.

    CSV: header = varied keys then `columns`; floats in full precision (repr), missing values empty.
    HDF5: group /runs with one dataset per column (floats with NaN for missing, ints with -1 for missing,
    strings UTF-8), attributes `varied` (the keys) and any `attrs` given (e.g. the base scene TOML).
    """
    outdir = Path(outdir)
    rows = sorted(rows, key=lambda r: r.get("index", 0))
    if columns is SUMMARY_COLUMNS and any(r.get("F_x") is not None for r in rows):
        columns = SUMMARY_COLUMNS + CREEP_COLUMNS      # a sweep over a [rolling] scene
    elif columns is SUMMARY_COLUMNS and any(r.get("n_patches") is not None for r in rows):
        columns = SUMMARY_COLUMNS + WHEELRAIL_COLUMNS  # a sweep over a [wheelrail] scene
    if any(r.get("pressure_centroid_x") is not None for r in rows):
        columns = tuple(columns) + VISCO_COLUMNS       # viscoelastic bodies
    if any(r.get("predicted_error") is not None for r in rows):
        columns = tuple(columns) + AUTO_COLUMNS        # a sweep of solver.fidelity = "auto"
    header = list(keys) + [c for c in columns if c not in keys]
    text = io.StringIO(newline="")
    writer = csv.writer(text)
    writer.writerow(header)
    for r in rows:
        writer.writerow([_csv_cell(r.get(c)) for c in header])
    write_text(outdir / f"{stem}.csv", text.getvalue(), "summary table")
    with new_hdf5(outdir / f"{stem}.h5", "summary table") as (h5, _):
        h5.attrs["varied"] = list(keys)
        h5.attrs["columns"] = header
        for k, v in (attrs or {}).items():
            h5.attrs[k] = v
        grp = h5.create_group("runs")
        for c in header:
            vals = [r.get(c) for r in rows]
            ds = grp.create_dataset(c, data=_column_array(c, vals))
            ds.attrs["units"] = COLUMN_UNITS.get(c) or key_unit(c)


def _csv_cell(v):
    if v is None:
        return ""
    if isinstance(v, float):
        return "" if math.isnan(v) else repr(v)
    return v


def _column_array(name, vals):
    present = [v for v in vals if v is not None and v != ""]
    if name in _INT_COLUMNS or (present and all(isinstance(v, (int, np.integer)) and not isinstance(v, bool)
                                                for v in present) and name not in _FLOAT_COLUMNS):
        return np.array([-1 if v is None or v == "" else int(v) for v in vals], dtype=np.int64)
    if name in _FLOAT_COLUMNS or (present and all(isinstance(v, (int, float, np.number)) for v in present)):
        return np.array([np.nan if v is None or v == "" else float(v) for v in vals], dtype=np.float64)
    return np.array(["" if v is None else str(v) for v in vals], dtype=h5py.string_dtype())


def read_summary(path) -> list[dict]:
    """Rows of a summary.csv as dicts (numbers parsed, empty cells None), sorted by index."""
    with open(path, newline="") as fh:
        rows = [{k: _csv_parse(k, v) for k, v in r.items()} for r in csv.DictReader(fh)]
    return sorted(rows, key=lambda r: r.get("index") or 0)


def _csv_parse(k, v):
    if v == "":
        return None
    if k in ("state", "status", "file", "error"):
        return v
    for conv in (int, float):
        try:
            return conv(v)
        except ValueError:
            pass
    return v



def table_attrs(path) -> dict | None:
    """The attributes of a summary table (<stem>.h5: varied keys, base_scene, overrides, ...) as Python values;
    None when the file is not such a table."""
    try:
        with h5py.File(path, "r") as h5:
            if "runs" not in h5:
                return None
            return {k: _text(v) for k, v in h5.attrs.items()}
    except OSError:
        return None


def _text(v):
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray) and v.dtype.kind in "OSU":
        return [x.decode() if isinstance(x, bytes) else str(x) for x in v]
    return v

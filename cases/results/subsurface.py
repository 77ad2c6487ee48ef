"""The subsurface stresses of a run file (/subsurface), read back: whole, as sections, or as block maxima.

Layout (README, "HDF5 layout"; names and units in cases.results.run_result.SUBSURFACE_UNITS; written by
cases.run.stresses):

    /subsurface         attrs: nu (the substrate's Poisson ratio used), depths ('default' or 'given')
    /subsurface/z       depths below the surface (mm), shape (nz,)
    /subsurface/step    the steps computed, shape (snapshots,); each is a stored step of /fields
    /subsurface/<name>  shape (snapshots, nz, ny, nx) on the run's grid (/grid/x, /grid/y): s_xx, s_yy, s_zz, s_yz,
                        s_xz, s_xy, von_mises, tresca, principal_1 (MPa)

The stresses are in the frame (x, y, z) with z the depth into the substrate, tension positive: at the surface
s_zz = -p, s_xz = -tau_x, s_yz = -tau_y. They depend on the substrate's Poisson ratio nu2 only.
"""
from __future__ import annotations

import h5py
import numpy as np

from rollcontact.bem.errors import InputError

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
    {'value', 'x', 'y', 'z'} of arrays (n,)}, and 'depths' (the block's z) (MPa, mm). Read one depth layer at a
    time (bounded memory)."""
    with h5py.File(path, "r") as h5:
        g = h5["subsurface"]
        x, y, z, steps = h5["grid/x"][()], h5["grid/y"][()], g["z"][()], g["step"][()]
        out = {"step": steps, "depths": z}
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


def _compact(steps) -> str:
    return ", ".join(map(str, steps)) if len(steps) <= 12 else f"{steps[0]}, {steps[1]}, ..., {steps[-1]}"

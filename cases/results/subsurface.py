"""The subsurface stresses of a run file (/subsurface), read back: whole, as sections, or as block maxima.

Layout (docs/hdf5_schema.md; names and units in cases.results.run_result.SUBSURFACE_UNITS; written by
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

from collections.abc import Mapping
from pathlib import Path

import h5py
import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.cases.results.run_result import SUBSURFACE_NAMES, UNITS, same_value


class Subsurface(Mapping):
    """The stresses below the contact of one run (RunResult.subsurface; the file's /subsurface): a mapping name ->
    array of shape (len(steps), len(z), ny, nx) in MPa for the SUBSURFACE_NAMES (s_xx ... s_xy in the frame x, y,
    z = depth, tension positive; von_mises, tresca, principal_1), read from the run file on first use.

    `z`: the depths below the surface (mm); `steps`: the stored steps computed (a list); `x`, `y`: the grid (mm);
    `nu`: the substrate's Poisson ratio used; `depths`: 'default' or 'given'; `units`: name -> unit (MPa, and mm for
    x, y, z); `at(name, step)`: the (nz, ny, nx) block of one step. What the run that wrote them did: `computed`,
    `reused` (the steps it computed, and those computed before a restart), `seconds` (computing). Empty (falsy, no
    names) when the run holds no subsurface stresses. Equal when the depths, steps, nu and every array are."""

    def __init__(self, path=None, *, z=None, steps=(), x=None, y=None, nu=None, depths=None, arrays=None,
                 seconds=0.0, computed=(), reused=()):
        self.path = None if path is None else Path(path)
        self.z = np.zeros(0) if z is None else np.asarray(z, dtype=float)
        self.steps = [int(s) for s in steps]
        self.x, self.y, self.nu, self.depths = x, y, nu, depths
        self.seconds, self.computed, self.reused = float(seconds), list(computed), list(reused)
        self._arrays = dict(arrays or {})
        self._names = list(self._arrays) if arrays is not None else (list(SUBSURFACE_NAMES) if self.steps else [])

    @classmethod
    def of_file(cls, path, **run_info) -> "Subsurface":
        """The /subsurface of the run file `path` (empty when it holds none); its arrays are read on first use.
        run_info: seconds, computed, reused of the run that wrote them."""
        with h5py.File(path, "r") as h5:
            if "subsurface" not in h5:
                return cls(**run_info)
            g = h5["subsurface"]
            return cls(path, z=g["z"][()], steps=g["step"][()], x=h5["grid/x"][()], y=h5["grid/y"][()],
                       nu=float(g.attrs["nu"]), depths=_text(g.attrs.get("depths", "")), **run_info)

    @property
    def units(self) -> dict:
        """name -> unit of what it holds: the nine fields (MPa), z, x, y (mm), step ('-'); empty when empty."""
        if not self:
            return {}
        return {**{name: UNITS[name] for name in self._names}, "z": "mm", "x": "mm", "y": "mm"}

    def __getitem__(self, name) -> np.ndarray:
        if name not in self._names:
            raise KeyError(f"subsurface {name!r}: not held; held: {self._names or 'none (no subsurface stresses)'}")
        if name not in self._arrays:
            with h5py.File(self.path, "r") as h5:
                self._arrays[name] = h5["subsurface"][name][()]
        return self._arrays[name]

    def __iter__(self):
        return iter(self._names)

    def __len__(self) -> int:
        return len(self._names)

    def at(self, name: str, step: int) -> np.ndarray:
        """The (nz, ny, nx) block of `name` at a computed `step` (MPa); KeyError naming the computed steps."""
        if int(step) not in self.steps:
            raise KeyError(f"step {step}: no subsurface stresses; computed steps: {self.steps}")
        return self[name][self.steps.index(int(step))]

    def __eq__(self, other):
        if not isinstance(other, Subsurface):
            return NotImplemented
        if not self and not other:
            return True
        return (bool(self) == bool(other) and self.steps == other.steps and same_value(self.z, other.z)
                and same_value(self.nu, other.nu) and list(self) == list(other)
                and all(same_value(self[n], other[n]) for n in self))

    __hash__ = None

    def __repr__(self) -> str:
        if not self:
            return "Subsurface(empty)"
        z = f"{len(self.z)} depths {self.z[0]:.4g} ... {self.z[-1]:.4g} mm" if len(self.z) else "no depths"
        return f"Subsurface(steps={_compact(self.steps)}, {z}, names={len(self)}, path={str(self.path)!r})"

    def report(self) -> str:
        """The line `rollcontact stresses` and `run --stresses` print: what was written where."""
        reused = len(self.reused)
        kept = f"; {reused} step(s) computed before and kept" if reused else ""
        z = self.z
        return (f"subsurface stresses of step(s) {_compact(self.steps)} at {len(z)} depths "
                f"({z[0]:.4g} ... {z[-1]:.4g} mm) written to {self.path} (/subsurface; computed in {self.seconds:.2f} s"
                f"{kept})")


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


def _text(value) -> str:
    return value.decode() if isinstance(value, bytes) else str(value)

"""The subsurface stresses of a run's stored steps computed as the run goes (`rollcontact run --stresses`): those of
each stored step when it is stored, kept in one small file per step in a folder beside the run's file, and copied
into the run's file by its final write as /subsurface, the group `rollcontact stresses RUN.h5 --all-steps` writes
(same values, layout and chunks: cases.run.stresses, cases.results.subsurface). Units: mm, MPa.

Why a file per step beside the run's file, and not the run's file itself: a checkpoint (cases.run.checkpoint) writes
the whole run file from the copy it keeps in memory; stresses in it would be held in memory and rewritten by every
checkpoint (9 fields x 30 depths: 10 MB a step on the paper's grid, uncompressed), so the checkpoints' cost would grow
with the steps computed. A step file is written once, atomically (a temporary file renamed into place), and outlives
the process in any way it ends, kill -9 included. Folder: `<run file>.subsurface/` (of the file the run writes: its
output, or the partial file beside a complete one), file `step_<N>.h5`: attributes step, nu and key (a digest of
the tractions, grid, nu and depths the stresses come from), datasets z (mm) and the nine fields (nz, ny, nx) with one
chunk per layer (cases.run.stresses.LAYER_FILTERS). The final write copies those chunks as they are (no second
compression) and removes the folder; a step file or a source's /subsurface stored with other filters is not copied.

What is never computed twice: a stored step whose file in the folder has the same key (a killed run continued in its
own file); the steps a restart inherits also take their stresses from the source's folder or from the source file's
/subsurface (at the same depths). Memory: the stress operator (48 padded arrays, 100 MB at 256 x 256), the kernel
spectra it keeps across steps (at most KEPT_KERNEL_BYTES) and one depth layer of the nine fields, whatever the counts
of depths and steps.
"""
from __future__ import annotations

from contextlib import contextmanager
import hashlib
from pathlib import Path
import shutil
import time

import h5py
import numpy as np

from rollcontact.bem.subsurface import SubsurfaceStresses
from rollcontact.cases.results.writing import new_hdf5, replacing, write_failed
from rollcontact.cases.results.run_result import SUBSURFACE_NAMES
from rollcontact.cases.run.stresses import (LAYER_FILTERS, create_group, grid_of, layer_fields, run_depths,
                                            same_filters, write_layer)
from rollcontact.cases.scene.scene import Scene


#: Bytes of kernel spectra kept across steps (bem.subsurface.SubsurfaceStresses kept_bytes): every default depth of
#: the paper's grid (63 MB), 4 depths of a 256 x 256 grid; a step's 30 layers then take 0.055 s instead of 0.19 s there.
KEPT_KERNEL_BYTES = 128 * 2**20


def folder_of(run_file) -> Path:
    """The folder of the step files of the run file `run_file`: <run file>.subsurface beside it."""
    run_file = Path(run_file)
    return run_file.with_name(run_file.name + ".subsurface")


class StepStresses:
    """The stresses of the stored steps of one run of `scene` that writes `target`, at `depths` (mm; None: the default
    depths of the run summary's contact radius, as `rollcontact stresses`). restart: the cases.run.restart.RestartSource
    the run continues (its stresses are reused); progress: callable(message) or None.

    `start(x, y, a)` with the run's grid and contact radius, `catch_up(recorder)` after each recorded step
    (cases.run.bem_run), `ensure` for any stored step, `fill(h5, steps)` in the final write, then `discard()`.
    `computed` and `reused` list the steps whose stresses this process computed or found already computed; `seconds`
    the time computing them (without writing them, as `add_subsurface` counts)."""

    def __init__(self, scene: Scene, target, depths=None, restart=None, progress=None):
        self.scene = scene
        self.nu = float(scene.materials.nu2)
        self.default = depths is None
        self.z = None if depths is None else run_depths(scene, np.nan, depths)     # given depths checked at once
        self.folder = folder_of(target)
        self.restart = restart
        self.progress = progress
        self.grid = None
        self.computed, self.reused = [], []
        self.seconds = 0.0
        self._done = set()          # steps whose file in the folder holds their stresses
        self._seen = 0              # snapshots of the recorder handled by catch_up
        self._op = self._layer = None

    def start(self, x, y, a: float):
        """The run's grid (cell centres, mm, as stored in /grid/x, /grid/y) and contact radius a (mm, its summary's
        `a`, which places the default depths)."""
        if self.grid is None:
            self._x, self._y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
            self.grid = grid_of(self._x, self._y)
        if self.z is None:
            self.z = run_depths(self.scene, float(a) if a is not None else np.nan)

    def catch_up(self, recorder):
        """The stresses of the snapshots `recorder` (cases.run.recorder.StepRecorder) stored since the last call."""
        while self._seen < len(recorder.stored):
            i = self._seen
            self.ensure(recorder.stored[i], *(recorder.field(n, i) for n in ("p", "tau_x", "tau_y")))
            self._seen += 1

    def ensure(self, step: int, pressure, tau_x, tau_y):
        """The file of stored step `step` (tractions in MPa, (ny, nx)) in the folder: kept if it matches, else copied
        from the restart's source, else computed."""
        step = int(step)
        if step in self._done:
            return
        key = self._key(pressure, tau_x, tau_y)
        path = self.folder / f"step_{step}.h5"
        if self._matches(path, key) or self._from_source(step, key, path):
            self.reused.append(step)
        else:
            self._compute(step, key, path, pressure, tau_x, tau_y)
            self.computed.append(step)
        self._done.add(step)

    def fill(self, h5, steps, fields) -> list:
        """/subsurface in the open run file `h5` for those of `steps` (the stored steps, their `fields` by name) that
        have their stresses (every one, unless the run was interrupted); returns them. No group when none has."""
        for i, step in enumerate(steps):     # an interrupt may come after a step's file is renamed into place
            if int(step) not in self._done and self.grid is not None and self.z is not None:
                key = self._key(*(fields[n][i] for n in ("p", "tau_x", "tau_y")))
                if self._matches(self.folder / f"step_{int(step)}.h5", key):
                    self._done.add(int(step))
        have = [int(s) for s in steps if int(s) in self._done]
        if not have:
            return have
        out = create_group(h5, self.nu, self.z, have, self.default, self.grid.shape)
        for i, step in enumerate(have):
            with h5py.File(self.folder / f"step_{step}.h5", "r") as src:
                for name in SUBSURFACE_NAMES:
                    source, dest = src[name].id, out[name].id
                    for j in range(len(self.z)):
                        mask, chunk = source.read_direct_chunk((j, 0, 0))
                        dest.write_direct_chunk((i, j, 0, 0), chunk, mask)
        return have

    def discard(self):
        """Remove the folder (its stresses are in the run's file now)."""
        shutil.rmtree(self.folder, ignore_errors=True)

    def _key(self, pressure, tau_x, tau_y) -> str:
        digest = hashlib.sha256()
        for values in (pressure, tau_x, tau_y, self._x, self._y, self.z, np.float64(self.nu)):
            digest.update(np.ascontiguousarray(values, dtype=np.float64).tobytes())
        return digest.hexdigest()

    def _matches(self, path: Path, key: str) -> bool:
        try:
            with h5py.File(path, "r") as h5:
                return (h5.attrs.get("key") == key and all(name in h5 for name in SUBSURFACE_NAMES)
                        and all(same_filters(h5[name]) for name in SUBSURFACE_NAMES))
        except (OSError, KeyError):
            return False

    def _from_source(self, step, key, path) -> bool:
        """Copy the stresses of `step` from the restart's source: its folder (same key), or its /subsurface when the
        step is one the restart inherits and the depths and nu are the same."""
        if self.restart is None:
            return False
        source_folder = folder_of(self.restart.path)
        if source_folder.resolve() != self.folder.resolve():
            other = source_folder / path.name
            if self._matches(other, key):
                self._make_folder()
                with replacing(path, "subsurface step file") as tmp:
                    shutil.copyfile(other, tmp)
                return True
        if step > self.restart.step:
            return False
        try:
            with h5py.File(self.restart.path, "r") as src:
                g = src.get("subsurface")
                if g is None or float(g.attrs["nu"]) != self.nu or not np.array_equal(g["z"][()], self.z) \
                        or not all(same_filters(g[name]) for name in SUBSURFACE_NAMES):
                    return False
                steps = [int(s) for s in g["step"][()]]
                if step not in steps:
                    return False
                k = steps.index(step)
                with self._step_file(path, step, key) as (out, _):
                    for name in SUBSURFACE_NAMES:
                        for j in range(len(self.z)):
                            mask, chunk = g[name].id.read_direct_chunk((k, j, 0, 0))
                            out[name].id.write_direct_chunk((j, 0, 0), chunk, mask)
            return True
        except (OSError, KeyError):     # the source cannot be read (a failed write is an OutputWriteError)
            return False

    def _compute(self, step, key, path, pressure, tau_x, tau_y):
        if self._op is None:
            self._op = SubsurfaceStresses(self.grid, self.nu, kept_bytes=KEPT_KERNEL_BYTES)
            self._layer = np.empty((6,) + self.grid.shape)
        start = time.perf_counter()
        worst = 0.0
        self._op.set_tractions(pressure, tau_x, tau_y)
        computing = time.perf_counter() - start
        with self._step_file(path, step, key) as (out, check):
            for j, depth in enumerate(self.z):
                t0 = time.perf_counter()
                values = layer_fields(self._op, float(depth), self._layer)
                computing += time.perf_counter() - t0
                for name, layer in values.items():
                    write_layer(out[name], (j,), layer)
                worst = max(worst, float(values["von_mises"].max()))
                check()            # a failed write stops the step at once (OutputWriteError)
        self.seconds += computing
        if self.progress:
            self.progress(f"subsurface stresses of step {step} written ({len(self.z)} depths, max von Mises "
                          f"{worst:.4g} MPa, {time.perf_counter() - start:.2f} s)")

    def _make_folder(self):
        """The folder of the step files, beside the run's file (whose folder is not made again if it vanished)."""
        try:
            self.folder.mkdir(exist_ok=True)
        except OSError as exc:
            raise write_failed(self.folder, exc, "subsurface folder") from None

    @contextmanager
    def _step_file(self, path, step, key):
        """The step file `path` written through a temporary file renamed into place at the end: (its nine datasets
        by name, check), check() raising OutputWriteError once a write failed (cases.results.writing.new_hdf5)."""
        self._make_folder()
        ny, nx = self.grid.shape
        with new_hdf5(path, "subsurface step file") as (h5, check):
            h5.attrs.update(step=step, nu=self.nu, key=key)
            h5.create_dataset("z", data=self.z).attrs["units"] = "mm"
            yield {name: h5.create_dataset(name, shape=(len(self.z), ny, nx), dtype=np.float64, chunks=(1, ny, nx),
                                           **LAYER_FILTERS)
                   for name in SUBSURFACE_NAMES}, check

"""A run file that grows as a run goes: kept in memory (an HDF5 file in a bytes buffer) with extendable history and
fields, each extension appending only the new steps and snapshots, and saved as a whole file image written atomically
(cases.results.hdf5.save_image) straight from that buffer (no copy of the image: it is the largest block a run holds). The checkpoints of a run (cases.run.checkpoint) rewrite their file this way at
a few milliseconds each, where building the file anew costs 15-25 ms (benchmarks/checkpoint.py). Units: those of
the run file (cases.results.run_result)."""
from __future__ import annotations

import io

import h5py
import numpy as np

from rollcontact.cases.results.hdf5 import append, fill_run, root_attrs, save_image, write_summary_attrs
from rollcontact.cases.results.run_result import RunResult

class GrowingRunFile:
    """The run file of `data` (with its compressed snapshots `chunks`) in memory, extendable."""

    def __init__(self, data: RunResult, chunks: dict):
        self._buffer = io.BytesIO()
        self.h5 = h5py.File(self._buffer, "w")
        fill_run(self.h5, data, chunks, growable=True)
        history, fields = self.h5["history"].id, self.h5["fields"].id
        self._history = {name: h5py.h5d.open(history, name.encode()) for name in data.history}
        self._fields = {name: h5py.h5d.open(fields, name.encode()) for name in list(data.fields) + ["step"]}
        self._root = (data.status, data.error, dict(data.attrs))
        self.steps = len(data.history["step"])
        self.snapshots = len(data.field_steps)
        self.summary = dict(data.summary)

    def extend(self, data: RunResult, chunks: dict, keep_snapshots: int):
        """Extend to `data`, a continuation of what the file holds: its history from the steps already held on,
        and its snapshots from `keep_snapshots` on (those before stay; a checkpoint's restart point after them is
        replaced); status, error, root attributes and the summary are updated."""
        if (data.status, data.error, data.attrs) != self._root:
            root_attrs(self.h5, data)
            self._root = (data.status, data.error, dict(data.attrs))
        for name, values in data.history.items():
            append(self._history[name], np.asarray(values), self.steps)
        steps = np.asarray(data.field_steps, dtype=np.int64)
        append(self._fields["step"], steps, keep_snapshots)
        for name, pieces in chunks.items():
            dataset = self._fields[name]
            shape = dataset.shape
            dataset.set_extent((len(steps),) + shape[1:])
            for i in range(keep_snapshots, len(steps)):
                dataset.write_direct_chunk((i, 0, 0), pieces[i])
        write_summary_attrs(self.h5["summary"].attrs, data.summary, self.summary)
        self.steps, self.snapshots, self.summary = len(data.history["step"]), len(steps), dict(data.summary)

    def save(self, path):
        """Write the file to `path` atomically."""
        self.h5.flush()
        with self._buffer.getbuffer() as image:
            return save_image(path, image)

    def close(self):
        self._history, self._fields = {}, {}
        self.h5.close()
        self._buffer.close()

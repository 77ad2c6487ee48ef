"""Checkpoints of a run: its finished steps written to its HDF5 file as it goes, so that a run killed by any means
(kill -9, an out-of-memory kill, a scheduler's pre-emption) leaves a file that opens and holds them, with status
'incomplete', and `rollcontact run --restart FILE` continues it.

A checkpoint is written at the end of the loading phase and of every period, and within a period at most every
CHECKPOINT_SECONDS of wall time; each holds the fields of its last step, the point a restart continues from. Each
is a whole file written atomically (cases.results.hdf5.write_run: a temporary file, then a rename), so a reader or
a crash never meets half a file; the field snapshots are compressed once, when they are recorded, so rewriting
the file costs little (benchmarks/checkpoint.py).
"""
from __future__ import annotations

from pathlib import Path
import time

from rollcontact.cases.results.hdf5 import extend_run, write_run

#: Longest wall time (s) between two checkpoints within a period.
CHECKPOINT_SECONDS = 5.0


class Checkpoints:
    """Writes checkpoints of one run to `target` (root attributes `attrs` added to each). The first is a whole
    growable file; each later one a copy of it extended by the new steps and snapshots (cases.results.hdf5.
    extend_run), renamed into place."""

    def __init__(self, target, attrs=None, interval: float = CHECKPOINT_SECONDS):
        self.target = Path(target)
        self.attrs = dict(attrs or {})
        self.interval = interval
        self.last = time.perf_counter()
        self.written = 0            # checkpoints written
        self.seconds = 0.0          # wall time spent writing them
        self._steps = 0             # history rows in the file
        self._snapshots = 0         # snapshots in the file that stay (not a checkpoint's restart point)
        self._summary = None        # the summary in the file

    def after_step(self, period_end: bool, result, stored: int):
        """Called after each finished step: `result(...)` builds the run so far (cases.run.bem_run.partial),
        `stored` is the number of snapshots the run keeps."""
        now = time.perf_counter()
        if not (period_end or now - self.last >= self.interval):
            return
        run = result(status="incomplete", state_label="incomplete", extra_snapshot=True)
        run.attrs.update(self.attrs)
        if self.written == 0:
            write_run(self.target, run, run.snapshot_chunks, growable=True)
        else:
            extend_run(self.target, run, run.snapshot_chunks, self._steps, self._snapshots, self._summary)
        self._steps, self._snapshots, self._summary = len(run.history["step"]), stored, run.summary
        self.last = time.perf_counter()
        self.written += 1
        self.seconds += self.last - now

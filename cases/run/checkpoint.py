"""Checkpoints of a run: its finished steps written to its HDF5 file as it goes, so that a run killed by any means
(kill -9, an out-of-memory kill, a scheduler's pre-emption) leaves a file that opens and holds them, with status
'incomplete', and `rollcontact run --restart FILE` continues it.

A checkpoint is written at the end of the loading phase and of every period, and within a period at most every
CHECKPOINT_SECONDS of wall time; each holds the fields of its last step, the point a restart continues from. Each
is a whole file written atomically (a temporary file, then a rename), so a reader or a crash never meets half a
file. The file is kept in memory and extended by each checkpoint's new steps, and the field snapshots are
compressed once, when they are recorded: a checkpoint costs a few milliseconds (benchmarks/checkpoint.py).
"""
from __future__ import annotations

from pathlib import Path
import time

from rollcontact.cases.results.growing_file import GrowingRunFile

#: Longest wall time (s) between two checkpoints within a period.
CHECKPOINT_SECONDS = 5.0


class Checkpoints:
    """Writes checkpoints of one run to `target` (root attributes `attrs` added to each), from a copy of the file
    kept in memory and extended by the new steps and snapshots (cases.results.growing_file)."""

    def __init__(self, target, attrs=None, interval: float = CHECKPOINT_SECONDS):
        self.target = Path(target)
        self.attrs = dict(attrs or {})
        self.interval = interval
        self.last = time.perf_counter()
        self.written = 0            # checkpoints written
        self.seconds = 0.0          # wall time spent writing them
        self._file = None           # the GrowingRunFile
        self._kept = 0              # snapshots in it that stay (not a checkpoint's restart point)

    def after_step(self, period_end: bool, result, stored: int):
        """Called after each finished step: `result(...)` builds the run so far (cases.run.bem_run.partial),
        `stored` is the number of snapshots the run keeps."""
        now = time.perf_counter()
        if not (period_end or now - self.last >= self.interval):
            return
        run = result(status="incomplete", state_label="incomplete", extra_snapshot=True)
        run.attrs.update(self.attrs)
        if self._file is None:
            self._file = GrowingRunFile(run, run.snapshot_chunks)
        else:
            self._file.extend(run, run.snapshot_chunks, self._kept)
        self._file.save(self.target)
        self._kept = stored
        self.last = time.perf_counter()
        self.written += 1
        self.seconds += self.last - now

    def close(self):
        """Free the file kept in memory (the run's final file is written anew)."""
        if self._file is not None:
            self._file.close()
            self._file = None

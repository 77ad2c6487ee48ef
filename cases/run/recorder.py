"""The history rows and field snapshots of a BEM run, recorded step by step as the steps finish
(cases.run.bem_run). Names and units: cases.results.run_result (HISTORY_UNITS, FIELD_UNITS)."""
from __future__ import annotations

import numpy as np

from rollcontact.cases.results.run_result import FIELD_NAMES, HISTORY_NAMES


class StepRecorder:
    """Per-step history and the snapshots of the steps in `snapshot_steps`; a restart starts from the stored history
    and snapshots up to its step (`restart`: cases.run.restart.RestartSource)."""

    def __init__(self, grid, path, snapshot_steps, restart=None):
        self.cell_area = grid.cell_area
        self.shape = grid.shape
        self.period = path.period
        self.snapshot_steps = set(int(s) for s in snapshot_steps)
        self.history = {k: [] for k in HISTORY_NAMES}
        self.fields = {k: [] for k in FIELD_NAMES}
        self.stored = []
        self.last = None     # the record of the last step recorded in full
        if restart is not None:
            n = restart.step + 1
            for k in HISTORY_NAMES:
                self.history[k] = list(np.asarray(restart.data.history[k])[:n])
            steps, fields = restart.snapshots()
            self.stored = [int(s) for s in steps]
            self.fields = {k: list(fields[k]) for k in FIELD_NAMES}

    @property
    def n_steps(self) -> int:
        return len(self.history["step"])

    def add(self, rec) -> dict:
        """Record a finished step (a solver.rolling.stepping.StepRecord); returns its history row."""
        nr, tr, st = rec.normal, rec.tangential, rec.state
        dA = self.cell_area
        row = dict(step=rec.step, period=int(self.period[rec.step]), W_x=rec.centre[0], W_y=rec.centre[1],
                   approach=nr.approach, Fn=nr.force, contact_area=float(nr.contact.sum()) * dA,
                   stick_area=float((tr.region == 1).sum()) * dA, U_x=st.rigid_shift[0], U_y=st.rigid_shift[1],
                   F_x=tr.force[0], F_y=tr.force[1], iterations=nr.iterations + tr.iterations,
                   normal_iterations=nr.iterations, tangential_iterations=tr.iterations,
                   outer_iterations=rec.outer_iterations, residual=max(nr.residual, tr.residual),
                   wall_time=rec.wall_time)
        for k, v in row.items():
            self.history[k].append(v)
        if rec.step in self.snapshot_steps:
            self.snapshot(rec)
        self.last = rec
        return row

    def snapshot(self, rec):
        """Store the fields of step `rec`."""
        self.stored.append(rec.step)
        nr, tr = rec.normal, rec.tangential
        for k, v in (("p", nr.pressure), ("u_z", nr.displacement), ("tau_x", tr.traction[0]),
                     ("tau_y", tr.traction[1]), ("slip_x", tr.slip[0]), ("slip_y", tr.slip[1]),
                     ("u_x", tr.displacement[0]), ("u_y", tr.displacement[1]), ("region", tr.region)):
            self.fields[k].append(v.copy())

    def keep_last_step_fields(self):
        """A run that stopped early keeps the fields of its last finished step (what output.fields = 'reversals'
        and 'last' promise, and what --restart needs)."""
        if self.last is not None and (not self.stored or self.stored[-1] != self.last.step):
            self.snapshot(self.last)

    def trim_to_whole_steps(self):
        """After an interrupt, which may come between the appends of one step: keep the steps recorded in full
        (and forget `last` when its appends were cut short)."""
        n = min(len(v) for v in self.history.values())
        for v in self.history.values():
            del v[n:]
        m = min([len(self.stored)] + [len(v) for v in self.fields.values()])
        del self.stored[m:]
        for v in self.fields.values():
            del v[m:]
        if self.last is not None and not (n and self.history["step"][-1] == self.last.step):
            self.last = None

    def arrays(self) -> tuple[dict, dict, np.ndarray]:
        """(history, fields, stored steps) as numpy arrays; fields of shape (snapshots, ny, nx)."""
        ny, nx = self.shape
        fields = {}
        for k, v in self.fields.items():
            dtype = np.int8 if k == "region" else np.float64
            fields[k] = np.array(v, dtype=dtype) if self.stored else np.zeros((0, ny, nx), dtype=dtype)
        history = {k: np.asarray(v) for k, v in self.history.items()}
        return history, fields, np.array(self.stored, dtype=np.int64)

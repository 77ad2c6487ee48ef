"""The history rows and field snapshots of a BEM run, recorded step by step as the steps finish
(cases.run.bem_run). Names and units: cases.results.run_result (HISTORY_UNITS, FIELD_UNITS)."""
from __future__ import annotations

import numpy as np

from rollcontact.cases.results.hdf5 import compress_snapshot
from rollcontact.cases.results.run_result import (FIELD_NAMES, FRICTION_FIELDS, FRICTION_HISTORY, HISTORY_NAMES,
                                                   VISCO_HISTORY_UNITS)
from rollcontact.cases.results.snapshots import SnapshotStack
from rollcontact.cases.run.viscoelastic import pressure_centroid


class StepRecorder:
    """Per-step history and the snapshots of the steps in `snapshot_steps`; a restart starts from the stored history
    and snapshots up to its step (`restart`: cases.run.restart.RestartSource). With `compress`, each snapshot is
    kept only as the gzip chunks of the run file (`chunks`, compressed once however often the file is written; read
    back by `field` and the SnapshotStack fields of `arrays`), else as arrays (`fields`).
    `transverse`: the unit vector across Ft (Scene.transverse_direction), along which U_perp is measured.
    A scene with a speed adds the history column `time` (step n ends at n path.step_time); one with a friction law
    (`friction`) the fields mu and slip_velocity and the history columns friction_iterations, frictional_power and
    friction_feedback; one with viscoelastic bodies (`states`: the names of their element states,
    ViscoMemory.states()) the columns pressure_centroid_x (along `rolling`, the unit vector of the rolling direction,
    from the sphere's centre) and viscous_dissipation, and the states to the snapshots."""

    def __init__(self, grid, path, snapshot_steps, restart=None, compress=False, transverse=(0.0, 1.0),
                 states=(), rolling=(1.0, 0.0), friction=False):
        self.grid = grid
        self.step_time = path.step_time
        self.rolling = (float(rolling[0]), float(rolling[1]))
        self.viscous = bool(states)
        self.history_names = HISTORY_NAMES + (("time",) if self.step_time is not None else ()) + \
            (FRICTION_HISTORY if friction else ()) + (tuple(VISCO_HISTORY_UNITS) if self.viscous else ())
        self.field_names = FIELD_NAMES + (FRICTION_FIELDS if friction else ()) + tuple(states)
        self.cell_area = grid.cell_area
        self.transverse = (float(transverse[0]), float(transverse[1]))
        self.shape = grid.shape
        self.period = path.period
        self.snapshot_steps = set(int(s) for s in snapshot_steps)
        self.history = {k: [] for k in self.history_names}
        self.fields = {k: [] for k in self.field_names}
        self.stored = []
        self.compress = compress
        self.chunks = {k: [] for k in self.field_names}
        self.last = None     # the record of the last step recorded in full
        if restart is not None:
            n = restart.step + 1
            stored = restart.data.history
            for k in self.history_names:
                if k == "U_perp" and k not in stored:      # a file written before U_perp existed
                    self.history[k] = list(self._across(np.asarray(stored["U_x"]), np.asarray(stored["U_y"]))[:n])
                else:                                      # dissipation: NaN in files written before it existed
                    self.history[k] = list(np.asarray(stored[k])[:n]) if k in stored else [np.nan] * n
            steps, fields = restart.snapshots()
            self.stored = [int(s) for s in steps]
            if compress:
                self.chunks = {k: [compress_snapshot(v) for v in fields[k]] for k in self.field_names}
            else:
                self.fields = {k: list(fields[k]) for k in self.field_names}

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
                   U_perp=self._across(st.rigid_shift[0], st.rigid_shift[1]), F_x=tr.force[0], F_y=tr.force[1],
                   iterations=nr.iterations + tr.iterations,
                   normal_iterations=nr.iterations, tangential_iterations=tr.iterations,
                   outer_iterations=rec.outer_iterations, residual=max(nr.residual, tr.residual),
                   wall_time=rec.wall_time, dissipation=rec.dissipation)
        if self.step_time is not None:
            row["time"] = rec.step * self.step_time
        if rec.friction is not None:
            row.update(friction_iterations=rec.friction.iterations, frictional_power=rec.friction.power,
                       friction_feedback=rec.friction.feedback)
        if self.viscous:
            row.update(pressure_centroid_x=pressure_centroid(self.grid, nr.pressure, rec.centre, self.rolling),
                       viscous_dissipation=rec.viscous_dissipation)
        for k, v in row.items():
            self.history[k].append(v)
        if rec.step in self.snapshot_steps:
            self.snapshot(rec)
        self.last = rec
        return row

    def _across(self, U_x, U_y):
        """The component of the shift (U_x, U_y) across Ft (mm)."""
        ex, ey = self.transverse
        return ex * U_x + ey * U_y

    def snapshot(self, rec):
        """Store the fields of step `rec`."""
        self.stored.append(rec.step)
        for k, v in field_values(rec).items():
            if self.compress:
                self.chunks[k].append(compress_snapshot(np.asarray(v, dtype=field_dtype(k))))
            else:
                self.fields[k].append(np.array(v, dtype=field_dtype(k)))

    def field(self, name: str, i: int) -> np.ndarray:
        """The (ny, nx) snapshot i (in the order stored) of field `name`."""
        if self.compress:
            return SnapshotStack([self.chunks[name][i]], self.shape, field_dtype(name))[0]
        return self.fields[name][i]

    def keep_last_step_fields(self):
        """A run that stopped early keeps the fields of its last finished step (what output.fields = 'reversals'
        and 'last' promise, and what --restart needs)."""
        if self.last is not None and (not self.stored or self.stored[-1] != self.last.step):
            self.snapshot(self.last)

    def trim_to_whole_steps(self):
        """After an interrupt, which may come between the appends of one step: keep the steps recorded in full, up to
        the last step `add` finished (a row whose step was cut short before `last` was set goes, with its snapshot),
        and forget `last` when its own appends were cut short."""
        n = min(len(v) for v in self.history.values())
        if self.last is not None and n and self.history["step"][n - 1] != self.last.step \
                and self.last.step in self.history["step"][:n]:
            n = self.history["step"].index(self.last.step) + 1     # a row appended, the step not yet done: drop it
        for v in self.history.values():
            del v[n:]
        m = min([len(self.stored)] + [len(v) for v in (self.chunks if self.compress else self.fields).values()])
        while m and n and self.stored[m - 1] > self.history["step"][n - 1]:
            m -= 1
        del self.stored[m:]
        for v in list(self.fields.values()) + list(self.chunks.values()):
            del v[m:]
        if self.last is not None and not (n and self.history["step"][-1] == self.last.step):
            self.last = None

    def arrays(self, extra_snapshot=False) -> tuple[dict, dict, np.ndarray, dict]:
        """(history, fields, stored steps, chunks): history as numpy arrays; fields of shape (snapshots, ny, nx),
        arrays, or with `compress` SnapshotStacks of the chunks (decompressed when read), and chunks the compressed
        snapshots (empty without `compress`). extra_snapshot: add the fields of the last recorded step when they are
        not stored (the restart point of a checkpoint), without storing them."""
        ny, nx = self.shape
        stored = list(self.stored)
        snaps = {k: list(v) for k, v in (self.chunks if self.compress else self.fields).items()}
        if extra_snapshot and self.last is not None and (not stored or stored[-1] != self.last.step):
            stored.append(self.last.step)
            for k, v in field_values(self.last).items():
                v = np.asarray(v, dtype=field_dtype(k))
                snaps[k].append(compress_snapshot(v) if self.compress else v)
        fields = {}
        for k, v in snaps.items():
            dtype = field_dtype(k)
            if self.compress:
                fields[k] = SnapshotStack(v, (ny, nx), dtype)
            else:
                fields[k] = np.array(v, dtype=dtype) if stored else np.zeros((0, ny, nx), dtype=dtype)
        history = {k: np.asarray(v) for k, v in self.history.items()}
        return history, fields, np.array(stored, dtype=np.int64), (snaps if self.compress else {})


def field_values(rec) -> dict:
    """The stored fields of a step record (solver.rolling.stepping.StepRecord), name -> (ny, nx) array."""
    nr, tr = rec.normal, rec.tangential
    out = {"p": nr.pressure, "u_z": nr.displacement, "tau_x": tr.traction[0], "tau_y": tr.traction[1],
           "slip_x": tr.slip[0], "slip_y": tr.slip[1], "u_x": tr.displacement[0], "u_y": tr.displacement[1],
           "region": tr.region}
    if rec.friction is not None:
        out.update(mu=rec.friction.mu, slip_velocity=rec.friction.slip_velocity)
    if getattr(rec, "memory_states", None):
        out.update(rec.memory_states)
    return out


def field_dtype(name: str):
    """The stored dtype of a field: int8 for the region codes, float64 otherwise."""
    return np.int8 if name == "region" else np.float64

"""A full disk, a folder that vanished and a read-only file system at every write: one line naming the file and the
failure, a non-zero exit, no traceback, never a crash of the process; the last good checkpoint and every finished file
kept, nothing partial under a result's name, and the `--restart` that continues printed.

Real file systems: a small tmpfs mounted for the test (as root; a full disk is a tmpfs a little smaller than the
run needs) and remounted read-only. Where mounting is not permitted, a full disk is the write failing at the OS level
(RLIMIT_FSIZE: a write past the limit fails with EFBIG) and a read-only folder is one without write permission (as a
user other than root); the tests say which they used. Coarse runs of the paper scene (a/dx = 12 at dx = 0.4 mm,
fields of every step: about 24 kB a step), a few seconds in all.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path
import resource
import shutil
import signal
import subprocess
import sys

import h5py
import pytest

import rollcontact
from rollcontact.cases.results.hdf5 import read_run

ROLLCONTACT = str(Path(sys.executable).with_name("rollcontact"))
COARSE = ["--set", "grid.dx=0.4", "--set", "motion.dW=0.4", "--set", "output.fields=all"]


class Disk:
    """A folder on a small file system of `size` bytes: a tmpfs when it can be mounted, else a plain folder whose
    "full disk" is RLIMIT_FSIZE in the processes started through `run` (`mounted` says which)."""

    def __init__(self, root: Path, size: int):
        self.path = root / "fs"
        self.path.mkdir()
        self.size = size
        self.mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(self.path)],
                                      capture_output=True).returncode == 0

    def grow(self, size: int):
        """More room (to continue a run after the disk filled up)."""
        if self.mounted:
            subprocess.run(["mount", "-o", f"remount,size={size}", str(self.path)], check=True)
        self.size = size

    def fill(self, leave: int):
        """Leave only about `leave` bytes free (a filler file; with RLIMIT_FSIZE, the limit)."""
        if self.mounted:
            free = shutil.disk_usage(self.path).free
            with open(self.path / ".filler", "wb") as fh:
                fh.write(bytes(max(free - leave, 0)))
        else:
            self.size = leave

    def readonly(self, on: bool = True):
        if self.mounted:
            subprocess.run(["mount", "-o", f"remount,{'ro' if on else 'rw'}", str(self.path)], check=True)
        elif os.geteuid() != 0:
            self.path.chmod(0o555 if on else 0o755)
        else:
            pytest.skip("read-only needs a mount (not permitted here) or a user other than root")

    def run(self, *args, cwd=None):
        """`rollcontact ARGS` in the folder (a fresh process: a crash shows as a signal)."""
        limit = None if self.mounted else self.size

        def limited():
            if limit is not None:
                signal.signal(signal.SIGXFSZ, signal.SIG_IGN)      # a write past the limit fails with EFBIG
                resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
        return subprocess.run([ROLLCONTACT, *args], cwd=cwd or self.path, capture_output=True, text=True,
                              timeout=300, preexec_fn=limited)

    def close(self):
        if self.mounted:
            subprocess.run(["umount", "-l", str(self.path)], capture_output=True)


@pytest.fixture
def disk(tmp_path):
    made = []

    def make(size):
        made.append(Disk(tmp_path, size))
        return made[-1]
    yield make
    for d in made:
        d.close()


@pytest.fixture(scope="module")
def run_file(tmp_path_factory):
    """A finished coarse run (one period, fields of every step), written on an ordinary disk."""
    folder = tmp_path_factory.mktemp("made")
    made = subprocess.run([ROLLCONTACT, "run", "-q", *COARSE, "--set", "motion.periods=1", "-o", "r.h5"],
                          cwd=folder, capture_output=True, text=True, timeout=300)
    assert made.returncode == 0, made.stderr[-2000:]
    return folder / "r.h5"


def one_error_line(proc, code=1) -> str:
    """The single stderr line of a command that failed cleanly (no traceback, not killed by a signal)."""
    assert proc.returncode == code, (proc.returncode, proc.stderr[-3000:])
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert "Traceback" not in proc.stderr and len(lines) == 1, proc.stderr[-3000:]
    return lines[0]


def no_temporaries(folder: Path):
    assert not [p.name for p in folder.rglob(".*") if p.name.endswith((".tmp", ".old")) or ".tmp." in p.name]


def test_a_full_disk_at_a_checkpoint_keeps_the_last_one_and_says_how_to_continue(disk):
    d = disk(1 << 20)          # 1 MiB: the checkpoints of the first periods fit (two copies while one replaces the other)
    proc = d.run("run", "-q", *COARSE, "--set", "motion.periods=6", "-o", "out.h5")
    line = one_error_line(proc)
    why = "no space left on the device (ENOSPC)" if d.mounted else "file too large (EFBIG)"
    assert line.startswith(f"rollcontact run: error: cannot write checkpoint out.h5: {why}; the run stopped; its "
                           "last checkpoint is kept in out.h5 (status 'incomplete', ")
    assert line.endswith("continue with: rollcontact run --restart out.h5"), line
    kept = read_run(d.path / "out.h5")
    assert kept.status == "incomplete" and int(kept.history["period"][-1]) >= 1 and len(kept.field_steps)
    no_temporaries(d.path)
    d.grow(8 << 20)
    done = d.run("run", "-q", "--restart", "out.h5")                  # the command it printed
    assert done.returncode == 0, done.stderr[-2000:]
    assert read_run(d.path / "out.h5").status == "complete"


def test_run_with_stresses_on_a_full_disk_stops_cleanly_keeping_the_finished_step_files(disk):
    """The segmentation fault after ENOSPC (exit 139): a failed write inside HDF5 left datasets half closed."""
    d = disk(1 << 20)
    proc = d.run("run", "-q", *COARSE, "--set", "motion.periods=2", "--stresses", "--depths", "0,0.5,1,2", "-o",
                 "o.h5")
    assert proc.returncode != -signal.SIGSEGV
    line = one_error_line(proc)
    assert line.startswith("rollcontact run: error: cannot write ") and "the run stopped" in line
    folder = d.path / "o.h5.subsurface"
    steps = sorted(folder.glob("step_*.h5")) if folder.exists() else []
    if steps:
        assert f"the subsurface stresses of {len(steps)} stored step(s) are kept in o.h5.subsurface" in line
        for step in steps:
            with h5py.File(step) as h5:
                assert "von_mises" in h5
    no_temporaries(d.path)


def test_stresses_of_a_run_on_a_nearly_full_disk_leaves_the_run_file_as_it_was(disk, run_file):
    d = disk(4 << 20)
    shutil.copy(run_file, d.path / "r.h5")
    before = hashlib.sha256((d.path / "r.h5").read_bytes()).hexdigest()
    d.fill((d.path / "r.h5").stat().st_size + (64 << 10))
    line = one_error_line(d.run("stresses", "-q", "r.h5", "--all-steps"))
    assert line.startswith("rollcontact stresses: error: cannot write run file r.h5: ")
    assert hashlib.sha256((d.path / "r.h5").read_bytes()).hexdigest() == before
    no_temporaries(d.path)


def test_a_read_only_file_system_is_named_at_every_command_that_would_write(disk, run_file):
    d = disk(8 << 20)
    shutil.copy(run_file, d.path / "r.h5")
    d.readonly()
    try:
        why = "read-only file system" if d.mounted else "permission denied"
        line = one_error_line(d.run("stresses", "-q", "r.h5"))
        assert line.startswith(f"rollcontact stresses: error: cannot write r.h5: {why}") and "r.h5.lock" in line
        line = one_error_line(d.run("plot", "r.h5"), code=2)
        assert line.startswith("rollcontact plot: error: -o plots: cannot create the folder")
        line = one_error_line(d.run("run", "-q", "-o", "x.h5"), code=2)
        assert line.startswith("rollcontact run: error: -o x.h5: cannot write in .")
    finally:
        d.readonly(False)
    assert sorted(p.name for p in d.path.iterdir()) == ["r.h5"]


def _stop_writes_at_the_first_progress_line(action):
    """A progress callable that, at the run's first line, does `action` once (a BEM run announces its grid before
    its first step, the MDR model its springs after its steps, before the run's file is written)."""
    done = []

    def progress(message):
        if not done:
            done.append(message)
            action()
    return progress


def test_a_folder_that_vanishes_during_a_run_is_named_and_not_made_again(tmp_path):
    folder = tmp_path / "out"
    folder.mkdir()
    scene = rollcontact.load_scene(overrides={"grid.dx": 0.4, "motion.dW": 0.4, "motion.periods": 2})
    with pytest.raises(rollcontact.OutputWriteError) as info:
        rollcontact.run(scene, folder / "run.h5", progress=_stop_writes_at_the_first_progress_line(
            lambda: shutil.rmtree(folder)))
    assert str(info.value).startswith(f"cannot write checkpoint {folder / 'run.h5'}: its folder no longer exists "
                                      "(ENOENT); the run stopped; no checkpoint of it was written")
    assert not folder.exists() and info.value.restart is None


def test_a_final_write_on_a_full_disk_keeps_the_result_in_memory(disk):
    """The MDR model writes no checkpoints: its one write is the final one (the disk fills up while it runs)."""
    d = disk(1 << 20)
    scene = rollcontact.load_scene(overrides={"motion.periods": 2, "solver.fidelity": "mdr"})
    if not d.mounted:
        pytest.skip("filling the disk in this process needs a mounted file system (RLIMIT_FSIZE would stop pytest)")
    with pytest.raises(rollcontact.OutputWriteError) as info:
        rollcontact.run(scene, d.path / "mdr.h5", progress=_stop_writes_at_the_first_progress_line(
            lambda: d.fill(0)))
    assert str(info.value).startswith(f"cannot write run file {d.path / 'mdr.h5'}: no space left on the device "
                                      "(ENOSPC); the run stopped; no checkpoint of it was written")
    assert info.value.result is not None and info.value.result.status == "complete"
    assert not (d.path / "mdr.h5").exists()
    no_temporaries(d.path)


def test_a_sweep_and_a_plot_on_a_full_disk_stop_with_their_finished_files_kept(disk, run_file):
    d = disk(1 << 20)
    proc = d.run("sweep", "--vary", "motion.periods=4", *COARSE, "--jobs", "1", "-q", "-o", "sw")
    line = one_error_line(proc)
    assert line.startswith("rollcontact sweep: error: cannot write checkpoint ") and "the sweep stopped" in line
    assert line.endswith("rerun the same command to resume")
    assert (d.path / "sw" / "summary.csv").exists()
    no_temporaries(d.path)
    shutil.rmtree(d.path / "sw")
    shutil.copy(run_file, d.path / "r.h5")
    d.fill(40 << 10)                              # room for a figure or two, not all of them
    line = one_error_line(d.run("plot", "r.h5"))
    assert line.startswith("rollcontact plot: error: cannot write figure plots/r_")
    assert not list((d.path / "plots").iterdir())  # none of the figures, and no temporary file

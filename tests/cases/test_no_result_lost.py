"""No result is lost and none is replaced unasked, checked with real processes: -o onto an existing file, two
writers of one file, kill -9 of a run and its restart, two sweeps on one folder, figures that exist.
Units mm, N, MPa."""
import hashlib
import os
from pathlib import Path
import re
import signal
import subprocess
import sys
import time

import h5py
import numpy as np
import pytest

from rollcontact.bem.errors import OutputInUseError
from rollcontact.cases.results.hdf5 import is_complete, read_run
from rollcontact.cases.results.lock import OutputLock, holder_of

ROLLCONTACT = str(Path(sys.executable).parent / "rollcontact")
#: the paper scene on a coarse grid (a/dx = 12 at 0.4 mm): about 0.1 s per period here
COARSE = ["--set", "grid.dx=0.4", "--set", "motion.dW=0.4"]


def rollcontact(*args, cwd, timeout=300):
    return subprocess.run([ROLLCONTACT, *args], cwd=cwd, capture_output=True, text=True, timeout=timeout)


def md5(path) -> str:
    return hashlib.md5(Path(path).read_bytes()).hexdigest()


def test_o_onto_a_text_file_or_another_run_is_refused_and_leaves_it_as_it_was(tmp_path):
    text = tmp_path / "precious.txt"
    text.write_text("measurements of 2026-11-25\n")
    other = tmp_path / "other.h5"
    assert rollcontact("run", "-q", "-o", str(other), "--set", "solver.fidelity=mdr", cwd=tmp_path).returncode == 0
    before = {p: md5(p) for p in (text, other)}
    for target in (text, other):
        proc = rollcontact("run", "-q", "-o", str(target), *COARSE, "--set", "motion.periods=1", cwd=tmp_path)
        assert proc.returncode == 2, proc.stderr
        assert f"-o {target}" in proc.stderr and "--overwrite" in proc.stderr and "exists" in proc.stderr
        assert md5(target) == before[target]
    described = rollcontact("run", "-q", "-o", str(other), cwd=tmp_path).stderr
    assert "complete run file" in described and "not a run file" in rollcontact(
        "run", "-q", "-o", str(text), cwd=tmp_path).stderr
    # asked: replaced, and by a whole file
    assert rollcontact("run", "-q", "-o", str(other), "--overwrite", *COARSE, "--set", "motion.periods=1",
                       cwd=tmp_path).returncode == 0
    assert is_complete(other) and read_run(other).summary["nx"] > 1


def test_two_runs_onto_one_file_one_succeeds_and_the_other_is_refused(tmp_path):
    out = tmp_path / "same.h5"
    args = [ROLLCONTACT, "run", "-q", "-o", str(out), *COARSE, "--set", "motion.periods=8"]
    procs = [subprocess.Popen(args, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for _ in range(2)]
    results = [(p.wait(timeout=300), p.stdout.read(), p.stderr.read()) for p in procs]
    codes = sorted(r[0] for r in results)
    assert codes == [0, 2], results
    refused = next(r for r in results if r[0] == 2)[2]
    # refused at once because the other holds the lock, or after it finished because the file exists
    assert re.search(r"is being written by process \d+ on host \S+|exists; rollcontact does not replace", refused)
    done = next(r for r in results if r[0] == 0)[1]
    assert f"results written to {out}" in done and is_complete(out)
    assert not (tmp_path / "same.h5.lock").exists()


def test_a_second_writer_is_refused_naming_the_holder_and_a_dead_holders_lock_is_taken_over(tmp_path):
    out = tmp_path / "held.h5"
    holder = subprocess.Popen([sys.executable, "-c", (
        "import sys, time\nfrom rollcontact.cases.results.lock import OutputLock\n"
        f"lock = OutputLock({str(out)!r}).acquire()\nprint('held', flush=True)\ntime.sleep(120)\n")],
        stdout=subprocess.PIPE, text=True)
    assert holder.stdout.readline().strip() == "held"
    with pytest.raises(OutputInUseError, match=rf"is being written by process {holder.pid} on host "):
        OutputLock(out, label=f"-o {out}").acquire()
    assert str(holder.pid) in holder_of(out)
    holder.send_signal(signal.SIGKILL)
    holder.wait()
    assert holder_of(out) is None                                   # the OS released the dead process's lock
    with OutputLock(out) as lock:                                   # and the next writer takes it over
        assert lock.held and str(os.getpid()) in lock.path.read_text()
    assert not lock.path.exists()


def _wait_for_periods(path: Path, periods: int, proc, timeout=120) -> int:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and proc.poll() is None:
        try:
            with h5py.File(path, "r") as h5:
                done = int(h5["history/period"][-1]) - 1 if len(h5["history/period"]) else -1
            if done >= periods:
                return done
        except (OSError, KeyError):
            pass
        time.sleep(0.02)
    raise AssertionError("the run finished (or stalled) before it could be killed")


def test_kill_9_leaves_the_finished_periods_and_restart_finishes_the_run_as_uninterrupted(tmp_path):
    """kill -9 after at least 3 periods: the file opens with status 'incomplete' and every finished period (its
    history and the fields of its last checkpoint); `run --restart FILE` continues in the same file, and the result
    equals an uninterrupted run: up to the restart step bit for bit, after it to round-off. The solvers carry the
    product A tau of the last traction from one step to the next (solver.memo) and that product is not in the
    file: after a restart it is recomputed by FFT, which differs from the carried one in the last bits (measured:
    F_x 3.4e-14 N of 9.07 N, 3.7e-15 relative), and a few steps count one product more or less. So: 1e-12
    relative on every history quantity (two hundred times the measured difference, a thousand times below the
    solver tolerance 1e-8 that bounds what these digits mean), the products within one per step, the stick area
    within one element (an element on the Coulomb bound to round-off is stick or slip by round-off), and equal
    states, shakedown displacement (to 1e-12) and numbers of periods."""
    args = ["run", "-q", *COARSE, "--set", "motion.periods=30"]
    killed = tmp_path / "killed.h5"
    proc = subprocess.Popen([ROLLCONTACT, *args, "-o", str(killed)], cwd=tmp_path, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    _wait_for_periods(killed, 3, proc)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    part = read_run(killed)
    assert part.status == "incomplete" and part.summary["state"] == "incomplete"
    n = len(part.history["step"])
    finished = int(part.history["period"][-1])
    assert finished >= 3 and list(part.history["step"]) == list(range(n))
    ends = [int(np.flatnonzero(part.history["period"] == k)[-1]) for k in range(finished)]
    assert set(ends) <= set(part.field_steps.tolist()) and part.field_steps[-1] == n - 1   # restart point stored
    restarted = rollcontact("run", "-q", "--restart", str(killed), cwd=tmp_path)
    assert restarted.returncode == 0, restarted.stderr
    assert f"results written to {killed}" in restarted.stdout
    whole = tmp_path / "whole.h5"
    assert rollcontact(*args, "-o", str(whole), cwd=tmp_path).returncode == 0
    a, b = read_run(killed), read_run(whole)
    assert a.status == "complete" and a.attrs["restart_step"] == n - 1
    for name in a.history:
        if name not in ("iterations", "normal_iterations", "tangential_iterations", "residual", "wall_time",
                        "stick_area"):
            np.testing.assert_array_equal(a.history[name][:n], b.history[name][:n], err_msg=name)
            pair = [name[:-1] + c for c in "xy"] if name.endswith(("_x", "_y")) else [name]   # a vector's scale
            pair = ["U_x", "U_y"] if name == "U_perp" else pair                            # a component of U
            scale = max(np.abs(b.history[k]).max() for k in pair)
            np.testing.assert_allclose(a.history[name], b.history[name], rtol=0, atol=1e-12 * scale, err_msg=name)
    assert np.abs(a.history["iterations"] - b.history["iterations"]).max() <= 1
    # an element whose traction lies on the Coulomb bound to round-off counts as stick or slip by round-off
    assert np.abs(a.history["stick_area"] - b.history["stick_area"]).max() <= 0.4 * 0.4 * (1 + 1e-9)
    assert a.history["residual"].max() <= 1e-8 and b.history["residual"].max() <= 1e-8   # both to the tolerance
    for key in ("state", "periods_to_shakedown", "steps"):
        assert a.summary.get(key) == b.summary.get(key), key
    assert a.summary["u_sd"] == pytest.approx(b.summary["u_sd"], rel=1e-12)
    np.testing.assert_allclose(a.field("tau_x"), b.field("tau_x"), rtol=0, atol=1e-12 * np.abs(b.field("tau_x")).max())


def test_two_sweeps_on_one_folder_share_the_work_and_both_summaries_are_complete(tmp_path):
    out = tmp_path / "shared"
    args = [ROLLCONTACT, "sweep", "-o", str(out), "--jobs", "1", "-q", "--vary", "load.ft=0.2,0.3,0.4,0.5",
            "--vary", "motion.angle=0,90", *COARSE, "--set", "motion.periods=3"]
    procs = [subprocess.Popen(args, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for _ in range(2)]
    outs = [(p.wait(timeout=600), p.stdout.read(), p.stderr.read()) for p in procs]
    assert all(code == 0 for code, _, _ in outs), outs
    counts = [re.search(r"(\d+) run\(s\): (\d+) run now, (\d+) skipped .*, (\d+) run by another process", o)
              for _, o, _ in outs]
    assert all(counts), outs
    planned = [int(c.group(1)) for c in counts]
    ran = [int(c.group(2)) for c in counts]
    assert planned == [8, 8] and sum(ran) == 8            # every run computed once, by one of the two
    for c in counts:                                      # each saw all 8: its own, skipped or the other's
        assert int(c.group(2)) + int(c.group(3)) + int(c.group(4)) == 8
    rows = (out / "summary.csv").read_text().splitlines()[1:]
    assert len(rows) == 8 and all(",complete," in r for r in rows)
    assert len([p for p in out.glob("*.h5") if p.name != "summary.h5"]) == 8 and not list(out.glob("*.lock"))


def test_figures_that_exist_are_not_replaced_unless_asked(tmp_path):
    run = tmp_path / "run.h5"
    assert rollcontact("run", "-q", "-o", str(run), "--set", "solver.fidelity=mdr", cwd=tmp_path).returncode == 0
    first = rollcontact("plot", str(run), "-o", str(tmp_path / "figs"), cwd=tmp_path)
    assert first.returncode == 0, first.stderr
    png = next((tmp_path / "figs").glob("*_history.png"))
    before = md5(png)
    again = rollcontact("plot", str(run), "-o", str(tmp_path / "figs"), cwd=tmp_path)
    assert again.returncode == 2 and str(png) in again.stderr and "--overwrite" in again.stderr
    assert md5(png) == before
    assert rollcontact("plot", str(run), "-o", str(tmp_path / "figs"), "--overwrite", cwd=tmp_path).returncode == 0
    assert not list((tmp_path / "figs").glob(".*.tmp*"))


@pytest.mark.slow
def test_a_sweep_on_dask_reports_a_worker_that_dies_and_finishes_every_run(tmp_path):
    """A scheduler and two workers started as the README says (`dask scheduler`, `dask worker`), one worker killed
    with SIGKILL while the sweep runs: the sweep says which worker left, the scheduler runs its runs again on the
    other one, and every run ends complete (about 40 s)."""
    pytest.importorskip("distributed", reason="optional extra 'dask' not installed")
    dask = str(Path(sys.executable).parent / "dask")
    info = tmp_path / "scheduler.json"
    logs = open(tmp_path / "dask.log", "w")
    scheduler = subprocess.Popen([dask, "scheduler", "--scheduler-file", str(info), "--port", "0",
                                  "--dashboard-address", ":0", "--no-show"], stdout=logs, stderr=logs)
    workers = []
    try:
        deadline = time.monotonic() + 60
        while not info.exists() and time.monotonic() < deadline:
            time.sleep(0.1)
        address = __import__("json").loads(info.read_text())["address"]
        elsewhere = tmp_path / "workers"          # the workers' own folder: a relative -o must not land there
        elsewhere.mkdir()
        for _ in range(2):
            workers.append(subprocess.Popen([dask, "worker", address, "--nthreads", "1", "--no-nanny",
                                             "--no-dashboard"], cwd=elsewhere, stdout=logs, stderr=logs))
        out = tmp_path / "sweep"
        proc = subprocess.Popen([ROLLCONTACT, "sweep", "-o", "sweep", "--scheduler", address, "--vary",
                                 "load.ft=0.2,0.3,0.4,0.5,0.6,0.7", *COARSE, "--set", "motion.periods=12"],
                                cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        deadline = time.monotonic() + 120     # both workers busy: two run files locked (the table's lock,
        while time.monotonic() < deadline and len(   # summary.h5.lock, comes before any run starts)
                [p for p in out.glob("*.h5.lock") if p.name != "summary.h5.lock"]) < 2:
            time.sleep(0.05)
        workers[0].send_signal(signal.SIGKILL)
        stdout, stderr = proc.communicate(timeout=300)
        assert proc.returncode == 0, stderr
        assert re.search(r"Dask worker \S+ left the scheduler", stderr), stderr
        rows = (out / "summary.csv").read_text().splitlines()[1:]
        assert len(rows) == 6 and all(",complete," in r for r in rows)
        assert all(is_complete(p) for p in out.glob("*.h5") if p.name != "summary.h5")
        assert not list(elsewhere.rglob("*.h5"))
    finally:
        for p in workers + [scheduler]:
            p.kill()
            p.wait()
        logs.close()


def test_a_partial_file_of_another_run_is_neither_replaced_nor_removed(tmp_path):
    """Beside a complete x.h5, a run with --overwrite writes its progress to x.partial.h5; when that name holds the
    result of another run (here a complete one, e.g. the restart of a killed --overwrite run), it uses
    x.partial-2.h5 and leaves x.partial.h5 as it was."""
    out, partial = tmp_path / "x.h5", tmp_path / "x.partial.h5"
    for path in (out, partial):
        assert rollcontact("run", "-q", "-o", str(path), *COARSE, "--set", "motion.periods=1",
                           cwd=tmp_path).returncode == 0
    before = md5(partial)
    done = rollcontact("run", "-q", "-o", str(out), "--overwrite", *COARSE, "--set", "motion.periods=2", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert md5(partial) == before and read_run(out).summary["steps"] > read_run(partial).summary["steps"]
    assert not (tmp_path / "x.partial-2.h5").exists()          # the run's own partial file went when it completed


def test_an_interrupted_run_without_stored_fields_can_still_be_restarted(tmp_path):
    """output.fields = 'none' stores no snapshots, but a run that stops early keeps the fields of its last step
    (what a restart continues from), as its checkpoints do."""
    out = tmp_path / "nofields.h5"
    proc = subprocess.Popen([ROLLCONTACT, "run", "-o", str(out), *COARSE, "--set", "motion.periods=2000",
                             "--set", "output.fields=none"], cwd=tmp_path, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    for line in proc.stderr:
        if line.startswith("step "):
            break
    proc.send_signal(signal.SIGINT)
    proc.communicate(timeout=120)
    part = read_run(out)
    assert part.status == "failed" and list(part.field_steps) == [part.history["step"][-1]]
    more = rollcontact("run", "-q", "--restart", str(out), "--set", f"motion.periods={int(part.history['period'][-1]) + 1}",
                       "-o", str(tmp_path / "more.h5"), cwd=tmp_path)
    assert more.returncode == 0, more.stderr


def test_two_different_sweeps_started_at_once_on_one_folder_one_is_refused(tmp_path):
    out = tmp_path / "folder"
    args = [ROLLCONTACT, "sweep", "-o", str(out), "--jobs", "1", "-q", "--vary", "load.ft=0.2,0.3",
            "--set", "solver.fidelity=mdr"]
    procs = [subprocess.Popen(args + ["--set", f"motion.periods={n}"], cwd=tmp_path, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True) for n in (2, 3)]
    outs = [(p.wait(timeout=300), p.stderr.read()) for p in procs]
    assert sorted(code for code, _ in outs) == [0, 2], outs
    assert "belongs to another sweep" in next(err for code, err in outs if code == 2)


def test_without_flock_the_lock_file_still_admits_one_writer(tmp_path):
    """On a file system without flock the lock is a hard link made atomically: of two processes that race for it,
    one gets it, ten times over."""
    code = ("import errno, fcntl, sys, time\n"
            "def none(*a, **k): raise OSError(errno.ENOLCK, 'no locks')\n"
            "fcntl.flock = none\n"
            "from rollcontact.cases.results.lock import OutputLock\n"
            "try:\n    lock = OutputLock(sys.argv[1]).acquire()\nexcept Exception as exc:\n"
            "    print(type(exc).__name__); sys.exit()\n"
            "print('got', flush=True); time.sleep(0.3); lock.release()\n")
    for trial in range(10):
        path = str(tmp_path / f"race{trial}.h5")
        procs = [subprocess.Popen([sys.executable, "-c", code, path], stdout=subprocess.PIPE, text=True)
                 for _ in range(2)]
        assert sorted(p.communicate(timeout=60)[0].strip() for p in procs) == ["OutputInUseError", "got"]
    assert not [p for p in tmp_path.iterdir()]                  # no lock, claim or probe file left

"""Interrupting `rollcontact run` (Ctrl-C or SIGTERM), as a user would: a real subprocess signalled once it has
reported its first rolling step. Nothing finished is lost: the finished steps, the fields of the last of them
(so that --restart can continue there) and a summary are written, one line says where and how to continue,
no traceback; and a complete run file already at the output path is kept (the partial run goes beside it)."""
import hashlib
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from rollcontact.cases.results.hdf5 import is_complete, read_run
from rollcontact.cases.run.restart import load_restart

ROLLCONTACT = str(Path(sys.executable).with_name("rollcontact"))
LONG = ["--set", "motion.periods=600"]  # 14402 steps at dx = 0.2 mm (about 40 s): far longer than the wait below


def interrupted_run(out, sig, cwd, *extra):
    proc = subprocess.Popen([ROLLCONTACT, "run", "-o", str(out), *LONG, *extra], cwd=cwd, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    for line in proc.stderr:    # progress lines "step k/N ..." every 2 s; wait for one past the first rolling step
        if line.startswith("step ") and int(line.split()[1].split("/")[0]) >= 3:   # (a slow step 0 on a busy
            break                                                                   # machine prints "step 1/N")
    proc.send_signal(sig)
    stdout, stderr = proc.communicate(timeout=120)
    return proc.returncode, stdout, stderr


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_an_interrupted_run_keeps_its_steps_and_says_how_to_continue(tmp_path, sig):
    out = tmp_path / "long.h5"
    code, stdout, stderr = interrupted_run(out, sig, tmp_path)
    assert code == 130, stderr
    assert "Traceback" not in stderr and "interrupted after" in stderr, stderr
    d = read_run(out)
    assert d.status == "failed" and d.error == "interrupted by the user" and not is_complete(out)
    n = len(d.history["step"])
    assert 1 < n < 14402
    assert all(len(v) == n for v in d.history.values())              # whole steps only
    assert list(d.history["step"]) == list(range(n))
    assert d.field_steps[-1] == n - 1                                   # the last finished step's fields
    assert d.fields["p"].shape[0] == len(d.field_steps)
    assert d.summary.get("steps") == n and d.summary.get("state")      # a summary, not an empty group
    assert f"--restart {out} --step {n - 1}" in stderr
    source = load_restart(out, n - 1)                                   # and it can be continued from there
    assert source.step == n - 1


def test_an_interrupted_rerun_does_not_replace_a_complete_run(tmp_path):
    out = tmp_path / "run.h5"
    done = subprocess.run([ROLLCONTACT, "run", "-q", "-o", str(out), "--set", "motion.periods=1"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0 and is_complete(out), done.stderr
    before = hashlib.md5(out.read_bytes()).hexdigest()
    again = subprocess.run([ROLLCONTACT, "run", "-o", str(out), *LONG], cwd=tmp_path, capture_output=True, text=True,
                           timeout=300)                                     # refused: the file exists
    assert again.returncode == 2 and "--overwrite" in again.stderr
    code, _, stderr = interrupted_run(out, signal.SIGINT, tmp_path, "--overwrite")
    assert code == 130
    assert hashlib.md5(out.read_bytes()).hexdigest() == before
    partial = tmp_path / "run.partial.h5"
    assert str(partial) in stderr and read_run(partial).status == "failed"
    assert np.all(np.diff(read_run(partial).history["step"]) == 1)


def test_an_interrupted_limit_search_says_where_its_results_are_and_how_to_resume(tmp_path):
    proc = subprocess.Popen([ROLLCONTACT, "limit-search", "--vary", "motion.w=0.23", "-o", str(tmp_path / "ls"),
                             "--jobs", "1", "--set", "grid.dx=0.4", "--set", "grid.dy=0.4"], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    for line in proc.stderr:                    # the first probe's line: the search is under way
        if line.startswith("limit-search "):
            break
    proc.send_signal(signal.SIGINT)
    _, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 130
    assert "Traceback" not in stderr
    assert f"interrupted; 0 of 1 search(es) finished are in {tmp_path / 'ls'}/limits.csv" in stderr, stderr
    assert "rerun the same command to resume" in stderr


def test_a_swallowed_interrupt_is_not_reported_as_a_traceback_once_it_is_requested():
    # A Ctrl-C that lands in a weakref callback or __del__ cannot be raised there: Python reports it through
    # sys.unraisablehook ("Exception ignored in ...", a traceback) and the sweep raises it again at its next check
    # (interrupt_requested). The report is dropped then, and only then; any other exception is still reported.
    from types import SimpleNamespace
    from rollcontact.cases.sweep.workers import _quiet_interrupts, interrupt_requested
    seen = []
    hook = _quiet_interrupts(seen.append)
    swallowed = SimpleNamespace(exc_type=KeyboardInterrupt)
    other = SimpleNamespace(exc_type=ValueError)
    assert not interrupt_requested.is_set()
    hook(swallowed)
    assert seen == [swallowed]                  # no interrupt was requested: a stray KeyboardInterrupt is reported
    interrupt_requested.set()
    try:
        hook(swallowed)
        hook(other)
    finally:
        interrupt_requested.clear()             # one command per process: the flag must not leak into other tests
    assert seen == [swallowed, other]

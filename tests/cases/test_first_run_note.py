"""The first run after an install compiles the kernels (rollcontact.bem.compiled: about half a minute before the
first step) and says so, once: a real `rollcontact run` with an empty cache (ROLLCONTACT_CACHE) announces the
compilation, and the same command run again, on the cache the first one wrote, does not."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROLLCONTACT = str(Path(sys.executable).with_name("rollcontact"))
NOTE = "compiling the numerical kernels"


@pytest.mark.slow
def test_the_first_run_announces_the_compilation_and_later_runs_do_not(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "ROLLCONTACT_KERNEL_CACHE"}
    env["ROLLCONTACT_CACHE"] = str(tmp_path / "cache")
    cmd = [ROLLCONTACT, "run", "-o", str(tmp_path / "run.h5"), "--set", "motion.periods=1"]
    first = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
    assert first.returncode == 0, first.stderr
    assert first.stderr.count(NOTE) == 1, first.stderr
    # announced before the first step, after the grid line
    lines = first.stderr.splitlines()
    at = next(i for i, line in enumerate(lines) if NOTE in line)
    assert lines[at - 1].startswith("grid ") and not any(line.startswith("step ") for line in lines[:at])
    again = subprocess.run(cmd + ["--overwrite"], cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
    assert again.returncode == 0, again.stderr
    assert NOTE not in again.stderr, again.stderr

"""`rollcontact run` refuses bad input with exit code 2 and one line naming the option, before any work.

Real files and real runs on a coarse grid; one subprocess checks that no Python traceback reaches the user.
"""
import os
from pathlib import Path
import subprocess
import sys

import h5py
import pytest

from rollcontact.cases.cli.main import main

COARSE = ["--set", "grid.dx=0.4", "--set", "motion.dW=0.4", "--set", "motion.periods=2"]
ROLLCONTACT = str(Path(sys.executable).with_name("rollcontact"))


def error_line(capsys):
    err = capsys.readouterr().err.strip()
    assert "Traceback" not in err and len(err.splitlines()) == 1, err
    return err


@pytest.fixture(scope="module")
def source(tmp_path_factory):
    path = tmp_path_factory.mktemp("src") / "src.h5"
    assert main(["run", "-q", "-o", str(path), *COARSE]) == 0
    return path


def test_restart_from_a_missing_file_names_the_option(tmp_path, capsys):
    assert main(["run", "-q", "--restart", str(tmp_path / "nonexist.h5"), "-o", str(tmp_path / "o.h5")]) == 2
    err = error_line(capsys)
    assert "--restart" in err and "no such file" in err


def test_restart_from_a_file_that_is_not_a_run_file_names_the_option(tmp_path, capsys):
    text = tmp_path / "README.md"
    text.write_text("# not HDF5\n")
    assert main(["run", "-q", "--restart", str(text), "-o", str(tmp_path / "o.h5")]) == 2
    assert "--restart" in error_line(capsys)
    other = tmp_path / "other.h5"                       # HDF5, but not written by `rollcontact run`
    with h5py.File(other, "w") as h5:
        h5["x"] = [1.0]
    assert main(["run", "-q", "--restart", str(other), "-o", str(tmp_path / "o.h5")]) == 2
    assert "--restart" in error_line(capsys)
    assert main(["run", "-q", "--restart", str(tmp_path), "-o", str(tmp_path / "o.h5")]) == 2
    assert "--restart" in error_line(capsys)


def test_output_that_is_a_directory_is_refused(tmp_path, capsys):
    (tmp_path / "results").mkdir()
    assert main(["run", "-q", "-o", str(tmp_path / "results"), *COARSE]) == 2
    assert "-o" in (err := error_line(capsys)) and "is a directory" in err
    assert main(["run", "-q", "-o", str(tmp_path / "new") + os.sep, *COARSE]) == 2
    assert "is a directory" in error_line(capsys)


@pytest.mark.parametrize("where", ["proc", "file_parent"])
def test_output_in_an_unwritable_place_is_refused_before_the_run(tmp_path, capsys, where):
    if where == "proc":
        if not Path("/proc/self").exists():
            pytest.skip("no /proc")
        out = "/proc/x.h5"
    else:
        (tmp_path / "plain").write_text("a file, not a folder")
        out = str(tmp_path / "plain" / "x.h5")
    # a scene whose run would take minutes: refused at once, so the check comes before the run
    assert main(["run", "-q", "-o", out, "--set", "motion.periods=20000"]) == 2
    err = error_line(capsys)
    assert "-o" in err and "cannot write" in err


def test_step_without_restart_is_an_error(tmp_path, capsys):
    assert main(["run", "-q", "--step", "3", "-o", str(tmp_path / "o.h5"), *COARSE]) == 2
    err = error_line(capsys)
    assert "--step" in err and "--restart" in err
    assert not (tmp_path / "o.h5").exists()


def test_step_not_stored_lists_the_stored_steps_as_plain_integers(source, tmp_path, capsys):
    assert main(["run", "-q", "--restart", str(source), "--step", "2", "-o", str(tmp_path / "o.h5")]) == 2
    err = error_line(capsys)
    assert "stored steps: [1, " in err and "np.int64" not in err


def test_no_traceback_reaches_the_user_from_the_console_script(tmp_path):
    res = subprocess.run([ROLLCONTACT, "run", "--restart", str(tmp_path / "nonexist.h5")], cwd=tmp_path,
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 2 and "Traceback" not in res.stderr
    assert res.stderr.startswith("rollcontact run: error: --restart")


@pytest.mark.parametrize("override, message", [
    # a grid above the element limit names the margin that made it so, and its allowed range
    ("grid.margin=1000", "allowed range at this dx, dy and amplitude is [grid] margin <= 199.5 mm"),
    # W / dW overflowed to inf and math.ceil raised OverflowError (a traceback, exit 1)
    ("motion.w=1e307", "[motion] W = 4.7857e+307 mm (= w a, a = 4.786 mm) with dW = 0.2 mm needs inf steps per "
                       "quarter period; allowed range is W <= 5e+04 mm"),
    # sqrt(Rx Ry) would overflow: the derived amplitude w a is refused with its origin
    ("geometry.R=1e200", "(= w a, a = 6.495e+66 mm)"),
    # squared tractions underflow: u_stat 1.6 % off without a word
    ("load.mu=1e-200", "[load] mu = 1e-200: allowed range is [1e-06, 10]"),
])
def test_extreme_values_are_refused_with_the_key_and_its_range(tmp_path, capsys, override, message):
    out = tmp_path / "x.h5"
    assert main(["run", "-q", "-o", str(out), "--set", override]) == 2
    assert message in error_line(capsys)
    assert not out.exists()


def test_a_margin_below_one_element_is_raised_to_one_element(tmp_path):
    """margin = 0.1 mm on the 0.2 mm grid passes validation, and the contact would touch the grid's edge at step 0
    (ContactEdgeError, exit 1): the grid keeps at least one element of margin."""
    out = tmp_path / "m.h5"
    assert main(["run", "-q", "-o", str(out), "--set", "grid.margin=0.1", "--set", "motion.periods=1"]) == 0
    with h5py.File(out) as h5:
        assert h5.attrs["status"] == "complete"
        x = h5["grid/x"][()]
    a = 4.7857  # Hertz a of the paper scene (mm); rolling is along y there, so x spans the contact alone
    assert x.max() - a >= 0.1 - 1e-9  # the outermost cell centre half an element or more beyond a


@pytest.mark.parametrize("command", [["sweep", "--vary", "load.ft=0.2"], ["limit-search", "--vary", "motion.w=0.23"]])
def test_an_output_folder_that_is_a_file_is_refused_before_any_run(tmp_path, capsys, command):
    text = tmp_path / "notes.md"
    text.write_text("# a file, not a folder\n")
    assert main([*command, "-o", str(text)]) == 2
    err = error_line(capsys)
    assert "-o" in err and "not a folder" in err
    assert text.read_text() == "# a file, not a folder\n"


def test_a_malformed_scheduler_address_is_refused_before_the_folder_is_made(tmp_path, capsys):
    out = tmp_path / "sweep"
    assert main(["sweep", "--vary", "load.ft=0.2", "-o", str(out), "--scheduler", "foo"]) == 2
    err = error_line(capsys)
    assert "--scheduler 'foo'" in err and "HOST:PORT" in err
    assert not out.exists()


CLOSED_READER = ("import os, sys\n"
                 "r, w = os.pipe(); os.close(r); os.dup2(w, 1)\n"  # stdout: a pipe whose reader has gone
                 "from {module} import {entry}\n"
                 "sys.exit({entry}(['limits', '--w', '0.23']))\n")


@pytest.mark.parametrize("module, entry, clean", [("rollcontact.cases.cli.main", "main", True),
                                                   ("rollcontact.cases.cli.limits_cmd", "run_cli", False)])
def test_a_reader_that_closes_the_pipe_early_gets_no_traceback(tmp_path, module, entry, clean):
    # `rollcontact limits --w 0.23 | head -1`: the command finishes quietly (exit 0), as other Unix tools do; the
    # bare subcommand entry without the CLI's guard shows that this situation does produce the error otherwise
    proc = subprocess.run([sys.executable, "-c", CLOSED_READER.format(module=module, entry=entry)], cwd=tmp_path,
                          capture_output=True, text=True, timeout=120)
    quiet = proc.returncode == 0 and "BrokenPipe" not in proc.stderr and "Traceback" not in proc.stderr
    assert quiet == clean, proc.stderr


@pytest.mark.parametrize("address", ["tcp://127.0.0.1:8786", "127.0.0.1:8786", "tcp://[::1]:8786", "tls://host:9"])
def test_well_formed_scheduler_addresses_pass_the_address_check(address):
    from rollcontact.bem.errors import InputError
    from rollcontact.cases.sweep.workers import require_dask
    try:
        require_dask(address)          # returns dask.distributed, or refuses only for want of the extra
    except InputError as exc:
        assert "HOST:PORT" not in str(exc), exc

"""`rollcontact run --restart RUN.h5 [--step N] [--set ...]`: what may change on a continuation, and the
continued file is complete (history and every field snapshot). Real runs on a coarse grid, real files."""
import h5py
import numpy as np
import pytest

from rollcontact.cases.cli.main import main
from rollcontact.cases.results.hdf5 import read_run
from rollcontact.cases.run.restart import RESTART_SAFE_KEYS

COARSE = ["--set", "grid.dx=0.4", "--set", "motion.dW=0.4", "--set", "motion.periods=2"]


@pytest.fixture(scope="module")
def source(tmp_path_factory):
    path = tmp_path_factory.mktemp("restart") / "src.h5"
    assert main(["run", "-q", "-o", str(path), *COARSE]) == 0
    return path


def restart(source, out, *args):
    return main(["run", "-q", "--restart", str(source), "-o", str(out), *args])


@pytest.mark.parametrize("override", [
    "grid.dx=0.2", "grid.margin=1.0", "motion.angle=0", "motion.w=0.3", "motion.dW=0.2", "geometry.R=30",
    "materials.E2=5", "load.ft=0.5", "load.Fn=20", "load.ramp_steps=2", 'solver.fidelity="mdr"',
    'solver.coupling="off"',
])
def test_an_override_the_stored_state_depends_on_is_refused_up_front(source, tmp_path, capsys, override):
    out = tmp_path / "out.h5"
    assert restart(source, out, "--set", override) == 2
    err = capsys.readouterr().err.strip()
    key = override.split("=")[0]
    assert len(err.splitlines()) == 1 and f"--set {override}" in err and "--restart" in err
    assert all(k in err for k in RESTART_SAFE_KEYS), err     # the message lists what may change
    assert key not in RESTART_SAFE_KEYS and not out.exists()


def test_an_override_that_keeps_the_stored_value_is_accepted(source, tmp_path):
    assert restart(source, tmp_path / "out.h5", "--set", "motion.angle=90", "--set", "grid.dx=0.4") == 0


def test_more_periods_continue_the_run_as_if_it_had_been_longer(source, tmp_path):
    longer = tmp_path / "longer.h5"
    assert restart(source, longer, "--set", "motion.periods=3", "--set", "solver.max_iter=800") == 0
    fresh = tmp_path / "fresh.h5"
    assert main(["run", "-q", "-o", str(fresh), *COARSE, "--set", "motion.periods=3"]) == 0
    c, f = read_run(longer), read_run(fresh)
    np.testing.assert_array_equal(c.history["step"], f.history["step"])
    assert np.abs(c.history["U_x"] - f.history["U_x"]).max() < 1e-6 * f.summary["U0"]
    np.testing.assert_array_equal(c.field_steps, f.field_steps)
    assert "periods = 3" in c.scene_toml and "max_iter = 800" in c.scene_toml
    with h5py.File(longer, "r") as h5:
        assert h5.attrs["restarted_from"] == str(source.resolve())
        assert h5.attrs["restart_step"] == int(read_run(source).field_steps[-1])
        assert list(h5.attrs["restart_overrides"]) == ["motion.periods=3", "solver.max_iter=800"]


def test_fewer_periods_than_the_restart_step_has_reached_are_refused(source, tmp_path, capsys):
    last = int(read_run(source).field_steps[-1])                     # in period 2
    assert restart(source, tmp_path / "o.h5", "--step", str(last), "--set", "motion.periods=1") == 2
    err = capsys.readouterr().err
    assert "motion.periods = 1" in err and "allowed range is periods >= 2" in err


def test_a_restart_keeps_the_snapshots_stored_before_the_restart_step(source, tmp_path, capsys):
    d = read_run(source)
    step = int(d.field_steps[len(d.field_steps) // 2])
    out = tmp_path / "cont.h5"
    assert main(["run", "--restart", str(source), "--step", str(step), "-o", str(out)]) == 0
    c = read_run(out)
    np.testing.assert_array_equal(c.field_steps, d.field_steps)
    n = int(np.searchsorted(d.field_steps, step)) + 1
    for name in ("p", "tau_x", "tau_y", "u_x", "region"):
        np.testing.assert_array_equal(c.fields[name][:n], d.fields[name][:n])        # copied
        assert np.abs(c.fields[name][n:] - d.fields[name][n:]).max() <= 1e-6 * np.abs(d.fields[name]).max()
    assert f"from step {step}" in capsys.readouterr().err


def test_writing_the_continuation_over_its_own_source_is_refused(source, tmp_path, capsys):
    before = source.read_bytes()
    assert restart(source, source, "--step", str(int(read_run(source).field_steps[1]))) == 2
    assert "-o" in capsys.readouterr().err and source.read_bytes() == before

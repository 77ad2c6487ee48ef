"""The command line, run as a user would: real subprocesses, real files."""
import os
import subprocess
import sys

import numpy as np
import pytest

from rollcontact.cases.cli.main import main
from rollcontact.cases.results.hdf5 import read_run
from rollcontact.cases.scene.scene import default_scene
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere

COARSE = ["--set", "grid.dx=0.4", "--set", "motion.dW=0.4", "--set", "motion.periods=2"]


def rollcontact(*args, cwd):
    exe = os.path.join(os.path.dirname(sys.executable), "rollcontact")
    return subprocess.run([exe, *args], cwd=cwd, capture_output=True, text=True, timeout=300)


def test_run_without_arguments_runs_the_paper_scene_and_says_where_results_went(tmp_path):
    res = rollcontact("run", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    out = tmp_path / "results" / "paper_perpendicular.h5"
    assert f"results written to {out}" in res.stdout
    assert "state: shakedown" in res.stdout and "max pressure" in res.stdout
    d = read_run(out)
    assert d.status == "complete" and d.summary["state"] == "shakedown"
    assert len(d.history["step"]) == 242  # loading (2 steps) + 10 periods x 24 steps (W/ceil(W/0.2))


def test_set_overrides_a_key_and_the_output_option_is_honoured(tmp_path):
    out = tmp_path / "x.h5"
    assert main(["run", "-q", "-o", str(out), "--set", "load.ft=0.77", *COARSE]) == 0
    d = read_run(out)
    assert d.summary["f_t"] == 0.77 and "ft = 0.77" in d.scene_toml


def test_bad_input_exits_with_code_2_and_a_message_naming_the_key(tmp_path, capsys):
    assert main(["run", "-q", "-o", str(tmp_path / "y.h5"), "--set", "load.ft=1.7"]) == 2
    assert "[load] ft = 1.7: allowed range is [0, 1]" in capsys.readouterr().err
    assert not (tmp_path / "y.h5").exists()


def test_a_failed_run_keeps_its_finished_steps_and_exits_1(tmp_path, capsys):
    out = tmp_path / "fail.h5"
    assert main(["run", "-q", "-o", str(out), *COARSE, "--set", "solver.max_iter=2"]) == 1
    d = read_run(out)
    assert d.status == "failed" and "ConvergenceError" in d.error
    assert "status: failed" in capsys.readouterr().out


def test_restart_from_a_stored_step_continues_to_the_same_end(tmp_path):
    full = tmp_path / "full.h5"
    assert main(["run", "-q", "-o", str(full), *COARSE]) == 0
    d = read_run(full)
    step = int(d.field_steps[2])
    cont = tmp_path / "cont.h5"
    assert main(["run", "-q", "--restart", str(full), "--step", str(step), "-o", str(cont)]) == 0
    c = read_run(cont)
    np.testing.assert_array_equal(c.history["step"], d.history["step"])
    assert np.abs(c.history["U_x"] - d.history["U_x"]).max() < 1e-6 * d.summary["U0"]
    assert c.summary["state"] == d.summary["state"]


def test_mdr_fidelity_writes_the_same_history_layout(tmp_path):
    out = tmp_path / "mdr.h5"
    assert main(["run", "-q", "-o", str(out), "--set", 'solver.fidelity="mdr"']) == 0
    d = read_run(out)
    from rollcontact.cases.results.run_result import HISTORY_NAMES
    assert set(d.history) == set(HISTORY_NAMES)
    # the 1D MDR model reaches the pure-MDR closed form u_sd(f_t, w, kappa = 3/2) (seed Eq. 15, theory 8.4; with
    # 4001 springs and dW = 0.2 mm measured within 6e-8), larger than the 3D model's at f_t 0.46, w 0.23
    from rollcontact.solver.mdr.limits import KAPPA_MDR, u_shakedown
    s = d.summary
    assert s["state"] == "shakedown"
    assert s["u_sd"] == pytest.approx(u_shakedown(s["f_t"], s["w"], KAPPA_MDR), abs=1e-6)


@pytest.mark.parametrize("overrides, message", [
    ("motion.w=4179 motion.dW=100", "exceeds the limit of"),          # W = 20000 mm: 55 x 200 001 elements > 2048^2
    ("motion.dW=0", r"\[motion\] dW = 0.0 mm: allowed range is \(0, inf\)"),
    ("motion.periods=-3", r"\[motion\] periods = -3: allowed range"),
    # 4.4e10 rolling steps: refused by the scene instead of a MemoryError while the path is built
    ("motion.dW=1e-9", r"\[motion\] dW = 1e-09 mm, periods = 10: .* allowed range is dW >= 4.4\d*e-05 mm"),
    ("motion.periods=100000", r"\[motion\] dW = 0.2 mm, periods = 100000: .*periods <= 41666"),
    # a/dx = 0.048: refused by the scene instead of a ContactEdgeError advising a larger margin
    ("grid.dx=100", r"\[grid\] dx = 100.0 mm: .* allowed range is 0 < dx <= 1.59\d* mm"),
])
def test_ill_posed_rolling_scenes_are_refused_before_any_work(tmp_path, capsys, overrides, message):
    import re
    sets = [a for o in overrides.split() for a in ("--set", o)]
    assert main(["run", "-q", "-o", str(tmp_path / "z.h5"), *sets]) == 2
    err = capsys.readouterr().err
    assert re.search(message, err), err
    assert not (tmp_path / "z.h5").exists()


def test_gross_sliding_is_a_result_the_cli_states_clearly_and_the_file_records(tmp_path, capsys):
    """f_t = 1 is inside the scene's range [0, 1]; Ft = mu Fn has no static equilibrium (gross sliding)."""
    out = tmp_path / "gs.h5"
    assert main(["run", "-q", "-o", str(out), *COARSE, "--set", "load.ft=1"]) == 0
    text = capsys.readouterr().out
    assert "state: gross_sliding at step 1 (of 26 planned)" in text
    assert "gross sliding: the tangential force reached the friction capacity" in text
    assert "reaches the friction capacity mu Fn" in text                   # the solver's own message
    d = read_run(out)
    assert d.status == "complete" and d.summary["state"] == "gross_sliding"
    assert d.summary["stopped_at_step"] == 1 and "friction capacity" in d.summary["state_message"]
    # the last completed step (Fn alone, step 0) is stored, as output.fields = "reversals" promises
    assert list(d.field_steps) == [0] and d.fields["p"].shape[0] == 1 and d.fields["p"].max() > 0


def test_u_stat_is_the_static_shift_at_f_t_also_when_further_force_levels_follow(tmp_path, capsys):
    """With load.levels the loading phase goes on past f_t (here unloading and reversal to -f_t); u_stat is the
    shift at the end of the ramp to f_t: Cattaneo-Mindlin (seed Eq. 4, within 1 %, docs/theory.md P10), not the shift
    after the last level (a review found the reversed value labelled with f_t)."""
    out = tmp_path / "levels.h5"
    assert main(["run", "-o", str(out), "--set", "grid.dx=0.2", "--set", "motion.periods=0", "--set", "load.ft=0.46",
                 "--set", "load.ramp_steps=3", "--set", "load.levels=[0.0, -0.46]"]) == 0
    d = read_run(out)
    s = d.summary
    cm = CattaneoMindlin(HertzSphere(40.0, default_scene().material_pair.E_star, 21.19), 0.93,
                         default_scene().material_pair.G_star)
    assert s["U_stat"] == pytest.approx(cm.shift(0.46), rel=0.01)
    assert s["U_stat"] == d.history["U_x"][3]  # step 3 ends the ramp (step 0: Fn alone)
    # Mindlin-Deresiewicz: the full reversal to -f_t re-slips the whole annulus, so the loop closes at -U_stat
    # (measured -0.99992 U_stat; 0.5 % leaves room for the reversal of the annulus on this 0.2 mm grid)
    assert d.history["U_x"][-1] == pytest.approx(-s["U_stat"], rel=0.005)
    assert f"U_stat = {s['U_stat']:.6f} mm" in capsys.readouterr().out


def test_version_option_names_the_installed_version(capsys):
    from rollcontact.cases.results.hdf5 import version
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0 and capsys.readouterr().out.strip() == f"rollcontact {version()}"

"""`run --stresses`: the subsurface stresses of each stored step computed when the step is stored
(cases.run.step_stresses), kept when the run fails or is killed, not computed again by its restart, and in the end the very /subsurface that
`rollcontact stresses RUN.h5 --all-steps` writes. Real runs of the paper scene on a coarse grid, real files, the
restart and kill -9 of tests/cases/test_no_result_lost.py. Units mm, MPa."""
from pathlib import Path
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

import rollcontact
from rollcontact.cases.cli.main import main as cli
from rollcontact.cases.results.hdf5 import read_run
from rollcontact.cases.run.step_stresses import folder_of

ROLLCONTACT = str(Path(sys.executable).parent / "rollcontact")
#: the paper scene on a coarse grid (a/dx = 12 at 0.4 mm, 27 x 33 elements)
COARSE = {"grid.dx": 0.4, "motion.dW": 0.4}
DEPTHS = "0,0.5,1.5,4"


def assert_same_as_computed_afterwards(path: Path, tmp_path: Path, depths=None):
    """/subsurface of `path` equals, bit for bit, what `rollcontact stresses COPY --all-steps` writes into a copy of
    it: the same datasets, shapes, chunks, compression, units, group attributes and values."""
    copy = tmp_path / "afterwards.h5"
    shutil.copyfile(path, copy)
    rollcontact.stresses(copy, steps="all", depths=depths)
    with h5py.File(path, "r") as a, h5py.File(copy, "r") as b:
        ga, gb = a["subsurface"], b["subsurface"]
        assert sorted(ga) == sorted(gb) and dict(ga.attrs) == dict(gb.attrs)
        np.testing.assert_array_equal(ga["step"][()], a["fields/step"][()])       # every stored step
        for name in gb:
            assert (ga[name].shape, ga[name].chunks, ga[name].compression) == \
                   (gb[name].shape, gb[name].chunks, gb[name].compression), name
            assert dict(ga[name].attrs) == dict(gb[name].attrs), name
            np.testing.assert_array_equal(ga[name][()], gb[name][()], err_msg=name)


def test_run_with_stresses_writes_what_stresses_all_steps_writes_after_the_run(tmp_path):
    """Default depths (30 down to 2a), a period of rolling: every stored step's stresses computed as the run went,
    one line each, and the file equals the one computed afterwards bit for bit; the step folder is gone."""
    out = tmp_path / "roll.h5"
    lines = []
    scene = rollcontact.load_scene(overrides={**COARSE, "motion.periods": 1})
    result = rollcontact.run(scene, out, stresses=True, progress=lines.append)
    stored = [int(s) for s in result.field_steps]
    assert len(stored) >= 3 and result.subsurface.computed == stored and result.subsurface.reused == []
    assert result.subsurface.steps == stored and len(result.subsurface.z) == 30
    written = [line for line in lines if line.startswith("subsurface stresses of step")]
    assert [int(line.split()[4]) for line in written] == stored and all("written" in line for line in written)
    assert not folder_of(out).exists()
    assert_same_as_computed_afterwards(out, tmp_path)


def test_a_failed_run_keeps_its_stresses_and_its_restart_computes_only_the_others(tmp_path):
    """A run that fails part-way (its iteration budget, solver.max_iter = 15, runs out in period 2) writes the stresses
    of every step it stored, the last one included; `restart` in its own file, with the budget raised, takes them
    (not one computed again, not one line 'written' for them) and computes those of the steps stored after; the
    complete file equals the stresses computed afterwards."""
    out = tmp_path / "failing.h5"
    scene = rollcontact.load_scene(overrides={**COARSE, "motion.periods": 2, "solver.max_iter": 15})
    failed = rollcontact.run(scene, out, stresses=True, depths=[0, 0.5, 1.5, 4])
    assert failed.status == "failed" and "ConvergenceError" in failed.error
    before = [int(s) for s in failed.field_steps]
    assert len(before) >= 3 and failed.subsurface.steps == before and not folder_of(out).exists()
    with h5py.File(out, "r") as h5:
        assert list(h5["subsurface/step"][()]) == before
    lines = []
    done = rollcontact.restart(out, output=out, overrides={"solver.max_iter": 500}, stresses=True,
                               depths=[0, 0.5, 1.5, 4], progress=lines.append)
    after = [int(s) for s in done.field_steps]
    assert done.status == "complete" and after[:len(before)] == before and len(after) > len(before)
    assert done.subsurface.reused == before and done.subsurface.computed == after[len(before):]
    written = [int(line.split()[4]) for line in lines if line.startswith("subsurface stresses of step")]
    assert written == after[len(before):]
    assert_same_as_computed_afterwards(out, tmp_path, depths=[0, 0.5, 1.5, 4])


def _wait_for(folder: Path, files: int, run_file: Path, proc, timeout=120):
    """Until `folder` holds `files` step files and `run_file` a checkpoint of a finished period."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and proc.poll() is None:
        try:
            if len(list(folder.glob("step_*.h5"))) >= files:
                with h5py.File(run_file, "r") as h5:
                    if int(h5["history/period"][-1]) >= 2:
                        return
        except (OSError, KeyError):
            pass
        time.sleep(0.02)
    raise AssertionError("the run finished (or stalled) before it could be killed")


def test_kill_9_keeps_the_stored_steps_stresses_and_the_restart_takes_them(tmp_path, capsys):
    """`rollcontact run --stresses` killed with SIGKILL: its folder keeps a readable file per step computed; `run
    --restart FILE --stresses` (the command line end to end) continues in the same file, takes every one of them for
    the steps it inherits (no line 'written' for them, the count said on stdout), computes the others, and the
    complete file holds /subsurface as computed afterwards, with the folder gone."""
    killed = tmp_path / "killed.h5"
    folder = folder_of(killed)
    args = ["run", "-q", "--set", "grid.dx=0.4", "--set", "motion.dW=0.4", "--set", "motion.periods=6", "--stresses",
            "--depths", DEPTHS, "-o", str(killed)]
    proc = subprocess.Popen([ROLLCONTACT, *args], cwd=tmp_path, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _wait_for(folder, 3, killed, proc)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    part = read_run(killed)
    assert part.status == "incomplete"
    with h5py.File(killed, "r") as h5:
        assert "subsurface" not in h5                              # the checkpoints never carry the stresses
    kept = {}
    for path in folder.glob("step_*.h5"):
        with h5py.File(path, "r") as h5:                          # whole files only: each was renamed into place
            kept[int(h5.attrs["step"])] = h5["von_mises"].shape
    assert len(kept) >= 3 and set(kept.values()) == {(4, len(part.y), len(part.x))}
    inherited = [int(s) for s in part.field_steps if int(s) in kept]     # the steps the restart continues after
    assert len(inherited) >= 2
    # a restart without --stresses (into another file) leaves the step files and says so
    assert cli(["run", "--restart", str(killed), "-o", str(tmp_path / "plain.h5")]) == 0
    assert f"note: {folder} holds the subsurface stresses of {len(kept)} stored step(s)" in capsys.readouterr().err
    assert len(list(folder.glob("step_*.h5"))) == len(kept)
    assert cli(["run", "--restart", str(killed), "--stresses", "--depths", DEPTHS]) == 0
    captured = capsys.readouterr()
    written = {int(line.split()[4]) for line in captured.err.splitlines() if line.startswith("subsurface stresses of")}
    stored = {int(s) for s in read_run(killed).field_steps}
    assert written and not written & set(inherited) and written <= stored - set(inherited)
    reused = int(captured.out.split(" step(s) computed before and kept")[0].split()[-1])
    assert len(written) + reused == len(stored) and reused >= len(inherited)
    assert read_run(killed).status == "complete" and not folder.exists()
    assert_same_as_computed_afterwards(killed, tmp_path, depths=[float(z) for z in DEPTHS.split(",")])


def test_the_command_line_refuses_depths_without_stresses_and_stresses_without_a_file(tmp_path, capsys):
    assert cli(["run", "-q", "--depths", "0,1", "-o", str(tmp_path / "x.h5")]) == 2
    assert "--depths applies only with --stresses" in capsys.readouterr().err
    scene = rollcontact.load_scene(overrides=COARSE)
    for call, message in ((lambda: rollcontact.run(scene, stresses=True), "give an output file"),
                          (lambda: rollcontact.run(scene, tmp_path / "y.h5", depths=[1.0]), "stresses=True")):
        try:
            call()
        except rollcontact.InputError as exc:
            assert message in str(exc)
        else:
            raise AssertionError("accepted")
    assert not (tmp_path / "y.h5").exists()


def test_an_interrupted_run_writes_the_stresses_of_every_step_it_said_it_wrote(tmp_path):
    """Ctrl-C (SIGINT) right after a line 'subsurface stresses of step N written': the run's file (status 'failed')
    holds the stresses of every step so announced, N included, whenever the interrupt came; the folder is gone."""
    out = tmp_path / "interrupted.h5"
    proc = subprocess.Popen([ROLLCONTACT, "run", "-o", str(out), "--set", "grid.dx=0.4", "--set", "motion.dW=0.4",
                             "--set", "motion.periods=600", "--stresses", "--depths", DEPTHS], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    announced = []
    for line in proc.stderr:
        if line.startswith("subsurface stresses of step"):
            announced.append(int(line.split()[4]))
            if len(announced) == 4:
                break
    proc.send_signal(signal.SIGINT)
    proc.communicate(timeout=120)
    assert proc.returncode == 130
    with h5py.File(out, "r") as h5:
        assert h5.attrs["status"] == "failed"
        computed = [int(s) for s in h5["subsurface/step"][()]]
        stored = [int(s) for s in h5["fields/step"][()]]
    assert announced == computed[:4] and set(computed) <= set(stored) and not folder_of(out).exists()


def test_stresses_stored_with_other_filters_are_computed_again_not_copied(tmp_path):
    """Layer chunks are copied between files as they are (the step files, a restart's source), so only from a file
    that stores them with the same filters (cases.run.stresses.LAYER_FILTERS): a source whose /subsurface was written
    with deflate alone (as an older rollcontact did) has its inherited steps' stresses computed again, and the result
    is what `stresses --all-steps` computes, bit for bit."""
    source = tmp_path / "source.h5"
    first = rollcontact.run(rollcontact.load_scene(overrides={**COARSE, "motion.periods": 1}), source, stresses=True,
                            depths=[0, 0.5, 1.5, 4])
    with h5py.File(source, "a") as h5:
        g = h5["subsurface"]
        for name in [n for n in g if n not in ("z", "step")]:
            values, units = g[name][()], g[name].attrs["units"]
            del g[name]
            g.create_dataset(name, data=values, chunks=(1, 1) + values.shape[2:], compression="gzip",
                             compression_opts=4).attrs["units"] = units
    step = int(first.field_steps[-1])
    out = tmp_path / "continued.h5"
    done = rollcontact.restart(source, step=step, output=out, overrides={"motion.periods": 2}, stresses=True,
                               depths=[0, 0.5, 1.5, 4])
    inherited = [int(s) for s in done.field_steps if s <= step]
    assert done.status == "complete" and inherited and done.subsurface.reused == []
    assert set(inherited) <= set(done.subsurface.computed)
    assert_same_as_computed_afterwards(out, tmp_path, depths=[0, 0.5, 1.5, 4])

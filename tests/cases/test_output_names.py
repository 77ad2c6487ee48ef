"""The default output file of `rollcontact run` (no -o): a variant never overwrites the plain scene's file."""
from pathlib import Path

from rollcontact.cases.cli.main import main
from rollcontact.cases.results.hdf5 import read_run
from rollcontact.cases.results.outputs import default_output

COARSE = ["--set", "grid.dx=0.4", "--set", "motion.dW=0.4", "--set", "motion.periods=2"]


def test_set_overrides_without_o_write_a_file_named_after_them(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["run", *COARSE]) == 0
    coarse = tmp_path / "results" / "paper_perpendicular__grid.dx=0.4__motion.dW=0.4__motion.periods=2.h5"
    assert coarse.exists() and not (tmp_path / "results" / "paper_perpendicular.h5").exists()
    out, err = capsys.readouterr()
    assert f"results written to {coarse}" in out and "no -o given: writing to" in err
    assert main(["run", "-q", *COARSE, "--set", "motion.angle=0"]) == 0
    par = coarse.with_name(f"{coarse.stem}__motion.angle=0.h5")
    assert "angle = 0.0" in read_run(par).scene_toml and "angle = 90.0" in read_run(coarse).scene_toml
    # a restart without -o writes beside, never over, its source
    step = int(read_run(coarse).field_steps[1])
    assert main(["run", "-q", "--restart", str(coarse), "--step", str(step)]) == 0
    assert (tmp_path / "results" / f"{coarse.stem}__from_step{step}.h5").exists()


def test_default_names_are_sanitised_and_bounded():
    assert default_output("paper_perpendicular") == Path("results/paper_perpendicular.h5")
    assert default_output("s", ['solver.fidelity="mdr"', "load.levels=[0.0, -0.5]"]).name == \
        "s__solver.fidelity=mdr__load.levels=-0.0--0.5-.h5"
    long = default_output("s", [f"load.ft=0.{i:03d}" for i in range(40)])
    other = default_output("s", [f"load.ft=0.{i:03d}" for i in range(1, 41)])
    assert len(long.name) <= 125 and long != other and "/" not in long.name

"""The Python API does all the command line does: a function per command, the commands a thin layer over them,
results that compare by value, print one short line and carry their units, errors in the API's own words. Real runs
(the 1-D MDR model and coarse BEM runs of the paper scene), real files."""
import ast
from pathlib import Path
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

import rollcontact
from rollcontact.cases.cli.main import build_parser, main
from rollcontact.cases.results.run_result import CREEP_SUMMARY_UNITS, SUMMARY_UNITS, UNITS, RunResult

ROOT = Path(__file__).resolve().parents[2]
ROLLCONTACT = str(Path(sys.executable).with_name("rollcontact"))
COARSE = {"grid.dx": 0.6, "grid.dy": 0.6, "motion.dW": 0.6, "motion.periods": 3}
#: command -> the API function it calls
COMMANDS = {"run": "run", "limits": "limits", "sweep": "sweep", "limit-search": "limit_search", "plot": "plot",
            "compare": "compare", "stresses": "stresses", "creep-curve": "creep_curve", "import-contact": "import_contact"}


@pytest.fixture(scope="module")
def coarse(tmp_path_factory):
    """A coarse BEM run of the paper scene written to a file, and the result run returned (not changed by the tests:
    those that add to a file copy it)."""
    path = tmp_path_factory.mktemp("api") / "coarse.h5"
    return rollcontact.run(rollcontact.load_scene(overrides=COARSE), path)


def copy_of(result, tmp_path) -> RunResult:
    path = tmp_path / "copy.h5"
    shutil.copy(result.path, path)
    return rollcontact.read_run(path)


def test_every_command_has_its_api_function_and_calls_nothing_else():
    """Each command of the parser is in COMMANDS, its API function is exported by `rollcontact`, and the modules of
    cases/cli import nothing of rollcontact but the API (and cases.arguments, how messages name the options)."""
    sub = next(a for a in build_parser()._actions if a.__class__.__name__ == "_SubParsersAction")
    assert set(sub.choices) == set(COMMANDS), set(sub.choices) ^ set(COMMANDS)
    assert all(callable(getattr(rollcontact, f)) for f in [*COMMANDS.values(), "restart", "read_run"])
    allowed = {"rollcontact", "rollcontact.cases.api", "rollcontact.cases.arguments", "rollcontact.bem.errors"}
    for path in sorted((ROOT / "cases" / "cli").glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("rollcontact"):
                module = node.module if node.module != "rollcontact.cases" else f"rollcontact.cases.{node.names[0].name}"
                assert module in allowed or module.startswith("rollcontact.cases.cli"), (path.name, module)


def test_a_result_equals_its_file_read_back_and_prints_one_short_line(coarse):
    back = rollcontact.read_run(coarse.path)
    assert coarse == back and back == coarse and coarse.equals(back)
    again = rollcontact.run(rollcontact.load_scene(overrides=COARSE))        # the same scene, in memory only
    assert again != back and again.equals(back, times=False)                # only the clock differs
    changed = rollcontact.read_run(coarse.path)
    changed.history["U_x"] = changed.history["U_x"] + 1e-12
    assert changed != back
    text = repr(back)
    assert "\n" not in text and len(text) < 200 and "array" not in text
    assert text.startswith("RunResult(scene='paper_perpendicular', status='complete', state='undecided', steps=")


def test_every_name_a_result_holds_has_its_unit(coarse, tmp_path):
    """History, fields, summary of a BEM, an MDR and a steady [rolling] run, and the subsurface stresses."""
    mdr = rollcontact.run(rollcontact.load_scene(overrides={**COARSE, "solver.fidelity": "mdr"}))
    creep = rollcontact.run(rollcontact.load_scene(ROOT / "cases" / "creep_steady.toml",
                                                   {"grid.dx": 0.5, "solver.tol": 1e-6}))
    coarse = copy_of(coarse, tmp_path)
    rollcontact.stresses(coarse, depths=[0.0, 1.0])
    for result in (coarse, mdr, creep):
        names = {*result.history, *result.fields, *result.summary, *result.subsurface}
        assert names <= set(result.units) | set(result.summary_units), names - set(result.units)
        assert result.units["x"] == "mm"
    assert coarse.units["U_x"] == "mm" and coarse.units["p"] == "MPa" and coarse.units["von_mises"] == "MPa"
    assert coarse.units["z"] == "mm" and creep.summary_units["M_z"] == "N mm" and creep.units["phi"] == "1/mm"
    same = {k for k in UNITS if k in {**SUMMARY_UNITS, **CREEP_SUMMARY_UNITS}}
    differ = {k for k in same if UNITS[k] != {**SUMMARY_UNITS, **CREEP_SUMMARY_UNITS}[k]}
    assert differ == {"step"}          # the step number in /history, the rolling step (mm) in a transient's summary


def test_stresses_take_a_run_file_or_a_result_and_read_back_as_arrays_with_depths_and_units(coarse, tmp_path):
    memory = rollcontact.run(rollcontact.load_scene(overrides=COARSE))
    coarse = copy_of(coarse, tmp_path)
    held = rollcontact.stresses(memory, steps="all", depths=[0.0, 0.5, 2.0])        # computed in memory
    written = rollcontact.stresses(coarse.path, steps="all", depths=[0.0, 0.5, 2.0])   # added to the file
    back = rollcontact.read_run(coarse.path).subsurface
    assert back == written and held.steps == back.steps == [int(s) for s in coarse.field_steps]
    np.testing.assert_array_equal(back.z, [0.0, 0.5, 2.0])
    assert back["von_mises"].shape == (len(back.steps), 3, len(coarse.y), len(coarse.x))
    np.testing.assert_allclose(held["von_mises"], back["von_mises"], rtol=0, atol=1e-12 * back["von_mises"].max())
    assert back.units["von_mises"] == "MPa" and back.units["z"] == "mm" and memory.subsurface is held
    assert back.report().startswith(f"subsurface stresses of step(s) {back.steps[0]}, ")


def test_overrides_as_text_are_read_as_set_reads_them():
    """load_scene(overrides={"load.ft": "0.3"}) was refused (the text became a TOML string) where --set worked."""
    assert rollcontact.load_scene(overrides={"load.ft": "0.3", "solver.fidelity": "mdr"}).to_dict() == \
        rollcontact.load_scene(overrides=["load.ft=0.3", 'solver.fidelity="mdr"']).to_dict()
    assert rollcontact.load_scene(overrides={"motion.periods": "1e1"}).motion.periods == 10


def test_errors_name_the_api_arguments_in_python_and_the_options_in_a_command(coarse, tmp_path, capsys):
    scene = rollcontact.load_scene(overrides=COARSE)
    with pytest.raises(rollcontact.OutputExistsError) as info:
        rollcontact.run(scene, coarse.path)
    text = str(info.value)
    assert text.startswith(f"output {coarse.path}: ") and "pass overwrite=True" in text and "--" not in text
    assert "(scene 'paper_perpendicular'; the same scene as this run's)" in text
    with pytest.raises(rollcontact.SceneError, match=r"^overrides 'load\.Ft=5': the scene gives load\.ft = 0\.46"):
        rollcontact.load_scene(overrides={"load.Ft": 5})
    assert main(["run", "-q", "-o", str(coarse.path), *sum((["--set", f"{k}={v}"] for k, v in COARSE.items()), [])]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"rollcontact run: error: -o {coarse.path}: ") and "add --overwrite" in err


def test_the_python_api_example_of_the_docs_runs_twice_in_a_row(tmp_path, monkeypatch):
    """The block of docs/python_api.md (the README's example, with overwrite=True) as written, twice."""
    page = (ROOT / "docs" / "python_api.md").read_text()
    block = re.search(r"```python\n(.*?)```", page, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    for _ in range(2):
        namespace = {}
        exec(compile(block, "docs/python_api.md", "exec"), namespace)
    result = namespace["result"]
    expected = re.search(r"# shakedown ([0-9.]+)", block).group(1)
    assert result.state == "shakedown" and f"{result.summary['u_sd']:.5f}" == expected


def test_two_runs_started_together_without_o_take_the_default_name_and_the_next(tmp_path):
    """The second was refused (its lock was taken) where the README says it takes the -2 name."""
    cmd = [ROLLCONTACT, "run", "-q", "--set", 'solver.fidelity="mdr"', "--set", "motion.periods=2"]
    procs = [subprocess.Popen(cmd, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for _ in range(2)]
    outs = [p.communicate(timeout=300) for p in procs]
    assert [p.returncode for p in procs] == [0, 0], [o[1][-500:] for o in outs]
    stem = "paper_perpendicular__solver.fidelity=mdr__motion.periods=2"
    assert sorted(p.name for p in (tmp_path / "results").iterdir()) == [f"{stem}-2.h5", f"{stem}.h5"]


def test_a_plot_refused_for_its_step_writes_no_figure(coarse, tmp_path):
    """`plot --step 9999` wrote the history figure before refusing; figures of runs given as files or results."""
    with pytest.raises(rollcontact.InputError, match="fields of step 9999 were not stored"):
        rollcontact.plot(coarse.path, step=9999, output=tmp_path / "figs")
    assert not list((tmp_path / "figs").glob("*"))
    figures = rollcontact.compare(coarse, coarse.path, output=tmp_path / "figs")       # a RunResult and a file
    assert len(figures.paths) == 6 and all(Path(p).exists() for p in figures.paths)
    with pytest.raises(rollcontact.OutputExistsError, match="pass overwrite=True"):
        rollcontact.compare(coarse, coarse.path, output=tmp_path / "figs")


def test_limits_and_the_creep_curve_are_functions_too(tmp_path):
    limits = rollcontact.limits(w=0.23, ft=0.46)
    assert limits.values["f_t_lim"]["pure MDR"] == pytest.approx(1 - 1.5 * 0.23 + 0.5 * 0.23 ** 3)
    assert limits.values["state"]["perpendicular"] == "shakedown" and "u_lim = 1 - w^2" in limits.report()
    with pytest.raises(rollcontact.InputError, match="give w .* and/or ft"):
        rollcontact.limits()
    scene = ROOT / "cases" / "creep_steady.toml"
    with pytest.raises(rollcontact.InputError, match="mode = 'transient': a creep curve is of the steady state"):
        rollcontact.creep_curve(scene, overrides={"rolling.mode": "transient"}, output=tmp_path)
    with pytest.raises(rollcontact.InputError, match=r"^points 1: allowed range"):
        rollcontact.creep_curve(scene, points=1, output=tmp_path)
    assert not list(tmp_path.iterdir())


def test_a_restart_keeps_the_scene_name_and_stores_no_empty_override(coarse, tmp_path):
    """It renamed the stored scene to the file's stem and wrote restart_overrides = ['']."""
    step = int(coarse.field_steps[-3])
    out = rollcontact.restart(coarse.path, step=step, output=tmp_path / "again.h5")
    back = rollcontact.read_run(out.path)
    assert back.scene.name == "paper_perpendicular" and back.scene_toml == coarse.scene_toml
    assert back.attrs["restart_overrides"] == [] and back.attrs["restart_step"] == step
    assert out == back


def test_the_state_docstring_names_every_state():
    doc = RunResult.state.__doc__
    for state in ("static", "shakedown", "cyclic_slip", "ratcheting", "undecided", "gross_sliding", "incomplete",
                  "steady", "transient"):
        assert f"'{state}'" in doc, state

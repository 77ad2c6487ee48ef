"""The installed distribution: one import package, `rollcontact`, which works outside the repository.

The wheel is built from the repository (pip, isolated build), its top-level names are listed, and it is installed
into a fresh virtual environment whose dependencies come from this environment's site-packages (a .pth file), so
that nothing is downloaded; the CLI and `import rollcontact` then run from a temporary folder outside the
repository, where the repository's bem/, solver/ and cases/ folders cannot be imported by accident.
"""
import ast
from pathlib import Path
import site
import subprocess
import sys
import tomllib
import venv
import zipfile

import pytest

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())


def test_every_package_folder_is_listed_in_the_packaging():
    setup = PYPROJECT["tool"]["setuptools"]
    listed = set(setup["packages"])
    mapped = {v: k for k, v in setup["package-dir"].items()}
    found = set()
    for init in ROOT.glob("*/**/__init__.py"):
        rel = init.parent.relative_to(ROOT)
        top = mapped.get(rel.parts[0])
        if top is not None:
            found.add(".".join((top,) + rel.parts[1:]))
    assert found == listed, (found - listed, listed - found)


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "-w", str(out), str(ROOT)],
                   check=True, capture_output=True, timeout=600)
    (path,) = out.glob("rollcontact-*.whl")
    return path


@pytest.fixture(scope="module")
def installed(wheel, tmp_path_factory):
    """A fresh venv with the wheel installed; returns its bin folder."""
    env = tmp_path_factory.mktemp("venv")
    venv.create(env, with_pip=True)
    py = env / "bin" / "python"
    purelib = subprocess.run([str(py), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                             check=True, capture_output=True, text=True).stdout.strip()
    # the dependencies (numpy, numba, pyfftw, h5py, ...) from this environment, not the editable rollcontact: a path
    # added by a .pth file has its own .pth files (the editable finder among them) ignored
    Path(purelib, "deps.pth").write_text("\n".join(site.getsitepackages()) + "\n")
    subprocess.run([str(py), "-m", "pip", "install", "--no-deps", "--no-index", "--quiet", str(wheel)], check=True,
                   capture_output=True, timeout=300)
    return env / "bin"


def test_the_wheel_holds_only_the_rollcontact_package(wheel):
    names = {n.split("/")[0] for n in zipfile.ZipFile(wheel).namelist()}
    assert {n for n in names if not n.endswith(".dist-info")} == {"rollcontact"}
    members = zipfile.ZipFile(wheel).namelist()
    assert "rollcontact/cases/paper_perpendicular.toml" in members       # the embedded default scene
    assert "rollcontact/solver/tangential/_tangcg.py" in members


def test_the_installed_cli_and_api_work_outside_the_repository(installed, tmp_path):
    run = lambda *args: subprocess.run(args, cwd=tmp_path, capture_output=True, text=True, timeout=600)  # noqa: E731
    version = run(str(installed / "rollcontact"), "--version")
    assert version.returncode == 0 and version.stdout.strip() == f"rollcontact {PYPROJECT['project']['version']}"
    code = ("import rollcontact, sys\n"
            "assert 'bem' not in sys.modules and 'cases' not in sys.modules\n"
            "print(rollcontact.__file__)\n"
            "s = rollcontact.load_scene(overrides={'solver.fidelity': 'mdr', 'motion.periods': 2})\n"
            "r = rollcontact.run(s, 'mdr.h5')\n"
            "print(r.state, repr(float(rollcontact.read_run('mdr.h5').history['U_x'][-1])))\n")
    api = run(str(installed / "python"), "-c", code)
    assert api.returncode == 0, api.stderr[-2000:]
    where, result = api.stdout.strip().splitlines()
    assert Path(where).is_relative_to(installed.parent) and not Path(where).is_relative_to(ROOT)
    import rollcontact        # the same run in this (editable) environment: the same code gives the same numbers
    here = rollcontact.run(rollcontact.load_scene(overrides={"solver.fidelity": "mdr", "motion.periods": 2}))
    assert result.split() == [here.state, repr(float(here.history["U_x"][-1]))]
    for module in ("bem", "solver", "cases"):      # no generic top-level names in the environment
        missing = run(str(installed / "python"), "-c", f"import {module}")
        assert missing.returncode != 0 and "ModuleNotFoundError" in missing.stderr


def test_modules_import_the_package_by_its_full_name():
    """Inside bem/, solver/ and cases/, imports of the project name `rollcontact.` (relative imports would work in
    both installs too, but one spelling is checked and greppable)."""
    bad = []
    for layer in ("bem", "solver", "cases"):
        for path in (ROOT / layer).rglob("*.py"):
            for node in ast.walk(ast.parse(path.read_text())):
                if isinstance(node, ast.ImportFrom) and node.level:
                    bad.append(f"{path.relative_to(ROOT)}:{node.lineno}")
    assert not bad

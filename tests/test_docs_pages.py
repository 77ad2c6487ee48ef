"""Every study page under docs/ is reproduced by its script: docs/scripts/<page>.py --quick computes a few cells of
each of the page's tables with the page's own settings, into a temporary folder, and they must equal the page's
within the tolerance the page states (docs/scripts/_study.py compares them). Run as written without --quick, the
same script reproduces every table and figure of the page."""
import importlib.util
from pathlib import Path
import re
import sys

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = ROOT / "docs" / "scripts"
#: pages that describe the code rather than show results: generated from it, or its reference
REFERENCES = {"theory", "scene_reference", "hdf5_schema", "python_api"}
STUDIES = sorted(p.stem for p in SCRIPTS.glob("*.py") if not p.stem.startswith("_") and p.stem != "reference")


def _load(name):
    spec = importlib.util.spec_from_file_location(f"docs_script_{name}", SCRIPTS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module              # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


def test_every_page_names_a_command_and_every_script_has_its_page():
    """Every page under docs/ but the references names a command that regenerates what it shows (a
    `.venv/bin/...` command); a page with a script in docs/scripts/ names that script and marks its tables for the
    comparison."""
    pages = {p.stem for p in (ROOT / "docs").glob("*.md")} - REFERENCES
    assert set(STUDIES) <= pages
    for name in sorted(pages):
        text = (ROOT / "docs" / f"{name}.md").read_text()
        assert re.search(r"\.venv/bin/(python|rollcontact) ", text), f"docs/{name}.md names no command"
    for name in STUDIES:
        text = (ROOT / "docs" / f"{name}.md").read_text()
        assert f".venv/bin/python docs/scripts/{name}.py" in text, name
        assert re.search(r"<!-- table \w+", text), f"docs/{name}.md has no table marked for the comparison"


@pytest.mark.parametrize("name", STUDIES)
def test_the_quick_run_of_the_page_script_reproduces_the_page(name, tmp_path, capsys):
    study = _load(name)
    code = study.main(["--quick", "-o", str(tmp_path / name)])
    out = capsys.readouterr().out
    assert code == 0, out[-3000:]
    assert "numbers compared" in out and " 0 numbers compared" not in out, out[-1000:]
    assert (tmp_path / name / "tables.md").exists()


def test_the_comparison_finds_a_changed_number_and_a_changed_state(tmp_path):
    """The comparison itself: a number outside the page's tolerance, or another state, is reported."""
    study = _load("_study")
    page = ("<!-- table t: tolerance 0.001 -->\n| a | b |\n|---|---|\n| 0.5000 | shakedown |\n<!-- end table -->\n")
    ok = study.render({"t": (["a", "b"], [["0.5005", "shakedown"]])})
    assert study.compare(page, ok).ok
    assert not study.compare(page, study.render({"t": (["a", "b"], [["0.5020", "shakedown"]])})).ok
    assert not study.compare(page, study.render({"t": (["a", "b"], [["0.5000", "ratcheting"]])})).ok
    assert study.compare(page, study.render({"t": (["a", "b"], [[study.SKIPPED, study.SKIPPED]])})).ok

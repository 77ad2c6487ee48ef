"""docs/scene_reference.md and docs/hdf5_schema.md are what docs/scripts/reference.py generates from the code now:
a scene key, a dataset or a unit added or changed without regenerating them (`.venv/bin/python docs/scripts/reference.py
-o docs`) fails here."""
import importlib.util
from dataclasses import fields
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("reference", ROOT / "docs" / "scripts" / "reference.py")
reference = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(reference)


@pytest.mark.parametrize("name", reference.PAGES)
def test_the_generated_reference_page_is_current(name):
    assert (ROOT / "docs" / name).read_text() == reference.pages()[name], \
        f"docs/{name} is stale: run {reference.COMMAND}"


def test_every_scene_key_has_a_meaning_and_every_dataset_a_unit():
    from rollcontact.cases.results import schema
    from rollcontact.cases.scene.keys import SECTIONS
    undocumented = [f"{sec}.{f.name}" for sec, cls in SECTIONS.items() for f in fields(cls) if not f.metadata.get("doc")]
    assert not undocumented
    page = (ROOT / "docs" / "hdf5_schema.md").read_text()
    for path, kind, rows in schema.groups():
        for name, unit, _ in rows:
            assert unit and f"| `{name}` | {unit} |" in page, (path, name)

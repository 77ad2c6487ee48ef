"""The regression data (tests/reference_data.py, tests/data/reference_data.json): every entry says what it is and
which scene it comes from, has a derivation that regenerates it, and the regeneration command writes only where
it is told to."""
import json

import pytest

import reference_data as R


def test_every_entry_is_described_and_has_its_derivation():
    data = R.load()
    assert set(data) == set(R.DERIVATIONS)
    for name, entry in data.items():
        assert entry["what"] and entry["scene"] and entry["values"], name


def test_the_regeneration_refuses_an_existing_file_and_unknown_entries(tmp_path, capsys):
    out = tmp_path / "reference_data.json"
    out.write_text(json.dumps({}))
    assert R.main(["-o", str(tmp_path)]) == 2
    assert "--overwrite" in capsys.readouterr().err and out.read_text() == "{}"
    with pytest.raises(SystemExit):
        R.main(["no_such_entry", "-o", str(tmp_path / "new")])
    assert not (tmp_path / "new").exists()

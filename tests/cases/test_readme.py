"""The README's commands run as written in a fresh clone after its set-up command (no activated venv)."""
from pathlib import Path
import re
import tomllib

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text()


def test_every_command_calls_the_console_script_inside_the_venv():
    lines = [ln.strip() for ln in README.splitlines() if ln.startswith("    ")]
    calls = [ln for ln in lines if re.search(r"(^|\s|/)rollcontact\s", ln)]
    assert calls
    for ln in calls:
        assert ln.startswith((".venv/bin/rollcontact ", "python3 -m venv .venv && ")), ln
    setup = [ln for ln in lines if ln.startswith("python3 -m venv .venv")]
    assert len(setup) == 2                                     # the two set-up commands at the top
    prose = "\n".join(ln for ln in README.splitlines() if not ln.startswith("    "))
    spans = re.findall(r"`([^`]*)`", prose)
    inline = [c for c in spans if re.search(r"rollcontact (run|plot|sweep|compare|limits|limit-search|COMMAND)", c)]
    assert inline
    assert all(c.startswith(".venv/bin/rollcontact") for c in inline), inline


def test_no_link_outside_the_repository_and_every_extra_mentioned_is_defined():
    assert "../" not in README
    extras = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"])
    mentioned = set(re.findall(r"`(\w+)` extra", README)) | set(re.findall(r"\.\[(\w+)\]", README))
    assert mentioned and mentioned <= extras, mentioned - extras

"""Every citation of the project's technical reference resolves, and nothing points outside the repository.

A citation is `docs/theory.md §N`, `§N.M` (continued as `§N.M, §K`, `§N.M-N.K`) or a pitfall `Pn`; each must name an
anchor of docs/theory.md (`<a id="s5.4">`, `<a id="P10">`). A section sign that is not headed by `docs/theory.md`
must belong to another named source (the seed paper, Johnson 1985, Kalker 1990, CONTACT's user guide, ...); a
pitfall number `Pn` is always headed by `docs/theory.md`. Background notes outside the repository (a folder beside it,
"theory notes") are never cited.
"""
import os
from pathlib import Path
import re

ROOT = Path(__file__).resolve().parents[1]
THEORY = ROOT / "docs" / "theory.md"
SKIP_DIRS = {".git", ".venv", "results", "build", "__pycache__", ".pytest_cache", ".ruff_cache"}
SUFFIXES = {".py", ".md", ".toml", ".sh", ".txt", ".cfg", ".ini", ".yml", ".yaml"}

#: one reference: a section (with an optional item letter, "§2.2a") or a range of sections
_SEC = r"§\s?\d+(?:\.\d+)?[a-z]?(?:\s?[-–]\s?(?:§\s?)?\d+(?:\.\d+)?)?"
_PIT = r"\bP\d{1,2}\b(?:\s?[-–]\s?P?\d{1,2})?"
#: a group of references separated by commas, slashes or "and"
GROUP = re.compile(rf"(?:{_SEC}|{_PIT})(?:(?:\s*[,/]\s*#?\s*|\s+(?:and|or)\s+)(?:{_SEC}|{_PIT}))*")
#: sources whose own sections a section sign may cite (the words just before the group): a named work, an
#: author-year citation ("Saad 2003, Iterative Methods ..., §9.3"), or another page of the repository ("docs/user_guide.md, §3")
OTHER_SOURCES = re.compile(r"((seed|Johnson|Kalker|CONTACT|user guide|Popov|Hamilton|Love|Mindlin|Sect|paper|"
                           r"Carslaw|Jaeger|Vollebregt|Hunter|Iwnicki|Polach|section|chapter|ch\.)(?:'s)?\W{0,3}"
                           r"(\d{4}\W{0,3})?|[A-Z][a-z]+\S* (et al\. )?(\d{4}|\(\d{4}\))[^()§]*|\.md\W{0,3})$", re.I)


def repository_files():
    """The text files of the repository (not the virtual environment, the outputs of runs, caches)."""
    for folder, dirs, files in os.walk(ROOT):
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.endswith(".egg-info")]
        for name in files:
            if Path(name).suffix in SUFFIXES:
                yield Path(folder) / name


def anchors() -> set:
    return set(re.findall(r'<a id="([^"]+)"></a>', THEORY.read_text()))


def own_sections(path: Path) -> set:
    """The numbered sections of a Markdown page ('## 4. Contact search' -> '4'): a bare § there cites the page."""
    if path.suffix != ".md":
        return set()
    return set(re.findall(r"^#+ (\d+(?:\.\d+)?)\.? ", path.read_text(errors="replace"), re.M))


def references(text: str):
    """(kind, number, head) for each reference in text: kind '§' or 'P', head the 100 characters before its group."""
    for m in GROUP.finditer(text):
        head = text[max(0, m.start() - 100):m.start()]
        for sec in re.finditer(r"§\s?(\d+(?:\.\d+)?)[a-z]?(?:\s?[-–]\s?(?:§\s?)?(\d+(?:\.\d+)?))?", m.group()):
            yield "§", sec.group(1), head
            if sec.group(2):
                yield "§", sec.group(2), head
        for pit in re.finditer(r"P(\d{1,2})(?:\s?[-–]\s?P?(\d{1,2}))?", m.group()):
            yield "P", pit.group(1), head
            if pit.group(2):
                yield "P", pit.group(2), head


def cites_theory(head: str) -> bool:
    return bool(re.search(r"docs/theory\.md[\s#]*[,;:(]?\s*$", head))


def test_the_theory_page_has_an_anchor_for_every_section_and_pitfall():
    ids = anchors()
    assert {f"s{n}" for n in range(13)} <= ids
    assert {f"P{n}" for n in range(1, 15)} <= ids
    assert {"s12.1", "s12.2", "s12.3", "s12.4", "s12.5"} <= ids


def test_every_citation_of_the_theory_page_resolves_to_an_anchor():
    ids, problems, count = anchors(), [], 0
    for path in repository_files():
        if path == THEORY or path == Path(__file__).resolve():
            continue
        text = path.read_text(errors="replace")
        own = own_sections(path)
        for kind, number, head in references(text):
            theory = cites_theory(head)
            if kind == "§":
                if not theory:
                    if own and number.split(".")[0] in own:
                        continue          # the page's own numbered section
                    if not OTHER_SOURCES.search(head):
                        problems.append(f"{path.relative_to(ROOT)}: §{number} after {head[-30:]!r}: cite it as "
                                        f"'docs/theory.md §{number}' (or name the source it belongs to)")
                    continue
                anchor = f"s{number}"
            else:
                if not theory and not ("pitfall" in head.lower() or 1 <= int(number) <= 14):
                    continue          # a name such as P0 in a formula, not a pitfall
                if not theory:
                    problems.append(f"{path.relative_to(ROOT)}: pitfall P{number} after {head[-30:]!r}: cite it "
                                    f"as 'docs/theory.md P{number}'")
                    continue
                anchor = f"P{number}"
            count += 1
            if anchor not in ids:
                problems.append(f"{path.relative_to(ROOT)}: {kind}{number} has no anchor '{anchor}' in docs/theory.md")
    assert not problems, "\n".join(problems)
    assert count > 100                      # the citations are found at all


def test_nothing_refers_to_files_outside_the_repository():
    problems = []
    for path in repository_files():
        if path == Path(__file__).resolve():
            continue
        for n, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            if re.search(r"\.\./shared|/work/|theory notes|(?<!docs/)(?<!\()theory\.md", line):
                problems.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()[:120]}")
            elif re.search(r"\btheory\s?§", line):
                problems.append(f"{path.relative_to(ROOT)}:{n}: 'theory §' is not a path: {line.strip()[:120]}")
    assert not problems, "\n".join(problems)

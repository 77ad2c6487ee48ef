"""A whole CONTACT deck read case by case: the module numbers, the cases of each module until its R digit returns
(R = 1, 3; R = 0, 2 stay in the module), module 0 at the end. Each result element (the optional REID, CPID after the
module number; 0 and 1 when left out) keeps its own state, so a case inherits from the earlier cases of its own
element; the case numbers count as the reference program's 'Case N' (one count for all cases of result element 0).
"""
from __future__ import annotations

from dataclasses import dataclass, field
import gzip
from pathlib import Path

from rollcontact.cases.decks import module1, module3
from rollcontact.cases.decks.case import Case, ElementState
from rollcontact.cases.decks.reader import DeckError, DeckText

READERS = {1: module1.read_case, 3: module3.read_case}


@dataclass
class Deck:
    """The cases of a deck (in the order of the file), the deck's name and folder, and notes on the deck as a
    whole (a missing module 0)."""
    name: str
    folder: Path | None
    cases: list[Case] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)


def read_deck(path) -> Deck:
    """Read the deck file `path` (`<experim>.inp`, or gzipped `<experim>.inp.gz`); DeckError for a deck the
    reference program would refuse or that cannot be read (missing file included), naming the line and the field."""
    path = Path(path)
    try:
        if path.suffix == ".gz":
            with gzip.open(path, "rt", encoding="latin-1") as f:
                text = f.read()
        else:
            text = path.read_text(encoding="latin-1")
    except (OSError, EOFError) as exc:
        raise DeckError(path.name, None, "deck file", f"cannot be read ({getattr(exc, 'strerror', None) or exc})") \
            from None
    name = path.name.removesuffix(".gz").removesuffix(".inp")
    return parse_deck(text, name=name, folder=path.parent, label=path.name)


def parse_deck(text: str, name: str = "deck", folder=None, label: str | None = None) -> Deck:
    """The deck in `text`; `folder` is where its profile files are looked for, `label` names it in errors."""
    lines = DeckText(text, label or f"{name}.inp")
    deck = Deck(name=name, folder=Path(folder) if folder is not None else None)
    states: dict[tuple, ElementState] = {}
    counters: dict[tuple, int] = {}
    while True:
        if lines.at_end:
            deck.notes.append("the deck ends without module 0 (the reference program stops with an error there, "
                              "after computing every case)")
            break
        got = lines.read("module number", "MODULE:i REID:I CPID:I")
        module = got["MODULE"]
        if module.value == 0:
            break
        if module.value not in READERS:
            raise lines.error(module.line, "module number", f"{module.value} is not a module: allowed are 1 "
                                                            "(wheel on rail), 3 (basic contact) and 0 (end of deck)")
        reid = got["REID"].value if "REID" in got else 0
        cpid = got["CPID"].value if "CPID" in got and module.value == 3 else 1
        for key, value in (("REID", reid), ("CPID", cpid)):
            if key in got and not 1 <= value <= 9999:
                raise lines.error(got[key].line, key, f"{value}: allowed 1-9999")
        element = (module.value, reid, cpid)
        state = states.setdefault(element, ElementState())
        count_key = (0,) if reid == 0 else element
        while True:
            counters[count_key] = counters.get(count_key, 0) + 1
            state.cases += 1
            start = lines.lines[lines.pos][0] if not lines.at_end else lines.last_line
            case = Case(number=counters[count_key], module=module.value, line=start, element=(reid, cpid))
            _read_safely(lines, case, state)
            case.values, case.effective = dict(state.values), dict(state.effective)
            deck.cases.append(case)
            if case.digits["R"] in (1, 3):
                break
    return deck


def _read_safely(lines: DeckText, case: Case, state: ElementState):
    """Read one case; a value the reader did not foresee becomes a DeckError at the line reached (never a
    traceback)."""
    try:
        READERS[case.module](lines, case, state)
    except DeckError:
        raise
    except (KeyError, IndexError, ValueError, ZeroDivisionError, TypeError, OverflowError) as exc:
        raise lines.error(lines.last_line, f"case {case.number}", f"this input cannot be read ({type(exc).__name__}"
                                                                  f": {exc})") from None

"""One case of a deck and the state a result element carries from case to case (what a case inherits).

A case reads some values and keeps the others from the earlier cases of its result element: the friction law when
L = 1, the materials and the rolling step when C = 0 or 1, the grid when D = 0, the undeformed distance when Z = 0,
the solver settings when G = 1, the subsurface points when S = 1, and in module 1 the track when Z = 0 and the
wheelset when E = 0 (the reference program's user guide, "The control integers"). `Case.values` holds the effective
input of the case, read or inherited, each value with the line it was read on.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from rollcontact.cases.decks.reader import Item


@dataclass
class Case:
    """A case of the deck: its number (the reference program's 'Case N'), module, result element (REid, CPid),
    control digits as read (after the program's own overrules, noted in `notes`), the line of each digit, the values
    read in this case, the effective values (read or inherited) and the effective digits of the inherited parts
    (`effective`: L, C, M2 of the last case that set them), its subsurface blocks and notes."""
    number: int
    module: int
    line: int
    element: tuple[int, int]
    digits: dict[str, int] = field(default_factory=dict)
    digit_lines: dict[str, int] = field(default_factory=dict)
    read: dict[str, Item] = field(default_factory=dict)
    values: dict[str, Item] = field(default_factory=dict)
    effective: dict[str, int] = field(default_factory=dict)
    subsurface: list = field(default_factory=list)
    subsurface_digits: tuple[int, int] | None = None
    notes: list[str] = field(default_factory=list)

    @property
    def skipped(self) -> bool:
        """R = 2 or 3: the reference program only prepares this case and computes nothing."""
        return self.digits.get("R", 1) >= 2

    def value(self, name: str, default=None):
        item = self.values.get(name)
        return default if item is None else item.value

    def line_of(self, name: str) -> int | None:
        item = self.values.get(name) or self.read.get(name)
        return None if item is None else item.line


@dataclass
class ElementState:
    """What one result element keeps between its cases: values, the effective L, C and M2 digits, the T digit of the
    last case, the subsurface blocks, and how many cases it has seen."""
    values: dict[str, Item] = field(default_factory=dict)
    effective: dict[str, int] = field(default_factory=dict)
    last_tang: int | None = None
    subsurface: list = field(default_factory=list)
    subsurface_digits: tuple[int, int] | None = None
    cases: int = 0

    def keep(self, case: Case, read: dict[str, Item]):
        """Record the values a case read as the element's current ones."""
        case.read.update(read)
        self.values.update(read)

    def drop(self, *names: str):
        for name in names:
            self.values.pop(name, None)

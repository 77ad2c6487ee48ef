"""The figures of a reference output (`<experim>.out`, the published examples' `*.ref_out`): per case the printed
tables of totals (FN, FX, FY, MZ, approach, PMAX, ...), the kinematic constants (creepages or shifts), the grid,
the contact statistics (elements in contact, adhesion, slip) and, where the output has it (O = 5), the traction in
each element; in module 1 the totals on the rail and the tables of each contact patch.

A table is a line of column labels followed by a line of as many numbers; it is filed under the section title above
it (the last line of capitals without numbers, e.g. 'TOTAL FORCES, TORSIONAL MOMENT, ...'). Units as printed:
mm, N, N/mm^2, rad; forces in CONTACT's convention (on body 1, the upper body; module 1: on the rail).
"""
from __future__ import annotations

from dataclasses import dataclass, field
import gzip
import math
from pathlib import Path
import re

_CASE = re.compile(r"^\s*Case\s+(\d+)")
_PATCH = re.compile(r"-----\s*DATA FOR CONTACT PATCH\s+(\d+)")
_ROW = re.compile(r"^\s*Y\s*=\s*(\S+)\s+ROW\s+\d+\s+OF THE POTENTIAL CONTACT")
_JOIN = re.compile(r"\b(SHIFT|CREEP) ([XY])\b")
_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?$")


@dataclass
class CaseOutput:
    """The figures of one case: `tables` {section: {label: value}} of the case (module 1: the totals), `patches`
    one such dict per contact patch (module 1), `traction` the element table when printed ({'x', 'y', 'pn',
    'abs_pt', 'arg_pt'}: lists, mm, N/mm^2, degrees)."""
    number: int
    tables: dict = field(default_factory=dict)
    patches: list = field(default_factory=list)
    traction: dict | None = None

    def find(self, label: str, section: str | None = None, patch: int | None = None) -> float | None:
        """The value under `label` (in the first section whose title contains `section`), or None."""
        source = self.patches[patch] if patch is not None else self.tables
        for title, table in source.items():
            if (section is None or section in title) and label in table:
                return table[label]
        return None


def _numbers(words):
    try:
        return [float(w.replace("D", "E").replace("d", "e")) for w in words]
    except ValueError:
        return None


def read_refout(path) -> dict[int, CaseOutput]:
    """{case number: CaseOutput} of a reference output (plain or .gz)."""
    path = Path(path)
    opener = gzip.open if path.suffix == ".gz" else open
    with opener(path, "rt", encoding="latin-1") as f:
        return parse_refout(f.read())


def parse_refout(text: str) -> dict[int, CaseOutput]:
    """{case number: CaseOutput} of the text of a reference output."""
    cases: dict[int, CaseOutput] = {}
    case = target = labels = row_y = None
    title = ""
    for line in text.splitlines():
        words = line.split()
        if not words:
            continue
        m = _CASE.match(line)
        if m:
            case = cases.setdefault(int(m.group(1)), CaseOutput(int(m.group(1))))
            target, title, labels, row_y = case.tables, "", None, None
            continue
        if case is None:
            continue
        m = _PATCH.search(line)
        if m:
            case.patches.append({})
            target, title, labels, row_y = case.patches[-1], "", None, None
            continue
        m = _ROW.match(line)
        if m:
            row_y = _numbers([m.group(1)])[0]
            if case.traction is None:
                case.traction = {"x": [], "y": [], "pn": [], "abs_pt": [], "arg_pt": []}
            continue
        values = _numbers(words)
        if values is not None:
            if labels is not None and len(values) == len(labels):
                target.setdefault(title, {}).update(zip(labels, values))
            elif row_y is not None and len(values) >= 7:
                tr = case.traction
                for key, v in zip(("x", "pn", "abs_pt", "arg_pt"), (values[0], values[2], values[4], values[5])):
                    tr[key].append(v)
                tr["y"].append(row_y)
            labels = None
            continue
        row_y = None
        if ":" in line and _keyed(line, target):
            labels = None
            continue
        if labels is not None:
            title = " ".join(labels)      # the line before was a title, not the labels of a table
        labels = _JOIN.sub(r"\1_\2", line).split()
    return cases


def _keyed(line: str, target: dict) -> bool:
    """A line 'SOME TEXT A,B: 1.0 2.0' files its numbers under the last labels before the colon (table 'KEYS')."""
    head, _, tail = line.rpartition(":")
    values = _numbers(tail.split())
    if not values:
        return False
    names = [w for w in head.replace(",", " ").split() if w not in ("ARE",)]
    if len(names) >= len(values):
        target.setdefault("KEYS", {}).update(zip(names[len(names) - len(values):], values))
    return True


def contact_area(case: CaseOutput, dx: float, dy: float, patch: int | None = None) -> float | None:
    """NCON dx dy (mm^2): the elements in contact times the element area."""
    n = case.find("NCON", patch=patch)
    return None if n is None or not (math.isfinite(dx) and math.isfinite(dy)) else n * dx * dy

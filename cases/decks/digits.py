"""The control digits of a CONTACT case: the three control words unpacked digit by digit, their names and the values
the reference program allows (its user guide, "The control integers"; modules 1 and 3).

A control word is an integer whose digits are read from the right (`022020` is L=0 D=2 C=2 M=0 Z=2 E=0, its leading
V=0 left out); a word with more digits than it has letters puts the excess into its first digit, which is then out of
range. `unpack` returns {letter: digit}; `check` raises DeckError naming the word's line, the digit, its value and
the allowed values.
"""
from __future__ import annotations

from rollcontact.cases.decks.reader import DeckError

#: the control words of each module, letters from the left
WORDS = {1: ("CPBTNFS", "VLDCMZE", "XHGIAOWR"), 3: ("PBTNFS", "VLDCMZE", "XHGIAOWR")}

#: the digits' names as the reference program prints them (module 3; module 1 where it differs)
NAMES = {"C1": "CONFIG", "P": "PVTIME", "B": "BOUND", "T": "TANG", "N": "NORM", "F": "FORCE", "S": "STRESS",
         "V": "VARFRC", "L": "FRCLAW", "D": "DISCNS", "C": "INFLCF", "M": "MATER", "Z": "RZNORM", "E": "EXRHS",
         "M2": "MATER2", "X": "XFLOW", "H": "HEAT", "G": "GAUSEI", "I": "IESTIM", "A": "MATFIL", "O": "OUTPUT",
         "W": "FLOW", "R": "RETURN"}
NAMES_MODULE1 = {**NAMES, "Z": "ZTRACK", "E": "EWHEEL"}

_COMMON = {"P": range(0, 4), "T": range(0, 4), "S": range(0, 4), "L": (0, 1, 2, 3, 4, 6), "M": range(0, 8),
           "M2": range(0, 3), "X": range(0, 2), "H": (0, 1, 3), "G": range(0, 6), "I": range(0, 4),
           "A": range(0, 3), "O": range(0, 6), "W": range(0, 10), "R": range(0, 4)}
ALLOWED = {
    3: {**_COMMON, "B": range(0, 7), "N": range(0, 2), "F": range(0, 3), "V": (0, 3), "D": range(0, 3),
        "C": (0, 1, 2, 3, 4, 9), "Z": range(0, 3), "E": (0, 1, 2, 3, 9)},
    1: {**_COMMON, "C1": (0, 1, 4, 5), "B": (0, 1, 5, 6), "N": range(0, 2), "F": (0, 1, 3), "V": range(0, 3),
        "D": range(0, 10), "C": range(0, 5), "Z": range(0, 4), "E": range(0, 6)},
}


def letters(word: str) -> list[str]:
    """The digit names of a control word, 'CPBTNFS' -> ['C1', 'P', 'B', ...] (module 1's C is C1, CONFIG)."""
    return ["C1" if (i == 0 and word.startswith("CP")) else ch for i, ch in enumerate(word)]


def unpack(word: str, value: int) -> dict[str, int]:
    """{digit: value} of one control word; the first digit takes whatever is left (possibly out of range)."""
    names = letters(word)
    out = {}
    for name in reversed(names[1:]):
        value, out[name] = divmod(value, 10)
    out[names[0]] = value
    return {name: out[name] for name in names}


def describe(value) -> str:
    values = list(value)
    if values == list(range(values[0], values[-1] + 1)):
        return f"{values[0]}-{values[-1]}"
    return ", ".join(str(v) for v in values)


def check(deck: str, module: int, digits: dict[str, int], lines: dict[str, int], words: dict[str, int]):
    """DeckError for the first digit out of its allowed values (lines: digit -> line; words: digit -> its word)."""
    names = NAMES_MODULE1 if module == 1 else NAMES
    for digit, value in digits.items():
        allowed = ALLOWED[module].get(digit)
        if allowed is not None and value not in allowed:
            word = f"; control word {words[digit]}" if digit in words else ""
            raise DeckError(deck, lines[digit], f"control digit {digit} ({names[digit]})",
                            f"{value} is not allowed in module {module}: allowed values are {describe(allowed)}"
                            f"{word}")

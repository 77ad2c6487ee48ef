"""The words of a CONTACT input deck and the reading of one group of values, with the line of every value.

The rules are those of the reference program's input file (its user guide, "Specification of the input file"):
'%' starts a comment (outside a quoted string) up to the end of the line; blank and comment-only lines are
skipped; values are separated by blanks, tabs, commas or '='; a group of values may run over several lines, its
optional values (written in upper case in a spec below) only on the line of its last mandatory value; the rest of
the line after a group is ignored (free text such as `FN, CKSI, CETA, CPHI`). Integers are plain (`3`, `-1`,
`0022033`), reals any Fortran form (`0.35`, `3.5E-1`, `1d-4`, `200.`), angles reals with an optional `d`
(degrees) or `r` (radians, the default) suffix, returned in radians, strings single-quoted.

Every error is a `DeckError` naming the deck, the line and the field (`cattaneo.inp, line 27: FSTAT: 'x' is not a
real number (friction)`), or the end of the file and the field that was expected there.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
import math
import re

from rollcontact.bem.errors import InputError

_INTEGER = re.compile(r"[+-]?\d+$")
_REAL = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?$")
_KINDS = {"i": "an integer", "d": "a real number", "a": "an angle (real, optional suffix d or r)",
          "s": "a quoted string ('...')"}


class DeckError(InputError):
    """A deck that cannot be read: the message names the deck, the line (or the end of the file) and the field."""

    def __init__(self, deck: str, line: int | None, field: str, message: str, after: int | None = None):
        self.deck, self.line, self.field = deck, line, field
        where = f"line {line}" if line else "end of file" + (f" (after line {after})" if after else "")
        super().__init__(f"{deck}, {where}: {field}: {message}")


@dataclass(frozen=True)
class Item:
    """One value read from the deck and the line it stands on (1-based)."""
    value: object
    line: int


@lru_cache(maxsize=None)
def parse_spec(spec: str) -> tuple[tuple[str, str, bool], ...]:
    """'MAXGS:i EPS:d NPOT_MAX:I' -> ((name, kind, optional), ...); an upper-case kind is optional."""
    out = []
    for word in spec.split():
        name, kind = word.rsplit(":", 1)
        out.append((name, kind.lower(), kind.isupper()))
    return tuple(out)


def split_words(text: str) -> list[str]:
    """The words of one line: the comment cut off, separators blanks, tabs, commas and '=', quoted strings whole."""
    words, word, quoted = [], [], False
    for ch in text:
        if ch == "'":
            quoted = not quoted
            word.append(ch)
        elif quoted:
            word.append(ch)
        elif ch == "%":
            break
        elif ch in " \t,=\r\n":
            if word:
                words.append("".join(word))
                word = []
        else:
            word.append(ch)
    if word:
        words.append("".join(word))
    return words


def parse_word(word: str, kind: str):
    """The value of one word of kind 'i', 'd', 'a' or 's'; ValueError when it is not one."""
    if kind == "i":
        if _INTEGER.match(word):
            return int(word)
    elif kind in ("d", "a"):
        scale = 1.0
        if kind == "a" and word[-1:].lower() in ("d", "r"):
            scale = math.pi / 180.0 if word[-1:].lower() == "d" else 1.0
            word = word[:-1]
        if _REAL.match(word):
            value = float(word.replace("d", "e").replace("D", "e")) * scale
            if math.isfinite(value):
                return value
    elif kind == "s":
        if len(word) >= 2 and word[0] == word[-1] == "'":
            return word[1:-1]
    raise ValueError(word)


class DeckText:
    """The non-empty lines of a deck as (line number, words), read front to back by `read` and `read_array`."""

    def __init__(self, text: str, name: str = "deck"):
        self.name = name
        self.lines = []
        for number, raw in enumerate(text.splitlines(), start=1):
            if raw.split("%", 1)[0].strip():
                self.lines.append((number, split_words(raw)))
        self.pos = 0

    @property
    def at_end(self) -> bool:
        return self.pos >= len(self.lines)

    @property
    def last_line(self) -> int:
        """The number of the last line read (0 before the first)."""
        return self.lines[self.pos - 1][0] if self.pos else 0

    def _next(self, field: str, group: str):
        if self.at_end:
            raise DeckError(self.name, None, field, f"missing: the deck is truncated (expected here: {group})",
                            after=self.last_line)
        line = self.lines[self.pos]
        self.pos += 1
        return line

    def error(self, line: int | None, field: str, message: str) -> DeckError:
        return DeckError(self.name, line, field, message)

    def read(self, group: str, spec: str) -> dict[str, Item]:
        """One group of values as {name: Item}: the mandatory ones, over as many lines as they need, then the
        optional ones present on the line of the last mandatory value (an unreadable optional word ends the group:
        it is the free text after it)."""
        fields = parse_spec(spec)
        n_req = sum(1 for _, _, optional in fields if not optional)
        values: dict[str, Item] = {}
        while len(values) < n_req:
            number, words = self._next(fields[len(values)][0], group)
            for word in words:
                if len(values) >= len(fields):
                    break
                name, kind, _ = fields[len(values)]
                try:
                    values[name] = Item(parse_word(word, kind), number)
                except ValueError:
                    if len(values) >= n_req:
                        break
                    raise self.error(number, name, f"{word!r} is not {_KINDS[kind]} ({group}: "
                                                   f"{' '.join(f[0] for f in fields)})") from None
        return values

    def read_array(self, group: str, name: str, kind: str, n: int) -> Item:
        """`n` values of one kind over as many lines as they need (the words after the n-th on its line are
        ignored) as one Item holding the list, at the line of the first."""
        out, first = [], None
        while len(out) < n:
            number, words = self._next(f"{name}({len(out) + 1})", group)
            first = first or number
            for word in words[: n - len(out)]:
                try:
                    out.append(parse_word(word, kind))
                except ValueError:
                    raise self.error(number, f"{name}({len(out) + 1})",
                                     f"{word!r} is not {_KINDS[kind]} ({group}, {n} values)") from None
        return Item(out, first)

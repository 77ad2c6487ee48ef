"""A scene being built from one or more cases: its sections and keys (each with the deck value it came from), what
could not be posed (name, value, what rollcontact would need), the notes on differences of discretisation, and the
options of the run (subsurface depths). The mapping functions (cases.decks.mapping, cases.decks.wheelrail_map)
fill it; `Draft.toml` writes it as a scene file with the origin of every key beside it.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import math


@dataclass(frozen=True)
class Unsupported:
    """A control digit or input value that rollcontact cannot pose: its name, value, line and what it would need."""
    name: str
    value: object
    needs: str
    line: int | None = None

    def text(self) -> str:
        where = f" (line {self.line})" if self.line else ""
        if self.value is None:
            return f"{self.name}{where}: {self.needs}"
        return f"{self.name} = {show(self.value)}{where}: {self.needs}"


def show(value) -> str:
    """A value as the report writes it (6 digits, a long list cut after 6 items)."""
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(show(v) for v in value[:6]) + (", ..." if len(value) > 6 else "") + "]"
    return str(value)


@dataclass
class Draft:
    """Scene sections {section: {key: value}}, the origin of each key, the refusals, notes and run options."""
    sections: dict = field(default_factory=dict)
    origins: dict = field(default_factory=dict)
    unsupported: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    ignored: list = field(default_factory=list)
    run_options: dict = field(default_factory=dict)
    files: dict = field(default_factory=dict)

    def set(self, section: str, key: str, value, origin: str = ""):
        self.sections.setdefault(section, {})[key] = value
        if origin:
            self.origins[(section, key)] = origin

    def get(self, section: str, key: str, default=None):
        return self.sections.get(section, {}).get(key, default)

    def refuse(self, name: str, value, needs: str, line: int | None = None):
        item = Unsupported(name, value, needs, line)
        if item not in self.unsupported:
            self.unsupported.append(item)

    def note(self, text: str):
        if text not in self.notes:
            self.notes.append(text)

    def ignore(self, text: str):
        if text not in self.ignored:
            self.ignored.append(text)

    @property
    def ok(self) -> bool:
        return not self.unsupported

    def toml(self, title: list[str]) -> str:
        """The scene as TOML: `title` as comment lines, then the sections with each key's origin as a comment."""
        lines = [f"# {t}" if t else "#" for t in title]
        for section, keys in self.sections.items():
            lines.append(f"\n[{section}]")
            for key, value in keys.items():
                origin = self.origins.get((section, key))
                text = f"{key} = {toml_value(value)}"
                lines.append(f"{text:<36} # {origin}" if origin else text)
        return "\n".join(lines) + "\n"


def toml_value(v) -> str:
    """A TOML literal of a number, string, bool or list (floats written to round-trip)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    raise TypeError(f"no TOML literal for {v!r}")

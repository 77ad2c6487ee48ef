"""Overrides of a scene's keys (`--set section.key=value`, `load_scene(overrides=...)`, a sweep's varied values):
how their values are read, and which keys are two spellings of one quantity. Used by `cases.scene.Scene.with_overrides`.

A value is read as TOML, else as a number as Python writes it (.5, 1., 1e3), else as text; a text key (a choice, a
path) takes the text. An override in the other spelling of a quantity the scene gives (load.Ft where it gives
load.ft, motion.W for motion.w, forces rolling.Fx, Fy for the creepages xi, eta) is refused, naming the scene's value
and its equivalent: it would drop the scene's value unannounced. Units: the scene's (mm, N, MPa, degrees).
"""
from __future__ import annotations

from dataclasses import fields
import math
import tomllib

from rollcontact.bem.errors import SceneError
from rollcontact.cases.arguments import arg
from rollcontact.cases.scene.geometry import SHAPE_KEYS
from rollcontact.cases.scene.keys import SECTIONS

#: keys of one section that are alternative spellings of one quantity: a scene gives one of each pair
ALTERNATIVE_KEYS = (("ft", "Ft"), ("w", "W"), ("R", "Rx"), ("R", "Ry"), ("xi", "Fx"), ("eta", "Fy"))
#: pairs of ALTERNATIVE_KEYS that an override may not switch from the scene's spelling to the other (the scene's
#: value would be dropped unannounced): the tangential load as f_t or in N, the amplitude as w or in mm, creepages or
#: forces. R and Rx, Ry switch the shape (sphere, ellipsoid), as geometry.shape does, and may be switched.
SPELLINGS = {("load", "ft"): "Ft", ("load", "Ft"): "ft", ("motion", "w"): "W", ("motion", "W"): "w",
             ("rolling", "xi"): "Fx", ("rolling", "Fx"): "xi", ("rolling", "eta"): "Fy", ("rolling", "Fy"): "eta"}


def other_spellings(key: str) -> set:
    """The alternative spellings of section.key: 'load.ft' -> {'load.Ft'}, 'geometry.R' -> {'geometry.Rx',
    'geometry.Ry'}; empty for a key without one."""
    sec, _, name = key.partition(".")
    return {f"{sec}.{b if name == a else a}" for a, b in ALTERNATIVE_KEYS if name in (a, b)}


def assignments_of(overrides) -> list[str]:
    """`section.key=value` strings (as `--set` takes them) from {"section.key": value}; a list of such strings
    passes through. Values are written as TOML, so that they parse back to the same value; a text value is
    taken as --set takes its text ({"load.ft": "0.3"} is --set load.ft=0.3). SceneError naming `overrides`
    (--set) for anything else."""
    if isinstance(overrides, dict):
        out = []
        for key, value in overrides.items():
            if not isinstance(key, str):
                raise SceneError(f"{arg('overrides')}: key {key!r} is not a 'section.key' string")
            out.append(f"{key}={value if isinstance(value, str) else toml_value(value)}")
        return out
    if isinstance(overrides, str):
        return [overrides]
    try:
        items = list(overrides)
    except TypeError:
        raise SceneError(f"{arg('overrides')} = {overrides!r}: expected {{'section.key': value}} or a list of "
                         "'section.key=value' strings") from None
    bad = [item for item in items if not isinstance(item, str)]
    if bad:
        raise SceneError(f"{arg('overrides')} {bad[0]!r}: expected a 'section.key=value' string")
    return items



def with_overrides(scene, assignments, replaces=()):
    """A new scene with overrides applied: `section.key=value` strings (values parsed as TOML, else as a number,
    else as text, as --set takes them), or a dict {"section.key": value} (a text value is parsed the same way).

    An override in the other spelling of a quantity the scene gives (load.Ft where the scene gives load.ft,
    motion.W for motion.w, forces rolling.Fx, Fy for the creepages xi, eta, and the reverse) is refused, naming
    the scene's value and its equivalent, unless its key is in `replaces` (a limit search sets the load.ft or
    motion.w it searches). SceneError names the key."""
    assignments = assignments_of(assignments)
    data = scene.to_dict()
    for key in scene.derived:  # re-derived from the overridden scene unless set explicitly
        sec, name = key.split(".")
        data.get(sec, {}).pop(name, None)    # [motion] is left out of a rolling scene's dict
    given = {}  # section.key -> the --set item that gave it
    for item in assignments:
        if "=" not in item or "." not in item.split("=", 1)[0]:
            raise SceneError(f"{arg('overrides')} {item!r}: expected section.key=value, e.g. load.ft=0.5")
        key, raw = item.split("=", 1)
        sec, name = key.strip().split(".", 1)
        if sec not in SECTIONS:
            raise SceneError(f"{arg('overrides')} {item!r}: unknown section {sec!r}; allowed: {list(SECTIONS)}")
        value = parse_value(raw.strip(), text=_is_text_key(sec, name))
        section = data.setdefault(sec, {})
        for other in sorted(other_spellings(f"{sec}.{name}")):
            if other in given:
                raise SceneError(f"{arg('overrides')} {given[other]!r} and {arg('overrides')} {item!r}: give "
                                 f"either {other} or {sec}.{name}, not both")
            o_name = other.partition(".")[2]
            if (o_name in section and SPELLINGS.get((sec, name)) == o_name
                    and f"{sec}.{name}" not in replaces):
                raise SceneError(_spelling_refusal(scene, item, sec, name, o_name, section[o_name], value))
            section.pop(o_name, None)
        section[name] = value
        given[f"{sec}.{name}"] = item
    if not scene.friction_on and any(key.startswith("friction.") for key in given) and "load.mu" not in given:
        data.get("load", {}).pop("mu", None)   # a law set from the command line takes the place of load.mu
    if "geometry.shape" in given:  # a new shape: the old shape's keys that it does not take are dropped
        keep = SHAPE_KEYS.get(data["geometry"]["shape"], ())
        for name in list(data["geometry"]):
            if name != "shape" and name not in keep and f"geometry.{name}" not in given:
                del data["geometry"][name]
    return type(scene).from_dict(data, name=scene.name)


def _spelling_refusal(scene, item, sec, name, other, stored, value) -> str:
    """The message refusing `item` (section.name=value) where the scene gives section.other = stored."""
    head = f"{arg('overrides')} {item!r}: the scene gives {sec}.{other} = {stored!r}"
    if sec == "rolling":
        given, wanted = (("forces", "creepages") if name in ("Fx", "Fy") else ("creepages", "forces"))
        return (f"{head}: prescribed forces (rolling.Fx, rolling.Fy) and creepages (rolling.xi, rolling.eta) "
                f"exclude each other, and the scene prescribes the {wanted}; override the {wanted}, or write "
                f"a scene file with the {given} in their place")
    equivalent = ""
    if _is_number(value):
        ld = scene.load
        if name == "Ft":
            equivalent = f" ({sec}.ft = {value / (ld.mu * ld.Fn):.6g} is Ft = {value} N here)"
        elif name == "ft":
            equivalent = f" ({sec}.Ft = {value * ld.mu * ld.Fn:.6g} N is ft = {value} here)"
        elif name == "W":
            equivalent = f" ({sec}.w = {value / scene.contact_radius:.6g} is W = {value} mm here)"
        elif name == "w":
            equivalent = f" ({sec}.W = {value * scene.contact_radius:.6g} mm is w = {value} here)"
    return (f"{head}, the same quantity in its other spelling: give {sec}.{other}{equivalent}, or a scene file "
            f"with {sec}.{name} in place of {sec}.{other}")


def _is_text_key(sec: str, name: str) -> bool:
    """True for a key whose values are text (a choice such as solver.fidelity, or geometry.path)."""
    for f in fields(SECTIONS[sec]):
        if f.name == name:
            return bool(f.metadata.get("choices")) or f.type == "str | None"
    return False


def parse_value(raw: str, text: bool = False):
    """A --set value: TOML, else a number as Python writes it (.5, 1., 1e3: not TOML), else the text. For a text
    key (`text`) the text itself unless it is a TOML string (geometry.path=1.5 is the file '1.5')."""
    try:
        parsed = tomllib.loads(f"v = {raw}")
    except tomllib.TOMLDecodeError:
        parsed = None
    if parsed is not None and list(parsed) == ["v"]:         # one value, not a value and further TOML lines
        value = parsed["v"]
        return value if not text or isinstance(value, str) else raw
    if text:
        return raw
    try:
        return float(raw)  # a NaN is refused with the key by the field check, like TOML's nan
    except ValueError:
        return raw


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, float):
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    return str(v)

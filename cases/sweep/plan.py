"""Sweep plans: the varied scene keys (`--vary`), their combinations as validated scenes, and run file names
(cases.sweep.runner; docs/theory.md §8).

    --vary load.ft=0.1:0.9:9        range start:stop:count, both ends included (count >= 2; 1 gives start)
    --vary motion.w=0.1,0.23,0.4    comma list (values parsed as TOML: numbers, or strings such as bem,mdr)

Every combination is the base scene, then the `--set` overrides, then the varied values, validated before any
run starts. Its file is named after the varied values plus 8 hex digits of sha1 of the full scene TOML, so a
changed scene gives a new file. Units: the scene's (mm, N, MPa, degrees).
"""
from __future__ import annotations

from dataclasses import dataclass
import hashlib
import itertools
import math
from pathlib import Path
import re
import tomllib

import numpy as np

from rollcontact.bem.errors import SceneError
from rollcontact.cases.arguments import arg, on_command_line

from rollcontact.cases.scene.scene import Scene

RANGE_DIGITS = 12          # range values are rounded to 12 significant digits (0.30000000000000004 -> 0.3)
_HASH_CHARS = 8


# ----------------------------------------------------------------------------------------------- axes
@dataclass(frozen=True)
class Axis:
    """One varied scene key and its values, in the order given."""

    key: str
    values: tuple

    @property
    def label(self) -> str:
        return self.key


def parse_vary(spec: str) -> Axis:
    """Parse one `--vary section.key=VALUES` argument.

    VALUES is either a range `start:stop:count` (count evenly spaced values, both ends included) or a comma
    list `v1,v2,...` (one value is allowed). Raises SceneError naming the argument and the expected syntax.
    """
    syntax = ("expected --vary section.key=start:stop:count (count >= 1, both ends included) or "
              "--vary section.key=v1,v2,... e.g. --vary load.ft=0.1:0.9:9 or --vary motion.w=0.1,0.23,0.4"
              if on_command_line() else
              "expected vary = {'section.key': [v1, v2, ...]} or {'section.key': 'start:stop:count'} (count >= 1, "
              "both ends included), e.g. {'load.ft': '0.1:0.9:9', 'motion.w': [0.1, 0.23, 0.4]}")
    if "=" not in spec:
        raise SceneError(f"{arg('vary')} {spec!r}: {syntax}")
    key, raw = (s.strip() for s in spec.split("=", 1))
    if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*\.[A-Za-z_][A-Za-z0-9_]*", key):
        raise SceneError(f"{arg('vary')} {spec!r}: key {key!r} is not of the form section.key; {syntax}")
    if not raw:
        raise SceneError(f"{arg('vary')} {spec!r}: no values; {syntax}")
    if ":" in raw:
        parts = raw.split(":")
        if len(parts) != 3:
            raise SceneError(f"{arg('vary')} {spec!r}: a range has three parts start:stop:count; {syntax}")
        try:
            start, stop = float(parts[0]), float(parts[1])
        except ValueError:
            raise SceneError(f"{arg('vary')} {spec!r}: range start and stop must be numbers; {syntax}") from None
        try:
            count = int(parts[2])
        except ValueError:
            raise SceneError(f"{arg('vary')} {spec!r}: range count {parts[2]!r} must be an integer >= 1; "
                             f"{syntax}") from None
        if count < 1:
            raise SceneError(f"{arg('vary')} {spec!r}: range count = {count}: allowed range is count >= 1")
        if not (math.isfinite(start) and math.isfinite(stop)):
            raise SceneError(f"{arg('vary')} {spec!r}: range start and stop must be finite numbers")
        if count == 1:
            values = (start,)
        else:
            values = tuple(float(f"{v:.{RANGE_DIGITS}g}") for v in np.linspace(start, stop, count))
        if len(set(values)) != len(values):
            raise SceneError(f"{arg('vary')} {spec!r}: the range repeats values; use start != stop")
        return Axis(key, values)
    items = [s.strip() for s in raw.split(",")]
    if any(not s for s in items):
        raise SceneError(f"{arg('vary')} {spec!r}: empty item in the comma list; {syntax}")
    values = tuple(_parse_value(s) for s in items)
    if len(set(map(repr, values))) != len(values):
        raise SceneError(f"{arg('vary')} {spec!r}: a value is listed twice")
    return Axis(key, values)


def vary_spec(key: str, values) -> str:
    """The `--vary` string of a key and its values: a list or tuple of values, or a string as `--vary` takes it
    after the '=' (a range "start:stop:count" or a comma list)."""
    if isinstance(values, str):
        return f"{key}={values}"
    if not isinstance(values, (list, tuple)):
        values = [values]
    return f"{key}={','.join(_toml_literal(v) for v in values)}"


def _parse_value(raw: str):
    try:
        return tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        return raw


def _format_value(v) -> str:
    """Value as written in --set and in file names: shortest round-trip form of floats, 0.0 -> 0."""
    if isinstance(v, float):
        if v.is_integer() and abs(v) < 1e15:
            return str(int(v))
        return repr(v)
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return v
    return str(v)


def _toml_literal(v) -> str:
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    return _format_value(v)


# ----------------------------------------------------------------------------------------------- plan
@dataclass(frozen=True)
class PlannedRun:
    """One run of a sweep: its varied values, the full scene (as TOML text, what the run file stores) and
    its output file."""

    index: int
    values: dict
    scene_toml: str
    path: Path
    scene_name: str = "scene"

    @property
    def name(self) -> str:
        return self.path.name


def _short_names(keys) -> dict:
    """Key -> short label for file names: the part after the section when that is unique in the sweep."""
    tails = [k.split(".", 1)[1] for k in keys]
    return {k: (t if tails.count(t) == 1 else k) for k, t in zip(keys, tails)}


def run_file_name(values: dict, scene_toml: str) -> str:
    """Deterministic, filesystem-safe file name: varied values, then 8 hex digits of sha1(scene TOML)."""
    short = _short_names(list(values))
    parts = [f"{short[k]}={_format_value(v)}" for k, v in values.items()]
    stem = re.sub(r"[^A-Za-z0-9._=+-]", "-", "_".join(parts)) or "run"
    digest = hashlib.sha1(scene_toml.encode()).hexdigest()[:_HASH_CHARS]
    return f"{stem}__{digest}.h5"


def build_scene(base: Scene, overrides, values: dict, replaces=()) -> Scene:
    """base + `--set` overrides + the varied values (in that order). Raises SceneError. replaces: keys that may
    replace the other spelling the base scene gives (Scene.with_overrides; the quantity a limit search searches)."""
    assignments = list(overrides) + [f"{k}={_toml_literal(v)}" for k, v in values.items()]
    return base.with_overrides(assignments, replaces=replaces)


def _refuse_set_of_a_varied_key(base: Scene, overrides, keys):
    """A --set of a varied key, or of its other spelling (load.Ft while load.ft is varied), would be replaced in every
    run: refused, naming both; so is a varied key whose other spelling the base scene gives (load.Ft varied where the
    scene gives load.ft)."""
    from rollcontact.cases.scene.scene import SPELLINGS, other_spellings
    for item in overrides:
        key_set = item.split("=", 1)[0].strip()
        for key in keys:
            if key == key_set or key in other_spellings(key_set):
                what = "the same key" if key == key_set else "two spellings of one quantity"
                raise SceneError(f"{arg('overrides')} {item!r} and {arg('vary')} {key}: {what}; the sweep sets {key} "
                                 f"in every run, so the {arg('overrides')} would be replaced unannounced: drop it")
    given = base.to_dict()
    set_keys = {item.split("=", 1)[0].strip() for item in overrides}
    for key in keys:
        sec, _, name = key.partition(".")
        other = SPELLINGS.get((sec, name))
        if other and other in given.get(sec, {}) and f"{sec}.{other}" not in set_keys:
            raise SceneError(f"{arg('vary')} {key}: the scene gives {sec}.{other} = {given[sec][other]!r}, the same "
                             f"quantity in its other spelling; vary {sec}.{other}, or use a scene file with {key} in "
                             f"place of {sec}.{other}")


def plan_sweep(base: Scene, axes, outdir, overrides=(), replaces=()) -> list[PlannedRun]:
    """Every combination of the axes (first axis slowest) as a validated PlannedRun.

    All combinations are validated before anything runs; if any is invalid a SceneError lists them (up to
    five, with the key, the value and the allowed range from the scene's own validation).
    """
    axes = list(axes)
    keys = [a.key for a in axes]
    if len(set(keys)) != len(keys):
        dup = sorted({k for k in keys if keys.count(k) > 1})
        raise SceneError(f"{arg('vary')}: key(s) {dup} given more than once; give each key once with all its values")
    _refuse_set_of_a_varied_key(base, [o for o in overrides if o.split("=", 1)[0].strip() not in replaces], keys)
    try:
        base_checked = base.with_overrides(list(overrides), replaces=replaces)
    except SceneError as exc:
        raise SceneError(f"{arg('overrides')}: {exc}") from None
    outdir = Path(outdir)
    runs, bad = [], []
    for index, combo in enumerate(itertools.product(*(a.values for a in axes))):
        values = dict(zip(keys, combo))
        try:
            scene = build_scene(base, overrides, values, replaces)
        except SceneError as exc:
            bad.append(f"  {describe(values)}: {exc}")
            continue
        toml = scene.to_toml()
        runs.append(PlannedRun(index, values, toml, outdir / run_file_name(values, toml), scene.name))
    if bad:
        n_total = math.prod(len(a.values) for a in axes)
        more = f"\n  ... and {len(bad) - 5} more" if len(bad) > 5 else ""
        raise SceneError(f"{len(bad)} of {n_total} sweep combination(s) are not valid scenes; nothing was run:\n"
                         + "\n".join(bad[:5]) + more)
    del base_checked
    return runs


def describe(values: dict) -> str:
    return " ".join(f"{k}={_format_value(v)}" for k, v in values.items()) or "(base scene)"


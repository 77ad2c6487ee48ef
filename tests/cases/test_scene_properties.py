"""Property-based checks of the scene parser and validator (Hypothesis): random TOML documents and random override
lists never produce a traceback. Each gives a valid scene, or a SceneError whose message names a section or key of
what was given (or, for text that is not TOML, says so); and every accepted scene round-trips through `to_toml`
(the scene read back from its TOML text is the same scene, and writes the same text).

The documents are built from the scene's own keys (cases.scene.keys), with values inside, at and beyond their ranges,
of the wrong type, non-finite, and keys and sections that do not exist. Runtime bounded: a fixed number of examples,
derandomized (the same examples every run, no example database), no deadline (a slow machine is not a failure).
"""
from dataclasses import fields
import math

from hypothesis import HealthCheck, given, settings, strategies as st
import pytest

from rollcontact.bem.errors import SceneError
from rollcontact.cases.scene.keys import SECTIONS
from rollcontact.cases.scene.scene import Scene, default_scene, shipped_scene_path

PROPERTY = settings(max_examples=250, deadline=None, derandomize=True, database=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])

KEYS = {sec: [f.name for f in fields(klass)] for sec, klass in SECTIONS.items()}
SPECS = {(sec, f.name): f for sec, klass in SECTIONS.items() for f in fields(klass)}


def _numbers():
    """Numbers as a scene meets them: ordinary, at and beyond the ranges, huge, tiny, signed zero, non-finite."""
    return st.one_of(
        st.floats(allow_nan=True, allow_infinity=True),
        st.floats(min_value=-2.0, max_value=2.0),
        st.floats(min_value=0.0, max_value=100.0),
        st.sampled_from([0, 1, -1, 0.5, 1e-9, 1e300, -0.0, 3, 4, 12, 24, 1000, 10**6, 10**7]),
        st.integers(min_value=-10**6, max_value=10**7),
    )


def _in_range(sec, key):
    """Values inside the key's range (its field spec), or among its choices: what a scene that runs gives."""
    meta = SPECS[(sec, key)].metadata
    if meta.get("choices"):
        return st.sampled_from(list(meta["choices"]))
    lo, hi = meta.get("lo"), meta.get("hi")
    lo = 0.0 if lo is None or not math.isfinite(lo) else float(lo)
    hi = lo + 100.0 if hi is None or not math.isfinite(hi) else float(hi)
    if SPECS[(sec, key)].type == "int":
        return st.integers(min_value=math.ceil(lo), max_value=min(math.floor(hi), 200))
    return st.floats(min_value=lo, max_value=hi, exclude_min=meta.get("lo_open", False),
                     exclude_max=meta.get("hi_open", False))


def _values(sec, key):
    """Mostly values in range; at times any number, or a value of the wrong type."""
    junk = st.one_of(st.text(max_size=6), st.booleans(), st.lists(_numbers(), max_size=3),
                     st.dictionaries(st.sampled_from(["a", "R"]), _numbers(), max_size=2))
    if (sec, key) not in SPECS:
        return st.one_of(_numbers(), junk)
    return st.integers(0, 9).flatmap(lambda k: _numbers() if k == 0 else junk if k == 1 else _in_range(sec, key))


@st.composite
def documents(draw):
    """{section: {key: value}}: the scene's own keys and sections, at times an unknown one."""
    doc = {}
    sections = draw(st.lists(st.sampled_from(list(SECTIONS)), max_size=5, unique=True))
    if draw(st.integers(0, 9)) == 0:
        sections.append("physics")
    for sec in sections:
        keys = draw(st.lists(st.sampled_from(KEYS.get(sec, ["g"])), max_size=3, unique=True))
        if draw(st.integers(0, 9)) == 0:
            keys.append("bogus")
        doc[sec] = {k: draw(_values(sec, k)) for k in keys}
    if draw(st.integers(0, 3)):      # most scenes that run give a sphere
        doc.setdefault("geometry", {}).setdefault("R", draw(st.sampled_from([40.0, 10.0, 1e-3, 1e6])))
    if "rolling" in doc and "mode" not in doc["rolling"] and draw(st.booleans()):
        doc["rolling"]["mode"] = draw(st.sampled_from(["steady", "transient"]))
    return doc


def _toml(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf") if math.isinf(value) else repr(value)
    if isinstance(value, str):
        return '"' + "".join(c if c.isprintable() and c not in '"\\' else f"\\u{ord(c):04x}" for c in value) + '"'
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return "{" + ", ".join(f"{k} = {_toml(v)}" for k, v in value.items()) + "}"


def toml_text(doc) -> str:
    return "\n".join(f"[{sec}]\n" + "".join(f"{k} = {_toml(v)}\n" for k, v in keys.items()) for sec, keys in doc.items())


def _names_what_was_given(message: str, given) -> bool:
    """The message names a section or key of a scene (`[load]`, `load.ft`), a section of `given` ({section: keys},
    or override strings) that does not exist, or says that the text is not TOML."""
    if "unknown section" in message or "not valid TOML" in message:
        return True
    sections = set(SECTIONS) | (set(given) if isinstance(given, dict)
                                else {item.split("=", 1)[0].split(".", 1)[0] for item in given})
    return any(f"[{sec}]" in message or f"{sec}." in message for sec in sections)


def _round_trips(scene: Scene):
    text = scene.to_toml()
    back = Scene.from_toml_text(text, run_limits=False)
    assert back.to_dict() == scene.to_dict() and back.name == scene.name
    assert back.to_toml() == text


@PROPERTY
@given(documents())
def test_a_random_scene_document_gives_a_scene_or_an_error_naming_a_key(doc):
    text = toml_text(doc)
    try:
        scene = Scene.from_toml_text(text, name="random")
    except SceneError as exc:
        assert _names_what_was_given(str(exc), doc), (str(exc), text)
        return
    _round_trips(scene)


@PROPERTY
@given(st.text(max_size=80))
def test_random_text_is_refused_as_a_scene_error(text):
    try:
        _round_trips(Scene.from_toml_text(text, name="text"))
    except SceneError:
        pass


def _items():
    """--set items: a known key (or at times an unknown one) and a value as text: in range, any number, a TOML
    value, junk, a TOML injection."""
    known = st.sampled_from(sorted(SPECS))
    good = known.flatmap(lambda k: _in_range(*k).map(lambda v: f"{k[0]}.{k[1]}={_toml(v)}"))
    key = st.one_of(known.map(lambda k: f"{k[0]}.{k[1]}"),
                    st.sampled_from(["load.bogus", "physics.g", "load", "load.ft.x", ".ft", "load."]))
    value = st.one_of(_numbers().map(_toml), _numbers().map(repr), st.text(max_size=8),
                      st.sampled_from(['"steady"', '"transient"', "mdr", "bem", "[0.2, -0.3]", "1e999", ".5",
                                       "0.3\n[motion]\nw = 5", "true", "{a = 1}"]))
    junk = st.one_of(st.tuples(key, value).map(lambda kv: f"{kv[0]}={kv[1]}"), st.text(max_size=10))
    return st.integers(0, 9).flatmap(lambda k: junk if k == 0 else good)


@pytest.fixture(scope="module")
def bases():
    return [default_scene(), Scene.from_toml(shipped_scene_path("creep_steady.toml"))]


@PROPERTY
@given(st.lists(_items(), max_size=5), st.integers(min_value=0, max_value=1))
def test_random_overrides_give_a_scene_or_an_error_naming_a_key(bases, items, which):
    try:
        scene = bases[which].with_overrides(items)
    except SceneError as exc:
        assert _names_what_was_given(str(exc), items) or "overrides" in str(exc), (str(exc), items)
        return
    _round_trips(scene)


@PROPERTY
@given(st.dictionaries(st.sampled_from(["load.ft", "motion.w", "motion.periods", "grid.dx", "solver.fidelity",
                                        "load.ft_amplitude", "load.cycles_per_period", "motion.steps_per_period"]),
                       st.one_of(_numbers(), _numbers().map(repr), st.text(max_size=5)), max_size=4))
def test_overrides_as_a_dict_of_values_or_texts_behave_as_set_items(overrides):
    """load_scene(overrides={"load.ft": "0.3"}) is --set load.ft=0.3; a value as text is read as --set reads it."""
    base = default_scene()
    try:
        scene = base.with_overrides(overrides)
    except SceneError as exc:
        assert _names_what_was_given(str(exc), [f"{k}=" for k in overrides]), str(exc)
        return
    _round_trips(scene)
    as_text = {k: v if isinstance(v, str) else repr(v) for k, v in overrides.items()}
    assert base.with_overrides(as_text).to_dict() == scene.to_dict()

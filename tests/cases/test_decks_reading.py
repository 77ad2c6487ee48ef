"""Reading CONTACT decks (cases.decks): the input file's rules (comments, separators, groups over lines, optional
values on the line of the last mandatory one, angles in degrees), what a case inherits from the earlier ones, and
bad decks: every error names the line (or the end of the file) and the field, never a traceback, also for decks
mutated at random (Hypothesis). The decks in tests/data/contact_decks were written for these tests."""
from pathlib import Path
import math

from hypothesis import HealthCheck, given, settings, strategies as st
import pytest

from rollcontact.bem.errors import InputError
from rollcontact.cases.decks.deck import parse_deck, read_deck
from rollcontact.cases.decks.reader import DeckError, DeckText, split_words
from rollcontact.cases.decks.importer import import_contact

DECKS = Path(__file__).resolve().parents[1] / "data" / "contact_decks"
HERTZ = (DECKS / "hertz_shift.inp").read_text()


def test_words_split_on_blanks_commas_and_equals_and_stop_at_a_comment():
    assert split_words("  1, 2.5e-3 =x 'a b%c' % comment") == ["1", "2.5e-3", "x", "'a b%c'"]
    assert split_words("% only a comment") == []


def test_a_group_runs_over_lines_and_takes_optional_values_only_on_its_last_line():
    text = DeckText("1.0 2.0 % first two\n 3.0\n 4.0 5.0 6.0\n 7.0 8.0 FREE TEXT\n")
    got = text.read("kinematics", "A:d B:d C:d D:d E:D F:D")
    assert [got[k].value for k in "ABCD"] == [1.0, 2.0, 3.0, 4.0]
    assert got["E"].value == 5.0 and got["F"].value == 6.0 and got["A"].line == 1 and got["D"].line == 3
    later = text.read("next", "G:d H:d I:I")
    assert later["G"].value == 7.0 and "I" not in later          # free text after the group is ignored


def test_angles_take_degrees_with_d_and_fortran_exponents_with_d():
    got = DeckText("180d 0.5r 1d-3 2.5D2\n").read("values", "A:a B:a C:d E:d")
    assert got["A"].value == pytest.approx(math.pi) and got["B"].value == 0.5
    assert got["C"].value == 1e-3 and got["E"].value == 250.0


def test_case_two_inherits_grid_materials_and_friction_with_the_lines_of_case_one():
    deck = parse_deck(HERTZ, "hertz_shift")
    one, two = deck.cases
    assert (one.number, two.number) == (1, 2) and two.digits["D"] == 0 and two.digits["L"] == 1
    assert one.value("CPHI") == 0.0 and one.line_of("FN") == 11 and one.line_of("CPHI") == 12   # over two lines
    for name in ("MX", "A1", "GG1", "FSTAT", "IPOTCN"):
        assert two.value(name) == one.value(name) and two.line_of(name) == one.line_of(name)
    assert two.value("FXREL") == -0.6 and two.line_of("FXREL") == 21 and "FN" in two.read
    assert one.digits["M2"] == 0 and one.digits["R"] == 0       # R = 0: case 2 has no module number


def test_the_published_example_decks_give_the_reference_outputs_case_count():
    examples = DECKS.parent / "contact_examples"
    counts = {"cattaneo": 2, "catt_to_cart": 171, "tractcurv": 120, "mbench_a22_right": 21, "spence35": 35,
              "subsurf": 2}
    for name, n in counts.items():
        assert len(read_deck(examples / f"{name}.inp.gz").cases) == n


# --- bad decks ----------------------------------------------------------------------------------------------------
def _error(text: str) -> str:
    with pytest.raises(DeckError) as info:
        parse_deck(text, "bad")
    return str(info.value)


def test_a_deck_cut_anywhere_names_the_end_of_the_file_and_the_missing_field():
    lines = HERTZ.splitlines()
    last_value = max(i for i, ln in enumerate(lines) if ln.split("%")[0].strip() and "MODULE" not in ln)
    for k in range(6, last_value + 1):
        if not lines[k - 1].split("%")[0].strip():
            continue
        message = _error("\n".join(lines[:k]) + "\n")
        assert message.startswith("bad.inp, end of file (after line ") and "truncated" in message


@pytest.mark.parametrize("change, where", [
    ((" 3   MODULE", " 2   MODULE"), "line 6: module number: 2 is not a module"),
    (("  200100      P-B-T-N-F-S", "  205100      P-B-T-N-F-S"), "line 7: control digit T (TANG): 5 is not allowed"),
    (("  022020  0", "  122020  0"), "line 8: control digit L: 1: the first case has no earlier friction law"),
    (("  022020  0", "  022000  0"), "line 8: control digit Z: 0: a new discretisation (D = 2)"),
    (("  022020  0", "  022120  0"), "line 8: control digit M: 1: viscoelastic materials need steady rolling"),
    (("  0.30  0.30  8.0E4", "  0.70  0.30  8.0E4"), "line 14: POISS1: 0.7 is out of range"),
    (("  1000.0   0.0   0.0  ", "  -5.0   0.0   0.0  "), "line 11: FN: -5.0 N: the normal force must be > 0"),
    (("  0.25   0.25", "  0.25   0.30"), "line 13: FSTAT: 0.25 differs from FKIN"),
    (("  -1                                IPOTCN", "  7   IPOTCN"), "line 15: IPOTCN: 7 is not allowed"),
    (("  23, 21,", "  0, 21,"), "line 16: MX: 0 is out of range"),
    (("  1000.0  -0.6  0.0  0.0", "  1000.0  -1.6  0.0  0.0"), "line 21: FX: -1.6 is out of range"),
    (("   100, 100, 30, 1, 1e-6", "   100, 1x0, 30, 1, 1e-6"), "line 10: MAXIN: '1x0' is not an integer"),
])
def test_a_bad_value_or_digit_is_named_with_its_line(change, where):
    assert change[0] in HERTZ
    message = _error(HERTZ.replace(change[0], change[1], 1))
    assert message.startswith("bad.inp, " + where.split(":")[0]) and where.split(": ", 1)[1] in message


def test_import_of_a_missing_file_is_a_deck_error():
    with pytest.raises(DeckError, match="cannot be read"):
        import_contact(DECKS / "no_such_deck.inp")


# --- random mutations -----------------------------------------------------------------------------------------------
_WORDS = st.one_of(st.integers(-10 ** 6, 10 ** 7).map(str), st.floats(allow_nan=True, allow_infinity=True).map(str),
                   st.sampled_from(["", "x", "'", "'a'", "1d400", "-0", "0022020", "9999999999", "3.", ".5e-3", "%",
                                    "180d", "nan", "1e309"]),
                   st.text(alphabet="0123456789.-+eEdD ,='%xT", max_size=8))


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_a_mutated_deck_imports_or_names_line_and_field_never_a_traceback(data, tmp_path_factory):
    lines = HERTZ.splitlines()
    kind = data.draw(st.sampled_from(["word", "delete", "duplicate", "truncate"]))
    k = data.draw(st.integers(0, len(lines) - 1))
    if kind == "word":
        words = lines[k].split() or [""]
        j = data.draw(st.integers(0, len(words) - 1))
        words[j] = data.draw(_WORDS)
        lines[k] = " " + " ".join(words)
    elif kind == "delete":
        del lines[k]
    elif kind == "duplicate":
        lines.insert(k, lines[k])
    else:
        lines = lines[:k]
    path = tmp_path_factory.mktemp("mutated") / "mutated.inp"
    path.write_text("\n".join(lines) + "\n")
    try:
        import_contact(path)
    except DeckError as exc:
        assert str(exc).startswith("mutated.inp, ") and ("line " in str(exc) or "end of file" in str(exc))
    except InputError as exc:                     # only DeckError is expected from a deck
        pytest.fail(f"{type(exc).__name__}: {exc}")

"""`import_contact`: a CONTACT deck read, its cases grouped into problems, each problem mapped onto a scene and
checked as rollcontact checks a scene file, the scenes written with the deck's report (docs/contact_decks.md).

Written into the output folder: `<deck>_case<N>.toml` (or `<deck>_cases<N>-<M>.toml` for a history run as one
scene) for every problem that converts, the wheel and rail profile files its [wheelrail] scenes name,
`<deck>_import.md` (the report: per case converted or not, and every digit or value rollcontact cannot pose, with
its value, line and what it would need) and `<deck>_import.json` (the same for programs, with the step of each
run that answers each case). Nothing is written when a file exists and `overwrite` is not given.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import json
from pathlib import Path
import shutil
import tempfile

from rollcontact.bem.errors import InputError, OutputExistsError
from rollcontact.cases.arguments import arg, flag
from rollcontact.cases.decks import problems as P
from rollcontact.cases.decks.deck import Deck, read_deck
from rollcontact.cases.decks.draft import Draft
from rollcontact.cases.decks.mapping import grid_margin
from rollcontact.cases.decks.report import report_text
from rollcontact.cases.decks.wheelrail_map import map_wheelrail


@dataclass
class DeckImport:
    """The import of one deck: the deck as read, its problems (each with its draft scene, refusals and notes), the
    files written (empty without an output folder)."""
    deck: Deck
    problems: list
    files: list = field(default_factory=list)

    @property
    def computed(self) -> list:
        return [p for p in self.problems if p.kind != "skipped"]

    @property
    def converted(self) -> list:
        return [p for p in self.computed if p.converted]

    @property
    def status(self) -> str:
        """'yes' when every computed case converts, 'partly' when some do, 'no' when none."""
        done = sum(len(p.cases) for p in self.converted)
        total = sum(len(p.cases) for p in self.computed)
        return "yes" if total and done == total else ("partly" if done else "no")

    def summary(self) -> str:
        done = sum(len(p.cases) for p in self.converted)
        total = sum(len(p.cases) for p in self.computed)
        skipped = sum(len(p.cases) for p in self.problems if p.kind == "skipped")
        return (f"{self.deck.name}: {done} of {total} computed cases converted into {len(self.converted)} scene"
                f"{'s' if len(self.converted) != 1 else ''}" + (f", {skipped} skipped (R = 2, 3)" if skipped else ""))

    def scene_text(self, problem) -> str:
        """The TOML text of a converted problem's scene."""
        return problem.draft.toml(_title(self.deck, problem))

    def markdown(self) -> str:
        """The import report (`<deck>_import.md`): per case converted or not, every refusal with its need."""
        return report_text(self)

    def report(self) -> str:
        """What `rollcontact import-contact` prints: the summary, one line per problem, the files written."""
        lines = [self.summary() + f" (converted: {self.status})"]
        for p in self.problems:
            which = f"case {p.numbers[0]}" if len(p.numbers) == 1 else f"cases {p.numbers[0]}-{p.numbers[-1]}"
            if p.kind == "skipped":
                lines.append(f"  {which}: skipped ({p.reason})")
            elif p.converted:
                lines.append(f"  {which}: {p.name}.toml ({kind_text(p.kind)})")
            else:
                first = p.draft.unsupported[0].text() if p.draft.unsupported else "?"
                more = len(p.draft.unsupported) - 1
                lines.append(f"  {which}: not converted: {first}" + (f" (+{more} more)" if more > 0 else ""))
        lines += [str(Path(f).resolve()) for f in self.files]
        return "\n".join(lines)

    def manifest(self) -> dict:
        return {"deck": self.deck.name, "status": self.status, "notes": self.deck.notes,
                "problems": [_manifest_entry(p) for p in self.problems]}


def import_contact(deck, output=None, *, overwrite: bool = False) -> DeckImport:
    """Read the CONTACT deck `deck` (a path to `<experim>.inp`), convert what rollcontact can pose and, when `output`
    (a folder) is given, write the scenes, profiles, report and manifest there (module docstring). DeckError names
    the line and field of a deck that cannot be read; OutputExistsError a file that exists without `overwrite`."""
    parsed = read_deck(deck)
    problems = []
    with tempfile.TemporaryDirectory(prefix="rollcontact-import-") as scratch:
        for problem in P.group(parsed.cases):
            problem.deck = parsed.name
            _convert(problem, parsed, Path(scratch))
            problems += _split_failed_history(problem, parsed, Path(scratch))
        result = DeckImport(parsed, problems)
        if output is not None:
            _write(result, Path(output), overwrite)
    return result


def _convert(problem, deck: Deck, scratch: Path):
    if problem.kind == "skipped":
        return
    problem.name = _name(deck.name, problem.numbers)
    try:
        if problem.cases[0].module == 1:
            map_wheelrail(problem, deck.folder)
        else:
            P.map_problem(problem)
    except (ValueError, ZeroDivisionError, OverflowError, TypeError) as exc:   # an input the mapping cannot take
        problem.draft = problem.draft or Draft()
        problem.draft.refuse(f"case {problem.numbers[0]}", None, f"the importer cannot map this input "
                                                                 f"({type(exc).__name__}: {exc})")
        return
    d = problem.draft
    if d.ok and problem.geometry is not None and problem.geometry.profile is not None:
        _profile_file(problem, d, scratch)
    if d.ok and problem.geometry is not None:
        _set_margin(problem, d)
    if d.ok:
        _validate(problem, d)


def _split_failed_history(problem, deck: Deck, scratch: Path) -> list:
    """A history that cannot run as one: its head alone when it is a problem of its own (it starts from zero
    tractions), and the continuation, not converted, with the history's reasons."""
    head = problem.cases[0]
    if problem.converted or len(problem.cases) < 2 or head.digits["P"] not in (1, 2) or head.module != 3:
        return [problem]
    alone = P.Problem(deck.name, [head], {0: "normal", 1: "single shift", 2: "single transient",
                                          3: "steady"}[head.digits["T"]])
    _convert(alone, deck, scratch)
    if not alone.converted:
        return [problem]
    rest = P.Problem(deck.name, problem.cases[1:], "history", draft=Draft(), name=_name(deck.name, problem.numbers))
    rest.draft.refuse(f"cases {rest.numbers[0]}-{rest.numbers[-1]} (P = 0)", None,
                      f"continue the history of case {head.number} (converted alone), which rollcontact cannot pose "
                      "as one run:")
    rest.draft.unsupported += problem.draft.unsupported
    rest.draft.notes += problem.draft.notes
    rest.draft.ignored += problem.draft.ignored
    return [alone, rest]


def steps_text(steps: dict) -> str:
    """'case 1 -> step 0, cases 2-57 -> steps 1-56': the run's steps answering the cases, consecutive runs joined."""
    items, parts = list(steps.items()), []
    i = 0
    while i < len(items):
        j = i
        while j + 1 < len(items) and items[j + 1][0] == items[j][0] + 1 and items[j + 1][1] == items[j][1] + 1:
            j += 1
        (c0, s0), (c1, s1) = items[i], items[j]
        parts.append(f"case {c0} -> step {s0}" if i == j else f"cases {c0}-{c1} -> steps {s0}-{s1}")
        i = j + 1
    return ", ".join(parts)


def _profile_file(problem, d: Draft, scratch: Path):
    """The sampled undeformed distance as `<scene>_profile.npz` (x, y, h; cases.scene.profile_file)."""
    import numpy as np
    x, y, h = problem.geometry.profile
    path = scratch / f"{problem.name}_profile.npz"
    np.savez(path, x=x, y=y, h=h)
    d.files["profile"] = path
    d.sections["geometry"]["path"] = path.name


def _name(deck: str, numbers: list[int]) -> str:
    return f"{deck}_case{numbers[0]}" if len(numbers) == 1 else f"{deck}_cases{numbers[0]}-{numbers[-1]}"


def _scene_of(problem, d: Draft, run_limits: bool):
    from rollcontact.cases.scene.scene import Scene
    data = {sec: dict(keys) for sec, keys in d.sections.items()}
    for key in ("wheel_profile", "rail_profile"):
        if key in d.files:
            data["wheelrail"][key] = str(d.files[key])
    if "profile" in d.files:
        data["geometry"]["path"] = str(d.files["profile"])
    return Scene.from_dict(data, name=problem.name, run_limits=run_limits)


def _set_margin(problem, d: Draft):
    """The margin that makes rollcontact's grid cover the deck's potential contact."""
    from rollcontact.cases.run.discretise import contact_extent
    try:
        scene = _scene_of(problem, d, run_limits=False)
    except (InputError, ValueError, ZeroDivisionError, OverflowError) as exc:
        d.refuse(f"scene {problem.name}", None, f"rollcontact refuses it: {exc}")
        return
    grid_margin(d, problem.geometry, contact_extent(scene))


def _validate(problem, d: Draft):
    """The checks `rollcontact run` makes of a scene file (ranges, resolution, steps, profile files)."""
    try:
        _scene_of(problem, d, run_limits=True)
    except (InputError, ValueError, ZeroDivisionError, OverflowError) as exc:
        d.refuse(f"scene {problem.name}", None, f"rollcontact refuses it: {exc}")


def _title(deck: Deck, problem) -> list[str]:
    cases = problem.numbers
    which = f"case {cases[0]}" if len(cases) == 1 else f"cases {cases[0]}-{cases[-1]} ({len(cases)} cases, one run)"
    run = f"rollcontact run {problem.name}.toml"
    options = problem.draft.run_options
    if options.get("stresses"):
        run += " --stresses --depths " + ",".join(f"{z:g}" for z in options["depths"])
    lines = [f"rollcontact scene '{problem.name}' from the CONTACT deck {deck.name}.inp, {which}: "
             f"{_KIND_TEXT.get(problem.kind, problem.kind)}", "written by `rollcontact import-contact` "
             "(docs/contact_decks.md); units: mm, N, MPa, " + ("rad, s" if problem.kind == "wheelrail" else
                                                                "degrees") + "; each key's origin in the deck beside it",
             f"run: {run}"]
    if problem.steps and len(problem.steps) > 1:
        lines.append("steps of the run answering the deck's cases: " + steps_text(problem.steps))
    for note in problem.draft.notes:
        lines.append("note: " + note)
    return lines


_KIND_TEXT = {"normal": "frictionless compression (T = 0)", "shift": "compression and shift(s) (T = 1)",
              "steady": "steady rolling (T = 3)", "transient": "transient rolling (T = 2)",
              "wheelrail": "a wheel on its rail (module 1, T = 3)", "history": "a history of cases",
              "single shift": "a shift (T = 1)", "single transient": "transient rolling (T = 2)"}


def kind_text(kind: str) -> str:
    return _KIND_TEXT.get(kind, kind)


def _manifest_entry(problem) -> dict:
    d = problem.draft
    entry = {"cases": problem.numbers, "kind": problem.kind,
             "status": "skipped" if problem.kind == "skipped" else ("converted" if problem.converted else
                                                                    "not converted")}
    if problem.kind == "skipped":
        entry["reason"] = problem.reason
        return entry
    if problem.converted:
        entry.update(scene=f"{problem.name}.toml", steps={str(k): v for k, v in problem.steps.items()},
                     frame=problem.frame, run_options=d.run_options)
    entry["unsupported"] = [{"name": u.name, "value": str(u.value), "line": u.line, "needs": u.needs}
                            for u in d.unsupported]
    entry["notes"] = d.notes
    entry["ignored"] = d.ignored
    return entry


def _write(result: DeckImport, out: Path, overwrite: bool):
    planned = {out / f"{p.name}.toml": p for p in result.converted}
    extra = {}
    for p in result.converted:
        for path in p.draft.files.values():
            extra[out / path.name] = path
    targets = list(planned) + list(extra) + [out / f"{result.deck.name}_import.md",
                                             out / f"{result.deck.name}_import.json"]
    if not overwrite:
        existing = [t for t in targets if t.exists()]
        if existing:
            raise OutputExistsError(f"{existing[0]}: exists; rollcontact does not replace a file unless asked: add "
                                    f"{flag('overwrite')}, or give another folder with {arg('output')}")
    out.mkdir(parents=True, exist_ok=True)
    for target, problem in planned.items():
        target.write_text(result.scene_text(problem))
    for target, source in extra.items():
        if target.resolve() != source.resolve():
            shutil.copyfile(source, target)
    (out / f"{result.deck.name}_import.md").write_text(result.markdown())
    (out / f"{result.deck.name}_import.json").write_text(json.dumps(result.manifest(), indent=1) + "\n")
    result.files = targets

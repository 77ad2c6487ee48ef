"""The tables of docs/contact_decks.md: the reference program's published examples imported and compared.

    .venv/bin/python docs/scripts/contact_decks.py [-o results/contact_decks] [--quick] [--examples DIR]

Every deck of the examples folder (default tests/data/contact_examples: CONTACT's examples, commit d431cdb) is
imported with `rollcontact.import_contact` into OUT/imports/<deck>/ (its scenes, report and manifest, as `rollcontact
import-contact DECK -o OUT/imports/<deck>` writes them); table `compatibility` says per deck how many of its computed
cases convert (yes / partly / no) and why the others do not. Every converted problem is then run and compared case by
case with the figures of the deck's reference output (cases.decks.compare: forces, creepages or shifts, approach,
maximum pressure, contact and adhesion areas, the traction where the output prints it): table `differences`, and
every compared figure in OUT/contact_decks.json. --quick: the compatibility table complete, the differences of
`cattaneo` only (a few seconds).
"""
from __future__ import annotations

from collections import Counter
import json
from pathlib import Path
import sys
import time

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _study import ROOT, SKIPPED, Study  # noqa: E402

EXAMPLES = ROOT / "tests" / "data" / "contact_examples"
QUICK_DECKS = ("cattaneo",)
#: the figures of the differences table, in its column order
COLUMNS = (("FX", "FY", "FS", "FX(TR)", "FY(TR)"), ("MZ",), ("CREEP X", "CREEP Y", "SHIFT X", "SHIFT Y", "CKSI",
                                                           "CETA", "CPHI"),
           ("approach",), ("PMAX",), ("contact area",), ("adhesion area",), ("traction pn (rms)",),
           ("traction |pt| (rms)",))
HEADERS = ("forces", "MZ", "creepage / shift", "approach", "PMAX", "contact area", "adhesion area", "pn rms",
           "pt rms")


def decks_in(folder: Path) -> list[Path]:
    return sorted(p for p in folder.iterdir() if p.name.endswith((".inp", ".inp.gz")))


def reference_of(deck: Path) -> Path | None:
    stem = deck.name.removesuffix(".gz").removesuffix(".inp")
    for name in (f"{stem}.ref_out", f"{stem}.ref_out.gz"):
        if (deck.parent / name).is_file():
            return deck.parent / name
    return None


def why_not(result) -> str:
    """The most frequent first reasons of the cases that do not convert: 'label (n cases)'."""
    counts = Counter()
    for p in result.computed:
        if not p.converted:
            u = p.draft.unsupported[0] if p.draft.unsupported else None
            label = _label(u) if u else "?"
            if u and u.name.startswith("cases ") and len(p.draft.unsupported) > 1:
                label = "continues a history that cannot run as one: " + _label(p.draft.unsupported[1])
            counts[label] += len(p.cases)
    return "; ".join(f"{label} ({n} case{'s' if n > 1 else ''})" for label, n in counts.most_common(3))


def _label(u) -> str:
    """A short reason: the digit or value and what it needs (without the case's own numbers in parentheses)."""
    from rollcontact.cases.decks.draft import show
    if u.name.startswith("scene "):
        return "rollcontact's check: " + u.needs.split("refuses it: ", 1)[-1].split(";")[0].split(" spans")[0]
    value = show(u.value)
    text = f"{u.name} = {value if len(value) < 40 else value[:36] + '...'}" if u.value is not None else u.name
    needs = u.needs.split(";")[0].split(" (")[0].replace("needs ", "")
    return f"{text}: {needs}"


def compatibility(study: Study, results: list):
    rows = []
    for r in results:
        computed = sum(len(p.cases) for p in r.computed)
        done = sum(len(p.cases) for p in r.converted)
        rows.append([f"`{r.deck.name}`", str(computed), f"{r.status} ({done})", str(len(r.converted)),
                     why_not(r) or "-"])
    study.table("compatibility", ["deck", "computed cases", "converted", "scenes", "not converted, why (cases)"], rows)


def differences(study: Study, entries: list):
    """One row per converted problem: the largest difference of each column over its cases (SKIPPED: not run)."""
    rows = []
    for problem, cmp in entries:
        cases = len(problem.cases)
        head = [f"`{problem.name}`", f"{problem.kind}{f' ({cases} cases)' if cases > 1 else ''}"]
        if cmp is None:
            rows.append(head + [SKIPPED] * (1 + len(HEADERS)))
            continue
        big = cmp.largest()
        cells = []
        for group in COLUMNS:
            values = [big[q] for q in group if q in big]
            cells.append(f"{max(values):.2g}" if values else "")
        grid = "x".join(map(str, cmp.grid)) if problem.kind != "wheelrail" else f"{cmp.grid[0]} / {cmp.grid[1]} p."
        rows.append(head + [grid] + cells)
    study.table("differences", ["scene", "problem", "grid", *HEADERS], rows)


def main(argv=None) -> int:
    study = Study.from_command_line("contact_decks", __doc__, argv, extra=lambda ap: ap.add_argument(
        "--examples", type=Path, default=EXAMPLES, help="folder of the decks and reference outputs"))
    import rollcontact
    from rollcontact.cases.decks.compare import compare_problem
    from rollcontact.cases.decks.refout import read_refout
    results, entries, records = [], [], []
    cpu = 0.0
    for deck in decks_in(study.args.examples):
        folder = study.out / "imports" / deck.name.split(".")[0]
        r = rollcontact.import_contact(deck, folder, overwrite=True)
        results.append(r)
        ref_path = reference_of(deck)
        run = ref_path is not None and not (study.quick and r.deck.name not in QUICK_DECKS)
        reference = read_refout(ref_path) if run else None
        for problem in r.converted:
            if not run:
                entries.append((problem, None))
                continue
            cmp = compare_problem(problem, rollcontact.load_scene(folder / f"{problem.name}.toml"), reference)
            cpu += cmp.seconds
            entries.append((problem, cmp))
            records.append({"deck": r.deck.name, "scene": problem.name, "kind": problem.kind, "status": cmp.status,
                            "grid": list(cmp.grid), "cpu_seconds": cmp.seconds, "rows": cmp.rows})
            print(f"{problem.name}: {cmp.status}, {cmp.seconds:.2f} s CPU", file=sys.stderr, flush=True)
    compatibility(study, results)
    differences(study, entries)
    (study.out / "contact_decks.json").write_text(json.dumps({"comparisons": records, "cpu_seconds": cpu,
                                                              "decks": [r.manifest() for r in results]},
                                                             indent=1) + "\n")
    print(f"{len(records)} problems run and compared, {cpu:.1f} s CPU in the runs ({time.strftime('%Y-%m-%d')})")
    return study.finish()


if __name__ == "__main__":
    sys.exit(main())

"""The reference program's published examples imported and compared: the tables of docs/contact_decks.md.

    .venv/bin/python benchmarks/contact_decks.py [-o DIR] [--quick] [--examples DIR] [--page PAGE]

Every deck of the examples folder (default tests/data/contact_examples: CONTACT's examples, commit d431cdb) is
imported with `rollcontact.import_contact` into DIR/imports/<deck>/ (its scenes and report); the compatibility
table says per deck how many of its computed cases convert (yes / partly / no) and why the others do not. Every
converted problem is then run and compared case by case with the figures of the deck's reference output
(cases.decks.compare: forces, creepages or shifts, approach, maximum pressure, contact and adhesion areas, the
traction where the output prints it). --quick compares only the decks in QUICK_DECKS (the import and the
compatibility table stay complete).

Written to DIR (default results/contact_decks/): contact_decks_tables.md (both tables, as in the page),
contact_decks.json (every compared figure). --page PAGE also replaces the generated part of PAGE (between its
markers '<!-- contact_decks.py: begin -->' and '<!-- contact_decks.py: end -->'): docs/contact_decks.md comes from
`-o docs/contact_decks --page docs/contact_decks.md`.
"""
from __future__ import annotations

import argparse
from collections import Counter
import datetime
import json
import os
from pathlib import Path
import platform

import rollcontact
from rollcontact.cases.decks.compare import compare_problem
from rollcontact.cases.decks.draft import show as _show
from rollcontact.cases.decks.refout import read_refout

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "tests" / "data" / "contact_examples"
QUICK_DECKS = ("cattaneo",)
BEGIN, END = "<!-- contact_decks.py: begin -->", "<!-- contact_decks.py: end -->"
#: the figures of the comparison table, in its column order
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
    if u.name.startswith("scene "):
        return "rollcontact's check: " + u.needs.split("refuses it: ", 1)[-1].split(";")[0].split(" spans")[0]
    value = _show(u.value)
    text = f"{u.name} = {value if len(value) < 40 else value[:36] + '...'}" if u.value is not None else u.name
    needs = u.needs.split(";")[0].split(" (")[0].replace("needs ", "")
    return f"{text}: {needs}"


def compatibility(results: list) -> list[str]:
    lines = ["| deck | computed cases | converted | scenes | not converted, why (cases) |", "|---|---|---|---|---|"]
    for r in results:
        computed = sum(len(p.cases) for p in r.computed)
        done = sum(len(p.cases) for p in r.converted)
        lines.append(f"| `{r.deck.name}` | {computed} | {r.status} ({done}) | {len(r.converted)} | "
                     f"{why_not(r) or '-'} |")
    return lines


def comparison_table(comparisons: list) -> list[str]:
    lines = ["| scene | problem | grid | " + " | ".join(HEADERS) + " | CPU s |",
             "|---|---|---|" + "---|" * len(HEADERS) + "---|"]
    for deck, problem, cmp in comparisons:
        big = cmp.largest()
        cells = []
        for group in COLUMNS:
            values = [big[q] for q in group if q in big]
            cells.append(f"{max(values):.2g}" if values else "")
        grid = "x".join(map(str, cmp.grid)) if problem.kind != "wheelrail" else f"{cmp.grid[0]} / {cmp.grid[1]} p."
        cases = len(problem.cases)
        lines.append(f"| `{problem.name}` | {problem.kind}{f' ({cases} cases)' if cases > 1 else ''} | {grid} | "
                     + " | ".join(cells) + f" | {cmp.seconds:.2f} |")
    return lines


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("-o", "--output", default=str(ROOT / "results" / "contact_decks"), help="output folder")
    ap.add_argument("--quick", action="store_true", help=f"compare only {', '.join(QUICK_DECKS)}")
    ap.add_argument("--examples", default=str(EXAMPLES), help="folder of the decks and reference outputs")
    ap.add_argument("--page", help="also replace the generated part of this page (docs/contact_decks.md)")
    args = ap.parse_args(argv)
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    results, comparisons, records = [], [], []
    for deck in decks_in(Path(args.examples)):
        r = rollcontact.import_contact(deck, out / "imports" / deck.name.split(".")[0], overwrite=True)
        results.append(r)
        ref_path = reference_of(deck)
        if ref_path is None or (args.quick and r.deck.name not in QUICK_DECKS):
            continue
        reference = read_refout(ref_path)
        folder = out / "imports" / r.deck.name
        for problem in r.converted:
            scene = rollcontact.load_scene(folder / f"{problem.name}.toml")
            cmp = compare_problem(problem, scene, reference)
            comparisons.append((r.deck.name, problem, cmp))
            records.append({"deck": r.deck.name, "scene": problem.name, "kind": problem.kind, "status": cmp.status,
                            "grid": list(cmp.grid), "cpu_seconds": cmp.seconds, "rows": cmp.rows})
            print(f"{problem.name}: {cmp.status}, {cmp.seconds:.2f} s CPU, largest differences (%): "
                  + ", ".join(f"{q} {v:.3g}" for q, v in cmp.largest().items()), flush=True)
    machine = f"{platform.machine()}, {os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}"
    stamp = f"`benchmarks/contact_decks.py{' --quick' if args.quick else ''}`, {datetime.date.today()}, {machine}"
    lines = [f"Generated by {stamp}.", "", "**Compatibility** (cases the reference program computes; R = 2, 3 "
             "cases compute nothing):", ""] + compatibility(results)
    lines += ["", "**Differences** from the reference output, largest over the cases of each scene, in per cent "
              "(forces and MZ of mu FN; the traction's rms of PMAX and mu PMAX; the others of the reference value):",
              ""] + comparison_table(comparisons)
    text = "\n".join(lines) + "\n"
    (out / "contact_decks_tables.md").write_text(text)
    (out / "contact_decks.json").write_text(json.dumps({"generated": stamp, "comparisons": records,
                                                        "decks": [r.manifest() for r in results]}, indent=1) + "\n")
    if args.page:
        page = Path(args.page)
        body = page.read_text()
        if BEGIN not in body or END not in body:
            raise SystemExit(f"{page}: no markers {BEGIN} ... {END}")
        head, rest = body.split(BEGIN, 1)
        page.write_text(head + BEGIN + "\n" + text + END + rest.split(END, 1)[1])
    print(f"written {out / 'contact_decks_tables.md'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""What the scripts of the study pages share: options, the commands they run, the tables they write, and the
comparison of those tables with the page.

A study script (docs/scripts/<page>.py) runs the `rollcontact` commands behind its page into a folder the user
chooses (-o OUT, default results/<page>/; nothing is written anywhere else unless --figures names a folder), writes
the page's tables to OUT/tables.md and its figures to OUT/figures/ (or --figures DIR), and then compares the tables
with the page: every table of the page between

    <!-- table NAME: tolerance 0.0005 -->        (absolute; "tolerance 1 %": relative; "tolerance 1 digit": one
                                                  unit of the last digit the page prints)
    | ... |
    <!-- end table -->

is the script's table NAME, number by number within the tolerance, text (states) exactly. `--quick` computes a
few cells of each table with the same settings (the others are written "…") in seconds, for the test suite
(tests/test_docs_pages.py) and for a first look.
"""
from __future__ import annotations

import argparse
from dataclasses import dataclass, field
from pathlib import Path
import re
import shlex
import shutil
import subprocess
import sys
import time

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
#: the console script of the interpreter running the study (the venv's rollcontact)
RC = Path(sys.executable).parent / "rollcontact"
#: a cell the quick mode did not compute
SKIPPED = "…"

_NUMBER = re.compile(r"[-+−]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_BLOCK = re.compile(r"<!-- table (?P<name>[\w-]+)(?::\s*(?P<spec>[^>]*?))?\s*-->\n(?P<body>.*?)\n?<!-- end table -->",
                    re.S)


@dataclass
class Study:
    """One study page's reproduction: the options, the output folder and the tables written so far."""
    page: str                                   # the page's name: docs/<page>.md
    args: argparse.Namespace
    tables: dict = field(default_factory=dict)  # name -> (header, rows)
    started: float = field(default_factory=time.perf_counter)

    @classmethod
    def from_command_line(cls, page: str, doc: str, argv=None, extra=None) -> "Study":
        ap = argparse.ArgumentParser(description=doc.strip().splitlines()[0],
                                     epilog=f"Reproduces the tables and figures of docs/{page}.md.")
        ap.add_argument("-o", "--output", type=Path, default=Path("results") / page,
                        help=f"folder of the runs, tables.md and figures/ (default: results/{page}/)")
        ap.add_argument("--figures", type=Path, default=None,
                        help="folder of the figures (default: OUT/figures; the page's own: see the page)")
        ap.add_argument("--quick", action="store_true", help="a few cells of each table, in seconds")
        ap.add_argument("--jobs", type=int, default=None, help="worker processes of sweeps and limit searches "
                                                                 "(default: the number of cores)")
        if extra:
            extra(ap)
        args = ap.parse_args(argv)
        if args.quick and args.jobs is None:
            args.jobs = 1                    # a few runs: worker processes would cost more than they save
        args.output.mkdir(parents=True, exist_ok=True)
        args.figures = args.figures or args.output / "figures"
        args.figures.mkdir(parents=True, exist_ok=True)
        return cls(page, args)

    @property
    def out(self) -> Path:
        return self.args.output

    @property
    def quick(self) -> bool:
        return self.args.quick

    def rc(self, *argv, capture=False) -> str:
        """Run `rollcontact ARGV...` (printed as the user would type it); its standard output if `capture`."""
        argv = [str(a) for a in argv]
        if self.args.jobs is not None and argv[0] in ("sweep", "limit-search"):
            argv += ["--jobs", str(self.args.jobs)]
        print("$ .venv/bin/rollcontact " + shlex.join(argv), file=sys.stderr, flush=True)
        proc = subprocess.run([str(RC), *argv], text=True, check=False,
                              stdout=subprocess.PIPE if capture else None)
        if proc.returncode != 0:
            raise SystemExit(f"rollcontact {argv[0]} failed (exit code {proc.returncode})")
        return proc.stdout if capture else ""

    def python(self, script, *argv) -> None:
        """Run another script of the repository (a benchmark) with this interpreter."""
        argv = [str(a) for a in argv]
        print(f"$ .venv/bin/python {script} " + shlex.join(argv), file=sys.stderr, flush=True)
        subprocess.run([sys.executable, str(ROOT / script), *argv], check=True)

    def figure(self, source: Path, name: str) -> Path:
        """Copy a PNG written by a command into the figures folder under the page's name for it."""
        target = self.args.figures / name
        shutil.copyfile(source, target)
        return target

    def table(self, name: str, header: list, rows: list) -> None:
        """Add table NAME (cells are strings; SKIPPED where the quick mode did not compute one)."""
        self.tables[name] = ([str(h) for h in header], [[str(c) for c in row] for row in rows])

    def finish(self) -> int:
        """Write OUT/tables.md, compare it with the page, print the verdict; the exit code (0: reproduced)."""
        text = render(self.tables)
        path = self.out / "tables.md"
        path.write_text(text)
        minutes = (time.perf_counter() - self.started) / 60
        print(f"tables written to {path.resolve()}, figures in {self.args.figures.resolve()} ({minutes:.1f} min)")
        report = compare((DOCS / f"{self.page}.md").read_text(), text)
        print(report.summary(f"docs/{self.page}.md"))
        return 0 if report.ok else 1


def render(tables: dict) -> str:
    """The tables as Markdown between the markers the pages use (without tolerances: the page states them)."""
    parts = []
    for name, (header, rows) in tables.items():
        lines = [f"<!-- table {name} -->", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
        lines += ["| " + " | ".join(row) + " |" for row in rows]
        parts.append("\n".join(lines + ["<!-- end table -->"]))
    return "\n\n".join(parts) + "\n"


def parse(text: str) -> dict:
    """name -> (spec, rows of cells) of the marked tables of a page or of a tables.md (the separator row dropped)."""
    out = {}
    for m in _BLOCK.finditer(text):
        rows = [[c.strip() for c in ln.strip().strip("|").split("|")] for ln in m["body"].splitlines()
                if ln.strip().startswith("|")]
        rows = [r for r in rows if not all(set(c) <= set("-: ") for c in r)]
        out[m["name"]] = (m["spec"] or "", rows)
    return out


def tolerance(spec: str) -> tuple[float, str]:
    """(value, kind) from a marker's 'tolerance 0.0005' (kind 'abs'), 'tolerance 1 %' ('rel') or 'tolerance 1 digit'
    ('digit': that many units of the last digit the page prints); no tolerance: exact."""
    m = re.search(r"tolerance\s+([0-9.eE+-]+)\s*(%|digits?)?", spec)
    if not m:
        return 0.0, "abs"
    value = float(m.group(1))
    kind = {"%": "rel", None: "abs"}.get(m.group(2), "digit")
    return (value / 100 if kind == "rel" else value), kind


def last_digit(text: str) -> float:
    """One unit of the last digit of a printed number: '0.045' -> 0.001, '3.2e-04' -> 1e-05, '12' -> 1."""
    mantissa, _, exponent = text.replace("−", "-").lower().partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 10.0 ** (-decimals + (int(exponent) if exponent else 0))


def numbers(cell: str) -> tuple[list, str]:
    """The numbers of a cell as (value, printed text), and the cell's text with the numbers taken out."""
    found = [(float(x.replace("−", "-")), x) for x in _NUMBER.findall(cell)]
    return found, " ".join(_NUMBER.sub("#", cell).split())


@dataclass
class Report:
    compared: int = 0
    skipped: int = 0
    worst: tuple = (0.0, "")
    problems: list = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.problems

    def summary(self, page: str) -> str:
        head = (f"{page}: {self.compared} numbers compared, {self.skipped} cells not computed (quick)"
                + (f"; largest difference {self.worst[0]:.3g} ({self.worst[1]})" if self.compared else ""))
        if self.ok:
            return head + ": the page is reproduced."
        return head + ":\n  " + "\n  ".join(self.problems[:40])


def compare(page_text: str, tables_text: str) -> Report:
    """Compare the tables of a run (tables.md) with the marked tables of the page (their tolerances)."""
    page, ours = parse(page_text), parse(tables_text)
    report = Report()
    for name in sorted(set(page) | set(ours)):
        if name not in ours:
            report.problems.append(f"table {name}: on the page, not written by the script")
            continue
        if name not in page:
            report.problems.append(f"table {name}: written by the script, not on the page")
            continue
        spec, want = page[name]
        _, got = ours[name]
        tol, kind = tolerance(spec)
        if len(want) != len(got) or any(len(a) != len(b) for a, b in zip(want, got)):
            report.problems.append(f"table {name}: {len(got)} rows on the run, {len(want)} on the page "
                                   "(or a row of another length)")
            continue
        for i, (row_want, row_got) in enumerate(zip(want, got)):
            for j, (w, g) in enumerate(zip(row_want, row_got)):
                if g == SKIPPED:
                    report.skipped += 1
                    continue
                nw, tw = numbers(w)
                ng, tg = numbers(g)
                where = f"table {name}, row {i}, column {j}"
                if tw != tg or len(nw) != len(ng):
                    report.problems.append(f"{where}: page {w!r}, run {g!r}")
                    continue
                for (a, text), (b, _) in zip(nw, ng):
                    if kind == "rel":
                        diff, limit = abs(a - b) / (abs(a) or 1.0), tol
                    elif kind == "digit":
                        diff, limit = abs(a - b) / last_digit(text), tol
                    else:
                        diff, limit = abs(a - b), tol
                    report.compared += 1
                    if diff > report.worst[0]:
                        report.worst = (diff, where)
                    if diff > limit * (1 + 1e-9) + 1e-15:
                        report.problems.append(f"{where}: page {w!r}, run {g!r} (tolerance {spec.strip()})")
    return report


def fmt(value, digits=4) -> str:
    """A number as the tables print it (fixed digits; '-' for None)."""
    if value is None:
        return "-"
    return f"{value:.{digits}f}"


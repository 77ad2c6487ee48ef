"""docs/scene_reference.md and docs/hdf5_schema.md, generated from the code.

    .venv/bin/python docs/scripts/reference.py -o docs           # refresh the committed pages
    .venv/bin/python docs/scripts/reference.py [-o DIR]          # write them to DIR (default results/reference/)
    .venv/bin/python docs/scripts/reference.py --check           # exit 1 if the committed pages are stale

The scene reference comes from the field metadata of cases/scene/keys.py (meaning, unit, default, allowed range,
the kinds of run a key applies to) and the shapes of cases/scene/geometry.py; the HDF5 schema from the unit tables of
cases/results/run_result.py with the meanings of cases/results/schema.py, and the sweep tables of
cases/sweep/table.py and cases/sweep/limit_search.py. tests/test_reference_pages.py fails when a page is stale.
"""
from __future__ import annotations

import argparse
from dataclasses import MISSING, fields
import math
from pathlib import Path
import sys

DOCS = Path(__file__).resolve().parents[1]
PAGES = ("scene_reference.md", "hdf5_schema.md")
COMMAND = ".venv/bin/python docs/scripts/reference.py -o docs"


def _number(v) -> str:
    if isinstance(v, float):
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return f"{v:g}"
    return str(v)


def _default(f) -> str:
    if f.default is not MISSING:
        v = f.default
    elif f.default_factory is not MISSING:
        v = f.default_factory()
    else:
        return "required"
    if v is None:
        return "—"
    if isinstance(v, str):
        return f'`"{v}"`'
    if isinstance(v, list):
        return "`[]`" if not v else f"`{v}`"
    return f"`{_number(v)}`"


def _allowed(f) -> str:
    m = f.metadata
    if m.get("choices"):
        return ", ".join(f'`"{c}"`' for c in m["choices"])
    lo, hi = m.get("lo"), m.get("hi")
    if lo is None and hi is None:
        return "text" if "str" in str(f.type) else "any"
    kind = "integers" if str(f.type) == "int" else ("list of values" if f.name == "levels" else "")
    left, right = ("(" if m["lo_open"] else "["), (")" if m["hi_open"] else "]")
    return f"{kind} {left}{_number(lo)}, {_number(hi)}{right}".strip()


def _cell(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def scene_reference() -> str:
    """The scene reference page (Markdown)."""
    from rollcontact.cases.scene import keys
    from rollcontact.cases.scene.geometry import AXISYMMETRIC, OPTIONAL, SHAPE_KEYS
    from rollcontact.cases.scene.limits import (MAX_RESOLUTION_PER_RADIUS, MAX_STEPS, MIN_ELEMENTS_PER_RADIUS,
                                               RESOLUTION_PER_ANNULUS, RESOLUTION_PER_RADIUS)
    out = ["# Scene reference", "",
           f"*Generated from the code by `{COMMAND}`; do not edit by hand (tests/test_reference_pages.py checks it).*",
           "",
           "A scene is a TOML file of the sections below; only `[geometry]` is required, and a key left out takes its "
           "default. Any key can be overridden from the command line, `--set section.key=value`, or from Python, "
           "`rollcontact.load_scene(path, overrides={\"section.key\": value})`. A key that is unknown, of the wrong "
           "type or out of its range is refused before any work (`SceneError`, exit code 2) with the key and the "
           "allowed range named. Units: mm, N, MPa, mm/s, degrees; a blank unit is dimensionless. Signs and "
           "normalisations: docs/theory.md §0.",
           "", "**Kinds of run** (the column *applies to*):", ""]
    out += [f"* `{name}`: {text}" for name, text in keys.MODES.items()]
    out += ["", "A key given in a kind of run it does not apply to is refused where it would change the meaning "
            "(e.g. `[load] ft` with `[rolling]`) and otherwise has no effect.", ""]
    for sec, cls in keys.SECTIONS.items():
        text = keys.SECTION_DOCS.get(sec, "")
        out += [f"## [{sec}]", "", (text[:1].upper() + text[1:] + ".") if text else "", "",
                "| key | meaning | unit | default | allowed | applies to |", "|---|---|---|---|---|---|"]
        for f in fields(cls):
            m = f.metadata
            modes = keys.key_modes(sec, f)
            applies = "all" if set(modes) == set(keys.ALL_MODES) else ", ".join(modes)
            out.append(f"| `{f.name}` | {_cell(m.get('doc', ''))} | {m.get('unit') or ''} | {_default(f)} | "
                       f"{_allowed(f)} | {applies} |")
        out.append("")
        if sec == "geometry":
            out += ["The keys each shape takes (`shape` left out: `\"sphere\"` with `R`, `\"ellipsoid\"` with `Rx` and "
                    "`Ry`); any other geometry key is refused:", "", "| shape | keys | optional (default) | MDR model |",
                    "|---|---|---|---|"]
            for shape, names in SHAPE_KEYS.items():
                optional = ", ".join(f"`{k}` ({OPTIONAL[k] if OPTIONAL[k] is not None else 'from the file'})"
                                     for k in names if k in OPTIONAL)
                out.append(f"| `{shape}` | {', '.join(f'`{k}`' for k in names)} | {optional} | "
                           f"{'yes' if shape in AXISYMMETRIC else 'no'} |")
            out.append("")
        if sec == "grid":
            out += [f"A grid left out has dx = a/{RESOLUTION_PER_RADIUS} (a the smaller Hertz semi-axis, or the shape's "
                    f"contact radius) to two digits, and `motion.dW` = dx; a tangential force oscillating at constant Fn "
                    f"without rolling gets {RESOLUTION_PER_ANNULUS} elements across its slip annulus, at most "
                    f"a/{MAX_RESOLUTION_PER_RADIUS}. A grid coarser than a/{MIN_ELEMENTS_PER_RADIUS} is refused, and so "
                    f"is a load path of more than {MAX_STEPS} steps.", ""]
    return "\n".join(out).rstrip() + "\n"


def hdf5_schema() -> str:
    """The HDF5 schema page (Markdown)."""
    from rollcontact.cases.results import schema
    from rollcontact.cases.sweep.limit_search import LIMIT_COLUMNS
    from rollcontact.cases.sweep.table import COLUMN_UNITS, CREEP_COLUMNS, SUMMARY_COLUMNS
    out = ["# HDF5 schema of a run file", "",
           f"*Generated from the code by `{COMMAND}`; do not edit by hand (tests/test_reference_pages.py checks it).*",
           "",
           "A run file (`rollcontact run`, `rollcontact.run(scene, path)`) holds the groups below. Every dataset carries "
           "a `units` attribute with the unit given here (`-`: a count, a flag, text or a dimensionless value). Steps "
           "are numbered from 0 (step 0: the normal load alone). Signs as in docs/theory.md §0: p and τ act on the "
           "substrate, u is the substrate relative to the sphere, U the sphere's rigid shift; a [rolling] run's "
           "summary uses Kalker's convention instead (forces on the rolling sphere). `rollcontact.read_run(path)` "
           "reads a file back into a `RunResult` (`history`, `fields`, `summary`) with the same names.",
           "",
           "Files are written atomically (a temporary file, then a rename). A summary value that does not apply is "
           "NaN, or −1 for a count; `read_run` returns None for both. Later versions add names, never rename them.",
           ""]
    for path, kind, rows in schema.groups():
        shape = {"/history": "one value per step", "/fields": "shape (stored steps, ny, nx)",
                 "/subsurface": "shape (computed steps, nz, ny, nx) for the stresses",
                 "/grid": "the cell centres",
                 "/patches/<k>/fields": "shape (1, ny, nx) on the patch's grid in its tangent plane"}.get(path, "")
        title = f"## `{path}` {kind}" + (f" ({shape})" if shape and kind == "datasets" else "")
        out += [title, "", "| name | unit | meaning |", "|---|---|---|"]
        out += [f"| `{name}` | {unit} | {_cell(text)} |" for name, unit, text in rows]
        out.append("")
        if path == "/subsurface" and kind == "datasets":
            out += ["Written by `rollcontact stresses` or `run --stresses` (kept meanwhile, step by step, in "
                    "`RUN.h5.subsurface/step_<N>.h5`); computing again replaces the group.", ""]
    out += ["## Sweep and limit-search tables", "",
            "`rollcontact sweep` writes `OUTDIR/summary.csv` and `OUTDIR/summary.h5`, `rollcontact limit-search` "
            "`OUTDIR/limits.csv` and `OUTDIR/limits.h5`: one row per run (or searched combination), the varied keys "
            "first (each with its scene unit), then the columns below. In the HDF5 table each column is a dataset "
            "`/runs/<column>` with its `units` attribute; missing values are empty CSV cells, NaN or −1.", "",
            "| table | columns (unit where not `-`) |", "|---|---|"]

    def cols(names):
        return ", ".join(f"`{c}`" + (f" ({COLUMN_UNITS[c]})" if c in COLUMN_UNITS else "") for c in names)

    out += [f"| summary | {cols(SUMMARY_COLUMNS)}; a sweep over a [rolling] scene adds {cols(CREEP_COLUMNS)} |",
            f"| limits | {cols(LIMIT_COLUMNS)} |", ""]
    return "\n".join(out).rstrip() + "\n"


def pages() -> dict:
    return {"scene_reference.md": scene_reference(), "hdf5_schema.md": hdf5_schema()}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    ap.add_argument("-o", "--output", type=Path, default=Path("results") / "reference",
                    help="folder to write the pages to (default results/reference/; the committed ones: -o docs)")
    ap.add_argument("--check", action="store_true", help="compare with the committed pages; exit 1 if stale")
    args = ap.parse_args(argv)
    generated = pages()
    if args.check:
        stale = [name for name, text in generated.items() if (DOCS / name).read_text() != text]
        for name in stale:
            print(f"docs/{name} is stale: run {COMMAND}")
        return 1 if stale else 0
    args.output.mkdir(parents=True, exist_ok=True)
    for name, text in generated.items():
        (args.output / name).write_text(text)
        print(args.output / name)
    return 0


if __name__ == "__main__":
    sys.exit(main())

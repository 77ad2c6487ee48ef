"""How long `import-contact` takes on the reference program's published decks (target: under a second each).

    .venv/bin/python benchmarks/contact_import_speed.py [--quick] [-o DIR]

Per deck (tests/data/contact_examples): the CPU time of `rollcontact.import_contact(deck)` without writing (median of
--repeat runs in this process, warm: modules loaded, the profile files' checksums cached), of reading the deck alone
(`read_deck`: the floor every import pays) and their ratio; and once, the command `rollcontact import-contact DECK -o
DIR` as a fresh process (cold: the interpreter, rollcontact's modules and numpy/scipy loaded, files written), CPU time
of the child (user + system) and wall time. --quick: three decks (the smallest, the longest, a wheel-rail one), 3
repeats. Written to DIR (default results/contact_import_speed/): contact_import_speed.json.
"""
from __future__ import annotations

import argparse
import json
import os
from pathlib import Path
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import rollcontact
from rollcontact.cases.decks.deck import read_deck

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "tests" / "data" / "contact_examples"
QUICK = ("cattaneo", "catt_to_cart", "mbench_a22_right")


def cpu(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.process_time()
        fn()
        times.append(time.process_time() - t0)
    return statistics.median(times)


def cold_command(deck: Path) -> tuple[float, float]:
    """(CPU s of the child, wall s) of `rollcontact import-contact deck -o <tmp>` in a fresh process."""
    exe = Path(sys.executable).with_name("rollcontact")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        subprocess.run([str(exe), "import-contact", str(deck), "-o", tmp], check=True, capture_output=True)
        wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), wall


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help=f"only {', '.join(QUICK)}, 3 repeats")
    ap.add_argument("--repeat", type=int, default=None, help="repeats of the warm timings (default 7, quick 3)")
    ap.add_argument("-o", "--output", default=str(ROOT / "results" / "contact_import_speed"), help="output folder")
    args = ap.parse_args(argv)
    repeat = args.repeat or (3 if args.quick else 7)
    decks = sorted(EXAMPLES.glob("*.inp.gz"))
    if args.quick:
        decks = [d for d in decks if d.name.split(".")[0] in QUICK]
    rollcontact.import_contact(decks[0])                  # load the modules once: the warm timings follow
    rows = []
    print(f"{'deck':<20} {'cases':>5} {'import ms':>10} {'read ms':>8} {'ratio':>6} {'command cold s (CPU/wall)':>26}")
    for deck in decks:
        n = len(read_deck(deck).cases)
        t_import = cpu(lambda: rollcontact.import_contact(deck), repeat)
        t_read = cpu(lambda: read_deck(deck), repeat)
        cold_cpu, cold_wall = cold_command(deck)
        rows.append({"deck": deck.name.split(".")[0], "cases": n, "import_cpu_s": t_import, "read_cpu_s": t_read,
                     "ratio": t_import / t_read, "command_cold_cpu_s": cold_cpu, "command_cold_wall_s": cold_wall})
        r = rows[-1]
        print(f"{r['deck']:<20} {n:>5} {1e3 * t_import:>10.1f} {1e3 * t_read:>8.1f} {r['ratio']:>6.1f} "
              f"{cold_cpu:>16.2f} / {cold_wall:.2f}", flush=True)
    slowest = max(rows, key=lambda r: r["command_cold_cpu_s"])
    machine = {"machine": platform.machine(), "processor": platform.processor(), "cores": os.cpu_count(),
               "load": os.getloadavg()[0], "python": platform.python_version()}
    print(f"slowest command: {slowest['deck']} {slowest['command_cold_cpu_s']:.2f} s CPU cold; slowest warm import "
          f"{max(r['import_cpu_s'] for r in rows):.3f} s CPU; load {machine['load']:.1f}")
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    (out / "contact_import_speed.json").write_text(json.dumps({"machine": machine, "repeat": repeat, "rows": rows},
                                                              indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""What every benchmark's JSON records, and where it goes (shared by the scripts of benchmarks/).

    import _record
    parser = _record.parser(__doc__)                # adds -o/--output DIR (default results/benchmarks/)
    args = parser.parse_args()
    ...
    path = _record.write("normal_hertz", data, args.output)

`write` adds a "recorded" entry to the data: the date (UTC), the machine (CPU model, cores), the load (the
1-, 5- and 15-minute load averages of `uptime` before and after the measurement), the command line and the
versions of Python, NumPy, SciPy, numba, pyFFTW, h5py and rollcontact (and the git commit when the scripts run
from a checkout). Timings taken on a loaded machine are inflated: read them with the load beside them.

No benchmark writes into the repository unless asked: the default folder is results/benchmarks/ of the working
directory (ignored by git); the committed figures of benchmarks/results/ are refreshed with `-o benchmarks/results`.
"""
from __future__ import annotations

import argparse
from datetime import datetime, timezone
from importlib import metadata
import json
import os
from pathlib import Path
import platform
import subprocess
import sys

ROOT = Path(__file__).resolve().parents[1]
#: the folder benchmarks write to when -o is not given (relative to the working directory; git ignores results/)
DEFAULT_DIR = Path("results") / "benchmarks"
#: the folder of the committed figures that benchmarks/README.md quotes
COMMITTED_DIR = ROOT / "benchmarks" / "results"
PACKAGES = ("numpy", "scipy", "numba", "pyfftw", "h5py", "matplotlib", "rollcontact")

_LOAD_AT_START = os.getloadavg()


def parser(doc: str | None, **kwargs) -> argparse.ArgumentParser:
    """An ArgumentParser with the shared -o/--output folder option (the first line of `doc` as description)."""
    description = (doc or "").strip().splitlines()[0] if doc else None
    ap = argparse.ArgumentParser(description=description, **kwargs)
    add_output(ap)
    return ap


def add_output(ap: argparse.ArgumentParser) -> None:
    """Add -o/--output DIR to an existing parser."""
    ap.add_argument("-o", "--output", type=Path, default=DEFAULT_DIR,
                    help=f"folder of the JSON (and figures) (default: {DEFAULT_DIR}/; the committed figures: "
                         "-o benchmarks/results)")


def machine() -> dict:
    """CPU model, number of cores, operating system."""
    model = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"cpu": model, "cores": os.cpu_count(), "system": f"{platform.system()} {platform.release()}"}


def versions() -> dict:
    """Python and the installed versions of the packages the measurements depend on."""
    out = {"python": platform.python_version()}
    for name in PACKAGES:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = None
    try:
        out["git_commit"] = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], text=True,
                                           capture_output=True, timeout=10).stdout.strip() or None
    except (OSError, subprocess.SubprocessError):
        out["git_commit"] = None
    return out


def recorded() -> dict:
    """The record of one measurement: date, machine, load (at start and now), command, versions."""
    return {"date": datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "machine": machine(),
            "load": {"start": [round(v, 2) for v in _LOAD_AT_START],
                     "end": [round(v, 2) for v in os.getloadavg()]},
            "command": " ".join([Path(sys.argv[0]).as_posix()] + sys.argv[1:]),
            "versions": versions()}


def write(name: str, data: dict, folder=None) -> Path:
    """Write `data` with its record to FOLDER/<name>.json (the folder created); return the path."""
    folder = Path(folder if folder is not None else DEFAULT_DIR)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}.json"
    data = dict(data)
    data["recorded"] = recorded()
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(json.dumps(data, indent=1, default=float) + "\n")
    os.replace(tmp, path)
    print(f"written {path}", file=sys.stderr)
    return path


def read(name: str, folder=None) -> dict:
    """The JSON `name` of FOLDER (default: the committed benchmarks/results/)."""
    folder = Path(folder) if folder is not None else COMMITTED_DIR
    return json.loads((folder / f"{name}.json").read_text())

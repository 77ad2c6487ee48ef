"""FFTW wisdom cached on disk, so that FFTW_MEASURE plans are measured once per machine (`bem.operator`).

The file is ROLLCONTACT_CACHE/fftw-wisdom.pkl, or $XDG_CACHE_HOME/rollcontact (default ~/.cache/rollcontact). It is
read once per process and written back only when the process plans a transform for the first time (exporting the
wisdom costs milliseconds); a read-only or missing cache only costs planning time.
"""
import os
import pickle
import threading
from pathlib import Path


#: serialises planning and the wisdom file's import and export within a process
lock = threading.Lock()
_loaded = set()    # wisdom files imported by this process
_planned = set()   # (k, shape, threads, planner) planned by this process: their wisdom is on disk


def wisdom_file() -> Path:
    root = os.environ.get("ROLLCONTACT_CACHE") or os.path.join(
        os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "rollcontact")
    return Path(root) / "fftw-wisdom.pkl"


def load():
    path = wisdom_file()
    if path in _loaded:
        return
    _loaded.add(path)
    try:
        with open(path, "rb") as fh:
            from rollcontact.bem._fftw import pyfftw
            pyfftw.import_wisdom(pickle.load(fh))
    except (OSError, pickle.UnpicklingError, EOFError, TypeError, ValueError):
        pass


def _save():
    """Write the wisdom through a per-process temporary file and an atomic rename. The temporary file is removed
    when the write fails or is interrupted, and those of processes that died while writing (a sweep worker
    killed by SIGTERM) are removed by the next save."""
    path = wisdom_file()
    tmp = path.with_suffix(f".{os.getpid()}.tmp")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        with open(tmp, "wb") as fh:
            from rollcontact.bem._fftw import pyfftw
            pickle.dump(pyfftw.export_wisdom(), fh)
        os.replace(tmp, path)
    except OSError:
        pass  # a read-only home only costs planning time
    finally:
        _unlink(tmp)
    _remove_orphaned_temporaries(path)


def _remove_orphaned_temporaries(path):
    """Remove <wisdom>.<pid>.tmp files whose process no longer exists."""
    for tmp in path.parent.glob(path.stem + ".*.tmp"):
        try:
            pid = int(tmp.name[len(path.stem) + 1:-len(".tmp")])
        except ValueError:
            continue
        if pid != os.getpid() and not process_exists(pid):
            _unlink(tmp)


def _unlink(path):
    try:
        path.unlink(missing_ok=True)
    except OSError:
        pass


def process_exists(pid: int) -> bool:
    """True while a process with this pid exists (also another user's)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True  # another user's process (or an impossible pid): leave its file alone
    return True


def save_if_new(keys):
    """Write the wisdom back when `keys` (k, shape, threads, planner) hold a transform not planned before by this
    process. Call under `lock`, after planning."""
    if not keys <= _planned:
        _planned.update(keys)
        _save()

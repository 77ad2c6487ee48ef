"""The on-disk FFTW wisdom cache (bem.wisdom): an atomic write that leaves no temporary file behind, also when the
write fails or is interrupted, and removal of the temporary files of processes that died while writing (a sweep
worker killed by SIGTERM during the save left one 0.3 MB file per kill in ~/.cache/rollcontact)."""
import os
import pickle
import subprocess
import sys

import pytest

from rollcontact.bem import wisdom as _wisdom


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ROLLCONTACT_CACHE", str(tmp_path))
    return tmp_path


def dead_pid():
    out = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True,
                         check=True)
    return int(out.stdout)


def test_a_save_writes_the_wisdom_and_removes_only_orphaned_temporaries(cache):
    orphan = cache / f"fftw-wisdom.{dead_pid()}.tmp"
    alive = cache / f"fftw-wisdom.{os.getppid()}.tmp"     # a live process's write in progress: kept
    other = cache / "fftw-wisdom.notapid.tmp"
    for f in (orphan, alive, other):
        f.write_bytes(b"partial")
    _wisdom.save_if_new({("test_wisdom", str(cache))})  # a key this process has not planned: it saves
    assert pickle.loads((cache / "fftw-wisdom.pkl").read_bytes())  # FFTW's wisdom tuple
    assert sorted(p.name for p in cache.iterdir()) == sorted(["fftw-wisdom.pkl", alive.name, other.name])


@pytest.mark.parametrize("error", [OSError("disk full"), KeyboardInterrupt()])
def test_a_failed_or_interrupted_save_leaves_no_temporary_file(cache, monkeypatch, error):
    def dump(obj, fh):
        fh.write(b"half")
        raise error

    monkeypatch.setattr(_wisdom.pickle, "dump", dump)
    if isinstance(error, OSError):
        _wisdom._save()                       # a cache that cannot be written only costs planning time
    else:
        with pytest.raises(KeyboardInterrupt):
            _wisdom._save()
    assert list(cache.iterdir()) == []

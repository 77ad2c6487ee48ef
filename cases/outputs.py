"""Where `rollcontact run` writes: the -o file, checked before the run so no computation is wasted."""
from __future__ import annotations

import os
from pathlib import Path
import tempfile

from bem.errors import InputError


def check_output(path) -> Path:
    """`path` as a Path if a run file can be written there; InputError naming -o otherwise.

    Refused: an existing directory (or a name ending in a path separator), a parent that is a file, and a
    folder where no file can be created (probed with a temporary file, which is removed at once; missing
    parent folders are created, as writing the run would).
    """
    raw = str(path)
    p = Path(path)
    if p.is_dir() or raw.endswith(("/", os.sep)):
        raise InputError(f"-o {raw}: is a directory; give a file name, e.g. -o {p / 'run.h5'}")
    parent = p.parent
    try:
        parent.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".probe", dir=parent)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        why = exc.strerror or type(exc).__name__
        raise InputError(f"-o {raw}: cannot write in {parent} ({why}); choose a writable location") from None
    return p

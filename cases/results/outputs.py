"""Where `rollcontact run` writes: the -o file (checked before the run, so no computation is wasted) and the
default file name when -o is left out."""
from __future__ import annotations

import hashlib
import os
from pathlib import Path
import re
import tempfile

from rollcontact.bem.errors import InputError
from rollcontact.cases.arguments import arg


def output_folder(path, option="output") -> Path:
    """The output folder `path` of sweep, limit-search, plot and compare, created if missing; InputError naming
    the option (an API keyword, cases.arguments) when it (or a parent) is an existing file, or when it cannot be
    created (a read-only file system, a full disk)."""
    folder = Path(path)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except (FileExistsError, NotADirectoryError):
        raise InputError(f"{arg(option)} {path}: is a file (or lies under one), not a folder; give a folder "
                         "name") from None
    except OSError as exc:
        raise InputError(f"{arg(option)} {path}: cannot create the folder ({exc.strerror}); choose a writable "
                         "location") from None
    return folder


def check_output(path) -> Path:
    """`path` as a Path if a run file can be written there; InputError naming the output (-o) otherwise.

    Refused: an existing directory (or a name ending in a path separator), a parent that is a file, and a
    folder where no file can be created (probed with a temporary file, which is removed at once; missing
    parent folders are created, as writing the run would).
    """
    raw = str(path)
    p = Path(path)
    if p.is_dir() or raw.endswith(("/", os.sep)):
        raise InputError(f"{arg('output')} {raw}: is a directory; give a file name, e.g. {arg('output')} "
                         f"{p / 'run.h5'}")
    parent = p.parent
    try:
        parent.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".probe", dir=parent)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        why = exc.strerror or type(exc).__name__
        raise InputError(f"{arg('output')} {raw}: cannot write in {parent} ({why}); choose a writable location") from None
    return p


#: Longest file stem derived from the overrides; a longer one is cut and made unique by a hash of them.
_MAX_STEM = 120


def default_output(scene_name: str, overrides=(), restart_step: int | None = None) -> Path:
    """results/<scene>.h5, or for a variant a name that says what differs, so that no variant silently
    overwrites the plain scene's file: results/<scene>__<key=value>__....h5 with the --set overrides
    (characters other than letters, digits and . _ = + - replaced by -), and __from_step<N> for a restart.
    """
    parts = [scene_name]
    if restart_step is not None:
        parts.append(f"from_step{restart_step}")
    parts += [re.sub(r"[^A-Za-z0-9._=+-]", "-", re.sub(r"[\s\"']", "", item)) for item in overrides]
    stem = "__".join(parts)
    if len(stem) > _MAX_STEM:
        digest = hashlib.sha1("\n".join(overrides).encode()).hexdigest()[:8]
        stem = f"{stem[:_MAX_STEM - 10]}__{digest}"
    return Path("results") / f"{stem}.h5"


def free_name(path) -> Path:
    """`path`, or the first of <stem>-2<suffix>, <stem>-3<suffix>, ... that does not exist (nor its lock file)."""
    path = Path(path)
    candidate, n = path, 1
    while candidate.exists() or candidate.with_name(candidate.name + ".lock").exists():
        n += 1
        candidate = path.with_name(f"{path.stem}-{n}{path.suffix}")
    return candidate

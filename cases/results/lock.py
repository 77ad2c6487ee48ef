"""One writer per output: an exclusive lock on `<output>.lock` while a run or a summary is written.

The lock file names its holder (pid, host, start time, command) for the message a second writer gets, and the
holder keeps an OS lock (flock) on it: the OS releases that lock when the process ends in any way, kill -9
included, so a lock left by a dead process is taken over by the next writer without any guessing. Where the
file system offers no flock (some network file systems), the lock falls back to the file's content: a holder
on this host whose pid no longer exists is stale and taken over; one on another host is refused, naming the
file to remove once that process is known to be gone.
"""
from __future__ import annotations

import errno
import fcntl
import os
from pathlib import Path
import socket
import sys
import time

from rollcontact.bem.errors import OutputInUseError
from rollcontact.bem.wisdom import process_exists
from rollcontact.cases.results.writing import write_failed


def lock_path(output) -> Path:
    output = Path(output)
    return output.with_name(output.name + ".lock")


def holder_text() -> str:
    """pid host start-time command: what a lock file says of its holder."""
    command = " ".join(os.path.basename(a) if i == 0 else a for i, a in enumerate(sys.argv)) or "python"
    return f"{os.getpid()} {socket.gethostname()} {time.strftime('%Y-%m-%dT%H:%M:%S')} {command}"


def describe_holder(text: str) -> str:
    parts = text.split(" ", 3)
    if len(parts) < 3:
        return "another process (the lock file names none)"
    pid, host, since = parts[:3]
    what = f" ({parts[3].strip()})" if len(parts) > 3 and parts[3].strip() else ""
    return f"process {pid} on host {host}, since {since}{what}"


class OutputLock:
    """Exclusive lock of one output (a run file, a sweep's summary). Use `acquire()` / `release()` or `with`.

    acquire() raises OutputInUseError naming the holder when another live process holds it; `label` is how the
    message names the output (e.g. '-o out.h5')."""

    def __init__(self, output, label=None):
        self.output = Path(output)
        self.path = lock_path(self.output)
        self.label = label or str(self.output)
        self._fd = None

    @property
    def held(self) -> bool:
        return self._fd is not None

    def acquire(self, wait: bool = False) -> "OutputLock":
        """Take the lock; OutputInUseError naming the holder when a live process holds it (with `wait`, wait for
        it instead: for short critical sections such as the check of a sweep's table); OutputWriteError naming the
        lock file when it cannot be written (a read-only file system, a full disk)."""
        try:
            return self._acquire(wait)
        except OSError as exc:
            raise write_failed(self.output, exc, via=f"its lock file {self.path}") from None

    def _acquire(self, wait: bool) -> "OutputLock":
        self.path.parent.mkdir(parents=True, exist_ok=True)
        if not _has_flock(self.path.parent):
            return self._acquire_by_link()
        for _ in range(100):   # the path may be replaced between open and flock by a releasing holder: retry
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
            try:
                got = self._lock(fd, wait)
            except BaseException:
                os.close(fd)
                raise
            if got is None:
                os.close(fd)
                raise OutputInUseError(f"{self.label}: the file system of {self.path} stopped offering locks")
            if not got:
                text = _read(fd)
                os.close(fd)
                raise self._in_use(text)
            if _same_file(fd, self.path):
                os.ftruncate(fd, 0)
                os.pwrite(fd, (holder_text() + "\n").encode(), 0)
                self._fd = fd
                return self
            os.close(fd)       # locked a file that its holder had just removed: take the new one
        raise OutputInUseError(f"{self.label}: could not take the lock file {self.path} (it keeps being replaced)")

    def _in_use(self, text) -> OutputInUseError:
        return OutputInUseError(f"{self.label}: is being written by {describe_holder(text)} (lock file {self.path});"
                                " wait for it to finish, or write to another file")

    @staticmethod
    def _lock(fd, wait) -> bool | None:
        """True: locked; False: held by another; None: this file system has no flock."""
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
            return True
        except BlockingIOError:
            return False
        except OSError as exc:
            if exc.errno in (errno.ENOLCK, errno.EOPNOTSUPP, errno.ENOSYS):
                return None
            raise

    def _acquire_by_link(self) -> "OutputLock":
        """Without flock: the lock file is created whole and atomically (a hard link of a file naming this process),
        and a stale one (a dead process on this host) is renamed away before the next attempt. A holder on
        another host cannot be checked: the message names the file to remove once that process is gone."""
        mine = self.path.with_name(f".{self.path.name}.{os.getpid()}.{socket.gethostname()}.claim")
        mine.write_text(holder_text() + "\n")
        try:
            for _ in range(100):
                try:
                    os.link(mine, self.path)
                    self._fd = os.open(self.path, os.O_RDONLY)
                    return self
                except FileExistsError:
                    text = self.path.read_text() if self.path.exists() else ""
                busy = OutputInUseError(f"{self.label}: is being written by {describe_holder(text)} (lock file "
                                        f"{self.path}, on a file system without flock: if that process is gone, "
                                        "remove the lock file)")
                if not _content_says_free(text):
                    raise busy
                stale = mine.with_suffix(".stale")
                try:
                    os.rename(self.path, stale)
                except FileNotFoundError:
                    continue          # another process took the stale lock away first: try again
                if stale.read_text() != text:   # a live claim replaced the stale one meanwhile: give it back
                    try:
                        os.link(stale, self.path)
                    except FileExistsError:
                        pass
                    stale.unlink(missing_ok=True)
                    raise busy
                stale.unlink(missing_ok=True)
            raise OutputInUseError(f"{self.label}: could not take the lock file {self.path}")
        finally:
            mine.unlink(missing_ok=True)

    def release(self):
        """Remove the lock file and drop the lock (idempotent)."""
        if self._fd is None:
            return
        try:
            if _same_file(self._fd, self.path):
                self.path.unlink(missing_ok=True)
        except OSError:
            pass
        os.close(self._fd)
        self._fd = None

    def __enter__(self):
        return self.acquire()

    def __exit__(self, *exc):
        self.release()


def holder_of(output) -> str | None:
    """The holder of `output`'s lock, described, or None when nobody holds it (no lock file, or a stale one)."""
    path = lock_path(output)
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return None
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
            return None
        except BlockingIOError:
            return describe_holder(_read(fd))
        except OSError:
            text = _read(fd)
            return None if _content_says_free(text) else describe_holder(text)
    finally:
        os.close(fd)


_FLOCK = {}


def _has_flock(folder: Path) -> bool:
    """Whether flock works on files in `folder` (tried once per folder and process, on a probe file)."""
    folder = Path(folder)
    if folder not in _FLOCK:
        probe = folder / f".rollcontact-flock-probe.{os.getpid()}"
        fd = os.open(probe, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            _FLOCK[folder] = True
        except OSError as exc:
            _FLOCK[folder] = exc.errno not in (errno.ENOLCK, errno.EOPNOTSUPP, errno.ENOSYS)
        finally:
            os.close(fd)
            probe.unlink(missing_ok=True)
    return _FLOCK[folder]


def _read(fd) -> str:
    try:
        return os.pread(fd, 4096, 0).decode(errors="replace").strip()
    except OSError:
        return ""


def _same_file(fd, path) -> bool:
    try:
        a, b = os.fstat(fd), os.stat(path)
    except OSError:
        return False
    return (a.st_dev, a.st_ino) == (b.st_dev, b.st_ino)


def _content_says_free(text: str) -> bool:
    parts = text.split(" ", 3)
    if len(parts) < 2 or not parts[0].isdigit():
        return True
    pid, host = int(parts[0]), parts[1]
    if pid == os.getpid() and host == socket.gethostname():
        return False
    return host == socket.gethostname() and not process_exists(pid)

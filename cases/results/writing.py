"""Every file rollcontact writes is written whole or not at all, and a write that fails (a full disk, a folder that
vanished, a read-only file system) raises one `OutputWriteError` naming the file and the failure.

A file is written to a temporary file beside it (.<name>.<pid>.tmp) and renamed over it: a reader sees the old file
or the new one, never half of one, and a failed write leaves the old file (a run's last good checkpoint) in place and
its temporary file removed. Folders are not created here: a folder that vanished while a run went on is reported,
not silently made again (the output is checked, and its folder created, before a run starts:
cases.results.outputs).

HDF5 files are written through `GuardedFile`, a file object that h5py writes to (its 'fileobj' driver) and that never
lets HDF5 see a failed write: the first OSError is kept, the later writes are dropped, HDF5 closes the file as if
all went well, and `new_hdf5` then raises the error. Why: when a write fails inside HDF5 (h5py 3.16, HDF5 2.0) while
it closes a file, its open datasets are left half closed, and freeing one of them later (when the Python objects
holding it go, e.g. with the traceback) crashes the process with a segmentation fault (`run --stresses` on a full
disk did, after its traceback).
"""
from __future__ import annotations

from contextlib import contextmanager
import errno
import os
from pathlib import Path
import threading

from rollcontact.bem.errors import OutputWriteError

_WHY = {errno.ENOSPC: "no space left on the device", errno.EDQUOT: "disk quota exceeded",
        errno.EROFS: "read-only file system", errno.ENOENT: "its folder no longer exists",
        errno.EACCES: "permission denied", errno.EPERM: "permission denied", errno.EIO: "input/output error",
        errno.EFBIG: "file too large", errno.ENOTDIR: "its folder is not a folder"}


def write_failed(path, exc: OSError, what: str = "", via: str = "") -> OutputWriteError:
    """The OutputWriteError of a failed write of `path`: 'cannot write [what] PATH: why (ECODE[; writing via])'
    (`what`: what the file is, e.g. 'checkpoint'; `via`: the file that failed when it is another one, e.g. a lock
    file)."""
    why = _WHY.get(exc.errno) or exc.strerror or str(exc)
    label = f"{what} {path}" if what else str(path)
    code = errno.errorcode.get(exc.errno, "OSError") + (f"; writing {via}" if via else "")
    return OutputWriteError(f"cannot write {label}: {why} ({code})", path=Path(path), errno=exc.errno)


def temporary(path) -> Path:
    """The temporary file beside `path` that this process writes before renaming it into place."""
    path = Path(path)
    return path.with_name(f".{path.name}.{os.getpid()}.tmp")


@contextmanager
def replacing(path, what: str = ""):
    """A temporary file beside `path` to write, renamed over `path` when the block ends without an error and removed
    in every case. An OSError of the block or of the rename becomes OutputWriteError naming `path` (`what`: how to
    name the file in the message)."""
    path = Path(path)
    tmp = temporary(path)
    try:
        try:
            yield tmp
            _replace(tmp, path)
        except OSError as exc:
            raise write_failed(path, exc, what) from None
    finally:
        try:
            tmp.unlink(missing_ok=True)
        except OSError:
            pass


def write_bytes(path, data: bytes, what: str = "") -> Path:
    """`data` to `path`, atomically; OutputWriteError when it cannot be written."""
    path = Path(path)
    with replacing(path, what) as tmp:
        with open(tmp, "wb") as fh:
            fh.write(data)
    return path


def write_text(path, text: str, what: str = "") -> Path:
    """`text` to `path` (UTF-8, '\\n' line ends), atomically; OutputWriteError when it cannot be written."""
    return write_bytes(path, text.encode(), what)


class GuardedFile:
    """A binary file that h5py writes through (driver 'fileobj') and whose writes never fail for HDF5: the first
    OSError is kept in `error`, and that write and every later one are dropped (reads return what the file holds,
    zeros beyond it). The writer raises `error` once HDF5 has closed the file (`new_hdf5`)."""

    def __init__(self, path):
        self.error: OSError | None = None
        self._fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_TRUNC, 0o644)
        self._pos = 0

    def seekable(self):
        return True

    def readable(self):
        return True

    def writable(self):
        return True

    def seek(self, offset, whence=os.SEEK_SET):
        if whence == os.SEEK_SET:
            self._pos = offset
        elif whence == os.SEEK_CUR:
            self._pos += offset
        else:
            self._pos = os.fstat(self._fd).st_size + offset
        return self._pos

    def tell(self):
        return self._pos

    def readinto(self, buffer):
        view = memoryview(buffer).cast("B")
        try:
            data = os.pread(self._fd, len(view), self._pos)
        except OSError as exc:
            self._fail(exc)
            data = b""
        view[:len(data)] = data
        view[len(data):] = bytes(len(view) - len(data))
        self._pos += len(view)
        return len(view)

    def read(self, size=-1):
        buffer = bytearray(max(size, 0))
        self.readinto(buffer)
        return bytes(buffer)

    def write(self, data):
        view = memoryview(data).cast("B")
        n = len(view)
        if self.error is None:
            pos = self._pos
            try:
                while view:
                    done = os.pwrite(self._fd, view, pos)
                    if done <= 0:
                        raise OSError(errno.EIO, "write returned 0 bytes")
                    view, pos = view[done:], pos + done
            except OSError as exc:
                self._fail(exc)
        self._pos += n
        return n

    def truncate(self, size=None):
        if self.error is None:
            try:
                os.ftruncate(self._fd, self._pos if size is None else size)
            except OSError as exc:
                self._fail(exc)
        return size

    def flush(self):
        pass

    def close(self):
        """Close the descriptor (an error of the close, as NFS reports a failed write back, is kept too)."""
        if self._fd is not None:
            try:
                os.close(self._fd)
            except OSError as exc:
                self._fail(exc)
            self._fd = None

    def check(self):
        """Raise the kept OSError, if a write failed."""
        if self.error is not None:
            raise self.error

    def _fail(self, exc: OSError):
        if self.error is None:
            self.error = exc


@contextmanager
def new_hdf5(path, what: str = ""):
    """(h5, check): a new HDF5 file to fill for `path` (an h5py File on a GuardedFile of the temporary file beside
    it), renamed over `path` when the block ends without an error and every write succeeded; else the temporary
    file is removed and, for a failed write, OutputWriteError naming `path` is raised. check() raises that error at
    once (a long writer calls it between its steps, so that it stops at the first failure)."""
    import h5py
    path = Path(path)
    tmp = temporary(path)
    try:
        guard = GuardedFile(tmp)
    except OSError as exc:
        raise write_failed(path, exc, what) from None

    def check():
        if guard.error is not None:
            raise write_failed(path, guard.error, what)
    try:
        try:
            with h5py.File(guard, "w") as h5:
                yield h5, check
        finally:
            guard.close()
        check()
        try:
            _replace(tmp, path)
        except OSError as exc:
            raise write_failed(path, exc, what) from None
    finally:
        try:
            tmp.unlink(missing_ok=True)
        except OSError:
            pass


def _replace(tmp: Path, path: Path):
    """os.replace(tmp, path), with the replaced file's last link removed in a background thread: freeing a file's
    blocks took 4-7 ms on the development machine (ext4 mounted with discard), the largest single cost of a
    checkpoint, while the rename itself takes microseconds. `path` names a complete file at every moment.
    `wait_for_replaced` joins the pending removals (a run does so after its final write)."""
    old = None
    if path.exists():
        old = path.with_name(f".{path.name}.{os.getpid()}.old")
        try:
            os.link(path, old)
        except OSError:          # no hard links here (or a leftover of this pid): remove it in line
            old = None
    try:
        os.replace(tmp, path)
    except OSError:
        if old is not None:
            _unlink_quietly(old)
        raise
    if old is not None:
        thread = threading.Thread(target=_unlink_quietly, args=(old,), name="rollcontact-unlink")
        thread.start()
        _pending.append(thread)


def _unlink_quietly(path: Path):
    try:
        path.unlink()
    except OSError:
        pass


#: background removals of replaced files (see _replace)
_pending: list = []


def wait_for_replaced():
    """Wait until the files replaced by `replacing`, `write_bytes` and `new_hdf5` are removed."""
    while _pending:
        _pending.pop().join()

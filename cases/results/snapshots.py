"""The field snapshots of a run held as the gzip chunks of its file (cases.results.hdf5.compress_snapshot) and
decompressed when read: a run that writes a file keeps each stored snapshot once, compressed, instead of the array
and its chunk (at dx = 0.05 mm on the paper scene, 126 MB of arrays against 48 MB of chunks). Units: the field's."""
from __future__ import annotations

import zlib

import numpy as np


class SnapshotStack:
    """A read-only stack of (ny, nx) snapshots of one field, shape (snapshots, ny, nx), from their gzip chunks.

    It reads like the array it stands for: `stack[i]` (one snapshot, decompressed), `stack[i, j]`, `stack[a:b]`,
    `np.asarray(stack)` (all of them), `shape`, `dtype`, `ndim`, `len`, and numpy's array methods (`stack.max()`,
    through the whole array). `chunks` are the file's chunks, written as they are."""

    ndim = 3

    def __init__(self, chunks, shape, dtype):
        self.chunks = list(chunks)
        self._plane = (int(shape[0]), int(shape[1]))
        self.dtype = np.dtype(dtype)

    @property
    def shape(self) -> tuple:
        return (len(self.chunks),) + self._plane

    @property
    def size(self) -> int:
        return len(self.chunks) * self._plane[0] * self._plane[1]

    def __len__(self):
        return len(self.chunks)

    def snapshot(self, i: int) -> np.ndarray:
        """Snapshot i (negative from the end), a new (ny, nx) array."""
        raw = zlib.decompress(self.chunks[i])
        return np.frombuffer(raw, dtype=self.dtype).reshape(self._plane).copy()

    def __getitem__(self, index):
        first, rest = (index[0], index[1:]) if isinstance(index, tuple) else (index, ())
        if isinstance(first, (int, np.integer)):
            plane = self.snapshot(int(first))
            return plane[rest] if rest else plane
        if isinstance(first, slice):
            picked = range(len(self.chunks))[first]
            stack = np.empty((len(picked),) + self._plane, dtype=self.dtype)
            for k, i in enumerate(picked):
                stack[k] = self.snapshot(i)
            return stack[(slice(None),) + rest] if rest else stack
        return np.asarray(self)[index]

    def __array__(self, dtype=None, copy=None):
        out = self[:]
        return out if dtype is None else out.astype(dtype, copy=False)

    def __iter__(self):
        return (self.snapshot(i) for i in range(len(self.chunks)))

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(np.asarray(self), name)

    def __repr__(self):
        return f"SnapshotStack({len(self.chunks)} snapshots of {self._plane[0]} x {self._plane[1]} {self.dtype})"


def _delegate(name):
    def method(self, *args):
        return getattr(np.asarray(self), name)(*args)
    method.__name__ = name
    return method


for _name in ("__add__", "__radd__", "__sub__", "__rsub__", "__mul__", "__rmul__", "__truediv__", "__rtruediv__",
              "__pow__", "__neg__", "__abs__", "__lt__", "__le__", "__gt__", "__ge__"):
    setattr(SnapshotStack, _name, _delegate(_name))

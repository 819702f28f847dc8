"""The last few results of a pure function of arrays, found again by the arrays' bytes.

Mutual prediction and validation predict the same stacked rows with many models, and a
compensator fits and predicts each target on the same inputs: a model whose features are
costly (the lag bank's filter responses) computes them once per distinct input.
"""

from __future__ import annotations

import hashlib
import threading
from collections import OrderedDict

import numpy as np


class ArrayMemo:
    """``fn(*arrays, *params)`` remembered for the ``size`` most recent distinct arguments.

    Arrays are keyed by dtype, shape and bytes (numeric arrays only: an object array's
    bytes are pointers), the other arguments by ``repr``.  Results (arrays, or tuples of
    them) are returned read-only.  With ``max_bytes`` the oldest are also forgotten while the
    results' arrays hold more (the newest is kept whatever its size).
    """

    def __init__(self, fn, size: int = 4, max_bytes: float | None = None):
        self.fn = fn
        self._results = BoundedCache(int(size), max_bytes)
        self._lock = threading.Lock()

    @property
    def size(self) -> int:
        return self._results.max_items

    @property
    def max_bytes(self) -> float | None:
        return self._results.max_bytes

    @staticmethod
    def key(*args) -> bytes:
        """The digest that finds ``fn(*args)`` again (a caller may build its own from it)."""
        digest = hashlib.sha256()
        for a in args:
            if isinstance(a, np.ndarray):
                if a.dtype == object:
                    raise TypeError("ArrayMemo keys numeric arrays only")
                digest.update(f"{a.dtype}{a.shape}".encode())
                digest.update(np.ascontiguousarray(a).data)
            else:
                digest.update(repr(a).encode())
            digest.update(b"|")
        return digest.digest()

    def __call__(self, *args):
        return self.lookup(self.key(*args), *args)

    def lookup(self, key: bytes, *args):
        """``fn(*args)``, remembered under ``key``: a caller that knows what ``args`` derive from
        (a digest of :meth:`key`, the settings) saves hashing large arrays."""
        with self._lock:
            if key in self._results:
                return self._results[key]
        out = self.fn(*args)
        _read_only(out)
        with self._lock:
            self._results[key] = out
        return out


class BoundedCache(OrderedDict):
    """A dict that forgets its least recently used entries while it holds more than
    ``max_items`` of them or its values' arrays more than ``max_bytes`` (``nbytes``; the newest
    is kept whatever its size); reading an entry makes it the most recent."""

    def __init__(self, max_items: int | None = None, max_bytes: float | None = None):
        super().__init__()
        self.max_items, self.max_bytes, self.nbytes = max_items, max_bytes, 0

    def __getitem__(self, key):
        value = super().__getitem__(key)
        self.move_to_end(key)
        return value

    def __setitem__(self, key, value) -> None:
        if key in self:
            self.nbytes -= _nbytes(super().__getitem__(key))
        super().__setitem__(key, value)
        self.move_to_end(key)
        self.nbytes += _nbytes(value)
        while len(self) > 1 and ((self.max_items is not None and len(self) > self.max_items) or
                                 (self.max_bytes is not None and self.nbytes > self.max_bytes)):
            _, old = self.popitem(last=False)
            self.nbytes -= _nbytes(old)

    def clear(self) -> None:
        super().clear()
        self.nbytes = 0          # or every entry after a clear would be over the bound


def _nbytes(out) -> int:
    if isinstance(out, np.ndarray):
        return out.nbytes
    if isinstance(out, tuple):
        return sum(_nbytes(item) for item in out)
    return 0


def _read_only(out) -> None:
    if isinstance(out, np.ndarray):
        out.flags.writeable = False
    elif isinstance(out, tuple):
        for item in out:
            _read_only(item)

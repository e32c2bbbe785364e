"""Answers of a pure function kept by the value of its inputs, the last few only: :class:`Kept`.

A warm process synthesises the same joins again and again (the studio re-animates the whole text at every pause
in typing, and only the joins the edit reached differ; a server answers the same sentences): a step whose answer
is a pure function of a few arrays keeps its last answers by a digest of those arrays' bytes (:func:`digest`),
so a join met again costs the digest. Unlike :class:`core.memo.Memo` (values kept by the object they derive
from, for its life), a :class:`Kept` outlives the objects: it is bounded, the least recently used answer goes
first, and threads may share it.
"""
from __future__ import annotations

import hashlib
import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Generic, TypeVar

import numpy as np

V = TypeVar("V")


def digest(*parts: object) -> bytes:
    """A 32-byte digest of ``parts`` by value: arrays by dtype, shape and bytes, anything else by its ``repr``
    (numbers, strings, ``None``, tuples of those)."""
    h = hashlib.blake2b(digest_size=32)
    for p in parts:
        if isinstance(p, np.ndarray):
            a = np.ascontiguousarray(p)
            h.update(f"{a.dtype.str}{a.shape}".encode())
            h.update(a.tobytes())
        else:
            h.update(repr(p).encode())
        h.update(b"\0")
    return h.digest()


class Kept(Generic[V]):
    """The last ``size`` answers, by key (the least recently used dropped first); safe to share between threads
    (an answer may be made twice by two threads at once: it is the same answer)."""

    __slots__ = ("size", "_values", "_lock")

    def __init__(self, size: int) -> None:
        self.size = size
        self._values: OrderedDict[Hashable, V] = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key: Hashable, make: Callable[[], V]) -> V:
        """The answer of ``key``: ``make()`` when it is not kept (then kept)."""
        with self._lock:
            if key in self._values:
                self._values.move_to_end(key)
                return self._values[key]
        return self.put(key, make())

    def known(self, key: Hashable) -> V | None:
        """The answer of ``key`` if it is kept, else ``None``."""
        with self._lock:
            if key not in self._values:
                return None
            self._values.move_to_end(key)
            return self._values[key]

    def put(self, key: Hashable, value: V) -> V:
        """Keep ``value`` as ``key``'s answer."""
        with self._lock:
            self._values[key] = value
            self._values.move_to_end(key)
            while len(self._values) > self.size:
                self._values.popitem(last=False)
        return value

    def clear(self) -> None:
        """Forget every answer."""
        with self._lock:
            self._values.clear()

    def __len__(self) -> int:
        return len(self._values)

"""Answers of a pure function kept by the value of its inputs, the last few only: :class:`Kept`.

A warm process synthesises the same joins again and again (the studio re-animates the whole text at every pause
in typing, and only the joins the edit reached differ; a server answers the same sentences): a step whose answer
is a pure function of a few arrays keeps its last answers by a digest of those arrays' bytes (:func:`digest`),
so a join met again costs the digest. Unlike :class:`core.memo.Memo` (values kept by the object they derive
from, for its life), a :class:`Kept` outlives the objects: it is bounded, the least recently used answer goes
first, and threads may share it.
"""
from __future__ import annotations

import dataclasses
import enum
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


def value_digest(*parts: object) -> bytes:
    """A 32-byte digest of ``parts`` by value, through what they hold: arrays by dtype, shape and bytes;
    dataclasses by their class and compared fields (an object with a ``cache`` that keeps derived values, a
    :class:`core.motion.Motion`, has its digest made once and kept there); tuples, lists and dicts by their
    items in order; numbers, strings, bytes, enums and ``None`` by type and ``repr``. Anything else is refused
    (``TypeError``): a key must not stand for values it cannot tell apart."""
    h = hashlib.blake2b(digest_size=32)
    for p in parts:
        _feed(h, p)
    return h.digest()


_SCALARS = (type(None), bool, int, float, complex, str, bytes, np.generic, enum.Enum)


def _feed(h, p: object) -> None:
    """Feed ``p``'s value to the hash ``h`` (:func:`value_digest`)."""
    if isinstance(p, _SCALARS):
        h.update(f"{type(p).__name__}:{p!r}\0".encode())
    elif isinstance(p, np.ndarray):
        a = np.ascontiguousarray(p)
        h.update(f"{a.dtype.str}{a.shape}".encode())
        h.update(a.tobytes())
    elif isinstance(p, (tuple, list)):
        h.update(f"{type(p).__name__}[{len(p)}]".encode())
        for x in p:
            _feed(h, x)
    elif isinstance(p, dict):
        h.update(f"dict[{len(p)}]".encode())
        for k, v in p.items():
            _feed(h, k)
            _feed(h, v)
    elif dataclasses.is_dataclass(p) and not isinstance(p, type):
        cache = getattr(p, "cache", None)
        if cache is not None and callable(getattr(cache, "get", None)):
            h.update(cache.get("kept.value_digest", lambda: _fields_digest(p)))
        else:
            _feed_fields(h, p)
    else:
        raise TypeError(f"no digest by value for {type(p).__name__}")


def _fields_digest(p: object) -> bytes:
    """:func:`value_digest` of one dataclass instance's class and compared fields."""
    h = hashlib.blake2b(digest_size=32)
    _feed_fields(h, p)
    return h.digest()


def _feed_fields(h, p: object) -> None:
    h.update(f"{type(p).__module__}.{type(p).__qualname__}(".encode())
    for f in dataclasses.fields(p):  # type: ignore[arg-type]
        if f.compare:
            _feed(h, getattr(p, f.name))
    h.update(b")")


class Kept(Generic[V]):
    """The last ``size`` answers, by key (the least recently used dropped first), and with ``weigh`` (an answer's
    bytes) no more than ``budget`` bytes of them (an answer heavier than the budget is given, not kept); safe to
    share between threads (an answer may be made twice by two threads at once: it is the same answer)."""

    __slots__ = ("size", "budget", "weigh", "_values", "_total", "_lock")

    def __init__(self, size: int, budget: int | None = None, weigh: Callable[[V], int] | None = None) -> None:
        self.size = size
        self.budget = budget
        self.weigh = weigh
        self._values: OrderedDict[Hashable, tuple[V, int]] = OrderedDict()
        self._total = 0
        self._lock = threading.Lock()

    def get(self, key: Hashable, make: Callable[[], V]) -> V:
        """The answer of ``key``: ``make()`` when it is not kept (then kept)."""
        known = self.known(key)
        return self.put(key, make()) if known is None else known

    def known(self, key: Hashable) -> V | None:
        """The answer of ``key`` if it is kept, else ``None``."""
        with self._lock:
            if key not in self._values:
                return None
            self._values.move_to_end(key)
            return self._values[key][0]

    def put(self, key: Hashable, value: V) -> V:
        """Keep ``value`` as ``key``'s answer (within the size and budget)."""
        weight = self.weigh(value) if self.weigh is not None else 0
        if self.budget is not None and weight > self.budget:
            return value
        with self._lock:
            old = self._values.pop(key, None)
            self._total += weight - (old[1] if old is not None else 0)
            self._values[key] = (value, weight)
            while len(self._values) > self.size or (self.budget is not None and self._total > self.budget):
                self._total -= self._values.popitem(last=False)[1][1]
        return value

    def clear(self) -> None:
        """Forget every answer."""
        with self._lock:
            self._values.clear()
            self._total = 0

    @property
    def weight(self) -> int:
        """The bytes of the answers kept (by ``weigh``; 0 without it)."""
        return self._total

    def __len__(self) -> int:
        return len(self._values)

"""Values computed once from an immutable object, kept by that object: :class:`Memo`.

A :class:`~core.skeleton.Skeleton` and a :class:`~core.motion.Motion` (its
:class:`~core.posecache.PoseCache`) each own one. Keys are hashable values that name the quantity and
its parameters (``("headings", 0.3)``); nothing is keyed by an object's identity, and the values go
with their owner.
"""
from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import Any, TypeVar

V = TypeVar("V")


class Memo:
    """Values computed once, by key (hashable values: a name and the parameters)."""

    __slots__ = ("_values",)

    def __init__(self) -> None:
        self._values: dict[Hashable, Any] = {}

    def get(self, key: Hashable, make: Callable[[], V]) -> V:
        """The value of ``key``: ``make()`` the first time."""
        try:
            return self._values[key]
        except KeyError:
            value = self._values[key] = make()
            return value

    def known(self, key: Hashable) -> Any:
        """The value of ``key`` if it was made, else ``None``."""
        return self._values.get(key)

    def put(self, key: Hashable, value: V) -> V:
        """Keep ``value`` as ``key``'s (one that grows: a wider window of the same values)."""
        self._values[key] = value
        return value

    def __contains__(self, key: Hashable) -> bool:
        return key in self._values

    def __len__(self) -> int:
        return len(self._values)

    def __reduce__(self):
        return type(self), ()  # a copy starts empty: its values are made again from the copy

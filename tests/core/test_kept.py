"""Answers kept by the value of their inputs (core.kept): the same values find the same answer, other values
(another dtype, shape or byte, or a field of a dataclass deep inside) do not, and only the last few are kept, within
a budget of bytes when one is given."""
from __future__ import annotations

import numpy as np

from dataclasses import dataclass, field

import pytest

from text2anim.core.kept import Kept, digest, value_digest
from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton


def test_a_digest_is_of_the_values_dtype_and_shape():
    a = np.arange(6, dtype=float)
    assert digest(a, 2.0, None) == digest(a.copy(), 2.0, None)
    assert digest(a[::2]) == digest(np.ascontiguousarray(a[::2]))  # a view reads as its values
    assert digest(a) != digest(a.reshape(2, 3))
    assert digest(a) != digest(a.astype(np.float32))
    b = a.copy()
    b[3] = np.nextafter(b[3], 10.0)
    assert digest(a) != digest(b)
    assert digest(a, 1.0) != digest(a, 1)  # 1.0 and 1 are other arguments


def test_kept_answers_are_made_once_and_the_least_recently_used_goes_first():
    made = []
    kept: Kept[str] = Kept(2)

    def answer(key: str) -> str:
        return kept.get(key, lambda: made.append(key) or key.upper())

    assert [answer("a"), answer("b"), answer("a")] == ["A", "B", "A"]
    assert made == ["a", "b"]
    answer("c")  # b was used least recently: it goes
    assert len(kept) == 2
    answer("a")
    answer("b")
    assert made == ["a", "b", "c", "b"]


def test_kept_answers_stay_within_their_budget_of_bytes():
    kept: Kept[bytes] = Kept(100, budget=10, weigh=len)
    for key in "abc":
        kept.put(key, b"xxxx")
    assert len(kept) == 2 and kept.weight == 8 and kept.known("a") is None  # the third would make 12 bytes
    assert kept.put("d", b"x" * 11) == b"x" * 11 and kept.known("d") is None  # heavier than the budget: given
    kept.put("b", b"xx")  # an answer made again replaces its weight
    assert kept.weight == 6


@dataclass(frozen=True)
class _Held:
    name: str
    frames: Motion
    notes: tuple = ()
    seen: list = field(default_factory=list, compare=False)


def _motion(shift: float = 0.0) -> Motion:
    sk = Skeleton(("hips", "knee"), np.array([-1, 0]), np.array([[0.0, 0.9, 0.0], [0.0, -0.4, 0.0]]))
    rot = np.tile([0.0, 0.0, 0.0, 1.0], (3, 2, 1))
    return Motion(sk, 30.0, np.array([[0.0, 0.9, z + shift] for z in range(3)]), rot)


def test_a_value_digest_reads_through_dataclasses_and_motions():
    a = _Held("walk", _motion(), ({"k": np.arange(3)},))
    assert value_digest(a) == value_digest(_Held("walk", _motion(), ({"k": np.arange(3)},), seen=[1]))
    assert value_digest(a) != value_digest(_Held("walk", _motion(1e-12), ({"k": np.arange(3)},)))  # a frame's bit
    assert value_digest(a) != value_digest(_Held("walk", _motion(), ({"k": np.arange(1, 4)},)))  # deep in a dict
    assert value_digest(a) != value_digest(_Held("run", _motion(), ({"k": np.arange(3)},)))
    assert value_digest(1) != value_digest(1.0) and value_digest((1,)) != value_digest([1])
    with pytest.raises(TypeError):
        value_digest(object())  # what it cannot read by value is refused, not taken by its repr

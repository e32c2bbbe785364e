"""Answers kept by the value of their inputs (core.kept): the same values find the same answer, other values
(another dtype, shape or byte) do not, and only the last few are kept."""
from __future__ import annotations

import numpy as np

from text2anim.core.kept import Kept, digest


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

"""Variants: co-actors and repeats of one verb do not play bit-identical clips.

When several clips tie for a motion (the same character, primary verb,
objects, body part, looping and postures as the best hit: the built-in
library's three captured walks, say), the ``k``-th use of that group in one
text takes its ``k % n``-th clip, and from the second round on a whole-body
clip is mirrored (the API plays it through :func:`core.mirror.mirror`), so two actors running side by
side, or three jumps in a row, are different motions. Uses are counted in the
order the scheduler asks for clips (the motions' order in the text), so the
same text and database always give the same choice; a verb used once gets
the best hit, as before.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Generic

from .clips import C, ClipMeta


def _kind(c: ClipMeta) -> tuple:
    return (c.character, c.verb, tuple(c.objects), c.body_part, c.cyclic, c.start_posture, c.end_posture, c.style)


def group(hits: Sequence[C]) -> list[C]:
    """The hits that tie with the best one (``hits`` best first, as ``MotionDB.search`` ranks them)."""
    if not hits:
        return []
    best = _kind(hits[0])
    return [h for h in hits if _kind(h) == best]


@dataclass(frozen=True)
class Pick(Generic[C]):
    """A clip to play and whether it is played mirrored."""

    clip: C
    mirrored: bool = False


def nth(hits: Sequence[C], k: int) -> Pick[C]:
    """The ``k``-th variant of ``hits``' best group (``k`` = 0: the best hit itself)."""
    return Variants._pick(group(hits), k)


@dataclass
class Variants:
    """Counts the uses of each group of tied clips and hands out the next variant."""

    uses: dict[tuple[str, ...], int] = field(default_factory=dict)

    def take(self, hits: Sequence[C], n: int = 1) -> list[Pick[C]]:
        """The next ``n`` variants of ``hits``' best group (``n`` > 1: the repetitions of one motion).

        A repetition whose clip would not fit the first one's length (shorter than it, or
        its core ending after it) plays the first clip again, mirrored every other time.
        """
        tied = group(hits)
        if not tied:
            return []
        key = tuple(h.name for h in tied)
        k = self.uses.get(key, 0)
        self.uses[key] = k + n
        picks = [self._pick(tied, k + i) for i in range(n)]
        first = picks[0].clip
        out: list[Pick[C]] = [picks[0]]
        for i, p in enumerate(picks[1:], 1):
            fits = p.clip.duration >= first.duration - 1e-9 and p.clip.core[1] <= first.duration + 1e-9
            out.append(p if fits else Pick(first, mirrored=(i % 2 == 1) != picks[0].mirrored
                                           and first.body_part is None))
        return out

    @staticmethod
    def _pick(tied: list[C], k: int) -> Pick[C]:
        clip = tied[k % len(tied)]
        return Pick(clip, mirrored=(k // len(tied)) % 2 == 1 and clip.body_part is None)

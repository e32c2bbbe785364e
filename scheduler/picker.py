"""The clip each motion plays, as :func:`plan.plan` asks for it: the best candidates' next variant.

A motion repeated ``n`` times (3回ジャンプする) takes ``n`` variants at once, one per
repetition (:meth:`variants.Variants.take`); a looping clip repeats itself instead.
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import Generic

from text2anim.nlp.lexicon import HAND_IN_HAND, RECIPROCAL_VERBS
from text2anim.nlp.types import MotionSpec

from .clips import C, ClipMeta, ClipSource, timing
from .errors import ScheduleError
from .types import ClipTiming
from .variants import Pick, Variants, group


#: How much shorter or longer (a fraction of its mate's length) a clip that does not loop may be and
#: still be played by a co-actor of the same motion: the three captured drinks last 3.8, 3.6 and 2.9 s,
#: so two people drinking together take the first two (one holds its last pose 0.2 s), not the third.
TOGETHER_SLACK = 0.1


def _about_as_long(clip: ClipMeta, mate: ClipMeta) -> bool:
    return abs(clip.duration - mate.duration) <= TOGETHER_SLACK * mate.duration + 1e-9


class Picker(Generic[C]):
    """A :data:`plan.ClipFinder` over ``source`` that remembers what it chose.

    Attributes:
        chosen: motion id -> its clip (the first repetition's).
        mirrored: ids of the motions whose clip plays mirrored.
        repeats: for a repeated motion whose clip does not loop, the clip of each repetition.
    """

    def __init__(self, source: ClipSource[C], together: Mapping[int, tuple[int, ...]] | None = None):
        """``together``: motion id -> the motions performed together with it (:func:`together.together`)."""
        self.source = source
        self.together = together or {}
        self.chosen: dict[int, C] = {}
        self.mirrored: set[int] = set()
        self.repeats: dict[int, tuple[Pick[C], ...]] = {}
        self.variants = Variants()

    def __call__(self, spec: MotionSpec, prefer: str | None) -> ClipTiming:
        hits = self.source.candidates(spec, prefer)
        if not hits:
            raise ScheduleError(f"the motion database has {spec.verb} but no clip of it fits"
                                + (f" the {spec.body_part}" if spec.body_part else ""))
        n = max(1, int(spec.repeat))
        picks = self._as_long_as_mates(spec.id, self.variants.take(hits, n), group(hits))
        if spec.target_role == "partner" and spec.verb in HAND_IN_HAND:  # the first on the partner's left
            picks[0] = Pick(picks[0].clip, mirrored=all(spec.id < m for m in self.together.get(spec.id, ())))
        elif picks[0].mirrored and spec.target_role == "partner" and spec.verb in RECIPROCAL_VERBS:
            picks[0] = Pick(picks[0].clip, mirrored=False)  # two people shake right hands: not mirrored
        self.chosen[spec.id] = picks[0].clip
        if picks[0].mirrored:
            self.mirrored.add(spec.id)
        if n > 1 and not picks[0].clip.cyclic:
            self.repeats[spec.id] = tuple(picks)
        return timing(picks[0].clip)

    def _as_long_as_mates(self, mid: int, picks: list[Pick[C]], tied: list[C]) -> list[Pick[C]]:
        """The variants of a motion performed together with one chosen already (:mod:`together`): a clip
        that does not loop must last about as long as its mate's, repetition by repetition (within
        :data:`TOGETHER_SLACK` of it; the planner then holds or trims it to the same time), else another
        of the ``tied`` captures that does, else the mate's own clip mirrored."""
        mate = next((m for m in self.together.get(mid, ()) if m in self.chosen), None)
        if mate is None or picks[0].clip.cyclic:
            return picks
        theirs = list(self.repeats.get(mate, ())) or [Pick(self.chosen[mate], mate in self.mirrored)]
        if len(theirs) != len(picks):
            return picks
        out = []
        for mine, their in zip(picks, theirs):
            if _about_as_long(mine.clip, their.clip):
                out.append(mine)
                continue
            other = next((c for c in tied if c.name != their.clip.name and _about_as_long(c, their.clip)), None)
            out.append(Pick(other) if other is not None else
                       Pick(their.clip, mirrored=not their.mirrored and their.clip.body_part is None))
        return out

    def take(self, spec: MotionSpec, clip: C) -> ClipTiming:
        """Record ``clip`` as ``spec``'s, chosen elsewhere (:meth:`postures.Arrangement.finder`)."""
        self.chosen[spec.id] = clip
        return timing(clip)


__all__ = ["Picker"]

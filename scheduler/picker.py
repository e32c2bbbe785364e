"""The clip each motion plays, as :func:`plan.plan` asks for it: the best candidates' next variant.

A motion repeated ``n`` times (3回ジャンプする) takes ``n`` variants at once, one per
repetition (:meth:`variants.Variants.take`); a looping clip repeats itself instead.
"""
from __future__ import annotations

from typing import Generic

from text2anim.nlp.lexicon import RECIPROCAL_VERBS
from text2anim.nlp.types import MotionSpec

from .clips import C, ClipSource, timing
from .errors import ScheduleError
from .types import ClipTiming
from .variants import Pick, Variants


class Picker(Generic[C]):
    """A :data:`plan.ClipFinder` over ``source`` that remembers what it chose.

    Attributes:
        chosen: motion id -> its clip (the first repetition's).
        mirrored: ids of the motions whose clip plays mirrored.
        repeats: for a repeated motion whose clip does not loop, the clip of each repetition.
    """

    def __init__(self, source: ClipSource[C]):
        self.source = source
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
        picks = self.variants.take(hits, n)
        if picks[0].mirrored and spec.target_role == "partner" and spec.verb in RECIPROCAL_VERBS:
            picks[0] = Pick(picks[0].clip, mirrored=False)  # two people shake right hands: not mirrored
        self.chosen[spec.id] = picks[0].clip
        if picks[0].mirrored:
            self.mirrored.add(spec.id)
        if n > 1 and not picks[0].clip.cyclic:
            self.repeats[spec.id] = tuple(picks)
        return timing(picks[0].clip)

    def take(self, spec: MotionSpec, clip: C) -> ClipTiming:
        """Record ``clip`` as ``spec``'s, chosen elsewhere (:meth:`postures.Arrangement.finder`)."""
        self.chosen[spec.id] = clip
        return timing(clip)


__all__ = ["Picker"]

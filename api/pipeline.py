"""The glue between the stages: text → analysis → time table (clips from the database).

Each stage keeps to its own records; this module turns one stage's records
into the next one's (``ClipInfo`` → ``ClipTiming`` for the scheduler, and
later ``ClipInfo`` + frames → ``synthesis.plan.Clip``).
"""
from __future__ import annotations

from dataclasses import dataclass, field

from text2anim import nlp
from text2anim.motiondb import ClipInfo, MotionDB, UnknownVerbError
from text2anim.motiondb.readings import same_word
from text2anim.nlp.types import Analysis, MotionSpec
from text2anim.scheduler import ClipTiming, ScheduleError, TimeTable, plan, without
from text2anim.core.bodyparts import GROUPS

from . import limits, postures
from .clip_timing import timing
from .fillers import fill_waits
from .variants import Pick, Variants


@dataclass(frozen=True)
class Planned:
    """A text's analysis and time table, with the clip chosen for each element id.

    ``fillers`` are the ids of the elements added to fill the waits (stops, idles:
    :mod:`text2anim.fillers`); ``skipped`` the verbs dropped as unknown; ``mirrored`` the
    element ids whose clip plays mirrored and ``repeats``, for a repeated element, the clip
    of each repetition (co-actors and repeats are not clones: :mod:`text2anim.variants`).
    """

    analysis: Analysis
    table: TimeTable
    clips: dict[int, ClipInfo]
    skipped: tuple[str, ...] = ()
    fillers: tuple[int, ...] = ()
    fallbacks: tuple = ()  # fallback.Substitution per motion animated with a verb nearest in meaning
    mirrored: frozenset[int] = frozenset()
    repeats: dict[int, tuple[Pick, ...]] = field(default_factory=dict)


def _kana_only(word: str) -> bool:
    """Whether ``word`` is written in hiragana/katakana only (``とぶ``, ``ジャンプする``)."""
    return all("\u3041" <= ch <= "\u30ff" for ch in word)


class ClipFinder:
    """Retrieves the best clip for each motion and remembers it (``chosen``: motion id -> clip)."""

    def __init__(self, db: MotionDB):
        self.db = db
        self.chosen: dict[int, ClipInfo] = {}
        self.mirrored: set[int] = set()
        self.repeats: dict[int, tuple[Pick, ...]] = {}
        self.variants = Variants()

    def search(self, spec: MotionSpec, prefer: str | None) -> list[ClipInfo]:
        part = spec.body_part if spec.body_part in GROUPS else None
        if spec.written and spec.written != spec.verb:
            # The dictionary's lemma may be another word of the same sound (撮る -> 取る, 閉める ->
            # 締める, 指す -> 差す): a clip declaring the verb as the user spelled it comes first.
            try:
                hits = self.db.search(spec.written, object=spec.object, body_part=part, prefer_character=prefer)
            except UnknownVerbError:
                hits = []
            if hits and spec.written in hits[0].verbs:
                return hits
        try:
            hits = self.db.search(spec.verb, object=spec.object, body_part=part, prefer_character=prefer)
        except UnknownVerbError as unknown:
            if not spec.reading or spec.reading == spec.verb or not _kana_only(spec.written or spec.verb):
                raise
            # A verb written in kana (とぶ) may be a spelling the database has in kanji; if not, the
            # error about the verb as written (with its suggestions) is the one to show. A verb
            # written in kanji that the database lacks is another word, not another spelling, of
            # any verb sharing its sound (吹く is not 拭く, 吐く is not 掃く).
            try:
                hits = self.db.search(spec.reading, object=spec.object, body_part=part, prefer_character=prefer)
            except UnknownVerbError:
                hits = None
            if hits is None:
                raise unknown from None  # the error about the written verb, with its suggestions
        if not hits and part:
            hits = self.db.search(spec.verb, object=spec.object, prefer_character=prefer)
        return self._same_word(spec, hits)

    @staticmethod
    def _same_word(spec: MotionSpec, hits: list[ClipInfo]) -> list[ClipInfo]:
        """``hits`` without clips the database matched by the verb's sound only, for a verb
        written in kanji (吹く matches 拭く's clip by フク: another word); raises
        :class:`UnknownVerbError` when nothing else is left."""
        written = spec.written or spec.verb
        if _kana_only(written):
            return hits
        # another spelling of the same word (後退りする for the library's 後ずさりする) is the verb itself
        same = [h for h in hits if spec.verb in h.verbs or written in h.verbs
                or any(same_word(written, v) for v in h.verbs)]
        if hits and not same:
            raise UnknownVerbError(written)
        return same

    def __call__(self, spec: MotionSpec, prefer: str | None) -> ClipTiming:
        hits = self.search(spec, prefer)
        if not hits:
            raise ScheduleError(f"the motion database has {spec.verb} but no clip of it fits"
                                + (f" the {spec.body_part}" if spec.body_part else ""))
        n = max(1, int(spec.repeat))
        picks = self.variants.take(hits, n)
        self.chosen[spec.id] = picks[0].clip
        if picks[0].mirrored:
            self.mirrored.add(spec.id)
        if n > 1 and not picks[0].clip.cyclic:
            self.repeats[spec.id] = tuple(picks)
        return timing(picks[0].clip)


def unknown_motions(analysis: Analysis, db: MotionDB) -> dict[int, UnknownVerbError]:
    """Motions whose verb no clip in ``db`` has, by motion id."""
    finder = ClipFinder(db)
    out = {}
    for spec in analysis.motions:
        try:
            finder.search(spec, None)
        except UnknownVerbError as exc:
            out[spec.id] = exc
    return out


def plan_text(text: str, db: MotionDB, *, fps: float = 30.0, skip_unknown: bool = False,
              fallback: str = "strict", max_seconds: float = limits.MAX_SECONDS) -> Planned:
    """Analyse ``text`` and schedule its motions with clips from ``db``, the waits filled.

    The table holds everything that will play: the text's motions, the clips
    bridging postures (:mod:`text2anim.postures`) and the stops and idles in
    the waits (:mod:`text2anim.fillers`). Unknown verbs raise :class:`UnknownVerbError`
    (naming every missing verb as written and the database verbs nearest in meaning)
    unless ``skip_unknown``, which drops those motions, or ``fallback="nearest"``, which
    animates each with the database verb nearest in meaning (:mod:`text2anim.fallback`).
    A text that asks for more than :mod:`text2anim.limits` allows (output over
    ``max_seconds``) raises :class:`limits.LimitError` before any frame is made.
    """
    limits.check_text(text)
    with db.memoised():  # the same motions are searched again by each step below
        return _plan(text, db, fps, skip_unknown, fallback, max_seconds)


def _plan(text: str, db: MotionDB, fps: float, skip_unknown: bool, fallback: str, max_seconds: float) -> Planned:
    from . import fallback as _fallback

    analysis = nlp.analyze(text)
    limits.check_analysis(analysis, max_seconds)
    unknown = unknown_motions(analysis, db)
    skipped: tuple[str, ...] = ()
    subs: tuple = ()
    if unknown and fallback == "nearest":
        analysis, subs = _fallback.substitute(analysis, unknown, db)
        unknown = {}
    if unknown:
        if not skip_unknown:
            raise _fallback.unknown_error(analysis, unknown, db)
        skipped = tuple(m.verb for m in analysis.motions if m.id in unknown)
        analysis = without(analysis, set(unknown))
        if not analysis.motions:
            raise ScheduleError("no motion of this text is in the motion database: " + "、".join(skipped))
    finder = ClipFinder(db)
    table = plan(analysis, finder, fps)
    # posture continuity: clips whose postures meet, bridging clips where none can (text2anim.postures)
    arranged = postures.arrange(analysis, table, finder.chosen, finder.search, db)
    if arranged.changed:
        analysis, finder = arranged.analysis, ClipFinder(db)
        table = plan(analysis, arranged.finder(finder), fps)
    limits.check_table(table, fps, max_seconds)
    filled = fill_waits(table, dict(finder.chosen), db, fps)
    return Planned(analysis, filled.table, filled.clips, skipped, filled.fillers, subs,
                   frozenset(finder.mirrored) | filled.mirrored, dict(finder.repeats))

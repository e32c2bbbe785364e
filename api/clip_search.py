"""The motion database as the scheduler queries it: the clips that can play a motion, best first.

:class:`DatabaseClips` is the :class:`scheduler.clips.ClipSource` the pipeline hands
the scheduler over a :class:`motiondb.MotionDB`. It decides which word a motion's verb
is (the phrase the user wrote, the spelling, the dictionary's lemma, a kana spelling's
kanji) and which of its clips do that sense of it (:mod:`phrase_sense`), and nothing about
the time table.
"""
from __future__ import annotations

from collections.abc import Sequence

from text2anim.core.bodyparts import GROUPS
from text2anim.motiondb import ClipInfo, MotionDB, UnknownVerbError
from text2anim.motiondb.readings import same_word
from text2anim.nlp.types import Analysis, MotionSpec

from .phrase_sense import asked, same_sense


def _style_rank(spec: MotionSpec, clip: ClipInfo) -> int:
    """0 for a clip of the style the motion asks for (a neutral one when it asks none), 1 for a neutral clip
    the modifiers can style, 2 for a clip of another style: a sad walk plays 歩く only when nothing else does."""
    return 0 if clip.style == spec.style else 1 if clip.style is None else 2


def _kana_only(word: str) -> bool:
    """Whether ``word`` is written in hiragana/katakana only (``とぶ``, ``ジャンプする``)."""
    return all("\u3041" <= ch <= "\u30ff" for ch in word)


class DatabaseClips:
    """The clips of ``db`` for a motion or a verb (a ``ClipSource[ClipInfo]``)."""

    def __init__(self, db: MotionDB):
        self.db = db

    def search(self, spec: MotionSpec, prefer: str | None) -> list[ClipInfo]:
        """The ranked clips of ``spec`` (``prefer``: that character's first); raises
        :class:`UnknownVerbError` for a verb the database lacks.

        Of the verb's clips, those declaring the motion's phrase (手を振る, 首を振る) come first, and
        those doing another sense of the verb (:func:`phrase_sense.same_sense`: the clips of 上げる
        raise a hand, not 足を上げる) are left out. Only where the verb finds nothing (手を合わせる:
        no clip lists 合わせる) or nothing of its sense is the phrase asked of the database itself,
        so a plan still asks once per motion.
        """
        part = spec.body_part if spec.body_part in GROUPS else None
        try:
            hits = self._by_verb(spec, part, prefer)
        except UnknownVerbError:
            declared = self._by_phrase(spec, part, prefer)
            if declared:
                return declared
            raise
        hits = sorted(hits, key=lambda h: spec.phrase not in h.verbs)  # stable: the database's order otherwise
        same = sorted((h for h in hits if same_sense(spec, h)), key=lambda h: _style_rank(spec, h))
        if hits and not same:
            declared = self._by_phrase(spec, part, prefer)
            if declared:
                return declared
            raise UnknownVerbError(asked(spec))
        return same

    def _by_phrase(self, spec: MotionSpec, part: str | None, prefer: str | None) -> list[ClipInfo]:
        """The clips declaring ``spec``'s phrase itself (a user's clip imported as 肩を回す), best first."""
        if not spec.phrase or spec.phrase == spec.verb:
            return []
        try:
            hits = self.db.search(spec.phrase, object=spec.object, body_part=part, prefer_character=prefer)
        except UnknownVerbError:
            return []
        return [h for h in hits if spec.phrase in h.verbs]

    def _by_verb(self, spec: MotionSpec, part: str | None, prefer: str | None) -> list[ClipInfo]:
        """The clips of ``spec``'s verb: as written, by lemma, or a kana spelling by its reading."""
        if spec.written and spec.written not in (spec.verb, spec.phrase):
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

    def candidates(self, spec: MotionSpec, prefer_character: str | None) -> Sequence[ClipInfo]:
        """:meth:`search`, ``[]`` for a verb the database lacks."""
        try:
            return self.search(spec, prefer_character)
        except UnknownVerbError:
            return []

    def by_verb(self, verb: str, *, prefer_character: str | None = None,
                prefer_start_posture: str | None = None) -> Sequence[ClipInfo]:
        """``db.search(verb, ...)``, ``[]`` for a verb the database lacks."""
        try:
            return self.db.search(verb, prefer_character=prefer_character, prefer_start_posture=prefer_start_posture)
        except UnknownVerbError:
            return []


def unknown_motions(analysis: Analysis, db: MotionDB) -> dict[int, UnknownVerbError]:
    """Motions whose verb no clip in ``db`` has, by motion id."""
    clips = DatabaseClips(db)
    out = {}
    for spec in analysis.motions:
        try:
            clips.search(spec, None)
        except UnknownVerbError as exc:
            out[spec.id] = exc
    return out


__all__ = ["DatabaseClips", "unknown_motions"]

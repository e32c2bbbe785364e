"""A predicate under analysis (:class:`Pred`), held by its phrase (``Phrase.pred``) while the clause is read."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(slots=True)
class Pred:
    """A predicate under analysis; becomes a ``MotionSpec`` when ``reason`` is empty."""

    phrase: int
    verb: str
    reading: str
    lemma: str
    start: int  # offsets of the predicate word in the normalised text (the span)
    end: int
    ending: str = "final"
    cue: str = ""
    reason: str = ""  # why this is not a motion (endings.NOT_MOTION key)
    negated: bool = False
    actor: str | None = None
    co_actors: tuple[str, ...] = ()  # 太郎と花子が: the others who perform it too
    causer: str | None = None  # 先生は生徒を進ませた: who makes the actor (生徒) do it (先生)
    object: str | None = None
    body_part: str | None = None
    repeat: int = 1
    speed: float = 1.0
    duration: float | None = None
    delay: float | None = None  # seconds before a motion that opens its track
    written: str = ""  # the verb in the user's spelling, dictionary form (登る where verb is 上る)
    noun: str = ""  # the を-noun (object or body part) as written: 足 of 足を止める
    verb_phrase: str = ""  # noun + を + written: 足を止める (MotionSpec.phrase)
    manner: str | None = None  # a manner word: よろよろ, 大股で (MotionSpec.manner)
    style: str | None = None  # the style it gives (nlp.manners): tired
    intensity: float = 1.0
    note: str = ""  # how the verb was read differently from how it is written (手を降る -> 振る)
    head: int | None = None  # phrase index of the head motion
    target: str | None = None  # whom or what it is directed at (nlp.targets)
    target_role: str | None = None
    target_side: str | None = None
    target_person: bool = False
    id: int = 0

    def say(self, said: str) -> None:
        """Add ``said`` to :attr:`note` (how the text was read, shown with the motion)."""
        self.note = f"{self.note}; {said}" if self.note else said

    @property
    def motion(self) -> bool:
        return not self.reason

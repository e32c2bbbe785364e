"""Acting together: 一緒に, 揃って, 二人で, みんなで, 〜を連れて (docs/language.md §9).

A together word (``lexicon.TOGETHER_WORDS``) makes more persons perform the motion it modifies:
the persons joined to it by と (太郎は花子と一緒に歩く: 花子 walks too; 友達と二人で), or, with no
one joined, the group it names itself (みんなで, 二人で, 三人で: its ``persons``, which
:mod:`reference` resolved to the persons named so far), or else the person last named before it in
its sentence who is not an actor there (太郎は花子の手を取って、一緒に踊る: 花子 dances too).  They join the actor from that motion to
the end of the sentence (太郎は花子と一緒に歩いて、座った: both sit), and, as co-actors of
太郎と花子が do, they perform it for the same time (the scheduler's ``together``).
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from .bunsetsu import Phrase
from .lexicon import LEADING_BY_HAND, LOCOMOTION_VERBS, TAKING_ALONG, TOGETHER_WORDS


@dataclass(frozen=True, slots=True)
class Joined:
    """The persons acting together with a motion's actor.

    ``group``: they are a whole group (みんなで), which replaces the actor's own list: its persons in
    the order they were named, the actor first only when the group does not include them.
    """

    names: tuple[str, ...]
    group: bool = False

    def join(self, actors: tuple[str, ...]) -> tuple[str, ...]:
        """The actors of the motion: ``actors`` (the topic or subject) with these persons."""
        if self.group:
            return tuple(dict.fromkeys((*[a for a in actors if a not in self.names][:1], *self.names)))
        return tuple(dict.fromkeys((*actors, *self.names)))


def together(phrases: list[Phrase], partners: Callable[[list[Phrase], int], list[str]]) -> dict[int, Joined]:
    """Predicate phrase index -> the persons who act together with its actor.

    ``partners(phrases, i)`` are the persons joined to phrase ``i`` by と (:func:`actors.partners`).
    """
    out: dict[int, Joined] = {}
    for i, ph in enumerate(phrases):
        if ph.pred is not None and ph.pred.lemma in TAKING_ALONG and ph.pred.ending == "te":
            _taken_along(phrases, i, out)
            continue
        if ph.pred is not None and ph.pred.lemma in LEADING_BY_HAND and ph.pred.ending == "te":
            _by_the_hand(phrases, i, out)
            continue
        if ph.key not in TOGETHER_WORDS and (ph.tokens[0].value is None or not _counted_group(ph)):
            continue
        target = next((k for k in range(i + 1, len(phrases))
                       if phrases[k].group == ph.group and phrases[k].pred), None)
        if target is None:
            continue
        names = partners(phrases, i)
        if names:
            out[target] = Joined(tuple(names))
        elif ph.persons:
            out[target] = Joined(ph.persons, group=True)
        elif ph.key in TOGETHER_WORDS and (other := _other_named(phrases, i)):
            out[target] = Joined((other,))
    return out


def _taken_along(phrases: list[Phrase], i: int, out: dict[int, Joined]) -> None:
    """犬を連れて散歩する, 弟を連れて歩く: the persons of the を-phrase before the て-form of 連れる (phrase ``i``)
    go along: they join the next motion of the sentence, and 連れて is no motion of its own (reason
    ``companion``)."""
    ph = phrases[i]
    taken = next((q for q in reversed(phrases[:i]) if q.group == ph.group and q.pred is None and q.persons
                  and q.key.endswith("を")), None)
    target = _next_in_sentence(phrases, i)
    if taken is None or target is None or ph.pred is None:
        return
    ph.pred.reason = "companion"
    out[target] = Joined(tuple(taken.persons))


def _by_the_hand(phrases: list[Phrase], i: int, out: dict[int, Joined]) -> None:
    """花子は太郎の手を引いて走った, 太郎は花子と手をつないで歩いた: the person whose hand is taken (太郎の手を)
    or held with (花子と) goes along on the walk or run that follows in the sentence; the hand-taking plays
    first, as written."""
    ph = phrases[i]
    before = [q for q in phrases[:i] if q.group == ph.group and q.pred is None]
    hand = next((k for k in range(len(before) - 1, -1, -1) if before[k].key.endswith("手を")), None)
    if hand is None:
        return
    owner = before[hand - 1] if hand > 0 and before[hand - 1].key.endswith("の") else None
    withs = [q for q in before[:hand] if q.key.endswith("と") and q.persons]
    persons = owner.persons if owner is not None and owner.persons else (withs[-1].persons if withs else ())
    target = _next_in_sentence(phrases, i)
    pred = phrases[target].pred if target is not None else None
    if persons and target is not None and pred is not None and pred.lemma in LOCOMOTION_VERBS:
        out[target] = Joined(tuple(persons))


def _next_in_sentence(phrases: list[Phrase], i: int) -> int | None:
    """The index of the first predicate phrase after phrase ``i`` in its sentence, if any."""
    return next((k for k in range(i + 1, len(phrases)) if phrases[k].sentence == phrases[i].sentence
                 and phrases[k].pred), None)


def _other_named(phrases: list[Phrase], i: int) -> str | None:
    """太郎は花子の手を取って、一緒に踊る: with no one joined by と, 一緒に is with the person last named
    before it in its sentence who is not an actor there (花子), if any."""
    sentence = phrases[i].sentence
    actors = {p for q in phrases[:i] if q.sentence == sentence and q.role == "actor" for p in q.persons}
    others = [p for q in phrases[:i] if q.sentence == sentence and q.role != "actor" for p in q.persons
              if p not in actors]
    return others[-1] if others else None


def _counted_group(ph: Phrase) -> bool:
    """三人で / 3人で: a number of persons doing it together (UniDic may tag this で as だ)."""
    toks = ph.tokens
    return len(toks) >= 3 and toks[0].is_number and toks[1].surface == "人" and toks[2].surface == "で"

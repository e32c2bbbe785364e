"""Dependency heads by rule (docs/language.md §4).

Japanese is head-final.  A motion's head is the next motion in its clause
group whose clause level (``endings.Ending.level``) is at least its own:
a て clause skips ながら / たまま clauses (they cannot contain it), a ながら
clause takes the very next motion.  Predicates that are not motions (negated,
relative clauses, の-complements) are never heads.  Every other bunsetsu
depends on the nearest following predicate.
"""
from __future__ import annotations

from .bunsetsu import Phrase
from .endings import ENDINGS


def level(ph: Phrase) -> int:
    return ENDINGS[ph.predicate.ending].level if ph.predicate.ending in ENDINGS else 3


def link_heads(phrases: list[Phrase]) -> None:
    """Set ``head`` and ``why`` on every phrase (motion heads drive the links)."""
    for group in _groups(phrases):
        motions = [ph for ph in group if ph.pred and ph.pred.motion]
        for k, a in enumerate(motions[:-1]):
            need = level(a)
            later = motions[k + 1:]
            head = next((b for b in later if level(b) >= need), later[-1])
            skipped = [b for b in later if b.index < head.index]
            a.head = head.index
            a.predicate.head = head.index
            a.why = _why(a, head, skipped)
        for i, ph in enumerate(group):
            if ph.head is None and not (ph.pred and ph.pred.motion and ph is _last(motions)):
                ph.head = next((b.index for b in group[i + 1:] if b.pred), None)
                if ph.head is not None and not ph.why:
                    ph.why = "depends on the next predicate"


def _last(motions: list[Phrase]) -> Phrase | None:
    return motions[-1] if motions else None


def _why(a: Phrase, head: Phrase, skipped: list[Phrase]) -> str:
    ending = a.predicate.ending
    text = f"{ending} ({a.predicate.cue or '-'}): next motion of level >= {level(a)}"
    if skipped:
        text += ", skipping " + ", ".join(s.key for s in skipped)
    return text


def _groups(phrases: list[Phrase]) -> list[list[Phrase]]:
    groups: list[list[Phrase]] = []
    for ph in phrases:
        if not groups or groups[-1][0].group != ph.group:
            groups.append([])
        groups[-1].append(ph)
    return groups

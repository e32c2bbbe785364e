"""What a phrase means: the action of a verb together with its を-noun.

The verb alone does not always name the action: 腰を上げる is standing up (上げる alone raises
a hand), 肩を落とす a droop, 膝をつく kneeling, 足を組む no arm crossing. :func:`read_phrases`
gives every motion with a を-noun (``Pred.noun``, set with the object and body part) its ``phrase`` (noun + を + the verb as written: 足を止める),
which a clip declaring that phrase plays first (``api/clip_search.py``), and reads the idioms
of ``phrases.json`` as the action they mean: the motion's verb becomes that action, ``written``
keeps the phrase as the user wrote it (dictionary form), and the noun is no object.
docs/language.md §2 ("What a phrase means") lists the rules with examples.
"""
from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from .actors import case_particle, noun_of
from .bunsetsu import Phrase
from .pred import Pred

DATA = Path(__file__).with_name("phrases.json")


@dataclass(frozen=True, slots=True)
class Idiom:
    """A を-noun + verb that means ``action`` (done with body part ``part``; None: the whole body),
    when one of the words ``with_`` (if any) modifies the verb too."""

    action: str
    part: str | None
    with_: frozenset[str]


@lru_cache(maxsize=1)
def _data() -> tuple[dict[tuple[str, str, str], tuple[Idiom, ...]], dict[str, str], frozenset[tuple[str, str]]]:
    """``((particle, noun, verb) -> idioms, body noun -> its part, the props' (noun, verb))`` from
    ``phrases.json``; an idiom with ``with`` words first; an idiom's particle is を unless it says (席に着く)."""
    data = json.loads(DATA.read_text(encoding="utf-8"))
    table: dict[tuple[str, str, str], list[Idiom]] = {}
    for entry in data["idioms"]:
        idiom = Idiom(entry["action"], entry["part"], frozenset(entry.get("with", ())))
        for noun in entry["nouns"]:
            for verb in entry["verbs"]:
                table.setdefault((entry.get("particle", "を"), noun, verb), []).append(idiom)
    ordered = {k: tuple(sorted(v, key=lambda i: not i.with_)) for k, v in table.items()}
    return ordered, dict(data["body_nouns"]), frozenset((n, v) for n, vs in data["props"].items() for v in vs)


@lru_cache(maxsize=1)
def _bare() -> dict[str, str]:
    """``phrases.json`` 'bare': a verb that is another action when it has no を-noun (掛ける: 座る)."""
    return dict(json.loads(DATA.read_text(encoding="utf-8"))["bare"])


def body_nouns() -> dict[str, str]:
    """Nouns of the actor's body that ``lexicon.BODY_PARTS`` gives no body part (目, 肩, 膝, ...), each with
    the part it is on: ``head``, ``torso``, ``arm`` or ``leg``."""
    return _data()[1]


def idiom(noun: str, verbs: tuple[str, ...], words: Callable[[], frozenset[str]] = frozenset,
          particle: str = "を") -> Idiom | None:
    """The idiom ``noun`` + ``particle`` + one of ``verbs`` (spellings of one verb: as written, its lemma)
    is, given the other ``words()`` that modify the verb (asked only of an idiom that needs one); None
    when the phrase means what its verb does."""
    table = _data()[0]
    for verb in verbs:
        for entry in table.get((particle, noun, verb), ()):
            if not entry.with_ or entry.with_ & words():
                return entry
    return None


def read_phrases(preds: list[Pred], phrases: list[Phrase]) -> None:
    """Give each motion of ``preds`` with a を-noun (``Pred.noun``: or a bare noun, 手振って) its
    phrase and read an idiom as the action it means (module docstring); ``phrases`` are the text's."""
    for k, pred in enumerate(preds):
        if not pred.noun and pred.motion and (pred.written or pred.verb) in _bare():
            # ソファに掛ける: 座る, looked up as that verb (the planner tries ``written`` first: hang_up)
            pred.verb, pred.written, pred.reading = _bare()[pred.written or pred.verb], "", ""
        if pred.noun and pred.motion:
            index = pred.phrase
            _read(pred, pred.noun, lambda: frozenset(p.key for p in phrases if p.head == index and p.pred is None))
            _hand_on(pred, preds[k + 1:], phrases)
        elif pred.motion:
            _read_place(pred, phrases)


def _hand_on(pred: Pred, later: list[Pred], phrases: list[Phrase]) -> None:
    """杖をついて歩く: a prop's phrase (``phrases.json`` 'props') in て-form is no motion; its noun is the
    object of the next motion of the sentence that has none (the walk, the cane in hand)."""
    spelled = {(pred.noun, pred.written or pred.verb), (pred.noun, pred.lemma)}
    if pred.ending not in ("te", "renyou") or not spelled & _data()[2]:
        return
    sentence = phrases[pred.phrase].sentence
    nxt = next((q for q in later if q.motion), None)
    if nxt is None or phrases[nxt.phrase].sentence != sentence:
        return
    pred.reason = "prop"
    if nxt.object is None:
        nxt.object = pred.noun


def _read_place(pred: Pred, phrases: list[Phrase]) -> None:
    """席に着く: an idiom of a に-noun (``particle`` に in ``phrases.json``) read as the action it means; the
    noun stays where the action is done (the seat sat on). 兄の後をついて: the noun after の of a phrase that
    ends in を (one phrase to UniDic) is read as a を-noun."""
    written = pred.written or pred.verb
    for ph in phrases:
        if ph.head != pred.phrase or ph.pred is not None:
            continue
        inner = _after_no(ph)
        noun, particle = (inner, "を") if inner else (noun_of(ph), "に") if case_particle(ph) == "に" else ("", "")
        found = idiom(noun, (written, pred.lemma, pred.verb), particle=particle) if noun else None
        if found is not None:
            pred.verb_phrase = f"{noun}{particle}{written}"
            _becomes(pred, found)
            return


def reread(pred: Pred, noun: str) -> None:
    """Read ``pred`` with the を-noun ``noun`` it turned out to have (それ: the ball, in バッターはそれを打った)."""
    _read(pred, noun, frozenset)


def _after_no(ph: Phrase) -> str:
    """The nouns between the last の and a final を of ``ph`` (兄の後を -> 後), '' when it is not so made."""
    toks = [t for t in ph.tokens if t.pos1 != "補助記号"]
    if len(toks) < 4 or toks[-1].surface != "を":
        return ""
    k = max((i for i, t in enumerate(toks[:-1]) if t.surface == "の" and t.pos1 == "助詞"), default=-1)
    between = toks[k + 1:-1]
    return "".join(t.surface for t in between) if k > 0 and between and all(t.pos1 == "名詞" for t in between) else ""


def _read(pred: Pred, noun: str, words: Callable[[], frozenset[str]]) -> None:
    written = pred.written or pred.verb
    pred.verb_phrase = f"{noun}を{written}"
    found = idiom(noun, (written, pred.lemma, pred.verb), words)
    if found is None:
        return
    if found.with_:  # 首を縦に振る: the word that makes it this idiom is part of the phrase
        pred.verb_phrase = f"{noun}を{min(found.with_ & words())}{written}"
    if _becomes(pred, found):
        pred.object = None


def _becomes(pred: Pred, found: Idiom) -> bool:
    """``pred`` read as the action ``found`` means, its phrase (``verb_phrase``) kept as written; an idiom done
    with the face alone (目を覚ます) is no motion, said in the note. Whether it became another action."""
    if not found.action:  # 目を覚ます: the face alone, which no clip animates
        pred.reason = "unseen"
        pred.say(f"{pred.verb_phrase}: the face is not animated, nothing plays for it")
        return False
    pred.verb, pred.written, pred.reading, pred.body_part = found.action, pred.verb_phrase, "", found.part
    return True

"""Actors: who performs each predicate, named as the user wrote it (docs/language.md §2, §7.1-§7.2).

A person noun or name marked は/が/も, a vocative (花子さん、), or a script's speaker
label (花子：) names the actor; は sets a topic that carries over, が binds to its
own clause, と joins co-actors.  The name keeps its prefix and suffixes (お父さん,
子供たち); only an honorific right after a given name is dropped (花子さん -> 花子).
"""
from __future__ import annotations

from .bunsetsu import FUNCTION_POS, Phrase
from .endings import ENDINGS
from .lexicon import HONORIFICS, PERSON_NOUNS, PLACE_OF_NOUNS, SCRIPT_HEADINGS, SIDE_NOUNS
from .persons import refers, words_of
from .together import Joined, together
from .tokens import is_name
from .types import Token


def case_particle(ph: Phrase) -> str:
    """The particle(s) after the nouns: は, が, を, で ... ('' if several or none)."""
    parts = [t.surface for t in ph.tokens if t.pos1 == "助詞"]
    return parts[0] if len(parts) == 1 else ""


def noun_of(ph: Phrase) -> str:
    """The noun of a noun phrase: its last run of nouns (with prefixes)."""
    run: list[str] = []
    for t in ph.tokens:
        if t.pos1 in ("名詞", "代名詞", "接頭辞") and not t.is_number:
            run.append(t.surface)
        elif t.pos1 == "接尾辞" and run:
            continue
        elif t.pos1 in FUNCTION_POS:
            break
        else:
            run = []
    return "".join(run)


def speaker_label(ph: Phrase) -> str | None:
    """花子: / お父さん： / 店員A: opening a line: a script's speaker label names the actor
    of that line, person noun or not (as written, honorific after a name dropped)."""
    toks = ph.tokens
    if len(toks) < 2 or toks[-1].surface != ":":
        return None
    words = toks[:-1]
    if not all(t.pos1 in ("名詞", "代名詞", "接頭辞", "接尾辞") for t in words):
        return None
    name = as_written(words)
    return None if name in SCRIPT_HEADINGS else name


def person_name(ph: Phrase) -> str | None:
    """The actor name if ``ph`` names a person (太郎, 花子さん, 彼, お父さん, 子供たち, 店長, 運転手),
    or refers to persons (二人, みんな: :mod:`reference` says whom), as written (kept in ``ph.named``)."""
    named = ph.named
    if named is False:
        named = ph.named = _person_name(ph)
    return named if isinstance(named, str) else None


def _person_name(ph: Phrase) -> str | None:
    toks = ph.tokens
    if toks[-1].surface == ":":
        return speaker_label(ph)
    nouns: list[Token] = []
    affixed = honorific = proper = False
    for k, t in enumerate(toks):  # one pass: this runs on most phrases of every text
        pos1 = t.pos1
        if pos1 == "助詞" and t.surface == "の" and nouns and side_after_no(toks[k + 1:]) is not None:
            return None  # 兄の後を, 花子の前に: a place beside a person, not a person
        if pos1 == "名詞" or pos1 == "代名詞":
            nouns.append(t)
            proper = proper or t.pos3 == "人名"
        elif pos1 == "接頭辞":
            affixed = True
        elif pos1 == "接尾辞":
            affixed = True
            honorific = honorific or t.surface in HONORIFICS
    if not nouns:
        return None
    name = nouns[0].surface if len(nouns) == 1 else "".join(t.surface for t in nouns)
    if not (honorific or proper or name in PERSON_NOUNS
            or (len(nouns) == 1 and nouns[0].pos1 == "名詞" and nouns[0].pos3 != "サ変可能" and is_name(name))
            or refers(words_of(toks))):  # ゴール (a goal; Gaul) is an action noun here, no name
        return None
    return as_written(toks) if affixed else name


def side_after_no(toks: list[Token]) -> str | None:
    """The side or place noun the words after a の name (後, 前, ところ: 花子の前に), ``None`` when they name none."""
    rel = "".join(t.surface for t in toks if t.pos1 in ("名詞", "接尾辞"))
    return rel if rel in SIDE_NOUNS or rel in PLACE_OF_NOUNS else None


def as_written(toks: list[Token]) -> str:
    """The name as the user wrote it: prefix, nouns and suffixes (お父さん, おじいちゃん,
    子供たち); an honorific right after a given name is not part of it (花子さん -> 花子)."""
    run: list[Token] = []
    for t in toks:
        if t.pos1 in ("名詞", "代名詞", "接頭辞") or (t.pos1 == "接尾辞" and run):
            run.append(t)
        elif run:
            break
    while (len(run) > 1 and run[-1].pos1 == "接尾辞" and run[-1].surface in HONORIFICS
           and given_name(run[-2]) and "".join(t.surface for t in run) not in PERSON_NOUNS):
        run.pop()  # 花子さん -> 花子, but 王様 stays 王様
    return "".join(t.surface for t in run)


def given_name(tok: Token) -> bool:
    """Can ``tok`` be a given name (花子, ゆうた), after which an honorific is no part of the name?"""
    return tok.pos3 == "人名" or (tok.pos1 == "名詞" and tok.surface not in PERSON_NOUNS and is_name(tok.surface))


def assign_actors(phrases: list[Phrase]) -> None:
    """は/も set the topic, which carries over; が binds to its own clause.

    A が-subject holds until a clause that ends it (てから, 間に, 前に, の,
    relative, ...); then the topic is back, or, if the text has no topic yet,
    the が-subject carries over as the contract's "nearest preceding" rule.
    Coordinated actors (太郎と花子が) are one group: every one of them performs
    the motions (the first is ``actor``, the others ``co_actors``).  Who a phrase
    names is its ``persons`` (:func:`reference.resolve_persons`: 彼女 is 花子); the
    persons who act together with the actor (花子と一緒に, みんなで:
    :func:`together.together`) join it from the motion they modify to the end of
    the sentence.
    """
    topic: tuple[str, ...] = ()
    subject: tuple[str, ...] = ()
    group = None
    joined = together(phrases, partners)
    companions: Joined | None = None
    for i, ph in enumerate(phrases):
        if ph.group != group:
            if subject:
                topic, subject = subject, ()
            if group is None or phrases[i - 1].sentence != ph.sentence:
                companions = None
            group = ph.group
        if ph.role == "actor":
            names = _distinct((*partners(phrases, i), *ph.persons))
            if case_particle(ph) == "が":
                subject = names
            else:
                topic, subject = names, ()
            companions = None
            continue
        pred = ph.pred
        if not pred:
            continue
        companions = joined.get(i, companions)
        if not (subject or topic):
            topic = _topic_after(phrases, i)  # 先生にお辞儀をして、生徒は走り去った: 生徒 bows too
        names = companions.join(subject or topic) if companions else subject or topic
        pred.actor = names[0] if names else None
        pred.co_actors = names[1:]
        ending = ENDINGS.get(pred.ending)
        closes = ending.closes_subject if ending else True
        if closes and subject:
            topic = topic or subject
            subject = ()


def _topic_after(phrases: list[Phrase], i: int) -> tuple[str, ...]:
    """The persons of the first は-topic later in phrase ``i``'s sentence, for a text that opens with a clause
    before its topic (先生にお辞儀をして、生徒は走り去った); () if none."""
    for ph in phrases[i + 1:]:
        if ph.sentence != phrases[i].sentence:
            break
        if ph.role == "actor" and case_particle(ph) in ("は", "も") and ph.persons:
            return _distinct((*partners(phrases, phrases.index(ph)), *ph.persons))
    return ()


def partners(phrases: list[Phrase], i: int) -> list[str]:
    """The persons joined to phrase ``i`` by と just before it (太郎と次郎と花子が)."""
    names: list[str] = []
    j = i - 1
    while j >= 0 and phrases[j].group == phrases[i].group and case_particle(phrases[j]) == "と":
        if not phrases[j].persons:
            break
        names[:0] = phrases[j].persons
        j -= 1
    return names


def _distinct(names) -> tuple[str, ...]:
    return tuple(dict.fromkeys(names))

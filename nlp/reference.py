"""Reference: whom each phrase naming a person refers to, across sentences (docs/language.md §9).

The text is read in order and every person it names (a name, a person noun, a speaker label: 花子,
店長, 係の人, おまわりさん) is remembered, the most recently named last, whatever the phrase's
particle (花子に, 花子を and 花子の name her too).  Then:

- a **pronoun or description** refers back to one of them: 彼 to the last man named, 彼女 to the
  last woman, その人 / あの人 / あいつ to the last person of either sex, その男 / あの子 by the sex
  of its noun, その店長 to the last 店長 first.  Whether a name is a man's or a woman's is read
  from its ending (花子: -子, :func:`persons.name_sex`), a guess; a person whose sex the text does
  not say is taken when no one of the pronoun's sex was named, and a pronoun that has only one
  candidate takes it, unless a word said that one's sex (父, or 彼 before).  A pronoun that is not the actor of its clause does not refer to
  that actor (太郎は彼に手を振る: 彼 is someone else).  First- and second-person words (私, 君)
  are never what 彼 refers to.
- a **group word** names several: 二人 / ふたり the last two persons named, 三人 the last three,
  みんな / 彼ら / 全員 every person named so far, in the order they were named; it needs at least
  two of them. A person noun after a counted group and の is that group (二人の子ども), and 一人 /
  もう一人 after a group are its members in turn (一人が転んだ。もう一人は…: 一人目, then 二人目).
- a pronoun or group that refers to no one named keeps its own name as before (彼女, 彼ら: a
  character of its own; みんな then names no one, and the motion is the default character's); a counted
  group (二人, 3人) is the persons named and new characters for the rest (一人目, 二人目, ...).

Each phrase gets ``persons``: the canonical names (as the actor field writes them) of whom it
names; the analysis says every reading of a pronoun or group in ``notes`` (stderr, ``--explain``).
"""
from __future__ import annotations

from typing import NamedTuple

from .actors import case_particle, person_name
from .bunsetsu import Phrase
from .lexicon import GROUP_WORDS, HONORIFICS, ONE_OF_GROUP, PERSON_HEADS, PRONOUNS, SPEAKERS
from .persons import DEMONSTRATIVES, group_size, is_person_noun, name_sex, noun_sex, pronoun_sex, words_of
from .tokens import is_name
from .types import Token


class Mention(NamedTuple):
    """What one phrase says of a person.

    ``kind``: ``name`` (a name or person noun), ``pronoun`` (彼, その人, その男), ``group`` (二人,
    みんな) or ``member`` (一人 of a group named before, 二人の子ども's 子ども); ``written``: the name as
    the analysis writes it (花子 for 花子さん) or the pronoun as written; ``sex``: "m", "f" or "" (either); ``size``: a group's size (0: everyone named);
    ``noun``: a description's own person noun (その店員: 店員), matched before any other;
    ``guessed``: the sex is read from a name's ending, not said by a word (父, 彼).
    """

    kind: str
    written: str
    sex: str = ""
    size: int = 0
    noun: str = ""
    guessed: bool = False


def mention(phrases: list[Phrase], i: int) -> Mention | None:
    """What phrase ``i`` says of a person, ``None`` when it names none (or is a predicate)."""
    ph = phrases[i]
    if ph.pred is not None:
        return None
    name = person_name(ph)
    if name is None:
        return None
    words = words_of(ph.tokens)
    prev = _neighbour(phrases, i, -1)
    if prev is not None and prev.key in DEMONSTRATIVES:
        words = [prev.tokens[0], *words]  # あの人: UniDic tags this あの a filler, a phrase of its own
    if words and (name in PRONOUNS or name in GROUP_WORDS or words[0].surface in DEMONSTRATIVES
                  or words[0].is_number):
        bare = words[1:] if words[0].surface in DEMONSTRATIVES else words
        size = group_size(bare)
        if size is not None:
            return Mention("group", name, size=size)
        sex = pronoun_sex(words)
        if sex is not None:
            noun = "".join(t.surface for t in bare) if len(words) > len(bare) else ""
            return Mention("pronoun", "".join(t.surface for t in words), sex,
                           noun="" if noun in PERSON_HEADS else noun)
    if _modifies_person(ph, _neighbour(phrases, i, 1)):
        return None  # 新入社員の山田さん, 係の人: the phrase after it names the person
    if prev is not None and _modifier(prev):
        if name in PERSON_HEADS:
            return Mention("name", prev.key + name, noun_sex(words))  # 係の人, 隣の人
        if not (_proper(words) or is_person_noun(words) or _honorific(words)):
            return None  # たろうのほう: after の, a word that could be a name is a thing (方)
    if any(t.pos3 == "人名" for t in words) or is_name(name):
        return Mention("name", name, name_sex(name), guessed=True)
    return Mention("name", name, noun_sex(words))


def resolve_persons(phrases: list[Phrase]) -> list[str]:
    """Set ``persons`` on every phrase naming a person (module docstring); the notes saying how each
    pronoun and group word was read (``read 彼女 as 花子 (the last woman named)``)."""
    seen = _Named()
    notes: list[str] = []
    acting: dict[int, tuple[str, ...]] = {}  # clause group -> the persons its last actor phrase named
    subjects: dict[int, list[str]] = {}  # sentence -> the persons its が-actors named so far
    counted: tuple[int, tuple[str, ...]] | None = None  # 二人の (its phrase, whom it names) before 子ども
    for i, ph in enumerate(phrases):
        if ph.role not in _MAY_NAME or ph.pred is not None or person_name(ph) is None:
            continue  # (asked of most phrases of every text: what mention() would refuse first, cheaply)
        m = mention(phrases, i)
        if m is None:
            continue
        particle = case_particle(ph)
        if m.kind == "name" and m.guessed and particle == "を" and not _tagged(ph):
            continue  # 本を取る: a を-object that is a name only because it can be one is a thing
        actor = ph.role == "actor" or particle in ("は", "が", "も")
        persons: tuple[str, ...]
        why = ""
        if m.written in ONE_OF_GROUP and seen.members:
            m = m._replace(kind="member")
            persons, why = seen.member(_after_mou(phrases, i))
        elif m.kind == "name" and counted and counted[0] == i - 1 and is_person_noun(words_of(ph.tokens)):
            m = m._replace(kind="member")
            persons, why = counted[1], f"{phrases[i - 1].key}{m.written}: a group of them"
        elif m.kind == "name":
            persons = (m.written,)
        elif m.kind == "group":
            persons, why = seen.group(m)
        elif not actor:
            persons, why = seen.pronoun(m, acting.get(ph.group, ()))
        else:
            topic = particle in ("は", "も")
            persons, why = _topic_pronoun(seen, m, tuple(subjects.get(ph.sentence, ())) if topic else ())
        if m.kind != "name" and not persons:
            later = _named_after(phrases, i, seen.order) if m.kind == "group" else ()
            persons = _unresolved(ph, m, seen.order, later)
            if len(persons) > 1:
                new = [p for p in persons if p in ORDINALS]
                notes.append(f"read {m.written} as {'、'.join(persons)} (" + ("fewer were named: the rest are new "
                             "characters" if new else "named in the sentences after it") + ")")
        elif persons != (m.written,):
            notes.append(f"read {m.written} as {'、'.join(persons)} ({why})")
        ph.persons = persons
        counted = (i, persons) if m.kind == "group" and ph.key.endswith("の") and len(persons) > 1 else None
        if m.kind in ("name", "pronoun"):
            seen.learn(persons, m.sex, m.guessed)
        elif m.kind == "group" and len(persons) > 1:
            seen.members, seen.picked = persons, []
        seen.add(persons)
        if actor:
            acting[ph.group] = persons  # 花子が泣いていると、太郎が…彼女の頭を: only 太郎 is not 彼女
        if particle == "が":
            subjects.setdefault(ph.sentence, []).extend(persons)
    return notes


def _topic_pronoun(seen: _Named, m: Mention, subjects: tuple[str, ...]) -> tuple[tuple[str, ...], str]:
    """Whom a pronoun that is an actor (彼は, 彼も) refers to. A が-subject earlier in its sentence is
    someone else when another fits (父は新聞を読んでいた。息子が帰ってくると、彼は顔を上げた: 彼 is 父;
    兄が止まると、彼も止まった: 彼 is not 兄): a clause's が marks a new subject, the main clause's
    は or も goes back to the one the story is about."""
    if subjects:
        persons, why = seen.pronoun(m, subjects)
        if persons:
            return persons, f"{why}, not {'、'.join(subjects)} of the clause before"
    return seen.pronoun(m, ())


def _tagged(ph: Phrase) -> bool:
    """Is ``ph`` a person by more than a word that can be a name: tagged a name here, a person noun,
    or with an honorific?"""
    return _proper(ph.tokens) or _honorific(ph.tokens) or is_person_noun(words_of(ph.tokens))


#: The roles of a phrase that may name a person (not a predicate, a body part, a time or manner word).
_MAY_NAME = frozenset(["actor", "object", "", "number"])  # number: 三人で


class _Named:
    """The persons named so far: in the order first named, most recent last, and their sex (``sure``:
    the persons whose sex a word said, not a name's ending)."""

    def __init__(self) -> None:
        self.order: list[str] = []
        self.recent: list[str] = []
        self.sexes: dict[str, str] = {}
        self.sure: set[str] = set()
        self.members: tuple[str, ...] = ()  # the last group named (二人), whose 一人 / もう一人 are its members
        self.picked: list[str] = []

    def learn(self, persons: tuple[str, ...], sex: str, guessed: bool) -> None:
        """A lone person named by a word of a sex takes it, where it was unknown or only guessed
        (店長 referred to by 彼 is a man from then on)."""
        if len(persons) != 1 or not sex or persons[0] in self.sure:
            return
        p = persons[0]
        if guessed and self.sexes.get(p):
            return
        self.sexes[p] = sex
        if not guessed:
            self.sure.add(p)

    def add(self, persons: tuple[str, ...]) -> None:
        """``persons`` were named (again): the most recent now."""
        for p in persons:
            if p not in self.order:
                self.order.append(p)
            if p in self.recent:
                self.recent.remove(p)
            self.recent.append(p)

    def pronoun(self, m: Mention, exclude: tuple[str, ...]) -> tuple[tuple[str, ...], str]:
        """(the person ``m`` refers to, why) or ((), "") when it refers to no one named."""
        cands = [p for p in reversed(self.recent) if p not in exclude and p not in SPEAKERS]
        if m.noun:
            same = [p for p in cands if p == m.noun or p.endswith(m.noun)]
            if same:
                return (same[0],), f"the last {m.noun} named"
        if m.sex:
            same = [p for p in cands if self.sexes.get(p) == m.sex]
            if same:
                return (same[0],), "the last man named" if m.sex == "m" else "the last woman named"
            lone = cands if len(cands) == 1 and cands[0] not in self.sure else []
            cands = [p for p in cands if not self.sexes.get(p)] or lone
        if not cands:
            return (), ""
        return (cands[0],), "the only person named" if len(self.order) == 1 else "the last person named"

    def member(self, other: bool) -> tuple[tuple[str, ...], str]:
        """一人 of the last group named: its first member not yet named so; もう一人 (``other``): one not
        yet named since (二人は歩いた。一人が止まった。もう一人は振り返った: 一人目, then 二人目)."""
        pick = next((p for p in self.members if p not in self.picked), self.members[0])
        self.picked.append(pick)
        group = "、".join(self.members)
        return (pick,), f"{'another' if other else 'one'} of {group}"

    def group(self, m: Mention) -> tuple[tuple[str, ...], str]:
        """(the persons group ``m`` names, in the order they were named, why) or ((), "")."""
        if len(self.order) < max(2, m.size):
            return (), ""
        if not m.size or m.size == len(self.order):
            return tuple(self.order), "the persons named so far"
        last = set(self.recent[-m.size:])
        return tuple(p for p in self.order if p in last), f"the last {m.size} persons named"


#: The characters a counted group that refers to no one named brings on: 二人 -> 一人目, 二人目.
ORDINALS = tuple(f"{k}人目" for k in "一二三四五六七八九十")


def _unresolved(ph: Phrase, m: Mention, named: list[str], later: tuple[str, ...] = ()) -> tuple[str, ...]:
    """A pronoun or group that refers to no one named: 彼女, 彼ら and 皆さん are characters of their
    own (as written, as before this rule); 二人 / 三人 with fewer named before are those ``named``, then
    the actors ``later`` sentences name first (:func:`_named_after`), and new characters for the rest
    (:data:`ORDINALS`, up to ten: 太郎は3人で踊った is 太郎, 二人目 and 三人目; 二人は並んで歩いた。途中で太郎が
    転んだ。花子は彼を助け起こした is 太郎 and 花子); みんな as an actor is a character of its own
    (花子が歌い出すと、みんなが手拍子をした: not 花子), elsewhere it names no one."""
    if m.kind == "group" and len(named) < m.size <= len(ORDINALS):
        known = (*named, *later[:m.size - len(named)])
        return (*known, *ORDINALS[len(known):m.size])
    if m.kind == "group" and not (any(t.pos1 == "代名詞" for t in ph.tokens) or _honorific(ph.tokens)
                                  or case_particle(ph) in ("は", "が")):
        return ()
    name = person_name(ph)
    return (name,) if name else ()


def _named_after(phrases: list[Phrase], i: int, named: list[str]) -> tuple[str, ...]:
    """The persons the sentences after phrase ``i``'s name first as actors (は, が, も) by a name or person noun,
    in order, not among ``named``: whom a counted group the text opens with turns out to be (二人は歩いた。
    途中で太郎が転んだ。花子は…). A reader takes the two for the two the story goes on with."""
    out: list[str] = []
    for j in range(i + 1, len(phrases)):
        ph = phrases[j]
        if ph.sentence == phrases[i].sentence or ph.pred is not None or ph.role not in _MAY_NAME \
                or person_name(ph) is None or case_particle(ph) not in ("は", "が", "も"):
            continue
        m = mention(phrases, j)
        if m is not None and m.kind == "name" and m.written not in ONE_OF_GROUP and m.written not in named \
                and m.written not in out:
            out.append(m.written)
    return tuple(out)


def _after_mou(phrases: list[Phrase], i: int) -> bool:
    """Is phrase ``i`` (一人) after もう (もう一人: the other one)?"""
    prev = _neighbour(phrases, i, -1)
    return prev is not None and prev.key == "もう" or phrases[i].tokens[0].surface == "もう"


def _neighbour(phrases: list[Phrase], i: int, step: int) -> Phrase | None:
    """The phrase before (``step`` -1) or after (+1) ``i`` in the same sentence."""
    j = i + step
    if 0 <= j < len(phrases) and phrases[j].sentence == phrases[i].sentence:
        return phrases[j]
    return None


def _modifier(ph: Phrase) -> bool:
    """係の / 隣の: nouns and の only, modifying the phrase after it."""
    toks = ph.tokens
    return (len(toks) >= 2 and toks[-1].surface == "の" and toks[-1].pos1 == "助詞"
            and all(t.pos1 in ("名詞", "接頭辞", "接尾辞") and not t.is_number for t in toks[:-1]))


def _modifies_person(ph: Phrase, nxt: Phrase | None) -> bool:
    """A person noun + の before the phrase naming that person: 新入社員の + 山田さん (apposition),
    係の + 人.  花子の友達 is not one: a name + の is whose friend it is."""
    if nxt is None or not _modifier(ph) or _proper(ph.tokens):
        return False
    head = words_of(nxt.tokens)
    return bool(head) and (_proper(head) or "".join(t.surface for t in head) in PERSON_HEADS)


def _proper(words: list[Token]) -> bool:
    return any(t.pos3 == "人名" for t in words)


def _honorific(words: list[Token]) -> bool:
    return any(t.pos1 == "接尾辞" and t.surface in HONORIFICS for t in words)

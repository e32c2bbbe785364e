"""Targets: whom or what a motion is directed at, and where it goes (docs/language.md §8).

A person or thing marked に / へ / まで / から / と (also 〜の前に, 〜のところへ, 〜に向かって) or a person
marked を becomes a field of the motion it depends on, not a motion: ``target`` (the noun as
written, a person by the actor's name), ``target_role`` and ``target_side``:

============== ======================================================================
``goal``       where a motion that travels ends: 花子に近づく, 駅まで走る, 花子の前に立つ
``source``     where it starts from: 花子から離れる, 椅子から立ち上がる, 店を出る
``addressee``  whom a gesture or speech is for: 花子に手を振る, 先生にお辞儀する
``patient``    the person a motion is done to: 花子を抱きしめる, 花子を指さす
``recipient``  the person a thing is sent to: 花子に本を渡す, 花子にボールを投げる
``partner``    the person who does it with the actor: 花子と握手する, 花子と歩く
``support``    the thing that holds the body up: 椅子に座る, ベンチに腰掛ける
``destination`` where a thing is put: 机に置く
``at``         any other thing the motion is done at: 壁に手をつく
============== ======================================================================

``target_side`` says where relative to the target (花子の前に: ``front``; ``behind``, ``beside``,
``near``, ``on``, ``under``, ``around``, ``left``, ``right``); で after a side noun says it as に does
(ドアの前で), and a side noun marked を is no object (花子の方を向く, 木の周りを歩く); 机の上のペンを取る takes
the pen from the desk (``source``). A motion keeps one target; another noun with a role is said in its
note. A partner performs the motion too (a co-actor, facing or beside the actor: the scene decides by the
verb); 向かい合って / 向き合って make the actors of the
next motion each other's partners and are no motion of their own, nor is に向かって (its noun is
the next motion's goal). A gesture with no target of its own right after a motion of the same actor
directed at a person (近づいて、お辞儀する) is addressed to that person, unless the body only went to their
side (隣に立って、写真を撮る). それ / これ as an object is the thing last named; a door verb with no object
(開ける, ノックする) is done to the thing the actor has just handled or gone to, a carry (運ぶ) to the thing
just handled.
"""
from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

from .actors import as_written, noun_of, person_name, side_after_no
from .bunsetsu import Phrase
from .lexicon import (
    ANIMALS, AROUND_NOUNS, BODY_PARTS, CATCHING_VERBS, CHASING_VERBS, CONTACT_VERBS, COUNTERPARTS, DIRECTION_TE, DOOR_VERBS,
    FACING_VERBS, HONORIFICS, LOCOMOTION_VERBS, LOWERING_VERBS, MOVING_VERBS, NOT_TARGETS, OFF_VERBS,
    PERSON_NOUNS, PLACE_OF_NOUNS, PLACING_VERBS, RECEIVING_VERBS, RECIPROCAL_VERBS, RISING_VERBS, SEATS, SIDE_NOUNS, SUPPORT_VERBS, TELLING,
    THING_ANAPHORS, THROWING_VERBS, TRANSFER_VERBS,
)
from .persons import refers, words_of
from .phrases import body_nouns, reread
from .pred import Pred
from .tagging import tagger
from .types import Constraint, MotionSpec

#: Particles that mark a target, and the ones a 〜の + noun phrase may end with.
TARGET_PARTICLES = frozenset("に へ まで から と".split())
#: Verbs whose を-place is where the actor leaves from (店を出る).
LEAVING_VERBS = frozenset("出る 離れる 去る 別れる 帰る 降りる 下りる 立ち去る 出て行く 走り去る 歩き去る 駆け去る 逃げ去る 逃げ出す".split())
#: The て-forms that may say a way or a facing, no motion of their own.
_WAY_TE = FACING_VERBS | DIRECTION_TE
#: Roles a person keeps as the addressee of a following gesture (近づいて、お辞儀する).
DIRECTED = frozenset(("goal", "addressee", "partner", "patient", "recipient"))
#: Sides of a goal that put the body by the person, not before them: a gesture after 花子の隣に立って is for
#: no one in particular (写真を撮る), not addressed to her.
ALONGSIDE = frozenset(("beside", "behind", "left", "right", "around", "under", "on"))


class Target:
    """A noun a motion is directed at: ``name`` as written, whether it is a ``person``, the particle
    that marked it and the side (``SIDE_NOUNS``), and the phrases it spans (``phrases``)."""

    __slots__ = ("name", "person", "particle", "side", "phrases", "sure", "covers")

    def __init__(self, name: str, person: bool, particle: str, side: str | None, phrases: tuple[int, ...],
                 sure: bool = True, covers: str | None = None):
        self.name, self.person, self.particle, self.side, self.phrases = name, person, particle, side, phrases
        self.sure = sure  # a person by more than a word that can be a name (机 is also a surname)
        self.covers = covers  # the side noun read as the motion's を-object (花子の方を向く: 方), if any


def attach_targets(phrases: list[Phrase]) -> None:
    """Give each motion its target (this module's docstring); a thing read from それ is said in its note."""
    pending: list[Target] = []
    group = None
    actors = {a for ph in phrases if ph.pred for a in (ph.pred.actor, *ph.pred.co_actors) if a}
    done: list[Pred] = []  # the motions so far
    for i, ph in enumerate(phrases):
        if ph.group != group:
            pending, group = [], ph.group
        pred = ph.pred
        if pred is None:
            found = _target_at(phrases, i)
            if found is not None and (not pending or i not in pending[-1].phrases):
                pending.append(found)
            continue
        if pred.reason in ("direction", "facing"):
            continue  # its noun waits for the motion it says the way of
        if pred.reason == "non-agent":
            by = next((t.name for t in reversed(pending) if t.person), None) or _person_by(phrases, i)
            _sent_to(pred, by, done)
            pending = []
            continue
        if pred.motion:
            done.append(pred)
            _settle(pred, pending, actors)
            _giving(pred)
            if pred.target is None and pred.verb in LOCOMOTION_VERBS and (_comes(ph) or pred.verb in COMING_VERBS):
                _come_to(pred, phrases, i)
        pending = []
    _follow_on([ph.pred for ph in phrases if ph.pred is not None])


#: Verbs of coming to someone: with no one named, to the person the story is with (:func:`_come_to`).
COMING_VERBS = frozenset("来る 駆けつける 駆け付ける 駆け寄る 走り寄る 近寄る 歩み寄る 近付く 戻る 現れる 現われる 姿を現す".split())
#: Verbs of parting: co-actors who part each leave the other (二人は握手をして別れた).
PARTING_VERBS = frozenset("別れる 分かれる".split())
#: Verbs of running away: with no one named, from whoever last came to the actor (熊が現れた。少年は逃げ出した).
FLEEING_VERBS = frozenset("逃げる 逃げ出す 逃げ去る".split())


#: 上げる with a thing sent to someone is giving it (花子に本をあげた: hands it over; 鳩にパンをあげた: puts it
#: down for the animal), no raised hand: what it is played as.
GIVING = {"person": "渡す", "animal": "置く"}


def _giving(pred: Pred) -> None:
    """花子に本をあげた, 鳩にパンをあげた: 上げる with a thing (no part of the body) sent to a person or an animal
    gives it (:data:`GIVING`); said in the note."""
    if pred.verb != "上げる" or pred.object is None or pred.object in BODY_PARTS or pred.target is None:
        return
    to = "person" if pred.target_person else "animal" if pred.target in ANIMALS else None
    if to is None:
        return
    pred.say(f"{pred.written or pred.verb} {pred.object} to {pred.target}: gives it, played as {GIVING[to]}")
    pred.verb = GIVING[to]


def _comes(ph: Phrase) -> bool:
    """Is ``ph`` a motion + て + くる (帰ってくる, 入ってきた, 走ってくる): towards where the story is?"""
    toks = ph.tokens
    return any(t.lemma == "て" and t.pos1 == "助詞" and toks[k + 1].lemma == "来る"
               for k, t in enumerate(toks[:-1]))


def _come_to(pred: Pred, phrases: list[Phrase], i: int) -> None:
    """息子が帰ってくると、父は…: someone who comes with nowhere named comes to the person the story is with,
    the actor named nearest before (else after) who is someone else."""
    def others(seq):
        return (a for ph in seq if ph.pred and ph.pred.motion for a in (ph.pred.actor,) if a and a != pred.actor)
    person = next(others(reversed(phrases[:i])), None) or next(others(phrases[i + 1:]), None)
    if person is not None:
        pred.target, pred.target_role, pred.target_person = person, "goal", True


# ---------------------------------------------------------------- the nouns


def _particle(ph: Phrase) -> str:
    """The last particle of a noun phrase (に of 花子の前に), '' if none."""
    for t in reversed(ph.tokens):
        if t.pos1 == "助詞":
            return t.surface
        if t.pos1 != "補助記号":
            return ""
    return ""


def _name(ph: Phrase, strict: bool = False) -> tuple[str, bool]:
    """The noun a phrase names and whether it is a person (花子さんに -> 花子). ``strict`` (a を-object:
    本を渡す) does not take a word for a name only because it can be one (本 is also a surname): the
    word must be tagged a name, be a person noun or carry an honorific."""
    person = person_name(ph)
    if person and len(ph.persons) == 1:
        person = ph.persons[0]  # 彼女に -> 花子: whom it refers to (reference.resolve_persons, §9)
    if person and strict and not _surely_person(ph):
        person = None
    if person:
        return person, True
    noun, run = noun_of(ph), as_written(ph.tokens)  # a thing or a place keeps its suffix: 会議室, not 会議
    return (run if noun and noun in run else noun), False


def _sure(ph: Phrase) -> bool:
    """Is ``ph`` a person by more than a word that can be a name: a tag, the lists, an honorific, a pronoun?"""
    return _surely_person(ph) or refers(words_of(ph.tokens))


def _surely_person(ph: Phrase) -> bool:
    toks = ph.tokens
    noun = noun_of(ph)
    return (any(t.pos3 == "人名" for t in toks) or noun in PERSON_NOUNS
            or any(t.pos1 == "接尾辞" and t.surface in HONORIFICS for t in toks) or _name_alone(noun))


@lru_cache(maxsize=1024)
def _name_alone(noun: str | None) -> bool:
    """Is ``noun`` tagged a name when written alone (太郎を: yes; 本を, 机を: no)? UniDic reads 太郎 as a common
    noun after another name (次郎は太郎を押した), not by itself; a thing that is also a surname stays a thing.
    Kept for the last 1,024 nouns asked (a studio process reads text after text)."""
    if not noun:
        return False
    words = tagger()(noun + "を")
    return len(words) == 2 and words[0].surface == noun and words[0].feature.pos3 == "人名"


def _before_no(ph: Phrase) -> Phrase | None:
    """``ph`` itself when it ends in の after a noun (花子の), else ``None``."""
    return ph if ph.key.endswith("の") and _particle(ph) == "の" and noun_of(ph) else None


def _target_at(phrases: list[Phrase], i: int) -> Target | None:
    """The target phrase ``i`` opens, if any: 花子に, 花子の + 前に, 花子の前に, 駅まで, 花子を (a person)."""
    ph = phrases[i]
    if ph.role == "object":
        name, person = _name(ph, strict=True)
        return Target(name, person, "を", None, (i,)) if name else None
    if ph.role:
        return None
    nxt = phrases[i + 1] if i + 1 < len(phrases) else None
    if _before_no(ph) and nxt is not None and nxt.group == ph.group \
            and (nxt.role in ("object", "body part") or (not nxt.role and _particle(nxt) == "に")) \
            and (noun_of(nxt) in BODY_PARTS or noun_of(nxt) in body_nouns()):
        name, person = _name(ph)  # 花子の肩を叩く, 彼女の肩に手を置く: done to 花子
        span = (i,) if nxt.role else (i, i + 1)  # 肩に is no place of its own
        return Target(name, True, "を", None, span, _sure(ph)) if person else None
    if _before_no(ph) and nxt is not None and nxt.group == ph.group and nxt.role == "object" \
            and (noun_of(nxt) in PLACE_OF_NOUNS or noun_of(nxt) in AROUND_NOUNS):
        rel = noun_of(nxt) or ""  # 花子の方を向く: towards her; 木の周りを歩く: around it
        name, person = _name(ph)
        toward = rel in PLACE_OF_NOUNS
        return Target(name, person, "へ" if toward else "を", None if toward else "around", (i, i + 1), _sure(ph), rel)
    if _before_no(ph) and nxt is not None and nxt.group == ph.group and not nxt.pred and not nxt.role:
        rel = noun_of(nxt)
        particle = _at_side(_particle(nxt))
        if not particle and rel in PLACE_OF_NOUNS:
            particle = "へ"  # 花子のとこ行く: spoken text drops the へ
        after = phrases[i + 2] if i + 2 < len(phrases) else None
        if particle == "の" and rel in SIDE_NOUNS and after is not None and after.role == "object":
            name, person = _name(ph)  # 机の上のペンを取る: where the pen lies (a thing; 太郎の隣の本 says no place)
            thing = name and not (person and _sure(ph))  # 机 can be a name, but is no person here
            return Target(name, False, "の", SIDE_NOUNS[rel], (i, i + 1), _sure(ph)) if thing else None
        if (rel in SIDE_NOUNS or rel in PLACE_OF_NOUNS) and particle in TARGET_PARTICLES:
            name, person = _name(ph)
            return Target(name, person, particle, SIDE_NOUNS.get(rel), (i, i + 1), _sure(ph))
    particle = _particle(ph)
    if particle not in TARGET_PARTICLES and particle != "で":
        return None
    inner = _inner_side(ph)
    if inner is not None or particle == "で":
        return inner
    name, person = _name(ph)
    if not name or name in BODY_PARTS or name in NOT_TARGETS or any(t.is_number for t in ph.tokens):
        return None
    return Target(name, person, particle, None, (i,), _sure(ph))


def _inner_side(ph: Phrase) -> Target | None:
    """花子の前に as one phrase: the noun before の, the side noun after it."""
    toks = ph.tokens
    for k, t in enumerate(toks):
        if t.surface == "の" and t.pos1 == "助詞" and 0 < k < len(toks) - 1:
            rel = side_after_no(toks[k + 1:])
            if rel is not None:
                head = Phrase(ph.index, toks[:k], ph.sentence, ph.quoted)
                name, person = _name(head)
                particle = _at_side(_particle(ph))
                return (Target(name, person, particle, SIDE_NOUNS.get(rel), (ph.index,), _sure(head))
                        if name and particle in TARGET_PARTICLES else None)
            return None
    return None


def _at_side(particle: str) -> str:
    """で after a side noun says where the body is, as に does (ドアの前で立ち止まる: in front of the door); a
    bare で-place (公園で遊ぶ) is where the whole scene is, no target."""
    return "に" if particle == "で" else particle


# ---------------------------------------------------------------- roles


def _person_by(phrases: list[Phrase], i: int) -> str | None:
    """The one person a phrase of predicate ``i``'s clause names before it with の, に, へ or まで (花子の足元で,
    花子の方へ, 花子に), if any."""
    for ph in reversed(phrases[:i]):
        if ph.group != phrases[i].group or ph.pred is not None:
            break
        if len(ph.persons) == 1 and _particle(ph) in ("の", "に", "へ", "まで"):
            return ph.persons[0]
    return None


def _sent_to(pred: Pred, person: str | None, done: list[Pred]) -> None:
    """ボールは転がって、花子の足元で止まった: a thing that comes to rest by a person (``person``, named in the
    clause of its non-agent predicate) was sent to that person by the last motion that sent it and named no one
    (太郎はボールを蹴った: to 花子, the recipient), said in that motion's notes."""
    if person is None or pred.object is None:
        return
    sender = next((p for p in reversed(done) if p.object == pred.object and p.verb in TRANSFER_VERBS), None)
    if sender is None or sender.target is not None or sender.actor == person:
        return
    sender.target, sender.target_role, sender.target_person = person, "recipient", True
    sender.say(f"{sender.object} sent to {person}: it comes to rest by them")


def _settle(pred: Pred, pending: list[Target], actors: set[str]) -> None:
    """The target of ``pred`` from the nouns before it in its clause (the nearest one with a role wins).
    A word taken for a person only because it can be a name, never an actor of the text, is a thing where
    the body goes beside it, onto it or down off it, or a thing is put on it (机の前に座る, 岩に座る, 台から飛び降りる,
    書類を机に置く: 机, 岩 and 台 are also names)."""
    chosen: Target | None = None
    for t in reversed(pending):
        if t.person and not t.sure and t.name not in actors and (
                t.side is not None or pred.verb in SUPPORT_VERBS or pred.verb in PLACING_VERBS
                or (pred.verb in OFF_VERBS and t.particle == "から")):
            t.person = False
        role = _role(pred, t)
        if role is None or (t.person and t.name == pred.actor):
            continue
        if chosen is not None:  # 駅から家まで走る: one target a motion; the other is said, never dropped
            pred.say(f"{t.name} ({role}) is not placed: the motion keeps one target, {chosen.name}")
            continue
        chosen = t
        pred.target, pred.target_role, pred.target_side, pred.target_person = t.name, role, t.side, t.person
        if t.covers is not None and pred.object == t.covers:
            pred.object = None  # 花子の方を向く: 方 says where, it is not a thing turned
        if role == "source" and t.particle == "を" and pred.object == t.name:
            pred.object = None  # 電車を降りる, 部屋を出る: the place left, not a thing handled
        if (role == "partner" or (t.particle == "と" and pred.verb in PARTING_VERBS)) and t.name not in pred.co_actors:
            pred.co_actors = (*pred.co_actors, t.name)  # 花子と握手する: she shakes hands too


def _role(pred: Pred, t: Target) -> str | None:
    verb = pred.verb
    if t.particle == "の":  # 机の上のペンを取る: taken from where it lies
        return "source"
    if t.particle == "を" and t.side == "around":  # 木の周りを歩く
        return "goal"
    if t.particle == "を":
        if t.person:
            return "goal" if verb in CHASING_VERBS else "patient"
        # 店を出る; 席を立つ: the seat risen from
        return "source" if verb in LEAVING_VERBS or (verb in RISING_VERBS and t.name in SEATS) else None
    if t.particle == "と":  # 花子と踊る: with her; 花子と別れる: each leaves the other
        return ("source" if verb in PARTING_VERBS else "partner") if t.person else None
    if t.particle == "から":
        return "source"
    if verb in PLACING_VERBS:
        return "destination"
    if t.side is not None and t.person:  # 花子の隣に並ぶ, 太郎の後ろに隠れる: where the body goes
        return "goal"
    if verb in TRANSFER_VERBS and pred.object not in BODY_PARTS:
        return "recipient" if t.person else "destination"
    if t.side is not None and t.side != "on":  # ドアの前で立ち止まる, 木の下に座る: where the body is
        return "goal"
    if t.particle in ("へ", "まで") or verb in LOCOMOTION_VERBS:
        return "goal"
    if verb in SUPPORT_VERBS:  # 机の前に座る: beside a thing is where the body goes, not what holds it up
        return "goal" if t.person or t.side not in (None, "on") else "support"
    if t.person:
        return "patient" if verb in CONTACT_VERBS else "addressee"
    return "at"


# ---------------------------------------------------------------- phrases that are no motion


def mark_ways(phrases: list[Phrase]) -> None:
    """花子に向かって走る: 向かって says the way of the next motion; 向かい合って that the actors face.
    Run before the modifiers attach: a を-noun or body part before the way (ボールを壁に向かって蹴る) is the
    next motion's."""
    for i, ph in enumerate(phrases):
        pred = ph.pred
        if pred is None or pred.reason or pred.verb not in _WAY_TE or pred.ending not in ("te", "renyou"):
            continue
        nxt = next((q for q in phrases[i + 1:] if q.pred), None)
        if nxt is None or nxt.group != ph.group or not nxt.predicate.motion:
            continue
        if pred.verb in FACING_VERBS:
            pred.reason = "facing"
        elif pred.verb in DIRECTION_TE and i > 0 and _particle(phrases[i - 1]) in ("に", "へ") \
                and phrases[i - 1].group == ph.group:
            pred.reason = "direction"


def _follow_on(preds: list[Pred]) -> None:
    """What a motion takes from the ones before it, in text order (one pass: it runs on every text):

    - co-actors of a motion done to each other (太郎と花子は抱き合う, 〜合う) or after 向かい合って are each
      other's partners;
    - a gesture right after a motion of the same actor directed at a person is addressed to that person
      (花子に近づいて、お辞儀する), a touch of them done to them (駆け寄って、抱きしめる), a thing sent goes
      to them (近づいて、ボールを渡す: she receives it); a leaving leaves them (手を振って、立ち去る);
    - それ / これ as an object is the thing last named (花子はそれを投げた: the ball), said in its note;
    - a thing given back (返す, 投げ返す) with no one named goes back to the one who gave it (健は花子に本を
      貸した。彼女はそれを返した: to 健).
    """
    last: dict[str | None, Pred] = {}
    givers: dict[str, str | None] = {}  # thing -> the person who sent it
    thing: str | None = None
    before: Pred | None = None
    for pred in preds:
        facing = before is not None and before.reason == "facing"
        before = pred
        if pred.reason == "non-agent" and pred.object:
            thing = pred.object  # ボールが転がってきた。少年はそれを拾った: the ball
        if not pred.motion:
            continue
        if (facing or pred.verb in RECIPROCAL_VERBS or pred.verb.endswith("合う")) and not pred.target \
                and pred.co_actors:
            pred.target, pred.target_role, pred.target_person = pred.co_actors[0], "partner", True
        elif pred.verb in PARTING_VERBS and not pred.target and pred.co_actors:
            pred.target, pred.target_role, pred.target_person = pred.co_actors[0], "source", True  # each leaves
            # the other (二人は握手をして別れた)
        if facing and pred.target_role == "partner":
            pred.target_side = "front"  # 向かい合って立つ: each in front of the other, not side by side
        prev = last.get(pred.actor)
        if prev is not None and pred.verb in DOOR_VERBS | MOVING_VERBS and not pred.object:
            gone_to = prev.target if pred.verb in DOOR_VERBS and prev.target and not prev.target_person else None
            handled = prev.object or gone_to
            if handled:  # ドアを引いて開ける, ドアの前で立ち止まってノックする, 台車を押して運ぶ: the thing just handled
                pred.object = handled
                pred.say(f"{pred.verb} read as done to {handled}, the thing just handled")
        if (prev is not None and pred.target is None and prev.target_person and pred.verb in LEAVING_VERBS
                and (prev.target_role in DIRECTED or (prev.target_role == "source" and prev.verb in RECEIVING_VERBS))):
            # 花子に手を振って、立ち去る, 太郎から受け取って、走り去る: leaves them, not towards them
            pred.target, pred.target_role, pred.target_person = prev.target, "source", True
        if (prev is not None and pred.target is None and prev.target_role in DIRECTED and prev.target_person
                and prev.target_side not in ALONGSIDE
                and pred.verb not in LOCOMOTION_VERBS and pred.verb not in SUPPORT_VERBS):
            role = ("patient" if pred.verb in CONTACT_VERBS
                    else "recipient" if pred.verb in TRANSFER_VERBS and pred.object and pred.object not in BODY_PARTS
                    else "addressee")
            pred.target, pred.target_role, pred.target_person = prev.target, role, True
        if pred.target is None and pred.verb in FLEEING_VERBS:
            _flee(pred, preds)
        if pred.target in pred.co_actors and pred.verb not in PARTING_VERBS:
            pred.target_role = "partner"  # 花子の手を取って、一緒に踊る: done with her, not at her
        _stand_at(pred, prev)
        last[pred.actor] = pred
        if pred.object in THING_ANAPHORS and thing is not None:
            pred.say(f"{pred.object} read as {thing}, the thing last named")
            pred.object = thing
            reread(pred, thing)
        elif pred.object and pred.object not in THING_ANAPHORS and pred.target_role != "patient":
            thing = pred.object
        _give_back(pred, givers)


def _flee(pred: Pred, preds: list[Pred]) -> None:
    """熊が現れた。少年は驚いて逃げ出した: a flight with no one named runs from whoever last came to the actor
    before it (a goal of theirs that is the actor), said in the notes."""
    k = preds.index(pred)
    came = next((p for p in reversed(preds[:k]) if p.motion and p.actor != pred.actor and p.target == pred.actor
                 and p.target_role == "goal"), None)
    if came is not None and came.actor is not None:
        pred.target, pred.target_role, pred.target_person = came.actor, "source", True
        pred.say(f"{pred.verb} read as from {came.actor}, who came to {pred.actor}")


def _stand_at(pred: Pred, prev: Pred | None) -> None:
    """先生は黒板の前に立った: someone on their feet who stands somewhere goes there (a walk that ends
    standing there, said in the note), rather than rising from a crouch they were never in; 向かい合って立った
    stands (待つ) with the partner."""
    if pred.verb != "立つ" or pred.target_role not in ("goal", "partner"):
        return
    if prev is not None and (prev.verb in SUPPORT_VERBS or prev.verb in LOWERING_VERBS):
        return
    if pred.target_role == "partner":  # 向かい合って立った: they stand there, on their feet already
        pred.verb = pred.written = "待つ"
        pred.reading = ""
        pred.say(f"立つ: stands with {pred.target}, on their feet already")
        return
    pred.verb = pred.written = "歩く"
    pred.reading = ""
    pred.say(f"立つ: walks to stand at {pred.target}")


def _give_back(pred: Pred, givers: dict[str, str | None]) -> None:
    """A thing given back with no one named goes to whoever sent it (:func:`_follow_on`); remember who sends."""
    if pred.object is None:
        return
    giver = givers.get(pred.object)
    if pred.target is None and pred.verb.endswith("返す") and giver is not None and giver != pred.actor:
        pred.target, pred.target_role, pred.target_person = giver, "recipient", True
    if pred.target_role == "recipient" and pred.target_person:
        givers[pred.object] = pred.actor


# ---------------------------------------------------------------- counterparts


def add_counterparts(specs: list[MotionSpec], constraints: list[Constraint]) -> list[str]:
    """太郎は花子に本を渡す: 花子 receives it (受け取る, directed back at 太郎), starting with the hand-over; and
    花子は太郎から箱を受け取る: 太郎 hands it over. Added after the text's motions (its span, a parallel link
    with the cue ``counterpart``) unless the other person already does the counterpart there; a later
    motion of the other person linked to the hand-over follows the counterpart instead. Returns the notes."""
    notes: list[str] = []
    next_id = max((s.id for s in specs), default=0) + 1
    for spec in list(specs):
        cp = COUNTERPARTS.get(spec.verb)
        if cp is None or spec.target is None or spec.target_role != cp[2] or spec.actor is None:
            continue
        verb, reading, _ = cp
        if any(s.actor == spec.target and s.verb == verb for s in specs):
            continue
        role = "source" if cp[2] == "recipient" else "recipient"
        other = replace(spec, id=next_id, actor=spec.target, verb=verb, written=verb, reading=reading,
                        target=spec.actor, target_role=role, target_side=None, target_person=True, repeat=1,
                        delay=None)
        for k, c in enumerate(constraints):
            if c.first == spec.id and _actor_of(specs, c.second) == spec.target:
                constraints[k] = replace(c, first=next_id)
        constraints.append(Constraint(spec.id, next_id, "parallel", None, None, "composition", "counterpart"))
        specs.append(other)
        notes.append(f"{spec.target} {verb}: implied by {spec.actor} {spec.written or spec.verb}")
        next_id += 1
    return notes


def add_causers(specs: list[MotionSpec], constraints: list[Constraint], causers: dict[int, str]) -> list[str]:
    """先生は生徒を前に進ませた: the causer of a causative motion (``causers``: motion id -> who makes its actor do
    it) tells its actor first (:data:`lexicon.TELLING`, addressed to them, the motion's span), and the motion
    follows the telling (a serial link with overlap, cue ``causative``); what led into the motion leads into
    the telling. Returns the notes."""
    notes: list[str] = []
    next_id = max((s.id for s in specs), default=0) + 1
    by_id = {s.id: s for s in specs}
    for motion_id, causer in causers.items():
        spec = by_id[motion_id]
        if spec.target is None and spec.verb in LOCOMOTION_VERBS:  # 生徒を前に進ませた: up to the teacher
            at = specs.index(spec)
            spec = specs[at] = replace(spec, target=causer, target_role="goal", target_person=True)
        verb, reading = TELLING
        specs.append(replace(spec, id=next_id, actor=causer, verb=verb, written=verb, reading=reading, object=None,
                             body_part=None, phrase="", target=spec.actor, target_role="addressee", target_side=None,
                             target_person=True, repeat=1, duration=None, delay=None, manner=None, style=None,
                             intensity=1.0))
        for k, c in enumerate(constraints):
            if c.second == motion_id:
                constraints[k] = replace(c, second=next_id)
        constraints.append(Constraint(next_id, motion_id, "serial", True, None, "transition", "causative"))
        notes.append(f"{causer} {verb}: {causer} makes {spec.actor} {spec.written or spec.verb}")
        next_id += 1
    return notes


def _leaves_after(specs: list[MotionSpec], constraints: list[Constraint], motion_id: int, giver: str) -> None:
    """花子は恥ずかしそうに受け取って、走り去った: the leaving that follows a receiving (motion ``motion_id``) with no
    one named leaves the giver it faced (``source``), as :func:`_follow_on` reads one after a gesture."""
    by_id = {s.id: s for s in specs}
    nxt = next((by_id[c.second] for c in constraints if c.first == motion_id and c.relation == "serial"
                and by_id[c.second].actor == by_id[motion_id].actor), None)
    if nxt is not None and nxt.target is None and nxt.verb in LEAVING_VERBS:
        specs[specs.index(nxt)] = replace(nxt, target=giver, target_role="source", target_person=True)


def _actor_of(specs: list[MotionSpec], motion_id: int) -> str | None:
    return next((s.actor for s in specs if s.id == motion_id), None)


def time_catches(specs: list[MotionSpec], constraints: list[Constraint]) -> None:
    """太郎は花子にボールを投げる。花子はボールを捕る。: the catch of the thing another person throws starts
    with the throw (a parallel link, cue ``catch``), so the scene can time it by the flight instead of
    after the throw has ended. A catch joined by て (投げて、花子がキャッチする) already starts as the
    throw's core ends: its link stays. A throw that names no one to throw to is thrown to the catcher
    (投げると、花子がキャッチした: to her). A hand-over's receiving written in the next sentence is its counterpart
    (a parallel link, cue ``counterpart``), as the one the hand-over implies (:func:`add_counterparts`)."""
    by_id = {s.id: s for s in specs}
    for k, c in enumerate(constraints):
        a, b = by_id.get(c.first), by_id.get(c.second)
        if (a is not None and b is not None and c.relation == "serial" and a.actor != b.actor and b.actor == a.target
                and COUNTERPARTS.get(a.verb, ("",))[0] == b.verb and b.object in (a.object, None)):
            # 太郎は花子にプレゼントを差し出した。花子は受け取った: her receiving is the hand-over's counterpart
            constraints[k] = Constraint(a.id, b.id, "parallel", None, None, "composition", "counterpart")
            if b.target is None and a.actor is not None:
                specs[specs.index(b)] = replace(b, target=a.actor, target_role="source", target_person=True)
                _leaves_after(specs, constraints, b.id, a.actor)
            continue
        if not (a is not None and b is not None and c.relation == "serial" and a.actor != b.actor
                and a.verb in THROWING_VERBS and b.verb in CATCHING_VERBS and b.object in (a.object, None)):
            continue
        if not c.overlap:
            constraints[k] = Constraint(a.id, b.id, "parallel", None, None, "composition", "catch")
        if a.target is None and b.actor is not None:
            specs[specs.index(a)] = replace(a, target=b.actor, target_role="recipient", target_person=True)

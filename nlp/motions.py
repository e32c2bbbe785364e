"""Motions: the role of every bunsetsu and the fields of each motion (§1-§2).

Roles: predicates (motions or not, with the reason), actors (person + は/が/も),
objects and body parts (を / で), repeat (N回), duration (N秒間), speed
(ゆっくり), manner て-forms (急いで), and time cues (そして, N秒後に,
しばらくして, ...) that adjust the link into the motion they modify.
"""
from __future__ import annotations

from dataclasses import dataclass

from .bunsetsu import FUNCTION_POS, Phrase
from .endings import ENDINGS
from .lexicon import (
    BODY_PARTS, CONNECTIVES, COUNTERS, HOMOPHONE_TYPOS, HONORIFICS, LIBRARY_VERBS, MANNER_TE, PERSON_NOUNS,
    REPEAT_WORDS, SCRIPT_HEADINGS, SIDE_PREFIX, SPEED_WORDS, STEPPING_VERBS,
)
from .pred import Pred
from .predicates import find_predicate, sahen_verb, settle_reason
from .tokens import is_name

_SIDED = {"手": "arm", "腕": "arm", "足": "leg", "脚": "leg", "て": "arm", "うで": "arm", "あし": "leg"}


@dataclass(frozen=True, slots=True)
class TimeCue:
    """A connective or delay adjusting the link into the motion ``target``."""

    phrase: int
    target: int  # phrase index of the motion it modifies
    relation: str
    overlap: bool | None
    method: str
    delay: float | None
    cue: str


def annotate(phrases: list[Phrase]) -> tuple[list[Pred], list[TimeCue]]:
    """Give every phrase its role; return the predicates and the time cues."""
    values: dict[int, float] = {}
    for i, ph in enumerate(phrases):
        nxt = phrases[i + 1] if i + 1 < len(phrases) else None
        role = _modifier_role(ph, values)
        if role:
            ph.role = role
            continue
        ph.pred = find_predicate(ph, nxt)
        opens = i == 0 or phrases[i - 1].sentence != ph.sentence
        ph.role = "predicate" if ph.pred else _noun_role(ph, opens)
    _bare_objects(phrases)
    _assign_groups(phrases)
    _mark_manner(phrases)
    preds = [ph.pred for ph in phrases if ph.pred]
    _merge_light_verbs(phrases)
    _mark_non_agents(phrases)
    _mark_embedded(phrases)
    _assign_actors(phrases)
    cues = _attach_modifiers(phrases, values)
    for pred in preds:
        _recover_homophone(pred)
    for ph in phrases:
        if ph.pred:
            ph.role = "motion" if ph.pred.motion else f"not a motion: {ph.pred.reason}"
    return preds, cues


# ---------------------------------------------------------------- roles


def _modifier_role(ph: Phrase, values: dict[int, float]) -> str:
    key = ph.key
    if key in CONNECTIVES:
        return "connective"
    if key in MANNER_TE:
        return "manner"
    if key in SPEED_WORDS:
        return "speed"
    if key in REPEAT_WORDS:
        values[ph.index] = REPEAT_WORDS[key]
        return "repeat"
    toks = ph.tokens
    if not toks[0].is_number or toks[0].value is None:
        return ""
    values[ph.index] = toks[0].value
    unit = toks[1].surface if len(toks) > 1 else ""
    kind = COUNTERS.get(unit, ("number",))[0]
    if kind == "seconds":
        after = toks[2].surface if len(toks) > 2 else ""
        kind = "delay" if after in ("後", "あと") else "duration"
        values[ph.index] *= COUNTERS[unit][1]
    elif kind == "duration":
        values[ph.index] *= COUNTERS[unit][1]
    return kind


def _noun_role(ph: Phrase, opens: bool = False) -> str:
    """``opens``: ``ph`` is the first phrase of its sentence (a vocative 花子さん、 there
    names whom the request is addressed to: the actor, like a topic)."""
    particle = _case_particle(ph)
    if opens and _label(ph):
        return "actor"
    if opens and not any(t.pos1 == "助詞" for t in ph.tokens) and ph.has_comma() and _person(ph):
        return "actor"
    if particle in ("は", "が", "も") and _person(ph):
        return "actor"
    if particle in ("を", "で"):
        noun = _noun(ph)
        if noun in BODY_PARTS:
            return "body part"
        return "object" if particle == "を" else ""
    return ""


def _case_particle(ph: Phrase) -> str:
    """The particle(s) after the nouns: は, が, を, で ... ('' if several or none)."""
    parts = [t.surface for t in ph.tokens if t.pos1 == "助詞"]
    return parts[0] if len(parts) == 1 else ""


def _noun(ph: Phrase) -> str:
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


def _label(ph: Phrase) -> str | None:
    """花子: / お父さん： / 店員A: opening a line: a script's speaker label names the actor
    of that line, person noun or not (as written, honorific after a name dropped)."""
    toks = ph.tokens
    if len(toks) < 2 or toks[-1].surface != ":":
        return None
    words = toks[:-1]
    if not all(t.pos1 in ("名詞", "代名詞", "接頭辞", "接尾辞") for t in words):
        return None
    name = _as_written(words)
    return None if name in SCRIPT_HEADINGS else name


def _person(ph: Phrase) -> str | None:
    """The actor name if ``ph`` names a person (太郎, 花子さん, 彼, お父さん, 子供たち), as written."""
    toks = ph.tokens
    if toks[-1].surface == ":":
        return _label(ph)
    nouns = [t for t in toks if t.pos1 in ("名詞", "代名詞")]
    if not nouns:
        return None
    name = "".join(t.surface for t in nouns)
    affixed = any(t.pos1 in ("接頭辞", "接尾辞") for t in toks)
    honorific = affixed and any(t.pos1 == "接尾辞" and t.surface in HONORIFICS for t in toks)
    if not (honorific or name in PERSON_NOUNS or any(t.pos3 == "人名" for t in nouns)
            or (len(nouns) == 1 and nouns[0].pos1 == "名詞" and is_name(name))):
        return None
    return _as_written(toks) if affixed else name


def _as_written(toks: list) -> str:
    """The name as the user wrote it: prefix, nouns and suffixes (お父さん, おじいちゃん,
    子供たち); an honorific right after a given name is not part of it (花子さん -> 花子)."""
    run = []
    for t in toks:
        if t.pos1 in ("名詞", "代名詞", "接頭辞") or (t.pos1 == "接尾辞" and run):
            run.append(t)
        elif run:
            break
    while (len(run) > 1 and run[-1].pos1 == "接尾辞" and run[-1].surface in HONORIFICS
           and _given_name(run[-2]) and "".join(t.surface for t in run) not in PERSON_NOUNS):
        run.pop()  # 花子さん -> 花子, but 王様 stays 王様
    return "".join(t.surface for t in run)


def _given_name(tok) -> bool:
    return tok.pos3 == "人名" or (tok.pos1 == "名詞" and tok.surface not in PERSON_NOUNS and is_name(tok.surface))


# ---------------------------------------------------------------- structure


def _assign_groups(phrases: list[Phrase]) -> None:
    """Clause groups: sentences, split after a 終止形 + 、 (歩く、走る)."""
    group = -1
    prev_sentence = None
    split_next = False
    for ph in phrases:
        if ph.sentence != prev_sentence or split_next:
            group += 1
        prev_sentence = ph.sentence
        ph.group = group
        split_next = bool(ph.pred and ph.pred.ending == "final")


def _bare_objects(phrases: list[Phrase]) -> None:
    """ボール蹴って！ / 手振って / 太郎歩く: casual speech drops を and が; a bare noun right
    before the predicate (no particle, no comma, not a time word (副詞可能) or a
    number) is its actor when it names a person, else its object or body part."""
    for ph, nxt in zip(phrases, phrases[1:]):
        if ph.role or not nxt.pred or nxt.sentence != ph.sentence or ph.has_comma():
            continue
        toks = [t for t in ph.tokens if t.pos1 != "補助記号"]
        if not toks or any(t.pos1 not in ("名詞", "接頭辞", "接尾辞") for t in toks):
            continue
        last = toks[-1]
        if last.pos1 != "名詞" or last.pos3 == "副詞可能" or last.pos2 == "数詞" or last.is_number:
            continue
        if _person(ph):
            ph.role = "actor"  # 太郎歩く: が dropped too
        elif not is_name(ph.key):
            ph.role = "body part" if _noun(ph) in BODY_PARTS else "object"


def _mark_manner(phrases: list[Phrase]) -> None:
    """音楽に合わせて踊る: a て-clause that only says how its head is done is no motion.

    The rule (language.md §1, "Manner て-forms"; docs in nlp/README.md): a
    predicate P in て-form is a manner of the next predicate H when
    1. P modifies H directly: no comma after P, H is the next predicate of its clause;
    2. P's only complement is a に-marked noun (no を object, no body part), the
       standard or guide H follows (音楽に, 号令に, 壁に);
    3. P is not itself a bodily action: not a library verb and no library verb
       is near it in meaning (``meaning.MIN_SIMILARITY``, chiVe vectors).
    椅子に座って手を振る keeps 座る (a library verb), 家に帰って寝る keeps 帰る (near 待つ/歩く).
    """
    for i in range(1, len(phrases) - 1):
        ph, prev = phrases[i], phrases[i - 1]
        pred = ph.pred
        if (not pred or pred.reason or pred.ending != "te" or ph.has_comma()
                or prev.group != ph.group or prev.pred or _case_particle(prev) != "に"):
            continue
        if _next_pred(phrases, i) is None:
            continue
        args = []
        for q in reversed(phrases[:i - 1]):
            if q.group != ph.group or q.pred:
                break
            args.append(q.role)
        if "object" not in args and "body part" not in args and not _bodily(pred.verb):
            pred.reason = "manner"


def _bodily(verb: str) -> bool:
    """A library verb, or one whose nearest library verb is near in meaning."""
    if verb in LIBRARY_VERBS:
        return True
    from . import meaning  # loads the vectors on first use only

    return bool(meaning.nearest(verb, sorted(LIBRARY_VERBS), n=1, floor=meaning.MIN_SIMILARITY))


def _merge_light_verbs(phrases: list[Phrase]) -> None:
    """ジャンプを(3回)する / お辞儀をする: the を-noun becomes the verb."""
    for i, ph in enumerate(phrases):
        pred = ph.pred
        if not pred or pred.reason != "light":
            continue
        j = i - 1
        while j >= 0 and phrases[j].group == ph.group and phrases[j].role in (
                "repeat", "duration", "speed"):
            j -= 1
        if j < 0 or phrases[j].group != ph.group or phrases[j].role != "object":
            continue
        noun_ph = phrases[j]
        nouns = [t for t in noun_ph.tokens if t.pos1 in ("名詞", "接頭辞") and not t.is_number]
        if not nouns:
            continue
        pred.verb, pred.written = sahen_verb(nouns)
        pred.reading = "".join(t.kana_form for t in nouns) + "スル"
        pred.start = nouns[0].start
        pred.reason = ""
        settle_reason(pred, ph.quoted)
        noun_ph.role = "action noun"


def _mark_non_agents(phrases: list[Phrase]) -> None:
    """雨が降る / 音楽が流れる / ボールが転がる: a が-subject that is neither a person nor
    a body part (手が震える is still the actor's) makes its predicate no action of anyone."""
    for i, ph in enumerate(phrases):
        if ph.role or ph.pred or _case_particle(ph) != "が" or any(t.is_number for t in ph.tokens):
            continue
        noun = _noun(ph)
        if not noun or noun in BODY_PARTS or _person(ph):
            continue
        target = _next_pred(phrases, i)
        if target is not None and target.predicate.motion:
            target.predicate.reason = "non-agent"


def _mark_embedded(phrases: list[Phrase]) -> None:
    """A clause without a comma right before a relative / の clause is inside it."""
    preds = [ph for ph in phrases if ph.pred]
    for a, b in zip(reversed(preds[:-1]), reversed(preds[1:])):
        if a.group != b.group or a.has_comma() or a.predicate.ending == "final":
            continue
        if b.predicate.reason in ("relative", "nominal", "embedded"):
            a.predicate.reason = a.predicate.reason or "embedded"


def _assign_actors(phrases: list[Phrase]) -> None:
    """は/も set the topic, which carries over; が binds to its own clause.

    A が-subject holds until a clause that ends it (てから, 間に, 前に, の,
    relative, ...); then the topic is back, or, if the text has no topic yet,
    the が-subject carries over as the contract's "nearest preceding" rule.
    Coordinated actors (太郎と花子が) are one group: every one of them performs
    the motions (the first is ``actor``, the others ``co_actors``).
    """
    topic: tuple[str, ...] = ()
    subject: tuple[str, ...] = ()
    group = None
    for i, ph in enumerate(phrases):
        if ph.group != group:
            if subject:
                topic, subject = subject, ()
            group = ph.group
        if ph.role == "actor":
            person = _person(ph)
            assert person is not None  # the role is given to persons only (_noun_role)
            names = (*_partners(phrases, i), person)
            if _case_particle(ph) == "が":
                subject = names
            else:
                topic, subject = names, ()
            continue
        pred = ph.pred
        if not pred:
            continue
        names = subject or topic
        pred.actor = names[0] if names else None
        pred.co_actors = names[1:]
        ending = ENDINGS.get(pred.ending)
        closes = ending.closes_subject if ending else True
        if closes and subject:
            topic = topic or subject
            subject = ()


def _partners(phrases: list[Phrase], i: int) -> list[str]:
    """The persons joined to the actor phrase ``i`` by と just before it (太郎と次郎と花子が)."""
    names: list[str] = []
    j = i - 1
    while j >= 0 and phrases[j].group == phrases[i].group and _case_particle(phrases[j]) == "と":
        name = _person(phrases[j])
        if not name:
            break
        names.insert(0, name)
        j -= 1
    return names


# ---------------------------------------------------------------- modifiers


def _attach_modifiers(phrases: list[Phrase], values: dict[int, float]) -> list[TimeCue]:
    cues: list[TimeCue] = []
    for i, ph in enumerate(phrases):
        if ph.pred:
            continue
        target = _next_pred(phrases, i)
        if target is None:
            continue
        ph.head = target.index
        pred = target.predicate
        role = ph.role
        if role in ("connective", "delay"):
            cue = _time_cue(phrases, i, values)
            if cue:
                cues.append(cue)
        elif not pred.motion:
            continue
        elif role == "object":
            pred.object = _noun(ph) or None  # never an empty string
        elif role == "body part":
            pred.body_part = _body_part(phrases, i)
        elif role == "repeat":
            if values[i] >= 1 and float(values[i]).is_integer():
                pred.repeat = int(values[i])
        elif role == "steps":
            if pred.verb in STEPPING_VERBS and values[i] >= 1 and float(values[i]).is_integer():
                pred.repeat = int(values[i])
        elif role == "duration":
            pred.duration = values[i]
        elif role in ("speed", "manner"):
            pred.speed = SPEED_WORDS.get(ph.key, pred.speed)
    return cues


def _recover_homophone(pred) -> None:
    """手を降る -> 手を振る: an IME homophone of a library verb, read as that verb where the
    written one gives no plausible motion (``lexicon.HOMOPHONE_TYPOS``); said in ``note``."""
    typo = HOMOPHONE_TYPOS.get(pred.written)
    if typo is None or not pred.motion:
        return
    meant, when = typo
    has_object = pred.object is not None or pred.body_part is not None
    if (when == "object" and not has_object) or (when == "no object" and has_object):
        return
    pred.note = f"read {pred.written} as {meant} (a homophone the IME may have chosen: {pred.written} is no motion here)"
    pred.verb = pred.written = meant


def _next_pred(phrases: list[Phrase], i: int, motion_level: int = 0) -> Phrase | None:
    """The nearest following predicate phrase in the same clause group.

    With ``motion_level`` only motions whose clause level is at least that
    (skipping ながら / たまま clauses) count; it falls back to any motion.
    """
    group = phrases[i].group
    fallback = None
    for ph in phrases[i + 1:]:
        if ph.group != group:
            break
        if not ph.pred:
            continue
        if not motion_level:
            return ph
        if ph.pred.motion:
            fallback = fallback or ph
            if ENDINGS[ph.pred.ending].level >= motion_level:
                return ph
    return fallback


def _time_cue(phrases: list[Phrase], i: int, values: dict[int, float]) -> TimeCue | None:
    target = _next_pred(phrases, i, motion_level=2)
    if target is None:
        return None
    ph = phrases[i]
    if ph.role == "delay":
        return TimeCue(i, target.index, "serial", False, "connection", values[i], ph.key)
    relation, overlap, method, delay = CONNECTIVES[ph.key]
    return TimeCue(i, target.index, relation, overlap, method, delay, ph.key)


def _body_part(phrases: list[Phrase], i: int) -> str:
    """右手 -> right_arm; 右の手 -> right_arm (side noun + の before the part)."""
    noun = _noun(phrases[i])
    part = BODY_PARTS[noun]
    if noun in _SIDED and i > 0:
        side = SIDE_PREFIX.get(phrases[i - 1].key.removesuffix("の"))
        if side and phrases[i - 1].key.endswith("の"):
            part = {"right": "right_", "left": "left_", "both": "both_"}[side] + _SIDED[noun]
            part = "leg" if part == "both_leg" else part.replace("both_arm", "both_arms")
    return part

"""Motions: the role of every bunsetsu and the fields of each motion (§1-§2).

Roles: predicates (motions or not, with the reason), actors (person + は/が/も),
objects and body parts (を / で), repeat (N回), duration (N秒間), speed
(ゆっくり), manner て-forms (急いで), mimetics (ぱちぱち, よろよろ: ``mimetics``), and
time cues (そして, N秒後に, しばらくして, ...) that adjust the link into the motion they
modify. A verb with its を-noun may be an idiom (腰を上げる: ``phrases``).
"""
from __future__ import annotations

from dataclasses import dataclass

from .actors import as_written, assign_actors, case_particle, noun_of, person_name, speaker_label
from .bunsetsu import Phrase
from .endings import ENDINGS
from .lexicon import (
    AMOUNT_NOUNS, BODY_PARTS, CONNECTIVES, COUNTERS, HONORIFICS, HONOURED_TITLES, JUMP_VERBS, LANDING_VERB, LIBRARY_VERBS,
    MANNER_TE, PLACE_OF_NOUNS, REPEAT_WORDS, SIDE_PREFIX, SPEED_WORDS, STEPPING_VERBS, WEATHER_VERBS,
)
from . import manners, mimetics
from .phrases import read_phrases
from .pred import Pred
from .predicates import find_predicate, sahen_verb, settle_reason
from .reference import resolve_persons
from .casual import recover_homophone
from .targets import attach_targets, mark_ways
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


def annotate(phrases: list[Phrase], notes: list[str] | None = None) -> tuple[list[Pred], list[TimeCue]]:
    """Give every phrase its role; return the predicates and the time cues.  How pronouns were
    read (:func:`reference.resolve_persons`) is appended to ``notes``."""
    values: dict[int, float] = {}
    mimetic: list[Phrase] = []
    styled = manners.find(phrases)
    for i, ph in enumerate(phrases):
        nxt = phrases[i + 1] if i + 1 < len(phrases) else None
        role = _modifier_role(ph, values) or ("manner" if i in styled else "")
        if role:
            ph.role = role
            if role == "mimetic":
                mimetic.append(ph)
            continue
        ph.pred = find_predicate(ph, nxt)
        ph.role = "predicate" if ph.pred else _noun_role(ph, _opens_sentence(phrases, i))
    _bare_objects(phrases)
    _assign_groups(phrases)
    _mark_manner(phrases)
    preds = [ph.pred for ph in phrases if ph.pred]
    _merge_light_verbs(phrases)
    _mark_non_agents(phrases)
    _mark_passives(phrases)
    _mark_embedded(phrases)
    said = resolve_persons(phrases)
    if notes is not None:
        notes.extend(said)
    assign_actors(phrases)
    _mark_causatives(phrases)
    _mark_landings(preds)
    mark_ways(phrases)
    cues = _attach_modifiers(phrases, values, styled)
    for pred in preds:
        recover_homophone(pred)
    read_phrases(preds, phrases)  # before the targets: their roles read the action (腰を下ろす: 座る on a support)
    mimetics.apply(mimetic, phrases)
    _pass_postures(phrases)
    attach_targets(phrases)
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
    if toks[0].pos1 == "副詞" and mimetics.word(key):
        return "mimetic"
    if not toks[0].is_number or toks[0].value is None:
        return ""
    if len(toks) > 1 and toks[1].surface == "人" and case_particle(ph) in ("は", "が", "も"):
        return ""  # 2人は: the actor, as 二人は (reference.py reads whom it names)
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
    particle = case_particle(ph)
    if opens and speaker_label(ph):
        return "actor"
    if opens and not any(t.pos1 == "助詞" for t in ph.tokens) and ph.has_comma() and person_name(ph):
        return "actor"
    if particle in ("は", "が", "も") and person_name(ph):
        return "actor"
    if particle in ("を", "で"):
        noun = noun_of(ph)
        if noun in BODY_PARTS:
            return "body part"
        return "object" if particle == "を" else ""
    return ""


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
    for k, (ph, nxt) in enumerate(zip(phrases, phrases[1:])):
        if (not ph.role and not nxt.pred and nxt.sentence == ph.sentence and _opens_sentence(phrases, k)
                and not ph.has_comma() and all(t.pos1 != "助詞" for t in ph.tokens) and person_name(ph)):
            ph.role = "actor"  # 太郎ボールを蹴る: the topic's は left out (docs/language.md §9)
            continue
        if ph.role or not nxt.pred or nxt.sentence != ph.sentence or ph.has_comma():
            continue
        toks = [t for t in ph.tokens if t.pos1 != "補助記号"]
        pointed = bool(toks) and toks[0].pos1 == "連体詞"  # そのボール取って: the ball, この / その / あの before it
        while toks[:1] and toks[0].pos1 == "連体詞":
            toks = toks[1:]
        if not toks or any(t.pos1 not in ("名詞", "接頭辞", "接尾辞") for t in toks):
            continue
        last = toks[-1]
        if last.pos1 != "名詞" or last.pos3 == "副詞可能" or last.pos2 == "数詞" or last.is_number:
            continue
        if ph.key in AMOUNT_NOUNS:
            continue  # 一口飲んで: how much, not what
        if ph.key in PLACE_OF_NOUNS and k and phrases[k - 1].key.endswith("の"):
            continue  # 花子のとこ行く: where she is, its へ dropped (nlp.targets), not a person
        if person_name(ph) and not (pointed and toks[-1].pos3 != "人名"):
            ph.role = "actor"  # 太郎歩く: が dropped too; この本読んで: 本 is no one's name here
        elif pointed or not is_name(ph.key):
            ph.role = "body part" if noun_of(ph) in BODY_PARTS else "object"


def _opens_sentence(phrases: list[Phrase], k: int) -> bool:
    """Phrase ``k`` opens its sentence, or follows only chat openers with their commas (てかさ、太郎寝てる,
    ねえ、やばい、太郎ずっと寝てる): phrases of no role and no predicate, naming no person."""
    for q in reversed(phrases[:k]):
        if q.sentence != phrases[k].sentence:
            return True
        if q.role or q.pred or not q.has_comma() or person_name(q):
            return False
    return True


def _mark_manner(phrases: list[Phrase]) -> None:
    """音楽に合わせて踊る: a て-clause that only says how its head is done is no motion.

    The rule (docs/language.md §1, "Manner て-forms"; docs in nlp/README.md): a
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
                or prev.group != ph.group or prev.pred or case_particle(prev) != "に"):
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
    from . import meaning  # loads the vectors on first use only

    return meaning.bodily(verb, LIBRARY_VERBS)


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
    """雨が降る / 音楽が流れる / ボールが転がる: a が- or は-subject that is neither a person nor
    a body part (手が震える is still the actor's) makes its predicates no action of anyone, up to the next
    subject of its clause group (ボールは転がって、花子の足元で止まった: neither is 太郎's); the subject is
    kept as their ``object``, the thing they are about. A は-thing before a person's が is the object
    of that person's action, as a topic (ボールは太郎が蹴った)."""
    for i, ph in enumerate(phrases):
        particle = case_particle(ph)
        if ph.role not in ("", "actor") or ph.pred or particle not in ("が", "は") \
                or any(t.is_number or (particle == "は" and t.pos3 == "副詞可能") for t in ph.tokens):
            continue  # 今日は, 朝は: when, not what
        noun = noun_of(ph)
        target = _next_pred(phrases, i)
        weather = target is not None and target.predicate.lemma in WEATHER_VERBS and not any(
            t.pos3 == "人名" or t.surface in HONORIFICS for t in ph.tokens)  # ゆきが降る: snow, not ゆき
        if not noun or noun in BODY_PARTS or (person_name(ph) and not weather):
            continue
        for pred in _governed(phrases, i):
            pred.reason = "non-agent"
            pred.object = noun  # the thing it is about: それ may name it next (targets._follow_on)


def _governed(phrases: list[Phrase], i: int) -> list:
    """The motions whose subject is phrase ``i``'s: the predicates after it in its clause group up to the next
    phrase naming an actor (none when that actor comes before the first predicate: ボールは太郎が蹴った) or the
    first predicate that is no motion (本当は踊りたいけど、座る)."""
    out = []
    for ph in phrases[i + 1:]:
        if ph.group != phrases[i].group or (ph.pred is None and ph.role == "actor"
                                              and case_particle(ph) in ("が", "は", "も")):
            break
        if ph.pred is not None:
            if not ph.pred.motion:  # 声がして、振り返る: the voice is heard, someone else turns
                break
            out.append(ph.pred)
    return out


def _mark_passives(phrases: list[Phrase]) -> None:
    """花子に言われた, 先生に呼ばれて: a verb with the passive れる / られる after a に-person of its clause is
    done to its subject by that person, no action of the subject's (the honorific 先生が来られた has no
    に-person: an action)."""
    for i, ph in enumerate(phrases):
        pred = ph.pred
        auxes = {t.lemma for t in ph.tokens if t.pos1 == "助動詞"}
        if pred is None or not pred.motion or not auxes & {"れる", "られる"} or auxes & {"せる", "させる"}:
            continue  # 母に野菜を食べさせられた: made to eat, she eats (the causative passive)
        by = next((q for q in reversed(phrases[:i]) if q.group == ph.group and q.pred is None
                   and case_particle(q) == "に" and person_name(q)), None)
        if by is not None and not _honoured_before(phrases, i):
            pred.reason = "passive"
            pred.say(f"{by.key}{pred.written or pred.verb} (passive): done by {person_name(by)}, not animated")


def _mark_causatives(phrases: list[Phrase]) -> None:
    """先生は生徒を前に進ませた, 母は子供に野菜を食べさせた: a verb with the causative せる / させる (not
    made passive: 歩かされた is the subject's own walk) is done by the person its clause makes do it (the を-
    or に-person before it, not the actor): that person becomes its actor, and the actor its ``causer``
    (:func:`analyze.add_causers` gives the causer the telling); the person is no object or target of it."""
    for i, ph in enumerate(phrases):
        pred = ph.pred
        auxes = [t.lemma for t in ph.tokens if t.pos1 == "助動詞"]
        if pred is None or not pred.motion or not {"せる", "させる"} & set(auxes) or {"れる", "られる"} & set(auxes):
            continue
        made = next((q for q in reversed(phrases[:i]) if q.group == ph.group and q.pred is None
                     and case_particle(q) in ("を", "に") and person_name(q) not in (None, pred.actor)), None)
        if made is None:
            continue
        made.role = "causee"
        pred.causer, pred.actor = pred.actor, person_name(made)
        pred.say(f"{''.join(t.surface for t in ph.tokens if t.pos1 in ('動詞', '助動詞'))} (causative): "
                 f"{pred.actor} {pred.written or pred.verb}, told by {pred.causer}")


def _mark_landings(preds: list[Pred]) -> None:
    """ジャンプして、着地した: 着地する right after a jump of the same actor is that jump's landing (the jump
    clip lands), no second jump; 着地した alone is played as the jump that lands (near.json)."""
    last: dict[str | None, Pred] = {}
    for pred in preds:
        if not pred.motion:
            continue
        before = last.get(pred.actor)
        if pred.verb == LANDING_VERB and before is not None and before.verb in JUMP_VERBS:
            pred.reason = "landing"
            pred.say(f"{pred.written or pred.verb}: the landing of {before.written or before.verb}, one jump")
            continue
        last[pred.actor] = pred


def _honoured_before(phrases: list[Phrase], i: int) -> bool:
    """The れる / られる of phrase ``i`` is the honorific one, not a passive by the に-person: its actor was
    just spoken of in keigo (社長がお立ちになり、皆に頭を下げられた: a verb keigo.py read from an honorific
    form, earlier in the sentence, no new actor named between), or is an honoured person
    (``lexicon.HONOURED_TITLES``) making a gesture with a part of the body (先生は生徒たちに手を振られた)."""
    gesture = any(q.role == "body part" for q in phrases[:i] if q.group == phrases[i].group)
    for q in reversed(phrases[:i]):
        if q.sentence != phrases[i].sentence:
            return False
        if q.pred is not None and any(t.honorific for t in q.tokens):
            return True
        if q.pred is None and case_particle(q) in ("は", "が") and person_name(q):
            return gesture and any(t.surface in HONOURED_TITLES for t in q.tokens)
    return False


def _mark_embedded(phrases: list[Phrase]) -> None:
    """A clause without a comma right before a relative / の clause is inside it."""
    preds = [ph for ph in phrases if ph.pred]
    for a, b in zip(reversed(preds[:-1]), reversed(preds[1:])):
        if a.group != b.group or a.has_comma() or a.predicate.ending == "final":
            continue
        if b.predicate.reason in ("relative", "nominal", "embedded"):
            a.predicate.reason = a.predicate.reason or "embedded"


# ---------------------------------------------------------------- modifiers


def _attach_modifiers(phrases: list[Phrase], values: dict[int, float],
                      styled: dict[int, manners.Manner | None]) -> list[TimeCue]:
    cues: list[TimeCue] = []
    for i, ph in enumerate(phrases):
        if ph.pred:
            continue
        target = _next_pred(phrases, i)
        while target is not None and target.predicate.reason in ("direction", "facing"):
            target = _next_pred(phrases, target.index)  # ボールを壁に向かって蹴る: the kick's ball
        if target is None:
            continue
        ph.head = target.index
        pred = target.predicate
        role = ph.role
        found = styled.get(i)
        if found is not None and pred.motion:  # the word nearest the verb is the last one set
            pred.manner, pred.style, pred.intensity = found.word, found.style, found.intensity
        elif pred.motion and not pred.style and i not in styled and (unread := manners.unread(phrases, i)):
            pred.manner = unread  # 丁寧にお辞儀する: said as not shown, never dropped in silence
        if role in ("connective", "delay"):
            cue = _time_cue(phrases, i, values)
            if cue:
                cues.append(cue)
        elif not pred.motion:
            continue
        elif role == "object":
            pred.noun = noun_of(ph)
            run = as_written(ph.tokens)  # a thing keeps its suffix: 教科書, not 教科
            # never an empty string; a person by whom it names (彼を助け起こす: 一人目, not a thing 彼)
            pred.object = ph.persons[0] if len(ph.persons) == 1 else (
                run if pred.noun and pred.noun in run else pred.noun) or None
        elif role == "body part":
            pred.body_part = _body_part(phrases, i)
            if case_particle(ph) != "で":  # 右手で投げる: the limb used, not what the verb acts on
                pred.noun = noun_of(ph)
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


def _pass_postures(phrases: list[Phrase]) -> None:
    """胸を張って歩く: a posture idiom in て-form right before a motion gives it its style
    (:func:`manners.passed_on`) unless a manner word of its own gives one."""
    for i, ph in enumerate(phrases):
        pred = ph.pred
        if pred is None or not pred.motion or pred.ending != "te" or ph.has_comma():
            continue
        found = manners.passed_on(pred.written)
        target = _next_pred(phrases, i)
        if found is None or target is None or not target.predicate.motion or target.predicate.style:
            continue
        target.predicate.manner = pred.written
        target.predicate.style, target.predicate.intensity = found.style, found.intensity


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
    noun = noun_of(phrases[i])
    part = BODY_PARTS[noun]
    if noun in _SIDED and i > 0:
        side = SIDE_PREFIX.get(phrases[i - 1].key.removesuffix("の"))
        if side and phrases[i - 1].key.endswith("の"):
            part = {"right": "right_", "left": "left_", "both": "both_"}[side] + _SIDED[noun]
            part = "leg" if part == "both_leg" else part.replace("both_arm", "both_arms")
    return part

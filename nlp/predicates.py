"""Predicates: which bunsetsu hold a verb, which verb, and how the clause ends.

A predicate bunsetsu holds a verb (走って), a サ変 noun + する (ジャンプする), a
mimetic + する (きょろきょろする), or a bare する whose action noun is in the bunsetsu
before (ジャンプをする, お辞儀をする).  Its *verb group* is the verb with its auxiliaries (た, ない,
ている, aspect auxiliaries 始める/続ける/出す/終わる) and a trailing て: the
``span`` of the motion.  What follows the group is the clause ending
(``endings.ENDINGS``) or a reason why the predicate is not a motion.
"""
from __future__ import annotations

from dataclasses import replace

from .bunsetsu import Phrase
from .lexicon import (
    BODY_PARTS, GREETINGS, LIBRARY_BY_READING, LIBRARY_VERBS, NON_ACTION_LEMMAS, VERB_ALIASES,
)
from .mimetics import REPEATS, as_verb, repeats
from .pred import Pred
from .tagging import is_hiragana
from .types import Token

_NEGATIONS = frozenset(["ない", "ず", "ぬ", "無い"])
_FORMAL_ENDINGS = {
    "まま": "mama", "侭": "mama", "後": "ato", "あと": "ato", "前": "mae", "間": "aida",
    "うち": "aida", "内": "aida", "時": "toki", "とき": "toki", "瞬間": "totan",
    "途端": "totan", "とたん": "totan",
}


def canonical_verb(tok: Token) -> str:
    """The library spelling of a verb: written base form first (跳ぶ vs 飛ぶ);
    a verb written in hiragana that UniDic reads as some other word (たつ as
    経つ) is matched to a library verb by its reading."""
    for cand in (tok.orth, tok.lemma):
        if cand in LIBRARY_VERBS:
            return cand
        if cand in VERB_ALIASES:
            return VERB_ALIASES[cand]
    if is_hiragana(tok.orth) and tok.kana in LIBRARY_BY_READING:
        return LIBRARY_BY_READING[tok.kana]
    return tok.lemma


def find_predicate(ph: Phrase, next_ph: Phrase | None) -> Pred | None:
    """The predicate of ``ph``, with its ending, or ``None`` if it has no verb."""
    toks = ph.tokens
    v = next((i for i, t in enumerate(toks) if t.pos1 == "動詞"), None)
    if v is None:
        return None
    first = toks[v]
    if first.lemma == "為る" and v > 0 and toks[v - 1].pos1 != "名詞":
        pred = _mimetic_verb(ph.index, toks[v - 1])
        if pred is None:
            return None  # しばらくして, そうして: an adverb + する
    elif first.lemma == "為る" and v > 0:
        s = _noun_run_start(toks, v)
        reading = "".join(t.kana_form for t in toks[s:v]) + "スル"
        pred = Pred(ph.index, "", reading, "為る", toks[s].start, 0)
        pred.verb, pred.written = sahen_verb(toks[s:v])
    elif v + 1 < len(toks) and toks[v + 1].lemma == "為る" and first.cform.startswith("連用形"):
        # 伸びする: the 連用形 is the action noun of a light verb
        pred = Pred(ph.index, first.surface + "する", first.kana_form + "スル", "為る",
                    first.start, 0)
    else:
        come = _come(toks, v)
        if come is not None:
            first = replace(come, start=first.start)  # やってくる / やって来る: 来る, nothing done (遣る)
        pred = Pred(ph.index, canonical_verb(first), first.kana, first.lemma, first.start, 0)
        pred.written = first.orth
        if first.lemma == "為る":
            pred.verb, pred.reason = "する", "light"
        elif first.lemma in NON_ACTION_LEMMAS:
            pred.reason = "state"
        elif is_potential(first) and not _imperative(toks, v):
            pred.reason = "potential"
    g = _group_end(toks, v)
    pred.end = toks[_verb_end(toks, v)].end
    pred.negated = any(t.lemma in _NEGATIONS and t.pos1 in ("助動詞", "形容詞")
                       for t in toks[v:g + 1]) and not _invitation(toks, g)
    if "".join(t.surface for t in toks if t.pos1 != "補助記号") in GREETINGS:
        pred.reason = "greeting"  # いらっしゃいませ: the shop's welcome, no one comes
    elif any(t.lemma == "たい" and t.pos1 == "助動詞" for t in toks[v:g + 1]):
        pred.reason = "desire"  # 走りたい, 踊りたくて: a wish, not the action
    elif _prohibition(toks, g):
        pred.reason = "prohibition"
    pred.ending, pred.cue = _ending(toks, g, ph, next_ph)
    settle_reason(pred, ph.quoted)
    return pred


def _come(toks: list[Token], v: int) -> Token | None:
    """The 来る or 行く of やってくる / やっていく (someone comes or goes), or ``None``."""
    if toks[v].lemma != "遣る" or v + 2 >= len(toks):
        return None
    te, verb = toks[v + 1], toks[v + 2]
    return verb if te.lemma == "て" and te.pos1 == "助詞" and verb.lemma in ("来る", "行く") else None


def _mimetic_verb(phrase: int, adverb: Token) -> Pred | None:
    """きょろきょろする, うろうろする: a mimetic of motion + する (``mimetics.as_verb``), else None."""
    found = as_verb(adverb)
    if found is None:
        return None
    verb, written, manner = found
    pred = Pred(phrase, verb, adverb.kana_form + "スル", "為る", adverb.start, 0)
    pred.written, pred.manner = written, manner
    pred.repeat = REPEATS if repeats(manner) else 1
    return pred


#: Kana of the e-row: a verb ending in one of them + る is 一段 (上げる), not 五段.
_E_ROW = frozenset("えけげせぜてでねへべぺめれ")


def is_potential(tok: Token) -> bool:
    """泳げる, 走れる, 飛べます: a potential verb (an ability, not an action).  UniDic
    tags it 下一段 with the 五段 verb as lemma (泳げる -> 泳ぐ); a 下一段 verb whose
    lemma is itself 下一段 (挙げる -> 上げる) is another spelling, not a potential."""
    lemma = tok.lemma
    return (tok.ctype.startswith("下一段") and lemma != tok.orth and len(lemma) >= 2
            and not (lemma.endswith("る") and lemma[-2] in _E_ROW))


def _imperative(toks: list[Token], v: int) -> bool:
    """しゃがめ！ / 泳げ: UniDic tags a 五段 verb's imperative as the 連用形 of its potential (しゃがめる);
    with nothing after it but punctuation or a sentence-final particle it is the imperative."""
    return toks[v].cform.startswith("連用形") and all(
        t.pos1 == "補助記号" or t.pos2 == "終助詞" for t in toks[v + 1:])


def _prohibition(toks: list[Token], g: int) -> bool:
    """走るな / 座るなよ: the dictionary form + the particle な forbids the action (座りな, a 連用形 + な,
    asks for it)."""
    return (g + 1 < len(toks) and toks[g + 1].surface == "な" and toks[g + 1].pos2 == "終助詞"
            and toks[g].pos1 == "動詞" and toks[g].cform.startswith("終止形"))


def _invitation(toks: list[Token], g: int) -> bool:
    """歩きませんか / 振ってくれない? / 座らないか: a negative question is a request or
    an invitation to do it, not a negation."""
    rest = [t.surface for t in toks[g + 1:]]
    return bool(rest) and (rest[0] in ("か", "?") or (rest[0] in ("の", "かな") and "?" in rest))


def _sentence_particles(words: list[Token]) -> bool:
    """ね, よ, な, か after the predicate: sentence-final particles end the clause."""
    return all(t.pos2 == "終助詞" for t in words)


def settle_reason(pred: Pred, quoted: bool) -> None:
    """Why the predicate is not a motion, strongest reason first ('' if it is one)."""
    if quoted or pred.ending == "quote":
        pred.reason = "quote"
    elif pred.ending in ("relative", "nominal"):
        pred.reason = pred.ending
    elif pred.negated:
        pred.reason = "negated"
    elif pred.reason not in ("light", "state", "potential", "non-agent", "desire", "prohibition", "greeting"):
        pred.reason = ""


def _noun_run_start(toks: list[Token], v: int) -> int:
    s = v - 1
    while s > 0 and toks[s - 1].pos1 in ("名詞", "接頭辞") and not toks[s - 1].is_number:
        s -= 1
    return s


def sahen_verb(nouns: list[Token]) -> tuple[str, str]:
    """(verb, as written) of an action noun + する: お + 辞儀 -> お辞儀する, ガッツ + ポーズ
    -> ガッツポーズする.  The lemma spelling is the verb when it is a library verb
    (おじぎする -> お辞儀する); otherwise the verb is named as the user wrote it
    (くしゃみする, not UniDic's 嚔する; 後ずさりする, not 後退りする)."""
    written = "".join(t.surface for t in nouns) + "する"
    by_lemma = "".join(t.surface if t.pos1 == "接頭辞" else t.lemma for t in nouns) + "する"
    return (by_lemma if by_lemma in LIBRARY_VERBS else written), written


def _verb_end(toks: list[Token], v: int) -> int:
    """Last token of the verb word itself: 走っ(て), 歩き始め(た), ジャンプ(を)する."""
    k = v
    while k + 1 < len(toks) and toks[k + 1].pos1 == "動詞":
        k += 1
    return k


def _group_end(toks: list[Token], v: int) -> int:
    """Index of the last token of the verb group starting at ``v``."""
    g = v
    for j in range(v + 1, len(toks)):
        t = toks[j]
        if t.pos1 == "助動詞" or (t.pos1 == "助詞" and t.lemma == "て" and t.pos2 == "接続助詞"):
            g = j
        elif t.pos1 == "動詞":
            g = j  # bunsetsu.chunk only lets auxiliary verbs into a phrase
        elif t.pos1 == "形容詞" and t.lemma == "無い":
            g = j
        else:
            break
    return g


def _ending(toks: list[Token], g: int, ph: Phrase, next_ph: Phrase | None) -> tuple[str, str]:
    """(ending kind, cue words) of the clause whose verb group ends at ``g``."""
    last = toks[g]
    words = [t for t in toks[g + 1:] if t.pos1 != "補助記号"]
    if words and words[0].surface == "か" and len(words) == 1 and not _ends_sentence(ph, next_ph):
        return "quote", "か"  # 何を食べようか考えた, 行くか迷った: a question asked in thought, not done
    if words and _sentence_particles(words):
        return "final", _punct(ph)
    if words and _attempt(words, last, next_ph):
        return "te", "".join(t.surface for t in words)  # 持ち上げようとした, 登ろうとして: tried, played
    if words:
        return _ending_from_words(words, last)
    if last.lemma == "て" and last.pos1 == "助詞":
        return "te", last.surface
    if last.pos1 == "助動詞" and last.cform.startswith("仮定形"):
        return "cond", last.surface  # 終わったら, 歩いたら
    if last.cform.startswith("連用形"):
        return "renyou", "、" if ph.has_comma() else ""
    if _ends_sentence(ph, next_ph) or ph.has_comma():
        return "final", _punct(ph)
    if _starts_with_noun(next_ph):
        return "relative", ""
    return "final", ""


def _attempt(words: list[Token], last: Token, next_ph: Phrase | None) -> bool:
    """A volitional form + と + する: an attempt (持ち上げようとした), not a quote; 走ろうと思った stays a thought."""
    return (last.cform.startswith("意志推量形") and words[0].surface == "と" and next_ph is not None
            and bool(next_ph.tokens) and next_ph.tokens[0].lemma == "為る")


def _ending_from_words(words: list[Token], last: Token) -> tuple[str, str]:
    w = words[0]
    cue = "".join(t.surface for t in words)
    surfaces = [t.surface for t in words]
    if w.surface in ("ながら", "つつ"):
        return "nagara", w.surface
    if w.surface == "から" and last.lemma == "て":
        return "tekara", "てから"
    if w.surface in ("たり", "だり"):
        return "tari", w.surface
    if "同時" in surfaces:
        return "douji", cue
    if w.surface == "の" and surfaces != ["の", "で"]:
        return "nominal", cue  # 歩くのが好き, 走るのではなく; not 来たので (UniDic: の + だ's で, the cause ので)
    if w.surface == "と" and w.pos2 == "格助詞":
        return "quote", cue
    if w.surface in ("と", "ば"):
        return "cond", w.surface
    kind = _FORMAL_ENDINGS.get(w.surface)
    if kind == "aida" and w.surface == "間" and w.kana != "アイダ":
        kind = None
    if kind == "toki" and last.lemma == "た":
        kind = "toki_past"
    if kind:
        return kind, cue
    return "other", cue


def _ends_sentence(ph: Phrase, next_ph: Phrase | None) -> bool:
    return next_ph is None or next_ph.sentence != ph.sentence or any(
        t.pos2 == "句点" for t in ph.tokens)


def _punct(ph: Phrase) -> str:
    t = ph.tokens[-1]
    return t.surface if t.pos1 == "補助記号" else ""


def _starts_with_noun(ph: Phrase | None) -> bool:
    if ph is None:
        return False
    t = ph.tokens[0]
    return t.pos1 in ("名詞", "代名詞", "接頭辞") and not t.is_number


def body_part_of(noun: str) -> str | None:
    return BODY_PARTS.get(noun)

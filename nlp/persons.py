"""What the words of a noun phrase say of a person: a person noun beyond the list, a pronoun,
a group, and whether it names a man or a woman (docs/language.md §9).

These are word-level readings of one phrase; :mod:`reference` reads them across the text
(who 彼 is).  ``words`` below are a phrase's content tokens: prefixes, nouns, pronouns and
suffixes, up to its first particle or punctuation mark.
"""
from __future__ import annotations

from .lexicon import (
    FEMALE_NAME_ENDINGS, FEMALE_NOUNS, GROUP_WORDS, KANA_NAMES, MALE_NAME_ENDINGS, MALE_NOUNS, PERSON_ENDINGS,
    PERSON_NOUNS, PERSON_SUFFIXES, PERSONLESS_NOUNS, PRONOUNS,
)
from .types import Token

#: Demonstratives that make a pronoun of a person noun after them (その男, あの子, この方).
DEMONSTRATIVES = frozenset(["その", "あの", "この"])


def words_of(tokens: list[Token]) -> list[Token]:
    """The content tokens a phrase opens with: prefixes, nouns, pronouns, suffixes, a demonstrative."""
    out: list[Token] = []
    for t in tokens:
        if t.pos1 in ("名詞", "代名詞", "接頭辞", "接尾辞") or (not out and t.surface in DEMONSTRATIVES):
            out.append(t)
        else:
            break
    return out


def is_person_noun(words: list[Token]) -> bool:
    """店長, 駅員, 運転手 (運転 + 手), 参加者, 新入社員 (新入 + 社員), 校長先生: a person by the
    list (``lexicon.PERSON_NOUNS``), by a person suffix after a noun (``PERSON_SUFFIXES``; たち / 達:
    家来たち), or by
    the ending of a one-word noun (駅員, 記者, 店長; not the ``PERSONLESS_NOUNS`` 身長, 定員 nor a
    サ変 noun: 延長, 成長).  A compound is a person when its last noun is."""
    if not words:
        return False
    last = words[-1]
    if last.pos1 == "接尾辞" and (last.surface in PERSON_SUFFIXES or last.lemma == "達") and len(words) >= 2:
        before = words[-2]
        return before.pos1 == "名詞" and not before.is_number and before.pos2 != "数詞"
    noun = next((t for t in reversed(words) if (t.pos1 == "名詞" or t.pos1 == "代名詞")
                 and not t.is_number and t.pos2 != "数詞"), None)
    if noun is None or noun.surface in PERSONLESS_NOUNS:
        return False
    return noun.surface in PERSON_NOUNS or (
        len(noun.surface) >= 2 and noun.surface.endswith(PERSON_ENDINGS) and noun.pos3 != "サ変可能")


def refers(words: list[Token]) -> bool:
    """Do ``words`` name a person beyond a name or the person list: a person noun by its suffix or
    ending (:func:`is_person_noun`), a group word (:func:`group_size`) or a pronoun (:func:`pronoun_sex`)?"""
    if not words:
        return False
    first = words[0]
    if first.surface in DEMONSTRATIVES or first.is_number:
        return group_size(words[1:] if first.surface in DEMONSTRATIVES else words) is not None \
            or pronoun_sex(words) is not None
    text = first.surface if len(words) == 1 else "".join(t.surface for t in words)
    return text in GROUP_WORDS or text in PRONOUNS or is_person_noun(words)


def group_size(words: list[Token]) -> int | None:
    """二人 -> 2, 三人 / 3人 -> 3, みんな / 彼ら / 全員 -> 0 (everyone named so far); ``None`` when
    ``words`` are no group word."""
    if len(words) >= 2 and words[0].is_number and words[1].surface == "人" and words[0].value:
        return int(words[0].value) if float(words[0].value).is_integer() else None
    return GROUP_WORDS.get("".join(t.surface for t in words))


def pronoun_sex(words: list[Token]) -> str | None:
    """The sex a pronoun or a demonstrative description names ("m", "f", "" for either), or
    ``None`` when ``words`` are neither: 彼 -> m, 彼女 -> f, その人 -> "", その男 -> m, あの子 -> ""."""
    text = "".join(t.surface for t in words)
    if text in PRONOUNS:
        return PRONOUNS[text]
    if len(words) >= 2 and words[0].surface in DEMONSTRATIVES and is_person_noun(words[1:]):
        return noun_sex(words[1:])
    return None


def noun_sex(words: list[Token]) -> str:
    """お父さん, 男の子, 母親 -> their sex; "" for a noun that names either (店長, 先生)."""
    for t in reversed(words):
        for w in (t.surface, t.lemma):
            if w in MALE_NOUNS:
                return "m"
            if w in FEMALE_NOUNS:
                return "f"
    whole = "".join(t.surface for t in words)
    return "m" if whole in MALE_NOUNS else "f" if whole in FEMALE_NOUNS else ""


def name_sex(name: str) -> str:
    """A given name's sex by its ending (花子, 美咲 -> f; 太郎, 健一 -> m), "" when it has none of
    the common ones (``lexicon.MALE_NAME_ENDINGS``, ``FEMALE_NAME_ENDINGS``): names are not
    gendered by a dictionary, so this is a guess a lone candidate overrides (:mod:`reference`)."""
    if name in KANA_NAMES:
        return KANA_NAMES[name]
    if name.endswith(FEMALE_NAME_ENDINGS):
        return "f"
    if name.endswith(MALE_NAME_ENDINGS):
        return "m"
    return ""

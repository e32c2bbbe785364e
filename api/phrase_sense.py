"""Which clips of a verb do what a phrase about the actor's body asks.

A verb's clips may do another sense of it. The clips of 上げる raise a hand (they declare
手を上げる), so 足を上げる has none; the wipe clip wipes things (it declares 窓, 黒板), so
目をこする is not it; arms_crossed declares 腕を組む, so 足を組む is not it. A motion whose
を-noun is the actor's body (``MotionSpec.phrase`` 足を上げる: a body part of
``nlp.lexicon.BODY_PARTS`` or a noun of ``nlp.phrases.body_nouns``) may play a clip only when
:func:`same_sense` holds, and it is named by that phrase to the user (:func:`asked`). Only
clip metadata is read: the verbs a clip declares, its body part and its objects.
"""
from __future__ import annotations

from text2anim.motiondb import ClipInfo
from text2anim.motiondb.readings import reading
from text2anim.nlp.lexicon import BODY_PARTS
from text2anim.nlp.phrases import body_nouns
from text2anim.nlp.types import MotionSpec

#: body_part values (and clip body-part groups) -> the part of the body they are on
_PART = {"arm": "arm", "right_arm": "arm", "left_arm": "arm", "both_arms": "arm", "leg": "leg",
         "right_leg": "leg", "left_leg": "leg", "head": "head", "torso": "torso"}
#: clip groups that cover several parts
_GROUPS = {"upper": frozenset(["arm", "head", "torso"]), "lower": frozenset(["leg"])}


def split(phrase: str) -> tuple[str, str]:
    """``(noun, verb)`` of a phrase ``NOUNをVERB`` (``("", phrase)`` when it has no を)."""
    noun, _, verb = phrase.partition("を")
    return (noun, verb) if verb else ("", phrase)


#: Prefixes that name which or how many of a part, not another part: 両膝, 片膝 and 膝 are knees.
_WHICH = ("両", "片", "右", "左")


def body(noun: str) -> str | None:
    """What of the actor's body ``noun`` names, as finely as the nouns tell it apart: the part for
    a body-part noun (手 and 右手 -> arm, 首 -> head), the reading of another noun of the body
    without 両/片/右/左 (膝, ひざ, 両膝 -> ヒザ; 目 and 口 are not the same thing); None for a thing (窓)."""
    part = BODY_PARTS.get(noun)
    if part is not None:
        return _PART[part]
    if noun not in body_nouns():
        return None
    bare = noun[1:] if noun.startswith(_WHICH) and len(noun) > 1 else noun
    return reading(bare) or bare


def _part(noun: str) -> str | None:
    """The part of the body ``noun`` is on (目 -> head, 膝 -> leg), None for a thing."""
    part = BODY_PARTS.get(noun)
    return _PART[part] if part is not None else body_nouns().get(noun)


def body_phrase(spec: MotionSpec) -> tuple[str, str] | None:
    """``(noun, verb)`` of ``spec``'s phrase when its noun is the actor's body (足を上げる), else None."""
    noun, verb = split(spec.phrase)
    return (noun, verb) if noun and body(noun) is not None else None


def asked(spec: MotionSpec) -> str:
    """The words naming ``spec``'s motion to the user: its phrase when the noun is the actor's body
    (足を上げる: the clips of 上げる raise a hand), else the verb as written."""
    return spec.phrase if body_phrase(spec) else (spec.written or spec.verb)


def _declared(spec: MotionSpec, clip: ClipInfo) -> list[str]:
    """The nouns of the phrases ``clip`` declares with ``spec``'s verb (手 of 手を上げる for 上げる)."""
    verbs = {spec.verb, spec.written, split(spec.phrase)[1]}
    return [noun for noun, verb in map(split, clip.verbs) if noun and verb in verbs]


def _fits(part: str | None, clip_part: str | None) -> bool:
    """Is a clip declared for ``clip_part`` (None: the whole body) done with the body's ``part``?"""
    if clip_part is None or part is None:
        return True
    return part in _GROUPS.get(clip_part, {_PART.get(clip_part)})


def same_sense(spec: MotionSpec, clip: ClipInfo) -> bool:
    """May ``clip`` play ``spec``? Always, unless ``spec``'s noun is the actor's body and the clip does
    the verb to something else: it declares the verb with another noun of the body and not with this
    one (手を上げる, not 足を上げる), it is declared for another body part, or it declares the things
    it acts on and this noun is not among them (窓 for 拭く, not 目)."""
    found = body_phrase(spec)
    if found is None:
        return True
    noun, _ = found
    nouns = _declared(spec, clip)
    if nouns:
        return any(body(n) == body(noun) for n in nouns)
    if not _fits(_part(noun), clip.body_part):
        return False
    return not clip.objects or noun in clip.objects


def does_body(spec: MotionSpec, clip: ClipInfo) -> bool:
    """Does ``clip`` act on the body ``spec``'s phrase names? For a stand-in, which needs this
    evidence: the clip declares a phrase with a noun of the same body (目, 首), or is declared for
    that part of the body. True when ``spec``'s noun is no body."""
    found = body_phrase(spec)
    if found is None:
        return True
    noun, _ = found
    if any(body(n) == body(noun) for n, v in map(split, clip.verbs) if n):
        return True
    return clip.body_part is not None and _fits(_part(noun), clip.body_part)


__all__ = ["asked", "body", "body_phrase", "does_body", "same_sense", "split"]

"""Issue 40's done-when: the manner corpus's texts animate visibly differently from the neutral ones, and
every styled output meets the quality limits of motion made from the built-in library.

Each line of tests/corpus/manner_corpus.jsonl with a ``neutral`` text (the same sentence without its manner
words) is animated both ways on the built-in library (``--fallback nearest``, as a user would for 出かける);
the two motions, each sampled at 60 instants over its length with the hips' travel taken out, must differ by
at least :data:`VISIBLE` at some joint, and the styled one must meet every limit (``core.metrics``) the neutral
one meets (the kick's toe goes 1.7 cm into the floor in both, as main's floor figure reads the chains' ends).
"""
from __future__ import annotations

import numpy as np
import pytest

import text2anim
from text2anim.core.metrics import against_limits, quality
from text2anim.motiondb import UnknownVerbError
import corpus_lines

#: A joint this far (m) from where the neutral motion has it, at some instant, is a difference one sees.
VISIBLE = 0.05


def _pairs() -> list[dict]:
    return [it for it in corpus_lines.items("manner_corpus.jsonl") if "neutral" in it]


def _shape(motion, n: int = 60) -> np.ndarray:
    """Joint positions ``(n, J, 3)`` at ``n`` instants over the motion, the hips' horizontal travel removed."""
    pos = motion.positions - motion.root_positions[:, None, :] * np.array([1.0, 0.0, 1.0])
    return pos[np.linspace(0, len(pos) - 1, n).round().astype(int)]


@pytest.fixture(scope="module")
def animated(library_db):
    """Each pair's (styled, neutral) animation; None for a text whose verb no clip plays."""
    out = {}
    for it in _pairs():
        try:
            out[it["text"]] = tuple(text2anim.animate(t, db=library_db, fallback="nearest")
                                    for t in (it["text"], it["neutral"]))
        except UnknownVerbError:
            out[it["text"]] = None
    return out


def test_forty_texts_with_a_manner_animate_visibly_differently_from_the_neutral(animated):
    played = {text: pair for text, pair in animated.items() if pair is not None}
    assert len(played) >= 40
    same = {}
    for text, (styled, neutral) in played.items():
        (a,), (b,) = styled.motions.values(), neutral.motions.values()
        apart = float(np.linalg.norm(_shape(a) - _shape(b), axis=-1).max())
        if apart < VISIBLE:
            same[text] = round(apart, 3)
    assert same == {}


def test_every_styled_output_meets_the_quality_limits_the_neutral_meets_and_says_how_it_was_made(animated):
    missed, unshown = {}, {}
    for text, pair in animated.items():
        if pair is None:
            continue
        styled, neutral = pair
        (motion,), (plain,) = styled.motions.values(), neutral.motions.values()
        theirs = against_limits(quality(plain))
        bad = [name for name, ok in against_limits(quality(motion)).items() if not ok and theirs[name]]
        if bad:
            missed[text] = bad
        if any(s.by is None for s in styled.manners) or not styled.manners:
            unshown[text] = [s.to_dict() for s in styled.manners]
    assert missed == {} and unshown == {}

"""The contact instant of the built-in exchanges, read from their motion (core.contact_instant).

Two actors' contacts (a handshake's grip, a high five's slap, the take of a hand-over, a catch, a
kick's impact, a throw's release) are timed together by these frames, so each clip must have one
clear instant inside its core, where the effector really does it.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from text2anim.core.bodyparts import body_map
from text2anim.core.contact_instant import REACH_TOLERANCE, contact_instant
from text2anim.core.motion import Motion
from text2anim.motiondb.library import builtin_clips

CLIPS = {c.name: c for c in builtin_clips()}
#: Each exchange of the library: the effector that makes its contact, and the kind of contact.
CONTACTS = {
    "handshake": ("right_hand", "reach"), "high_five": ("right_hand", "reach"), "receive": ("both_hands", "reach"),
    "hand_over": ("both_hands", "reach"), "hug": ("both_hands", "reach"), "catch": ("both_hands", "reach"),
    "kick": ("right_foot", "strike"), "kick_10_03": ("right_foot", "strike"),
    "throw": ("right_hand", "release"), "throw_shot": ("right_hand", "release"),
}


def _point(m: Motion, effector: str) -> np.ndarray:
    """``(T, 3)`` the effector's joint (wrist or ankle; both hands: their mean)."""
    bm = body_map(m.skeleton)
    if effector == "both_hands":
        return m.positions[:, [bm.hands["left"], bm.hands["right"]]].mean(axis=1)
    side, part = effector.split("_")
    return m.positions[:, bm.hands[side] if part == "hand" else bm.feet[side][0]]


def _ahead(m: Motion, p: np.ndarray) -> np.ndarray:
    """``(T,)`` metres ``p`` is ahead of the hips along the way the clip faces at its first frame."""
    facing = Rotation.from_quat(m.rotations[0, 0]).apply([0.0, 0.0, 1.0]) * np.array([1.0, 0.0, 1.0])
    return (p - m.root_positions) @ (facing / np.linalg.norm(facing))


def _speed(m: Motion, p: np.ndarray) -> np.ndarray:
    return np.linalg.norm(np.gradient(p, axis=0), axis=1) * m.fps


@pytest.mark.parametrize("name", sorted(CONTACTS))
def test_each_exchange_has_one_clear_contact_inside_its_core(name):
    clip = CLIPS[name]
    effector, kind = CONTACTS[name]
    m = clip.motion
    f = contact_instant(m, effector, kind, clip.core)
    a, b = (int(round(t * m.fps)) for t in clip.core)
    assert a <= f <= b, (name, f / m.fps, clip.core)
    p = _point(m, effector)
    speed = _speed(m, p)
    if kind == "reach":  # come out to its furthest point ahead, and stopped there
        ahead = _ahead(m, p)
        assert ahead[f] >= ahead[a:b + 1].max() - REACH_TOLERANCE
        assert ahead[f] - ahead[max(0, f - int(m.fps)):f].min() > 0.05, "not arriving"
        assert ahead[f + 1:f + int(0.2 * m.fps)].max() <= ahead[f] + 0.002, "still coming"
        assert speed[f] < 0.25, speed[f]
        # one far point: the frame furthest out (the simplest reading of a reach) is the same instant
        assert abs(a + int(np.argmax(ahead[a:b + 1])) - f) <= 0.2 * m.fps
    elif kind == "strike":  # the kicking foot at full speed, low, where a ball lies
        assert speed[f] == speed[a:b + 1].max() and speed[f] > 5.0
        assert p[f, 1] < 0.3
    else:  # the throwing hand whipping out, ahead of the body
        assert speed[f] > 2.0 and _ahead(m, p)[f] > 0.3


@pytest.mark.parametrize("name", ["handshake", "kick", "throw_shot"])
def test_the_instant_is_read_from_the_motion_not_the_clock(name):
    """Played later (a second of the first pose before it) the contact comes that much later."""
    clip = CLIPS[name]
    effector, kind = CONTACTS[name]
    m = clip.motion
    lead = int(m.fps)
    later = m.replace(rotations=np.concatenate([np.repeat(m.rotations[:1], lead, axis=0), m.rotations]),
                      root_positions=np.concatenate([np.repeat(m.root_positions[:1], lead, axis=0),
                                                     m.root_positions]))
    core = (clip.core[0] + 1.0, clip.core[1] + 1.0)
    assert contact_instant(later, effector, kind, core) == contact_instant(m, effector, kind, clip.core) + lead
    assert contact_instant(later, effector, kind) == contact_instant(m, effector, kind) + lead


def test_a_throw_is_released_at_the_whip_not_at_the_fastest_frame():
    """The basketball shot's hands come down faster after the ball has gone: the release is the upward flick."""
    clip = CLIPS["throw_shot"]
    m = clip.motion
    f = contact_instant(m, "right_hand", "release", clip.core)
    p = _point(m, "right_hand")
    fastest = int(np.argmax(_speed(m, p)[: int(clip.core[1] * m.fps) + 1]))
    assert f < fastest and np.gradient(p[:, 1])[f] > 0 and p[f, 1] > 1.4


def _hand(m: Motion, side: str) -> np.ndarray:
    """The middle of the hand (wrist to the base of the fingers)."""
    s = m.skeleton
    return (m.positions[:, s.index(f"{side}Hand")] + m.positions[:, s.index(f"{side}HandIndex1")]) / 2


def _chest(m: Motion) -> np.ndarray:
    return m.positions[:, m.skeleton.index("Spine1")]


def test_a_handshake_meets_a_partner_0_6_m_away_at_1_m_height():
    clip = CLIPS["handshake"]
    m = clip.motion
    f = contact_instant(m, "right_hand", "reach", clip.core)
    hand = _hand(m, "Right")
    assert 0.3 <= (_ahead(m, hand) - _ahead(m, _chest(m)))[f] <= 0.35  # half of 0.6 m, in front of the chest
    assert abs(hand[f, 1] - 1.0) < 0.05
    # two pumps: while it holds on, the hand dips twice 3 cm below where it gripped
    low = hand[f:int(2.1 * m.fps), 1] < hand[f, 1] - 0.03
    assert np.count_nonzero(np.diff(low.astype(int)) == 1) == 2


def test_a_high_five_meets_at_head_height_half_way_to_a_partner_0_7_m_away():
    clip = CLIPS["high_five"]
    m = clip.motion
    f = contact_instant(m, "right_hand", "reach", clip.core)
    hand = _hand(m, "Right")
    head = m.positions[f, m.skeleton.index("Head")]
    assert 0.3 <= _ahead(m, hand)[f] <= 0.4
    assert head[1] <= hand[f, 1] <= head[1] + 0.25
    assert _speed(m, hand)[f - int(0.15 * m.fps)] > 1.0  # a slap: fast in, then the stop


def test_receive_takes_at_chest_height_and_ends_holding_it_at_the_chest():
    clip = CLIPS["receive"]
    m = clip.motion
    f = contact_instant(m, "both_hands", "reach", clip.core)
    hands = (_hand(m, "Left") + _hand(m, "Right")) / 2
    assert 0.35 <= _ahead(m, hands)[f] <= 0.5 and 1.0 <= hands[f, 1] <= 1.25
    assert _ahead(m, hands)[-1] < _ahead(m, hands)[f] - 0.1 and clip.end_posture == "standing"


def test_an_unknown_effector_or_kind_is_refused_by_name():
    m = CLIPS["kick"].motion
    with pytest.raises(ValueError, match="unknown effector 'head'.*right_foot"):
        contact_instant(m, "head", "strike")
    with pytest.raises(ValueError, match="unknown contact kind 'grab'.*release"):
        contact_instant(m, "right_foot", "grab")

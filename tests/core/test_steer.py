"""Steering a motion on its way (core.steer): a real walk turns over its steps about the planted foot."""
from __future__ import annotations

import numpy as np
import pytest

import text2anim
from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import detect_contacts
from text2anim.core.ground import headings, wrap_angle
from text2anim.core.metrics import against_limits, quality
from text2anim.core.steer import steer


@pytest.fixture(scope="module")
def walk(library_db):
    return text2anim.animate("太郎は5秒間歩く。", db=library_db).motions["太郎"]


def _planted_slide_cm(m, contacts) -> float:
    """The largest distance a foot's toe moves in one frame while that foot is on the floor, cm."""
    bm = body_map(m.skeleton)
    worst = 0.0
    for side in ("left", "right"):
        toe = m.positions[:, bm.feet[side][1], :][:, [0, 2]]
        down = contacts.of(side)
        step = np.linalg.norm(np.diff(toe, axis=0), axis=1)[down[1:] & down[:-1]]
        worst = max(worst, float(step.max(initial=0.0)) * 100)
    return worst


@pytest.mark.parametrize("degrees", [60.0, -90.0])
def test_a_walk_turns_by_the_angle_over_its_steps_and_its_planted_feet_stay(walk, degrees):
    start, end = 20, 80
    turned = steer(walk, start, end, np.radians(degrees))
    assert np.array_equal(turned.root_positions[:start], walk.root_positions[:start])
    assert np.array_equal(turned.rotations[:start], walk.rotations[:start])
    assert np.array_equal(turned.rotations[:, 1:], walk.rotations[:, 1:])  # only the root turns
    gained = wrap_angle(headings(turned, 0.5)[-1] - headings(walk, 0.5)[-1])
    assert abs(np.degrees(gained) - degrees) < 2.0
    path = turned.root_positions[end:, [0, 2]] - turned.root_positions[end, [0, 2]]
    own = walk.root_positions[end:, [0, 2]] - walk.root_positions[end, [0, 2]]
    c, s = np.cos(np.radians(degrees)), np.sin(np.radians(degrees))
    assert np.allclose(path, np.stack([c * own[:, 0] + s * own[:, 1], -s * own[:, 0] + c * own[:, 1]], axis=1),
                       atol=1e-9)  # after the turn, the same walk in the new direction
    contacts = detect_contacts(walk)
    assert _planted_slide_cm(turned, contacts) < _planted_slide_cm(walk, contacts) + 1.5
    assert all(against_limits(quality(turned)).values())


def test_no_turn_is_the_motion_itself(walk):
    assert steer(walk, 10, 40, 0.0) is walk

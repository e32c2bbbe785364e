"""The core on real capture that ships with the tests (``tests/data/walk_tiny.bvh``): no ``../shared`` needed.

1.2 s of a CMU walk in the cgspeed layout (CMU length units, a T-pose frame 0, ZYX channels).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.bvh import CMU_UNIT, guess_scale, parse_bvh, read_bvh
from text2anim.core.contacts import detect_contacts
from text2anim.output.bvh_write import format_bvh

WALK = Path(__file__).resolve().parents[1] / "data" / "walk_tiny.bvh"


def walk():
    return read_bvh(WALK, drop_first=True)


def test_the_fixture_reads_as_a_person_in_metres():
    raw = read_bvh(WALK, scale=1)
    assert guess_scale(raw.skeleton) == CMU_UNIT  # CMU units, recognised by size and joint names
    m = walk()
    assert (m.n_frames, m.skeleton.n_joints) == (36, 31)
    assert abs(m.fps - 30.0) < 1e-3
    height = m.positions[:, :, 1].max() - m.positions[:, :, 1].min()
    assert 1.2 < height < 2.0  # metres: a standing adult


def test_the_walker_covers_a_walking_distance():
    r = walk().root_positions
    d = float(np.linalg.norm((r[-1] - r[0])[[0, 2]]))
    assert 1.0 < d < 2.0  # about 1.1 m/s for 1.2 s


def test_both_feet_step():
    m = walk()
    feet = body_map(m.skeleton).feet
    assert set(feet) == {"left", "right"}
    c = detect_contacts(m)
    for side in ("left", "right"):
        down = c.of(side)
        assert 0 < down.sum() < m.n_frames  # planted some of the time, swinging the rest
    assert (c.left | c.right).mean() > 0.8  # a walk: a foot is nearly always on the ground


def test_write_then_read_gives_the_same_motion():
    m = walk()
    back = parse_bvh(format_bvh(m), scale=1)
    assert back.skeleton.names == m.skeleton.names
    assert np.abs(back.positions - m.positions).max() < 1e-6

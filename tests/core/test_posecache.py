"""A motion's cache (``core.posecache``): every derived quantity computed once, the same as computed fresh,
never stale because the motion cannot change, and gone with its motion."""
from __future__ import annotations

import pickle
import weakref
from pathlib import Path

import numpy as np
import pytest

from text2anim.core import Motion, concatenate, read_bvh
from text2anim.core.contacts import detect_contacts

WALK = Path(__file__).resolve().parents[1] / "data" / "walk_tiny.bvh"


@pytest.fixture
def walk() -> Motion:
    return read_bvh(WALK)


def fresh(m: Motion) -> Motion:
    """A motion of the same frames in arrays of its own, nothing known yet."""
    return Motion(m.skeleton, m.fps, m.root_positions.copy(), m.rotations.copy(),
                  None if m.translations is None else m.translations.copy())


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    return a.shape == b.shape and a.tobytes() == b.tobytes()


def test_each_quantity_is_computed_once(walk):
    assert walk.pose is walk.pose
    assert detect_contacts(walk) is detect_contacts(walk)
    made = []
    for _ in range(3):
        value = walk.cache.get(("test", 1), lambda: made.append(1) or len(made))
    assert value == 1 and made == [1]
    assert walk.cache.get(("test", 2), lambda: "other parameter") == "other parameter"  # keyed by value


def window_edit(m: Motion, lo: int = 4, hi: int = 9, joint: int = 5) -> Motion:
    """``m`` with ``joint``'s rotations over frames ``[lo, hi)`` played backwards (a leg solved on a window)."""
    rots = m.rotations[lo:hi].copy()
    rots[:, joint] = rots[::-1, joint]
    return m.with_rotations(lo, rots)


def shared(m: Motion) -> Motion:
    """The same frames in arrays of their own, their pose shared with ``m``'s (a finished join's track)."""
    return fresh(m).share_pose(m, np.arange(m.n_frames))


def root_moved_at(m: Motion, lo: int, hi: int) -> Motion:
    root = m.root_positions.copy()
    root[lo:hi] += [0.1, 0.0, -0.2]
    return m.replace(root_positions=root)


@pytest.mark.parametrize("derive", [
    lambda m: m[3:11],
    lambda m: m.replace(rotations=np.where(np.arange(m.skeleton.n_joints)[None, :, None] == 5, m.rotations[::-1],
                                           m.rotations)),
    lambda m: m.replace(root_positions=m.root_positions + [0.5, 0.0, -0.25]),
    lambda m: concatenate([m[:6], m[2:9], m]),
    window_edit,
    lambda m: window_edit(m)[2:7],
    lambda m: window_edit(m)[10:],
    lambda m: window_edit(window_edit(m), 7, 12, 2),
    lambda m: window_edit(shared(m)),
    lambda m: root_moved_at(shared(m), 2, 6),
    lambda m: shared(shared(m)),
    lambda m: fresh(window_edit(shared(m))).share_pose(window_edit(shared(m)), np.arange(m.n_frames)),
], ids=["slice", "limb edit", "root moved", "concatenation", "window edit", "window edit sliced", "slice past the window",
        "window edit of a window edit", "window edit of shared frames", "root moved on shared frames",
        "shared through a share", "shared with an edited share"])
def test_a_motion_made_from_one_whose_pose_is_known_has_the_pose_computed_fresh_bit_for_bit(walk, derive):
    walk.pose  # known: what is derived from it reuses it
    made = derive(walk)
    again = fresh(made)
    assert same_bits(made.pose.positions, again.pose.positions)
    assert same_bits(made.pose.rotations, again.pose.rotations)
    assert all(same_bits(detect_contacts(made).of(s), detect_contacts(again).of(s)) for s in ("left", "right"))


def test_a_motion_cannot_be_edited_in_place(walk):
    walk.pose
    for array in (walk.rotations, walk.root_positions, walk.positions, walk.pose.rotations,
                  detect_contacts(walk).left):
        assert not array.flags.writeable
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 0.0


def test_the_arrays_handed_to_a_motion_are_frozen_so_its_maker_cannot_change_it_later(walk):
    root, rots = walk.root_positions.copy(), walk.rotations.copy()
    m = Motion(walk.skeleton, walk.fps, root, rots)
    before = m.positions.copy()
    with pytest.raises(ValueError, match="read-only"):
        rots[:, 3] = [0.0, 0.0, 0.0, 1.0]
    assert same_bits(m.positions, before)


def test_an_edit_is_a_new_motion_with_its_own_cache(walk):
    contacts = detect_contacts(walk)
    slide = np.arange(walk.n_frames)[:, None] / walk.fps * np.array([1.0, 0.0, 0.0])  # 1 m/s sideways
    moved = walk.replace(root_positions=walk.root_positions + slide)
    assert moved.cache is not walk.cache and "contacts" not in moved.cache
    assert detect_contacts(walk) is contacts
    assert not detect_contacts(moved).left.any()  # computed from the new frames: every foot slides


def test_the_cache_goes_with_its_motion(walk):
    m = fresh(walk)
    pose = weakref.ref(m.pose)
    contacts = weakref.ref(detect_contacts(m))
    gone = weakref.ref(m)
    del m
    assert gone() is None and pose() is None and contacts() is None  # no reference cycle: freed at once


def test_a_motion_waiting_for_its_parts_pose_lets_them_go_once_it_is_computed(walk):
    part = fresh(walk)
    whole = concatenate([part, fresh(walk)])  # the parts' poses are not known: a recipe holds them
    kept = weakref.ref(part)
    del part
    assert kept() is not None
    whole.pose
    assert kept() is None


def test_a_pickled_motion_comes_back_read_only_with_an_empty_cache(walk):
    detect_contacts(walk)
    back = pickle.loads(pickle.dumps(walk))
    assert same_bits(back.rotations, walk.rotations) and not back.rotations.flags.writeable
    assert len(back.cache) == 0 and back.cache.known_pose() is None
    assert same_bits(back.positions, walk.positions)

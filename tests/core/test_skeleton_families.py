"""Any normal human skeleton imports without a --map file: its joints are mapped, its floor and contacts found,
and it is retargeted onto the character cleanly (issue: everyday capture, "any human BVH imports clean")."""
from __future__ import annotations

import numpy as np
import pytest

from limb_checks import limb_errors
from shared_data import EVERYDAY_DIR, library_motion, requires_everyday
from skeleton_families import FAMILIES, family_bvh
from text2anim.core import read_bvh
from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import detect_contacts
from text2anim.core.floor import find_floor, place_on_floor
from text2anim.core.retarget import map_skeletons
from text2anim.motiondb import ImportOptions, MotionDB


@pytest.fixture(scope="module")
def db(tmp_path_factory, library_db):
    """A copy of the seeded library database, so imports onto the built-in character do not leak."""
    path = tmp_path_factory.mktemp("families") / "motions.sqlite"
    path.write_bytes(open(library_db.removeprefix("sqlite:///"), "rb").read())
    out = MotionDB.open(f"sqlite:///{path}")
    yield out
    out.close()


@pytest.mark.parametrize("family", sorted(FAMILIES))
def test_a_family_imports_onto_the_character_with_floor_and_contacts(family, db, tmp_path):
    path = family_bvh(family, tmp_path / f"walk_{family}.bvh")
    source, _ = place_on_floor(read_bvh(path))
    bm = body_map(source.skeleton)  # every joint placed in a body part
    assert len(bm.groups["left_leg"]) >= 3 and len(bm.groups["right_arm"]) >= 3
    notes: list[str] = []
    db.import_bvh([path], ImportOptions(("歩く",), cyclic=True), notify=lambda _p, msg: notes.append(msg))
    clip = db.load(path.stem)
    assert abs(find_floor(clip).height) < 0.01  # on the floor within 1 cm
    fc = detect_contacts(clip)
    assert fc.left.sum() > 5 and fc.right.sum() > 5  # both feet plant
    mapping = map_skeletons(source.skeleton, clip.skeleton)
    assert mapping.scale == pytest.approx(1.0, abs=0.02)  # metres whatever the file's unit
    for role, err in limb_errors(source, clip.positions, mapping).items():
        assert err < 0.02, (family, role, err)
    if family not in ("cmu",):
        assert any(f"{family} to cmu rig" in m for m in notes), notes


@requires_everyday
def test_a_daz_friendly_cmu_take_imports_without_a_map(db):
    take = EVERYDAY_DIR / "13_09.bvh"  # drinking from a bottle, cgspeed's Daz-friendly names, centimetres
    db.import_bvh([take], ImportOptions(("飲む",), drop_first=True))
    clip = db.load("13_09")
    assert abs(find_floor(clip).height) < 0.01
    fc = detect_contacts(clip)
    assert fc.left.mean() > 0.5 and fc.right.mean() > 0.5  # she stands still, both feet down
    head = clip.positions[:, body_map(clip.skeleton).head, 1]
    assert 1.4 < np.median(head) < 1.8  # a standing adult, in metres


@pytest.mark.parametrize("dy", [0.93, -0.5])
def test_contacts_come_from_the_motion_wherever_its_floor_is(dy):
    """PyMO's demo walk stands 0.93 m up (its toes never near y = 0): both feet still plant, as on the floor."""
    walk = library_motion("walk")
    moved = walk.replace(root_positions=walk.root_positions + np.array([0.0, dy, 0.0]))
    on_floor, off_floor = detect_contacts(walk), detect_contacts(moved)
    for side in ("left", "right"):
        assert off_floor.of(side).sum() > 10
        assert np.mean(off_floor.of(side) == on_floor.of(side)) > 0.95

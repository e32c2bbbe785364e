"""Clips enter the database clean: on the floor, and on their character's skeleton (real CMU captures)."""
from __future__ import annotations

import numpy as np
import pytest

from limb_checks import limb_errors
from shared_data import EVERYDAY_DIR, cmu, requires_cmu, requires_everyday
from text2anim.core import read_bvh
from text2anim.core.contacts import detect_contacts, runs
from text2anim.core.floor import (FOOT_CLEARANCE, find_floor, lowest_foot_heights, lowest_points, place_on_floor,
                                  shifted)
from text2anim.core.metrics import skating_ratio, toe_joints
from text2anim.core.retarget import map_skeletons
from text2anim.motiondb import ClipValidationError, ImportOptions

pytestmark = requires_cmu

#: The character is subject 02; then subjects 07, 08 and 09, whose bones are 2.5-4.7 cm longer or shorter.
CHARACTER = "02_01_walk"
OTHERS = ("07_02_walk", "08_04_slowwalk", "09_05_run")


def bone_lengths(skel) -> np.ndarray:
    return np.linalg.norm(skel.offsets, axis=1)


def test_the_floor_of_a_capture_is_found_wherever_the_capture_put_it():
    walk = read_bvh(cmu("07_02_walk"), drop_first=True)
    floor = find_floor(walk)
    assert floor.method == "contacts" and floor.contact_frames > 100
    for dy in (-0.3, 0.0, 0.25):  # a capture volume calibrated 30 cm low or 25 cm high
        moved, again = place_on_floor(shifted(walk, dy))
        assert again.method == "contacts" and again.height == pytest.approx(floor.height + dy, abs=1e-3)
        planted = detect_contacts(moved)
        low = lowest_foot_heights(moved)
        both = np.concatenate([low[planted.left, 0], low[planted.right, 1]])
        assert np.median(both) == pytest.approx(FOOT_CLEARANCE, abs=0.01)  # planted feet on y = 0 (1 cm)


@requires_everyday
@pytest.mark.parametrize("take", ["13_35", "14_21"])  # climbing three steps: feet that end at the ankle
def test_a_capture_whose_feet_end_at_the_ankle_stands_on_its_floor_not_in_it(take):
    """Issue 46: these skeletons have no toe joint (the toes are an end site), and their ankle was taken for
    the ball of the foot: imported, the climbs stood 3.9 cm too low, toe tips 3.3 and 4.7 cm under the floor."""
    climb = read_bvh(EVERYDAY_DIR / f"{take}.bvh", scale="auto", drop_first=True)
    placed, floor = place_on_floor(climb)
    assert floor.method == "contacts"
    assert abs(floor.height) < 0.015  # the capture's calibrated floor, within its spread
    assert lowest_points(placed).min() > -0.01  # toe tips (end sites) on the floor, not in it


@requires_everyday
def test_a_climb_imported_with_its_t_pose_dropped_keeps_the_exporters_blend_out_of_the_floor(empty_db):
    """Issue 46: cgspeed's takes blend out of their T-pose over 4 frames (joints at 20-30 m/s) and, retargeted,
    the climbs' toe tips went 1.4-2.4 cm under the floor there; db import holds those frames still, at the
    first captured pose, keeping every frame (a core interval in the file's seconds means what it meant)."""
    takes = ("13_33", "14_21")
    notes = []
    empty_db.import_bvh([cmu(CHARACTER)] + [EVERYDAY_DIR / f"{t}.bvh" for t in takes],
                        ImportOptions(("登る",), character="cmu", drop_first=True),
                        notify=lambda path, msg: notes.append((path, msg)))
    for take in takes:
        clip = empty_db.load(take)
        source = read_bvh(EVERYDAY_DIR / f"{take}.bvh", drop_first=True)
        assert clip.n_frames == source.n_frames and clip.fps == pytest.approx(source.fps)
        assert lowest_points(clip).min() > -0.01  # nothing under the floor it stands on
        fastest = np.linalg.norm(np.diff(clip.positions, axis=0), axis=2).max(axis=1) * clip.fps
        assert fastest[:4].max() < 1e-6 < fastest[4] < 5.0  # four held frames, then the capture at its own pace
        assert any(p.endswith(f"{take}.bvh") and "blend out of the dropped T-pose" in msg for p, msg in notes)
    walk = empty_db.load(CHARACTER)  # a take with no blend is imported as it was
    assert np.linalg.norm(np.diff(walk.positions[:2], axis=0), axis=-1).max() > 0


def test_an_import_onto_the_built_in_character_keeps_the_captures_foot_clearance():
    """Issue 46: the built-in character's foot is longer than subject 16's, so the retarget carried the walk's
    swinging feet lower than captured (GMD's figure 0.162 as captured, 0.231 retargeted); db import gives the
    swinging feet their captured height back, and leaves the planted ones where they were."""
    from text2anim.core.metrics import at_rate, skating_ratio_gmd
    from text2anim.core.retarget import retarget
    from text2anim.motiondb.bvh_import import conform
    from text2anim.motiondb.library.skeleton import canonical_skeleton

    walk = read_bvh(cmu("16_15_walk"), scale="auto", drop_first=True)
    source, _ = place_on_floor(walk)
    plain = retarget(source, canonical_skeleton())
    imported, _ = conform(walk, canonical_skeleton(), "16_15_walk", "test")
    captured = skating_ratio_gmd(at_rate(source))
    assert skating_ratio_gmd(at_rate(plain)) > captured + 0.05  # what the retarget alone does
    assert skating_ratio_gmd(at_rate(imported)) <= captured + 0.01
    planted = detect_contacts(source)
    toe = toe_joints(imported)
    for k, side in enumerate(("left", "right")):
        on = planted.of(side)
        assert np.abs(imported.positions[on, toe[k]] - plain.positions[on, toe[k]]).max() < 1e-9


def test_a_clip_with_too_few_contacts_is_floored_by_its_lowest_foot_reach():
    jump = read_bvh(cmu("16_05_jump"), drop_first=True)
    fc = detect_contacts(jump)
    air = runs(~(fc.left | fc.right))
    a, b = max(air, key=lambda r: r[1] - r[0])  # the flight of the jump: no foot on the ground
    flight = jump.frames(int(a), int(b))
    floor = find_floor(flight)
    assert floor.method == "lowest" and floor.contact_frames < 6
    placed, _ = place_on_floor(flight)
    assert np.percentile(lowest_foot_heights(placed), 5) == pytest.approx(FOOT_CLEARANCE, abs=1e-9)


def test_subjects_imported_under_one_character_are_retargeted_onto_its_skeleton(empty_db):
    names = (CHARACTER,) + OTHERS
    notes = []
    empty_db.import_bvh([cmu(n) for n in names], ImportOptions(("歩く",), character="cmu", drop_first=True),
                        notify=lambda path, msg: notes.append((path, msg)))
    character = empty_db.load(CHARACTER).skeleton
    for name in OTHERS:
        source, _ = place_on_floor(read_bvh(cmu(name), drop_first=True))
        assert np.abs(bone_lengths(source.skeleton) - bone_lengths(character)).max() > 0.02  # another body
        clip = empty_db.load(name)
        assert np.array_equal(clip.skeleton.offsets, character.offsets)  # bone lengths: the character's
        assert abs(find_floor(clip).height) < 0.01  # floor at y = 0 within 1 cm
        assert skating_ratio(clip.resample(30)) <= skating_ratio(source.resample(30))
        # hands and feet where the source's are, up to the leg-length scale, on planted frames
        m = map_skeletons(source.skeleton, character)
        assert m.scale != pytest.approx(1.0, abs=0.015)
        for role, err in limb_errors(source, clip.positions, m).items():
            assert err < 0.02, (name, role, err)
        assert any(p.endswith(f"{name}.bvh") and msg.startswith("retargeted") for p, msg in notes)


def test_a_skeleton_no_name_table_maps_is_read_by_its_shape_and_a_map_still_places_it(empty_db, tmp_path):
    empty_db.import_bvh([cmu(CHARACTER)], ImportOptions(("歩く",), character="cmu", drop_first=True))
    text = cmu("07_02_walk").read_text()
    odd = tmp_path / "odd_rig.bvh"  # a rig whose spine and upper-leg joints have names no known rig uses
    odd.write_text(text.replace("LowerBack", "Waist").replace("LeftUpLeg", "LeftThighBone")
                   .replace("RightUpLeg", "RightThighBone"))
    # no --map needed: the shape places the thighs where the names would (core/skeleton_shape.py)
    empty_db.import_bvh([odd], ImportOptions(("歩く",), character="cmu", drop_first=True, names=("by_shape",)))
    # a joint map places them too, and the clip joins the character on its skeleton: the same motion
    empty_db.import_bvh([odd], ImportOptions(("歩く",), character="cmu", drop_first=True, names=("mapped",),
                                             joint_map={"leftUpperLeg": "LeftThighBone",
                                                        "rightUpperLeg": "RightThighBone"}))
    mapped, by_shape = empty_db.load("mapped"), empty_db.load("by_shape")
    assert mapped.skeleton.names == empty_db.load(CHARACTER).skeleton.names and abs(find_floor(mapped).height) < 0.01
    assert np.abs(mapped.positions - by_shape.positions).max() < 1e-6
    # under a character of its own it is its own skeleton: nothing to map, it is only put on the floor
    empty_db.import_bvh([odd], ImportOptions(("歩く",), character="odd", drop_first=True))
    assert abs(find_floor(empty_db.load("odd_rig")).height) < 1e-9
    assert sorted(c.name for c in empty_db.clips()) == sorted([CHARACTER, "by_shape", "mapped", "odd_rig"])

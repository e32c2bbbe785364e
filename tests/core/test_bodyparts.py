"""Body-part groups from joint names for the conventions users bring."""
from __future__ import annotations

import pytest

from shared_data import cmu
from text2anim.core import Skeleton, read_bvh
from text2anim.core.bodyparts import BodyMapError, body_map, mirror_index

MIXAMO = ["Hips", "Spine", "Spine1", "Spine2", "Neck", "Head", "HeadTop_End",
          "LeftShoulder", "LeftArm", "LeftForeArm", "LeftHand", "LeftHandThumb1",
          "RightShoulder", "RightArm", "RightForeArm", "RightHand", "RightHandThumb1",
          "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase", "LeftToe_End",
          "RightUpLeg", "RightLeg", "RightFoot", "RightToeBase", "RightToe_End"]
MIXAMO_PARENTS = [-1, 0, 1, 2, 3, 4, 5, 3, 7, 8, 9, 10, 3, 12, 13, 14, 15, 0, 17, 18, 19, 20, 0, 22, 23, 24, 25]


def _skel(names, parents):
    return Skeleton(names, parents, [[0, 0.1, 0]] * len(names))


def _names(skel, idx):
    return {skel.names[j] for j in idx}


def test_cmu_groups():
    s = read_bvh(cmu("02_01_walk")).skeleton
    bm = body_map(s)
    assert _names(s, bm.joints("right_arm")) >= {"RightShoulder", "RightArm", "RightForeArm", "RightHand"}
    assert _names(s, bm.joints("left_leg")) >= {"LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase"}
    assert _names(s, bm.joints("head")) == {"Neck", "Neck1", "Head"}
    assert "Hips" in _names(s, bm.joints("lower")) and "Hips" not in _names(s, bm.joints("upper"))
    assert set(bm.joints("lower")) | set(bm.joints("upper")) == set(range(s.n_joints))
    assert not set(bm.joints("lower")) & set(bm.joints("upper"))
    assert [s.names[j] for j in bm.feet["left"]] == ["LeftFoot", "LeftToeBase"]


def test_mixamo_names_with_namespace():
    s = _skel(["mixamorig:" + n for n in MIXAMO], MIXAMO_PARENTS)
    bm = body_map(s)
    assert _names(s, bm.joints("left_arm")) == {"mixamorig:" + n for n in
                                                ("LeftShoulder", "LeftArm", "LeftForeArm", "LeftHand", "LeftHandThumb1")}
    assert "mixamorig:HeadTop_End" in _names(s, bm.joints("head"))
    assert "mixamorig:Spine2" in _names(s, bm.joints("torso"))
    assert s.names[bm.hands["right"]] == "mixamorig:RightHand"


def test_blender_side_suffixes():
    names = ["pelvis", "spine", "neck", "head", "upper_arm.L", "forearm.L", "hand.L", "upper_arm.R", "forearm.R",
             "hand.R", "thigh.L", "shin.L", "foot.L", "toe.L", "thigh.R", "shin.R", "foot.R", "toe.R"]
    parents = [-1, 0, 1, 2, 1, 4, 5, 1, 7, 8, 0, 10, 11, 12, 0, 14, 15, 16]
    s = _skel(names, parents)
    bm = body_map(s)
    assert _names(s, bm.joints("right_leg")) == {"thigh.R", "shin.R", "foot.R", "toe.R"}
    assert [s.names[j] for j in bm.feet["left"]] == ["foot.L", "toe.L"]
    assert [s.names[j] for j in mirror_index(s)][4:7] == ["upper_arm.R", "forearm.R", "hand.R"]


def test_unmappable_skeleton_names_the_joints():
    s = _skel(["Hips", "Bone001", "Bone002", "LeftArm", "RightArm", "LeftUpLeg", "LeftFoot"], [-1, 0, 1, 0, 0, 0, 5])
    with pytest.raises(BodyMapError, match="Bone001, Bone002"):
        body_map(s)

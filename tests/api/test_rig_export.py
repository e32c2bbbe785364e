"""The animation on the user's rig (BVH), and the engine conventions: root motion, in place, units, loop."""
from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import text2anim
from cli_run import assert_clean_error, text2anim as run_cli
from rig_builders import mixamo_rig, smpl_rig, unreal_rig, vrm_rig
from limb_checks import limb_errors
from shared_data import cmu, requires_cmu
from text2anim.core import read_bvh
from text2anim.core.contacts import detect_contacts
from text2anim.core.conventions import looped
from text2anim.core.floor import find_floor, place_on_floor
from text2anim.core.metrics import skating_ratio
from text2anim.core.retarget import map_skeletons
from text2anim.export import ExportError, ExportOptions

RIGS = {"mixamo_a_pose": mixamo_rig, "smpl": smpl_rig, "unreal": unreal_rig, "vrm": vrm_rig}


def _angles(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Angle in degrees between quaternions ``a`` and ``b`` (same shape ``(..., 4)``)."""
    d = Rotation.from_quat(a.reshape(-1, 4)).inv() * Rotation.from_quat(b.reshape(-1, 4))
    return np.degrees(d.magnitude()).reshape(a.shape[:-1])


@pytest.mark.parametrize("rig", list(RIGS))
def test_the_animation_is_written_on_the_users_rig(walk, tmp_path, rig, walk_motion):
    rig_file = RIGS[rig](tmp_path / f"{rig}.bvh")
    out_file = walk.save_bvh(tmp_path / "out.bvh", ExportOptions(rig=rig_file))[0]
    src, out, user = walk_motion, read_bvh(out_file), read_bvh(rig_file).skeleton
    assert out.skeleton.names == user.names and np.allclose(out.skeleton.offsets, user.offsets, atol=1e-6)
    assert out.skeleton.channels == user.channels
    m = map_skeletons(src.skeleton, out.skeleton)
    assert m.scale != pytest.approx(1.0, abs=0.01)  # every test rig has other proportions
    for role, err in limb_errors(src, out.positions, m).items():
        assert err < 0.02, (rig, role, err)
    assert skating_ratio(out) <= skating_ratio(src)
    assert abs(find_floor(out).height) < 0.01


def test_an_a_pose_rest_is_not_copied_into_the_motion(walk, tmp_path, walk_motion):
    """The A-pose rig's arms hang as the source's do: upper-arm directions agree (its rest would put them 45° off;
    the captured walk's arm swing, issue 12, leaves up to 7°)."""
    out = read_bvh(walk.save_bvh(tmp_path / "a.bvh", ExportOptions(rig=mixamo_rig(tmp_path / "m.bvh")))[0])
    src = walk_motion
    m = map_skeletons(src.skeleton, out.skeleton)
    for side in ("left", "right"):
        def direction(motion, roles):
            p = motion.positions
            d = p[:, roles[f"{side}LowerArm"]] - p[:, roles[f"{side}UpperArm"]]
            return d / np.linalg.norm(d, axis=-1, keepdims=True)
        cos = np.sum(direction(out, m.target) * direction(src, m.source), axis=-1)
        assert np.degrees(np.arccos(np.clip(cos, -1, 1))).max() < 10.0


def test_a_rig_with_unknown_names_is_read_by_its_shape_and_a_joint_map_still_places_it(walk, tmp_path):
    text = mixamo_rig(tmp_path / "m.bvh").read_text()
    odd = tmp_path / "odd.bvh"
    odd.write_text(text.replace("mixamorig:LeftUpLeg", "Thigh_Left").replace("mixamorig:RightUpLeg", "Thigh_Right"))
    proc = run_cli("太郎は歩く。", "--rig", odd, "-o", tmp_path / "x.bvh")
    assert proc.returncode == 0, proc.stderr  # no map needed: the thighs are where the shape says
    by_shape = read_bvh(tmp_path / "x.bvh")
    assert "Thigh_Left" in by_shape.skeleton.names and abs(find_floor(by_shape).height) < 0.01
    joint_map = tmp_path / "map.json"
    joint_map.write_text(json.dumps({"leftUpperLeg": "Thigh_Left", "rightUpperLeg": "Thigh_Right"}))
    out = read_bvh(walk.save_bvh(tmp_path / "y.bvh", ExportOptions(rig=odd, joint_map=joint_map))[0])
    assert "Thigh_Left" in out.skeleton.names and abs(find_floor(out).height) < 0.01


def test_root_motion_puts_the_travel_on_a_root_bone_at_the_floor(walk, tmp_path, walk_motion):
    src = walk_motion
    out = read_bvh(walk.save_bvh(tmp_path / "r.bvh", ExportOptions(root_motion=True))[0], scale=1)
    assert out.skeleton.names[0] == "root" and out.skeleton.names[1:] == src.skeleton.names
    assert np.allclose(out.positions[:, 1:], src.positions, atol=1e-5)  # the motion itself is unchanged
    root = out.positions[:, 0]
    assert np.abs(root[:, 1]).max() < 1e-9  # on the floor
    travel = src.root_positions[-1, [0, 2]] - src.root_positions[0, [0, 2]]
    assert np.linalg.norm(travel) > 1.0
    assert np.allclose(root[-1, [0, 2]] - root[0, [0, 2]], travel, atol=0.05)  # the travel is the root's
    hips_local = out.local_translations()[:, 1]
    assert np.abs(hips_local[:, [0, 2]]).max() < 0.1  # the hips only sway about it
    # a rig with its own root bone (the Unreal mannequin) carries the travel on that bone
    unreal = read_bvh(walk.save_bvh(tmp_path / "u.bvh", ExportOptions(rig=unreal_rig(tmp_path / "ue.bvh"),
                                                                     root_motion=True))[0])
    assert unreal.skeleton.names[0] == "root"
    m = map_skeletons(src.skeleton, unreal.skeleton)
    assert np.allclose(unreal.positions[-1, 0, [0, 2]] - unreal.positions[0, 0, [0, 2]], m.scale * travel, atol=0.05)
    assert np.abs(unreal.local_translations()[:, m.target["hips"]][:, [0, 2]]).max() < 0.1


def test_in_place_removes_the_hips_travel(walk, tmp_path, walk_motion):
    src = walk_motion
    out = read_bvh(walk.save_bvh(tmp_path / "i.bvh", ExportOptions(in_place=True))[0], scale=1)
    hips = out.root_positions
    assert np.linalg.norm(src.root_positions[-1] - src.root_positions[0]) > 1.0
    # within the captured walk's own sideways sway of the hips (issue 12: up to 3.5 cm apart at the ends)
    assert np.abs(hips[:, [0, 2]]).max() < 0.1 and np.linalg.norm(hips[-1, [0, 2]] - hips[0, [0, 2]]) < 0.05
    assert np.allclose(hips[:, 1], src.root_positions[:, 1], atol=1e-6)  # height kept
    rel = lambda m: m.positions - m.positions[:, :1]  # noqa: E731
    assert np.allclose(rel(out), rel(src), atol=1e-5)  # the body moves as before about its hips


def test_units_cm_writes_every_length_times_100(walk, tmp_path):
    metres = read_bvh(walk.save_bvh(tmp_path / "m.bvh")[0], scale=1)
    cm = read_bvh(walk.save_bvh(tmp_path / "cm.bvh", ExportOptions(units="cm"))[0], scale=1)
    assert np.allclose(cm.skeleton.offsets, 100 * metres.skeleton.offsets, atol=1e-6)
    assert np.allclose(cm.root_positions, 100 * metres.root_positions, atol=1e-5)
    assert np.allclose(cm.rotations, metres.rotations, atol=1e-6) or np.allclose(
        np.abs(np.sum(cm.rotations * metres.rotations, axis=-1)), 1.0, atol=1e-6)


def _flows_into_first(m) -> bool:
    """Last frame -> first frame changes every joint's rotation no more than its largest step within the clip."""
    steps = _angles(m.rotations[1:], m.rotations[:-1]).max(axis=0)
    wrap = _angles(m.rotations[-1], m.rotations[0])
    dy = np.abs(np.diff(m.root_positions[:, 1])).max()
    return bool(np.all(wrap <= 1.05 * steps + 0.5) and abs(m.root_positions[-1, 1] - m.root_positions[0, 1]) <= dy)


@requires_cmu
def test_a_captured_walk_is_cut_and_blended_into_a_loop():
    capture, _ = place_on_floor(read_bvh(cmu("07_02_walk"), drop_first=True).resample(30))
    assert not _flows_into_first(capture)
    loop = looped(capture)
    assert loop.n_frames >= capture.n_frames // 2 and _flows_into_first(loop)


def test_loop_makes_a_single_cyclic_motion_loop_and_refuses_a_sequence(walk, library_db, tmp_path, walk_motion):
    out = read_bvh(walk.save_bvh(tmp_path / "l.bvh", ExportOptions(loop=True, in_place=True))[0], scale=1)
    assert _flows_into_first(out) and out.n_frames < walk_motion.n_frames
    assert np.linalg.norm(out.root_positions[-1, [0, 2]] - out.root_positions[0, [0, 2]]) < 0.05
    two = text2anim.animate("太郎は歩いて、走る。", db=library_db)
    with pytest.raises(ExportError, match="single cyclic motion"):
        two.save_bvh(tmp_path / "two.bvh", ExportOptions(loop=True))
    assert not (tmp_path / "two.bvh").exists()
    with pytest.raises(ExportError, match="exclude each other"):
        ExportOptions(root_motion=True, in_place=True)


@pytest.mark.parametrize("rig", list(RIGS))
def test_body_parts_of_the_known_rigs(tmp_path, rig):
    """Contacts, IK and partial actions find each rig's legs, arms, feet and hands by their names."""
    from text2anim.core.bodyparts import body_map, side_of

    skel = read_bvh(RIGS[rig](tmp_path / "r.bvh")).skeleton
    bm = body_map(skel)
    for side in ("left", "right"):
        sided = {j for j, n in enumerate(skel.names) if side_of(n) == side}
        assert sided == set(bm.groups[f"{side}_leg"]) | set(bm.groups[f"{side}_arm"])
        ankle, toe = bm.feet[side]
        assert skel.names[ankle].lower().split(":")[-1].replace("_", "") in (
            f"{side}foot", f"{side}ankle", f"foot{side[0]}") and toe != ankle
        assert "hand" in skel.names[bm.hands[side]].lower() or "wrist" in skel.names[bm.hands[side]].lower()


@requires_cmu
def test_convert_puts_a_capture_on_the_users_rig_in_centimetres(tmp_path):
    rig = smpl_rig(tmp_path / "smpl.bvh")
    out = tmp_path / "walk_smpl.bvh"
    proc = run_cli("convert", cmu("07_02_walk"), "--drop-first", "--rig", rig, "--units", "cm", "-o", out)
    assert proc.returncode == 0, proc.stderr
    floor = find_floor(read_bvh(cmu("07_02_walk"), drop_first=True)).height  # 07_02's planted toes: 3.7 cm up
    assert f"floor: moved {'down' if floor >= 0 else 'up'} {100 * abs(floor):.1f} cm" in proc.stdout
    cm = read_bvh(out, scale=1)
    user = read_bvh(rig).skeleton
    assert cm.skeleton.names == user.names and np.allclose(cm.skeleton.offsets, 100 * user.offsets, atol=1e-4)
    src, _ = place_on_floor(read_bvh(cmu("07_02_walk"), drop_first=True))
    out_m = read_bvh(out, scale=0.01)
    m = map_skeletons(src.skeleton, out_m.skeleton)
    fc = detect_contacts(src)
    planted = fc.left | fc.right
    for role in ("leftToes", "rightToes", "leftHand", "rightHand"):
        err = np.linalg.norm(out_m.positions[planted, m.target[role]] - m.scale * src.positions[planted, m.source[role]],
                             axis=-1)
        assert err.max() < 0.03, (role, err.max())  # the capture's arms reach 2.9 cm further than this rig's can


@requires_cmu
@pytest.mark.parametrize("take", ["07_02_walk", "02_03_run"])
def test_replanting_keeps_the_thighs_twist_on_straight_legs(take):
    """The ankle IK re-placing a captured walk or run keeps every thigh and upper arm turning smoothly: no
    frame-to-frame step beyond 0.3 rad (the bend plane of a nearly straight leg once flipped it by up to
    2.5 rad), and the toes still plant where the source's do."""
    from text2anim.core.retarget import retarget
    from text2anim.motiondb.library.skeleton import canonical_skeleton

    src, _ = place_on_floor(read_bvh(cmu(take), scale="auto").frames(1))
    out = retarget(src, canonical_skeleton())
    R = out.pose.rotations
    for name in ("LeftUpLeg", "RightUpLeg", "LeftArm", "RightArm"):
        j = out.skeleton.index(name)
        step = (Rotation.from_matrix(R[1:, j]).inv() * Rotation.from_matrix(R[:-1, j])).magnitude()
        assert step.max() < 0.3, (name, step.max())
    m = map_skeletons(src.skeleton, out.skeleton)
    fc = detect_contacts(src)
    for side, mask in (("left", fc.left), ("right", fc.right)):
        role = f"{side}Toes"
        err = np.linalg.norm(out.positions[mask, m.target[role]] - m.scale * src.positions[mask, m.source[role]], axis=-1)
        assert err.max() < 0.02, (role, err.max())

"""The built-in motion library: contents, determinism, and plausibility of every clip.

Plausibility uses the project's own contact detector and metrics: no foot
skating, feet not through the floor, knees and elbows within human limits,
no velocity spikes (jerk bounded by what real captures show), loops without a
pop, locomotion with alternating steps at human speeds and cadences.
"""
from __future__ import annotations

import sys

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from text2anim.motiondb.library import build_all, builtin_clips, canonical_skeleton, capture, keyframe_curves, keyframes
from text2anim.motiondb.types import ClipRecord
from shared_data import CMU_FILES, requires_cmu
from text2anim.core import read_bvh
from text2anim.core.bodyparts import GROUPS, body_map
from text2anim.core.contacts import detect_contacts
from text2anim.core.metrics import BUILTIN_LIMITS, foot_skate, jerk, quality, skating_ratio
from text2anim.core.mirror import mirror
from text2anim.motiondb.library.skeleton import SHOE_SOLE
from text2anim.output.bvh_write import write_bvh

BUILT = {b.record.name: b for b in build_all(30.0)}
CLIPS = {name: b.record for name, b in BUILT.items()}
#: Issue 11: built-in clips whose GMD skating ratio (either foot, 30 fps) is above the 0.02 threshold;
#: measured ceilings so a regression still fails. Only the keyframed dance, which the captured one
#: replaces (not seeded); fall and stop (0.031) meet it since the floor convention of core.floor.
SKATING_ABOVE_LIMIT = {"dance": 0.034}
NAMES = sorted(CLIPS)
CMU_NAMES = ("Hips, LHipJoint, LeftUpLeg, LeftLeg, LeftFoot, LeftToeBase, RHipJoint, RightUpLeg, RightLeg, "
             "RightFoot, RightToeBase, LowerBack, Spine, Spine1, Neck, Neck1, Head, LeftShoulder, LeftArm, "
             "LeftForeArm, LeftHand, LeftFingerBase, LeftHandIndex1, LThumb, RightShoulder, RightArm, "
             "RightForeArm, RightHand, RightFingerBase, RightHandIndex1, RThumb").split(", ")

#: Jerk bounds (m/s^3, all joints, 30 fps). Real captures at 30 fps (the shared CMU clips) peak at
#: 1,000-7,400 (one marker glitch reaches 20,700) with RMS 100-700; fast actions (kicks, throws,
#: punches) are at the top of that range.
JERK_MAX = 9000.0
JERK_RMS = 1000.0

#: Verbs the issue asks for, each with the body part it must be served with (None: whole body).
REQUIRED = {
    "歩く": None, "歩き出す": None, "進む": None, "前進する": None, "近づく": None,
    "走る": None, "走り出す": None, "ダッシュする": None,
    "下がる": None, "後退する": None, "後ろに下がる": None, "スキップする": None,
    "立ち止まる": None, "止まる": None,
    "ジャンプする": None, "跳ぶ": None, "飛ぶ": None, "跳ねる": None, "転ぶ": None, "倒れる": None,
    "回る": None, "回転する": None, "ターンする": None, "踊る": None, "ダンスする": None,
    "座る": None, "腰掛ける": None, "立ち上がる": None, "立つ": None, "起き上がる": None,
    "しゃがむ": None, "かがむ": None, "しゃがみ込む": None,
    "蹴る": None, "キックする": None, "シュートする": None, "殴る": None, "パンチする": None, "構える": None,
    "投げる": None, "拾う": None, "持ち上げる": None, "置く": None, "押す": None, "引く": None,
    "キャッチする": None, "受け取る": None,
    "振る": "right_arm", "手を振る": "right_arm", "上げる": "right_arm", "手を上げる": "right_arm",
    "両手を上げる": "both_arms", "バンザイする": "both_arms", "両手を広げる": "both_arms", "広げる": "both_arms",
    "拍手する": "both_arms", "叩く": "both_arms", "手を叩く": "both_arms",
    "指さす": "right_arm", "指差す": "right_arm",
    "うなずく": "head", "頷く": "head", "首を振る": "head", "見回す": "head", "見上げる": "head",
    "お辞儀する": None, "会釈する": None, "挨拶する": None, "振り向く": None, "振り返る": None,
    "喜ぶ": None, "ガッツポーズする": None, "泣く": None, "笑う": None, "伸びする": None, "伸びをする": None,
    "待つ": None,
    # issue 14: common everyday verbs (clips/everyday.json)
    "食べる": None, "飲む": None, "読む": None, "書く": None, "寝る": None, "横になる": None, "眠る": None,
    "掃除する": None, "掃く": None, "拭く": None, "洗う": None, "持つ": None, "運ぶ": None,
    "打つ": None, "電話する": None, "考える": None, "話す": None, "祈る": None, "開ける": None, "閉める": None,
    "着る": None, "脱ぐ": None, "渡す": None, "切る": None, "撮る": None, "掴む": None, "抱く": None,
    # issues 39 and 45: phrases whose verb is not the action, and two people acting together
    "ひざまずく": None, "膝をつく": None, "肩を落とす": None, "うなだれる": None, "胸を張る": None,
    "頭を抱える": None, "背を向ける": None, "そっぽを向く": None, "握手する": None, "ハイタッチする": None,
    "もらう": None,
}
LOCOMOTION = ("walk", "run", "walk_back", "skip")


def _clips_with(verb: str) -> list[ClipRecord]:
    return [c for c in CLIPS.values() if verb in c.verbs]


# --------------------------------------------------------------- contents
def test_library_api_and_records():
    clips = builtin_clips()
    assert len(clips) >= 40
    assert all(isinstance(c, ClipRecord) for c in clips)
    assert len({c.name for c in clips}) == len(clips)
    skel = canonical_skeleton()
    assert list(skel.names) == CMU_NAMES
    assert 1.65 <= skel.height() <= 1.75
    body_map(skel)  # the body-part map works unchanged
    assert skel.channels[0] == ("Xposition", "Yposition", "Zposition", "Zrotation", "Yrotation", "Xrotation")
    assert all(ch == ("Zrotation", "Yrotation", "Xrotation") for ch in skel.channels[1:])
    for c in clips:
        assert c.motion.skeleton is skel
        assert c.motion.fps == 30.0
        assert c.character == "default" and c.source.startswith("builtin")
        assert c.verbs and all(v and " " not in v for v in c.verbs)
        assert c.body_part is None or c.body_part in GROUPS
        assert c.core is not None and 0.0 <= c.core[0] < c.core[1] <= c.motion.duration + 1e-6


@pytest.mark.parametrize("verb", sorted(REQUIRED))
def test_every_required_verb_is_served(verb):
    part = REQUIRED[verb]
    found = _clips_with(verb)
    assert found, f"no clip for {verb}"
    if part is None:
        assert any(c.body_part is None for c in found)
    else:
        assert any(c.body_part == part for c in found)


def test_near_synonyms_are_on_their_clips_each_with_its_reason():
    """near.json: a verb a clip already shows, added after the clip's own verbs, never without a reason."""
    from text2anim.motiondb.library.keyframes import ClipDataError
    from text2anim.motiondb.library.near import near_synonyms, with_near_synonyms
    near = near_synonyms()
    records = {c.name: c for c in builtin_clips()}
    assert len(near) >= 5
    for name, verbs in near.items():
        own = records[name].verbs[: len(records[name].verbs) - len(verbs)]
        assert own and not set(own) & set(verbs), name  # the clip's own verbs first, primary unchanged
        for verb, why in verbs.items():
            assert verb in records[name].verbs and len(why) >= 20, (name, verb)
    with pytest.raises(ClipDataError, match="no_such_clip"):
        with_near_synonyms(builtin_clips(), {"no_such_clip": {"歩く": "a reason long enough to pass"}})


def test_head_shake_is_found_by_furu_with_the_head():
    shake = [c for c in _clips_with("振る") if c.body_part == "head"]
    assert len(shake) == 1 and "首を振る" in shake[0].verbs
    assert CLIPS["wave_hand"].verbs[0] == "振る"  # 振る alone means waving the hand


def test_kick_is_about_a_ball():
    assert "ボール" in CLIPS["kick"].objects


def test_nlp_library_verbs_all_exist():
    from text2anim.nlp import lexicon
    have = {v for c in CLIPS.values() for v in c.verbs}
    missing = sorted(set(lexicon.LIBRARY_VERBS) - have)
    assert not missing, missing


# ------------------------------------------------------ generation itself
def test_generation_is_deterministic():
    """The same clips bit for bit when built again (its cost is benchmarks/bench_speed.py's seeding row)."""
    build_all.cache_clear()
    again = {b.record.name: b.record for b in build_all(30.0)}
    for name, clip in CLIPS.items():
        a, b = clip.motion, again[name].motion
        assert a.rotations.tobytes() == b.rotations.tobytes(), name
        assert a.root_positions.tobytes() == b.root_positions.tobytes(), name


def test_cached_and_read_only():
    first, second = builtin_clips(), builtin_clips()
    assert all(a.motion is b.motion for a, b in zip(first, second))
    with pytest.raises(ValueError):
        first[0].motion.rotations[0, 0, 0] = 1.0
    for clip in first:  # keyframed and captured alike: a shared clip cannot be edited in place
        assert not clip.motion.rotations.flags.writeable, clip.name
        assert not clip.motion.root_positions.flags.writeable, clip.name
    assert {c.source.split(":")[1] for c in first} == {"keyframed", "capture"}


def test_other_frame_rates():
    clips = {b.record.name: b.record for b in build_all(24.0)}  # the keyframed walk: generated per rate
    walk = clips["walk"].motion
    assert walk.fps == 24.0
    # A whole number of frames per cycle, so the loop stays exact.
    period = BUILT["walk"].data.period
    assert walk.n_frames % round(period * 24) == 0
    assert skating_ratio(walk.resample(30)) <= BUILTIN_LIMITS["skating_ratio"]


def test_bvh_round_trip(tmp_path):
    m = CLIPS["jump"].motion
    path = tmp_path / "jump.bvh"
    write_bvh(m, path)
    back = read_bvh(path, scale=1)
    assert back.skeleton.names == m.skeleton.names
    assert np.allclose(back.positions, m.positions, atol=1e-4)


def test_bad_data_is_refused_with_the_clip_named():
    poses, _ = keyframes.load_json_dir()
    raw = {"name": "broken", "verbs": ["壊す"], "duration": 1.0,
           "keys": [{"t": 0.0, "pose": "stand"}, {"t": 0.5, "set": {"LeftElbow": [0, 0, 0]}}]}
    clip = keyframes.parse_clip(raw)
    with pytest.raises(keyframes.ClipDataError, match="broken.*LeftElbow"):
        keyframe_curves.sample_curves(clip, poses, canonical_skeleton(), np.linspace(0, 1, 5))


# ------------------------------------------------------------ plausibility
def _signed_flexion(m, chain, hinge):
    skel = m.skeleton
    a, b, c = (skel.index(j) for j in chain)
    p = m.positions
    u1, u2 = p[:, b] - p[:, a], p[:, c] - p[:, b]
    cos = np.sum(u1 * u2, 1) / np.linalg.norm(u1, axis=1) / np.linalg.norm(u2, axis=1)
    ang = np.degrees(np.arccos(np.clip(cos, -1, 1)))
    axis = np.einsum("tij,j->ti", m.pose.rotations[:, a], hinge)
    return ang * np.where(np.sum(np.cross(u1, u2) * axis, 1) >= 0, 1.0, -1.0)


@pytest.mark.parametrize("name", NAMES)
def test_feet_do_not_skate(name):
    m = CLIPS[name].motion
    assert skating_ratio(m) <= SKATING_ABOVE_LIMIT.get(name, BUILTIN_LIMITS["skating_ratio"])
    for side, fs in foot_skate(m).items():
        assert fs.mean_speed_cm_s < 0.5, (side, fs)


@pytest.mark.parametrize("name", NAMES)
def test_plants_are_exact(name):
    report = BUILT[name].report
    assert report is not None and report.max_error < 1e-3 and report.stray_contacts == 0


@pytest.mark.parametrize("name", NAMES)
def test_nothing_goes_through_the_floor(name):
    m = CLIPS[name].motion
    bm = body_map(m.skeleton)
    feet = [j for side in ("left", "right") for j in bm.feet[side]]
    assert m.positions[:, feet, 1].min() > -0.01
    assert m.positions[:, :, 1].min() > -0.03  # knees, hands, elbows on the floor in a fall


@pytest.mark.parametrize("name", NAMES)
def test_knees_and_elbows_within_human_limits(name):
    m = CLIPS[name].motion
    for side in ("Left", "Right"):
        knee = _signed_flexion(m, (f"{side}UpLeg", f"{side}Leg", f"{side}Foot"), (1.0, 0.0, 0.0))
        assert knee.min() > -5.0 and knee.max() < 160.0, (side, knee.min(), knee.max())
        sign = -1.0 if side == "Left" else 1.0
        elbow = _signed_flexion(m, (f"{side}Arm", f"{side}ForeArm", f"{side}Hand"), (0.0, sign, 0.0))
        assert elbow.min() > -5.0 and elbow.max() < 150.0, (side, elbow.min(), elbow.max())


@pytest.mark.parametrize("name", NAMES)
def test_no_velocity_spikes(name):
    j = jerk(CLIPS[name].motion)
    assert j.max < JERK_MAX and j.rms < JERK_RMS, j


def _steps_between_plants(name: str) -> bool:
    """Whether a clip's data lifts a foot between two of its plants (a step, a hop, a stomp)."""
    built = BUILT[name]
    for side in ("left", "right"):
        t = [(p.start, p.stop) for p in built.data.plants if p.side == side and np.isfinite(p.start)]
        if len(t) > 1 or (built.data.cyclic and t):
            return True
    return False


SEEDED_STEPPING = [n for n in NAMES if n not in capture.replaced() and BUILT[n].data.plants
                   and _steps_between_plants(n)]


@pytest.mark.parametrize("name", SEEDED_STEPPING)
def test_stepping_clips_meet_the_builtin_jerk_limit(name):
    """Issue 11's limit for a built-in animation (jerk p99 <= 2,300 m/s³, all joints, 30 fps) holds for
    every seeded keyframed clip whose feet step: the turn's 0.16 s steps and the skip's hop had
    snapped the knee (3,107 and 2,912) when the swing's clearance rose in one frame."""
    assert quality(CLIPS[name].motion).jerk_p99 <= BUILTIN_LIMITS["jerk_p99"]


def test_a_short_swing_lifts_the_foot_as_smoothly_as_a_captured_turn():
    """The keyframed turn steps in 0.16 s swings. Its toes' height may change its per-frame speed
    (second difference, metres) no more abruptly than the captured turns' toes do; two clearance
    humps had met in a square wave there, lifting the ball 5.6 cm in one frame (6.3 cm)."""
    def abrupt(m):
        toes = [body_map(m.skeleton).feet[s][1] for s in ("left", "right")]
        return float(np.abs(np.diff(m.positions[:, toes, 1], n=2, axis=0)).max())

    captured = [abrupt(c.motion) for c in capture.capture_records(30.0) if c.name.startswith("turn")]
    assert captured
    assert abrupt(CLIPS["turn"].motion) <= max(captured)


@requires_cmu
def test_library_jerk_is_in_the_range_of_real_captures():
    cmu_max = []
    for path in CMU_FILES:
        cmu_max.append(jerk(read_bvh(path, drop_first=True).resample(30)).max)
    ours = [jerk(c.motion).max for c in CLIPS.values()]
    assert np.median(ours) <= np.median(cmu_max)
    assert max(ours) <= np.percentile(cmu_max, 90) * 1.3


@pytest.mark.parametrize("name", [n for n in NAMES if not CLIPS[n].cyclic])
def test_one_shot_clips_start_and_end_at_rest_in_their_posture(name):
    built = BUILT[name]
    m = CLIPS[name].motion
    p = m.positions - m.root_positions[:, None] * np.array([1.0, 0.0, 1.0])
    reference = CLIPS["wait"].motion.positions[0]  # the standing pose
    if built.starts == "stand" and name != "stop":
        # 1.5 cm: a gesture's knees follow the captured idle's hips (keyframe_curves.IDLE_CLIP) from its
        # first frames, and a clip keyed lower (guts_pose, hips 0.94 m) starts 1.2 cm from the standing pose
        assert np.abs(p[0] - reference).max() < 0.015
    if built.ends == "stand":  # facing wherever it has turned (turn_away ends with its back to the start)
        heading = Rotation.from_quat(m.rotations[-1, 0]).apply([0.0, 0.0, 1.0])
        facing = Rotation.from_euler("y", -np.arctan2(heading[0], heading[2]))
        assert np.abs(facing.apply(p[-1]) - reference).max() < 0.06
    speed = np.linalg.norm(m.positions[-1] - m.positions[-2], axis=-1) * m.fps
    assert speed.max() < 0.25  # settled, not cut mid-move


@pytest.mark.parametrize("name", [n for n in NAMES if not CLIPS[n].cyclic and BUILT[n].ends != "floor"])
def test_standing_clips_are_never_dead_still(name):
    m = CLIPS[name].motion
    head = m.positions[:, body_map(m.skeleton).head]
    win = int(0.5 * m.fps)
    for a in range(0, m.n_frames - win, win // 2):
        assert np.ptp(head[a:a + win], axis=0).max() > 0.001, f"frozen around {a / m.fps:.1f} s"


@pytest.mark.parametrize("name", [n for n in NAMES if CLIPS[n].cyclic])
def test_cyclic_clips_loop_without_a_pop(name):
    m = CLIPS[name].motion
    data = BUILT[name].data
    travel = data.travel * data.cycles
    # Frames N-2, N-1, then 0 and 1 shifted by the clip's travel: the seam must look like any frame step.
    p = m.positions
    seam = np.concatenate([p[-2:], p[:2] + travel])
    steps = np.linalg.norm(np.diff(p, axis=0), axis=-1).max()
    accel = np.linalg.norm(np.diff(p, n=2, axis=0), axis=-1).max()
    assert np.linalg.norm(np.diff(seam, axis=0), axis=-1).max() <= steps * 1.05 + 1e-9
    assert np.linalg.norm(np.diff(seam, n=2, axis=0), axis=-1).max() <= accel * 1.05 + 1e-9
    q = m.rotations
    step_angle = (Rotation.from_quat(q[1:].reshape(-1, 4)).inv() * Rotation.from_quat(q[:-1].reshape(-1, 4))).magnitude().max()
    seam_angle = (Rotation.from_quat(q[0]).inv() * Rotation.from_quat(q[-1])).magnitude().max()
    assert seam_angle <= step_angle * 1.05 + 1e-9
    assert m.n_frames >= 2 * round(data.period * m.fps)


def _steps(m):
    c = detect_contacts(m)
    return sorted((a, side) for side in ("left", "right") for a, _ in c.intervals(side)), c


@pytest.mark.parametrize("name, per_cycle", [("walk", 2), ("run", 2), ("walk_back", 2)])
def test_locomotion_steps_alternate(name, per_cycle):
    m = CLIPS[name].motion
    steps, c = _steps(m)
    sides = [s for _, s in steps]
    assert all(a != b for a, b in zip(sides, sides[1:])), sides
    cycles = BUILT[name].data.cycles
    # Contacts cut by the clip's ends may add one interval at each end.
    assert per_cycle * cycles <= len(steps) <= per_cycle * cycles + 2


def test_skip_is_step_hop():
    steps, c = _steps(CLIPS["skip"].motion)
    sides = [s for _, s in steps]
    # two contacts of one foot (step, hop), then two of the other
    pairs = [sides[i:i + 2] for i in range(0, len(sides) - 1, 2)]
    assert len(sides) >= 10
    assert any(len(set(p)) == 1 for p in pairs)
    assert any(st == "none" for _, _, st in c.phases())


def test_walk_and_run_speeds_and_cadence():
    for name, (v_lo, v_hi), (cad_lo, cad_hi) in (("walk", (1.25, 1.5), (100, 120)), ("run", (2.6, 3.6), (160, 190)),
                                                  ("walk_back", (0.5, 1.0), (80, 120))):
        data = BUILT[name].data
        speed = np.linalg.norm(data.travel) / data.period
        cadence = 2 * 60 / data.period
        assert v_lo <= speed <= v_hi and cad_lo <= cadence <= cad_hi, (name, speed, cadence)
        m = CLIPS[name].motion
        measured = np.linalg.norm(m.root_positions[-1] - m.root_positions[0]) / (m.duration - 1 / m.fps)
        assert abs(measured - speed) < 0.1


def test_walk_has_double_support_and_run_has_flight():
    _, walk = _steps(CLIPS["walk"].motion)
    assert "both" in {st for _, _, st in walk.phases()} and "none" not in {st for _, _, st in walk.phases()}
    _, run = _steps(CLIPS["run"].motion)
    assert any(st == "none" and (b - a) / 30 >= 0.06 for a, b, st in run.phases())


def test_jump_has_a_real_flight():
    m = CLIPS["jump"].motion
    c = detect_contacts(m)
    air = [(b - a) / m.fps for a, b, st in c.phases() if st == "none"]
    assert air and 0.3 <= max(air) <= 0.6
    rise = m.root_positions[:, 1].max() - m.root_positions[0, 1]
    assert 0.15 <= rise <= 0.4


def test_stop_ends_standing_with_feet_together():
    m = CLIPS["stop"].motion
    bm = body_map(m.skeleton)
    last = m.positions[-1]
    left, right = last[bm.feet["left"][1]], last[bm.feet["right"][1]]
    assert abs(left[2] - right[2]) < 0.08 and 0.12 < abs(left[0] - right[0]) < 0.35


def test_sit_and_stand_up_meet():
    sit, up = CLIPS["sit_down"].motion, CLIPS["stand_up"].motion
    assert np.abs(sit.positions[-1] - up.positions[0]).max() < 0.04
    assert sit.root_positions[-1, 1] < 0.6


@pytest.mark.parametrize("name", NAMES)
def test_declared_postures_are_what_the_classifier_sees(name):
    """The postures the data declares (starts/ends) match the frames, as an imported clip's would be classified."""
    from text2anim.motiondb import classify_posture

    built, m = BUILT[name], CLIPS[name].motion
    assert (CLIPS[name].start_posture, CLIPS[name].end_posture) == (built.start_posture, built.end_posture)
    assert classify_posture(m, 0) == built.start_posture
    assert classify_posture(m, m.n_frames - 1) == built.end_posture


@pytest.mark.parametrize("first, then", [("crouch_down", "stand_from_crouch"), ("fall", "get_up"),
                                         ("crouch", "crouch_down"), ("kneel", "stand_from_kneel"),
                                         ("kneel", "wait_kneeling")])
def test_posture_changes_meet(first, then):
    """Where one clip ends off its feet, the clip that rises from there starts in the same pose."""
    a, b = CLIPS[first].motion, CLIPS[then].motion
    assert np.abs(a.positions[-1] - b.positions[0]).max() < 0.04
    assert BUILT[first].end_posture == BUILT[then].start_posture


def test_crouch_down_stays_down_as_crouch_does():
    crouch, down = CLIPS["crouch"].motion, CLIPS["crouch_down"].motion
    hold = int(round(1.9 * 30))  # crouch's last frame down, before it comes back up
    assert np.abs(crouch.positions[:hold] - down.positions[:hold]).max() < 0.05
    assert down.root_positions[-1, 1] < 0.5 and CLIPS["stand_from_crouch"].motion.root_positions[-1, 1] > 0.9


def test_get_up_goes_through_hands_and_knees_with_the_knees_on_the_floor():
    from text2anim.motiondb import classify_posture

    m = CLIPS["get_up"].motion
    seen = [classify_posture(m, f) for f in range(0, m.n_frames, 3)]
    phases = [p for k, p in enumerate(seen) if k == 0 or p != seen[k - 1]]
    # (rising from the half-kneel it passes through a crouch: hips low, over the feet)
    assert phases[0] == "lying" and phases[1] == "kneeling" and phases[-1] == "standing", phases
    assert "seated" not in phases
    knees = [m.skeleton.index(n) for n in ("LeftLeg", "RightLeg")]
    assert m.positions[:, knees, 1].min() > 0.03  # resting on the floor, never through it
    hands = [m.skeleton.index(n) for n in ("LeftHand", "RightHand")]
    on_floor = m.positions[: int(1.6 * 30), hands, 1]
    # both hands stay where fall put them until the step: keyed 5 cm up, + the shoe sole every clip stands on
    assert np.abs(on_floor - 0.05 - SHOE_SOLE).max() < 0.01


def test_kneel_rests_the_right_knee_on_the_floor_on_tucked_toes():
    """Down on one knee: from 1.6 s the right knee rests on the floor (its joint centre a knee's thickness
    up, as get_up's), the right foot on the ball of its foot with the heel high, the left foot flat and
    upright over it; the kneeling idle and the rise start from that pose."""
    from text2anim.motiondb import classify_posture

    m = CLIPS["kneel"].motion
    s = m.skeleton
    down = slice(int(1.6 * m.fps), m.n_frames)
    knee = m.positions[down, s.index("RightLeg"), 1]
    assert 0.03 < knee.min() and knee.max() < 0.08
    assert m.positions[down, s.index("LeftLeg"), 1].min() > 0.4  # the front knee up
    heel_up = m.positions[down, s.index("RightFoot"), 1] - m.positions[down, s.index("RightToeBase"), 1]
    assert heel_up.min() > 0.1  # the ankle high over the ball: toes tucked under
    seen = [classify_posture(m, f) for f in range(m.n_frames)]
    assert seen[0] == "standing" and set(seen[down]) == {"kneeling"}
    assert not {"seated", "lying"} & set(seen)  # (on the way down the hips pass low over the feet: crouched)


def test_mirroring_serves_the_left_side():
    wave = CLIPS["wave_hand"]
    bm = body_map(wave.motion.skeleton)
    left = mirror(wave.motion)
    lift = left.positions[:, bm.hands["left"], 1].max() - left.positions[0, bm.hands["left"], 1]
    assert lift > 0.7


# ---------------------------------------------------------- contact sheets
def test_contact_sheet_png(tmp_path):
    pytest.importorskip("matplotlib")
    from text2anim.output.sheet import contact_sheet

    path = tmp_path / "walk.png"
    contact_sheet(CLIPS["walk"].motion, path, title="walk 歩く", n=6, core=CLIPS["walk"].core)
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000
    assert [p.name for p in tmp_path.iterdir()] == ["walk.png"]  # no temporary file left


def test_a_small_character_is_drawn_at_a_person_s_size(tmp_path):
    """A 0.2 m rig's walk filled a corner of each panel, its feet never marked as down (the contact rule's
    centimetres are a person's): its stick figures are now drawn as the 1.7 m walk's."""
    pytest.importorskip("matplotlib")
    from matplotlib.image import imread

    from text2anim.core.conventions import scaled
    from text2anim.output.sheet import contact_sheet

    walk = CLIPS["walk"].motion
    contact_sheet(walk, tmp_path / "person.png", n=4)
    contact_sheet(scaled(walk, 0.2 / 1.7), tmp_path / "small.png", n=4)
    person, small = imread(tmp_path / "person.png"), imread(tmp_path / "small.png")
    assert person.shape == small.shape
    panels = slice(0, int(0.7 * person.shape[0]))  # the frames; the strip's label names the factor
    assert np.abs(person[panels] - small[panels]).max() < 0.05


def test_contact_sheet_without_matplotlib_says_how_to_install(tmp_path, monkeypatch):
    from text2anim.output import sheet

    monkeypatch.setitem(sys.modules, "matplotlib", None)
    with pytest.raises(sheet.PlotUnavailableError, match=r"pip install 'text2anim\[plot\]'"):
        sheet.contact_sheet(CLIPS["walk"].motion, tmp_path / "x.png")
    assert getattr(sheet.PlotUnavailableError, "user_facing", False)


STANDING = [n for n in NAMES if not CLIPS[n].cyclic and BUILT[n].data.raw.get("plants") == "both"]


def test_the_standing_gestures_are_the_library_s_gestures():
    assert {"nod", "head_shake", "point", "wave_hand", "bow"} <= set(STANDING) and len(STANDING) > 40


@pytest.mark.parametrize("name", STANDING)
def test_a_standing_gesture_plays_over_a_living_body(name):
    """Issue 24: the hips shift weight as the captured idle's do (keyframe_curves.IDLE_CLIP), never frozen legs."""
    hips = CLIPS[name].motion.root_positions
    assert np.ptp(hips[:, [0, 2]], axis=0).max() > 0.01


def test_every_seeded_clip_meets_the_clip_limits(library_db):
    """Issues 24 and 46, measured as bench_library prints it: at 30 fps no built-in clip skates (on the
    floor y = 0, and as GMD measures it, above its own lowest foot point), goes through the floor (joints,
    toe and finger tips) or holds a foot on air beyond core.metrics.CLIP_LIMITS; GMD's figure is what the
    shared capture reaches, or for a captured clip whose own cut reaches more, no more than that cut's."""
    from text2anim.core.metrics import CLIP_LIMITS, SKATING_MARGIN, quality
    from text2anim.motiondb import MotionDB
    from text2anim.motiondb.library.capture import source_skating

    sources = source_skating()
    with MotionDB.open(library_db) as db:
        over = {}
        for c in db.clips():
            q = quality(db.load(c.name))
            limits = dict(CLIP_LIMITS)
            if c.name in sources:
                limits["skating_gmd"] = max(limits["skating_gmd"], sources[c.name] + SKATING_MARGIN)
            bad = {k: round(getattr(q, k), 3) for k, v in limits.items() if getattr(q, k) > v}
            if bad:
                over[c.name] = bad
    assert over == {}
    assert len(sources) >= 50 and 0.0 < max(sources.values()) < 0.5  # the build measured every captured cut

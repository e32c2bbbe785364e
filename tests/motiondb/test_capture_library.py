"""The built-in library's motion-capture clips (issue 12): what ships, how it was cut, how it plays.

The arrays ship in the package; tests that rebuild them from the CMU files skip without ``../shared``.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import text2anim
from text2anim.core.contacts import detect_contacts
from text2anim.core.metrics import foot_skate, skating_ratio
from text2anim.core.motion import Motion
from text2anim.motiondb import MotionDB
from text2anim.motiondb.library import builtin_clips, canonical_skeleton, capture
from text2anim.output.bvh_write import format_bvh
from shared_data import CMU_DIR, requires_cmu

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "library"))  # the build scripts (not installed)
import build_capture as build  # noqa: E402

#: The actions issue 12 asks to be served by capture, by one verb each (the idle: 待つ).
ACTIONS = {"歩く": "walk", "走る": "run", "跳ぶ": "jump", "蹴る": "kick", "殴る": "punch", "投げる": "throw",
           "振る": "wave", "座る": "sit down", "立ち上がる": "stand up", "笑う": "laugh", "曲がる": "turn",
           "踊る": "dance", "しゃがむ": "squat", "くぐる": "duck", "拾う": "pick up", "待つ": "idle"}

CAPTURED = {r.name: r for r in capture.capture_records()}


def frozen_share(m: Motion) -> float:
    """docs/timetable.md §3: the share of frame pairs on which every joint moves slower than 0.5 cm/s."""
    speed = np.linalg.norm(np.diff(m.positions, axis=0), axis=-1).max(axis=1) * m.fps
    return float((speed < 0.005).mean())


# ------------------------------------------------------------------------- what ships
def test_every_cut_is_shipped_on_the_built_in_skeleton():
    cuts = capture.cut_list()
    assert [c.name for c in cuts] == list(CAPTURED)
    skel = canonical_skeleton()
    for c in cuts:
        r = CAPTURED[c.name]
        m = r.motion
        assert m.skeleton.same_hierarchy(skel) and np.allclose(m.skeleton.offsets, skel.offsets)
        assert m.fps == 30.0
        assert m.duration == pytest.approx(c.cut[1] - c.cut[0] + c.extra, abs=1.5 / 30)
        assert np.allclose(np.linalg.norm(m.rotations, axis=-1), 1.0)
        assert r.source == f"builtin:capture:CMU {c.trial} {c.cut[0]:.2f}-{c.cut[1]:.2f}s"
        assert (CMU_DIR.parent / "cmu").name == "cmu" and c.file.startswith(c.trial)


def test_at_least_fifteen_verbs_are_served_by_capture(library_db):
    lemmas = {v for r in CAPTURED.values() for v in r.verbs}
    assert len(lemmas) >= 15
    with MotionDB.open(library_db) as db:
        for verb, action in ACTIONS.items():
            best = db.search(verb)[0]
            assert best.source.startswith("builtin:capture:CMU "), (verb, action, best.name)


def test_a_verb_with_capture_never_plays_the_keyframes(library_db):
    """The keyframed clips a capture replaces are not seeded, and each of their verbs now finds a
    captured clip first, unless a remaining keyframed clip has it as its primary verb: another
    action (立つ from a crouch, しゃがみ込む down to stay), found first for that reason."""
    from text2anim.motiondb.library import build_all

    records = builtin_clips()
    kept = {r.name for r in records if r.source.startswith("builtin:keyframed")}
    kept_primary = {r.verbs[0] for r in records if r.source.startswith("builtin:keyframed")}
    replaced = [b.record for b in build_all() if b.record.name in capture.replaced()]
    assert replaced and not kept & {r.name for r in replaced}
    with MotionDB.open(library_db) as db:
        for r in replaced:
            for verb in r.verbs:
                if verb not in kept_primary:
                    assert db.search(verb)[0].source.startswith("builtin:capture:"), (r.name, verb)
    assert {r.source.split(":")[1] for r in records} == {"capture", "keyframed"}


def test_db_list_shows_the_source_of_every_clip(library_db, capsys):
    from text2anim.cli.main import main

    assert main(["db", "list", "--db", library_db]) == 0
    rows = capsys.readouterr().out.splitlines()
    assert rows[0].split()[-1] == "source"
    body = rows[1:]
    assert len(body) == len(builtin_clips())
    assert all(" capture:CMU " in row or " keyframed:" in row for row in body)


# ------------------------------------------------------------------------- how it was made
@requires_cmu
def test_rebuilding_from_the_capture_gives_the_shipped_arrays(tmp_path):
    """Cut, retarget, floor and resample again: bit for bit the shipped float32 arrays, and the
    zip writer gives the same bytes twice."""
    cuts = {c.name: c for c in capture.cut_list()}
    with np.load(capture.ARRAYS) as shipped:
        for name in ("wait", "jump", "dance", "wave_hand"):  # a plain cut, a blended loop, a spot loop, a repeated cycle
            c = cuts[name]
            m = build.cut_clip(*build.load_take(CMU_DIR / c.file), c)
            assert np.array_equal(m.rotations.astype(np.float32), shipped[f"{name}.rot"])
            assert np.array_equal(m.root_positions.astype(np.float32), shipped[f"{name}.root"])
            arrays = {f"{name}.rot": shipped[f"{name}.rot"]}
    build.write_arrays(tmp_path / "a.npz", arrays)
    build.write_arrays(tmp_path / "b.npz", arrays)
    assert (tmp_path / "a.npz").read_bytes() == (tmp_path / "b.npz").read_bytes()


@pytest.mark.parametrize("name", sorted(CAPTURED))
def test_clips_stand_on_the_floor_and_plant_their_feet(name):
    m = CAPTURED[name].motion
    feet = m.positions[:, [4, 5, 9, 10], 1]
    assert feet.min() > -0.015  # nothing through the floor
    c = detect_contacts(m)
    assert c.left.any() or c.right.any()
    start = m.positions[0, 0]
    assert abs(start[0]) < 1e-5 and abs(start[2]) < 1e-5  # starts at the origin


@pytest.mark.parametrize("name", sorted(CAPTURED))
def test_planted_feet_are_cleaned(name):
    """Contact sliding after cleaning (lock_feet): at most 12.5 cm/s on average (the turning steps of
    the dances pivot on the ball of the foot), from 2-16 cm/s as cut."""
    m = CAPTURED[name].motion
    for side, fs in foot_skate(m).items():
        assert fs.mean_speed_cm_s < 12.5, (side, fs.mean_speed_cm_s)


def test_the_idle_is_captured_standing_and_alive():
    for name in ("wait",):
        r = CAPTURED[name]
        m = r.motion
        assert r.cyclic and r.verbs[0] == "待つ" and r.start_posture == r.end_posture == "standing"
        assert frozen_share(m) == 0.0
        assert np.linalg.norm(m.root_positions[-1, [0, 2]] - m.root_positions[0, [0, 2]]) < 0.03
        c = detect_contacts(m)
        assert c.left.mean() > 0.9 and c.right.mean() > 0.9  # both feet down: standing, not stepping


def test_crouch_down_ends_in_the_squat_that_stand_from_crouch_starts_from():
    down, up = CAPTURED["crouch_down"], CAPTURED["stand_from_crouch"]
    assert down.end_posture == up.start_posture == "crouched"
    assert down.motion.root_positions[0, 1] > 0.85 and down.motion.root_positions[-1, 1] < 0.45
    assert up.motion.root_positions[-1, 1] > 0.85
    pa = down.motion.positions[-1] - down.motion.root_positions[-1] * [1, 0, 1]
    pb = up.motion.positions[0] - up.motion.root_positions[0] * [1, 0, 1]
    assert np.abs(pa - pb).max() < 0.03


def test_dances_loop_on_the_spot(library_db):
    """A dance cycle ends where it began (its captured travel, 0.8-0.95 m a cycle, taken out), and the
    engine plays 20 s of it without the dancers travelling away; the planted feet stay cleaned."""
    for name in ("dance", "dance_05_03"):
        m = CAPTURED[name].motion
        assert CAPTURED[name].cyclic
        assert np.linalg.norm(m.root_positions[-1, [0, 2]] - m.root_positions[0, [0, 2]]) < 0.03
    anim = text2anim.animate("太郎と花子は20秒踊る。", db=library_db)
    assert {anim.planned.clips[e.id].name for e in anim.table.elements} == {"dance", "dance_05_03"}
    for actor, m in anim.motions.items():
        hips = m.root_positions[:, [0, 2]]
        assert m.duration >= 20.0 - 1e-6
        assert np.linalg.norm(hips - hips[0], axis=1).max() < 0.5, actor
        assert frozen_share(m) == 0.0


def test_a_dance_after_a_walk_stands_on_the_floor(library_db):
    """The join settles the dance onto the walk's locked foot by the foot's lowest point: the dancer
    stands on the ball of her left foot (heel 14 cm up) where the walk's foot was flat, which read as the
    whole dance sinking 6 cm through the floor."""
    from text2anim.core.metrics import quality

    (m,) = text2anim.animate("太郎は歩いて、踊る。", db=library_db).motions.values()
    assert quality(m).floor_penetration_cm <= 1.0


def test_the_wave_swings_the_right_hand_for_about_three_seconds(library_db):
    (m,) = text2anim.animate("太郎は手を振る。", db=library_db).motions.values()
    assert 2.5 < m.duration < 3.8
    names = m.skeleton.names
    hand, left, head = (m.positions[:, names.index(j)] for j in ("RightHand", "LeftHand", "Head"))
    up = hand[:, 1] > head[:, 1] - 0.1
    assert up.mean() > 0.75  # the hand is up by the head for most of the wave
    side = hand[up, 0] - m.root_positions[up, 0]  # side to side (the actor faces +Z)
    turns = np.flatnonzero(np.diff(np.sign(np.diff(np.convolve(side, np.ones(3) / 3, "valid")))) != 0)
    assert len(turns) >= 5  # three swings out and back
    assert (left[:, 1] < m.positions[:, names.index("LeftShoulder"), 1] - 0.2).all()  # one hand: the left stays down


def test_stand_up_starts_where_sit_down_ends():
    end, start = CAPTURED["sit_down"].motion, CAPTURED["stand_up"].motion
    pa = end.positions[-1] - end.root_positions[-1] * [1, 0, 1]
    pb = start.positions[0] - start.root_positions[0] * [1, 0, 1]
    assert np.abs(pa - pb).max() < 0.03


# ------------------------------------------------------------------------- how it plays
@pytest.mark.parametrize("text", ["太郎は走る。3秒後に花子が歩く。", "太郎は待つ。そして歩く。",
                                  "太郎は走って、ボールを蹴る。そして喜ぶ。", "花子は歩いて、座る。"])
def test_no_output_holds_a_frozen_pose(library_db, text):
    anim = text2anim.animate(text, db=library_db)
    for actor, m in anim.motions.items():
        assert frozen_share(m) == 0.0, actor


def test_coactors_are_not_clones(library_db):
    anim = text2anim.animate("太郎と花子が走る。", db=library_db)
    taro, hanako = anim.table.elements
    assert anim.planned.clips[taro.id].name != anim.planned.clips[hanako.id].name
    a, b = anim.motions["太郎"], anim.motions["花子"]
    n = min(len(a), len(b))
    assert not np.allclose(a.rotations[:n, 1:], b.rotations[:n, 1:], atol=1e-3)


def test_a_verb_with_one_clip_is_mirrored_for_the_second_actor(library_db):
    anim = text2anim.animate("太郎と花子がお辞儀する。", db=library_db)
    first, second = anim.table.elements
    assert anim.planned.clips[first.id].name == anim.planned.clips[second.id].name == "bow"
    assert second.id in anim.planned.mirrored and first.id not in anim.planned.mirrored


def test_repeated_jumps_rebound_about_once_a_second_with_variants(library_db):
    anim = text2anim.animate("太郎は3回跳ぶ。", db=library_db)
    (e,) = anim.table.elements
    picks = anim.planned.repeats[e.id]
    assert len(picks) == 3
    assert len({(p.clip.name, p.mirrored) for p in picks}) == 3
    assert (e.end - e.start) / 3 <= 1.1  # a jump cut from the crouch to the rebound: about a second each
    (m,) = anim.motions.values()
    feet = m.positions[:, [4, 9], 1].min(axis=1)
    airborne = feet > 0.12
    takeoffs = np.flatnonzero(airborne[1:] & ~airborne[:-1])
    assert len(takeoffs) == 3  # three flights, no dead standing between them
    assert np.diff(takeoffs).max() / m.fps < 1.3  # 1.46 s between the first two with the 1.25 s cut
    assert frozen_share(m) == 0.0


def test_the_variant_choice_is_deterministic(library_db):
    def digest():
        anim = text2anim.animate("太郎と花子が跳ぶ。そして太郎は2回跳ぶ。", db=library_db)
        return {k: format_bvh(m) for k, m in anim.motions.items()}

    assert digest() == digest()


def test_a_captured_run_played_alone_keeps_its_shape(library_db):
    """The run's seam is spread over its cycle by the engine: a few cm at most, and no skating."""
    with MotionDB.open(library_db) as db:
        source = db.load("run")
    (m,) = text2anim.animate("走る。", db=library_db).motions.values()
    n = min(len(m), len(source))
    here = np.linalg.norm(m.positions[:n] - m.positions[:n, :1], axis=-1)
    there = np.linalg.norm(source.positions[:n] - source.positions[:n, :1], axis=-1)
    assert np.abs(here - there).max() < 0.04
    assert skating_ratio(m) <= skating_ratio(source) + 0.01  # issue 11's criterion against the source


#: Corpus sentences (tests/corpus/nlp_corpus.jsonl) over the captured clips that skated, jerked, went
#: through the floor or held still before the floor convention and the clip cleaning of issues 11/12:
#: walk, run into a stop, a jump (capture glitch), dance, kick, throw, pick up from the floor, a fall.
BUILTIN_SENTENCES = ["歩いてください。", "花子は走って、そして止まる。", "太郎はジャンプする。", "太郎は踊り出す。",
                     "太郎はボールをける。", "太郎はボールを拾う。そして投げる。",
                     "太郎は転んでしまう。"]


@pytest.mark.parametrize("text", BUILTIN_SENTENCES)
def test_builtin_sentences_meet_the_quality_thresholds(library_db, text):
    """Issue 11's bounds for motion made from the built-in library (root pop <= 15 m/s², jerk p99 <=
    2,300 m/s³, GMD skating <= 0.02, floor penetration <= 1 cm, at 30 fps) and issue 12's: no frozen
    frame, through the real pipeline with the default engine."""
    from text2anim.core.metrics import against_limits, quality

    anim = text2anim.animate(text, db=library_db)
    for actor, m in anim.motions.items():
        q = quality(m)
        assert all(against_limits(q).values()), (actor, q)
        assert q.frozen_fraction == 0.0 and frozen_share(m) == 0.0, actor

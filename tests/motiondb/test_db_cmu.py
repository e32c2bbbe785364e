"""Real CMU captures (../shared/mocap/cmu) imported into a temporary database and retrieved by verb."""
from __future__ import annotations

import numpy as np
import pytest

from text2anim.motiondb import ClipValidationError, ImportOptions
from shared_data import cmu, requires_cmu
from text2anim.core import read_bvh
from text2anim.core.contacts import detect_contacts
from text2anim.core.bodyparts import body_map
from text2anim.core.floor import lowest_points, place_on_floor

pytestmark = requires_cmu

RUNS = ("02_03_run", "16_35_run", "127_07_run")


def test_imported_captures_are_found_by_verb_and_load_unchanged(empty_db):
    progress = []
    infos = empty_db.import_bvh([cmu(n) for n in RUNS],
                                ImportOptions(("走る", "駆ける", "ダッシュする"), character="cmu", cyclic=True,
                                              drop_first=True), progress=lambda *a: progress.append(a))
    assert [i.name for i in infos] == list(RUNS)
    assert [p[:2] for p in progress] == [(0, 3), (1, 3), (2, 3), (3, 3)]
    empty_db.import_bvh([cmu("16_01_jump")], ImportOptions(("跳ぶ", "ジャンプする"), character="cmu", core=(0.5, 2.0),
                                                         drop_first=True))
    empty_db.import_bvh([cmu("02_01_walk")], ImportOptions(("歩く",), objects=(), character="cmu", drop_first=True))

    assert [c.name for c in empty_db.search("走る")] == sorted(RUNS)
    assert [c.name for c in empty_db.search("かける")] == sorted(RUNS)       # by reading of the synonym 駆ける
    assert [c.name for c in empty_db.search("とぶ")] == ["16_01_jump"]       # 跳ぶ by its reading
    assert [c.name for c in empty_db.search("ジャンプする")] == ["16_01_jump"]
    walk = empty_db.search("歩く", character="cmu")[0]
    assert walk.name == "02_01_walk" and walk.fps == pytest.approx(120, abs=0.01)

    original = read_bvh(cmu("02_01_walk"), drop_first=True)
    assert walk.frames == original.n_frames == 343
    assert walk.source.endswith("02_01_walk.bvh") and walk.joints == 31
    # same subject as the character's first clip (02_03_run): same skeleton, so only the floor moves
    floored, floor = place_on_floor(original)
    assert floor.method == "contacts" and 0.005 < floor.height < 0.05
    contacts = detect_contacts(floored)
    assert walk.left_contacts == tuple(contacts.intervals("left"))
    assert walk.right_contacts == tuple(contacts.intervals("right"))
    assert len(walk.left_contacts) >= 2 and len(walk.right_contacts) >= 2  # steps of a walk
    loaded = empty_db.load(walk)
    toes = [toe for _, toe in body_map(original.skeleton).feet.values()]
    kept = np.setdiff1d(np.arange(original.skeleton.n_joints), toes)
    assert np.array_equal(loaded.rotations[:, kept], original.rotations[:, kept])
    # only a toe tip that dipped under the floor is bent up onto it (issue 46), and only about it
    dipped = lowest_points(floored) < 0.0
    bent = (loaded.rotations[:, toes] != original.rotations[:, toes]).any(axis=(1, 2))
    assert dipped.any() and bent[dipped].all() and lowest_points(loaded).min() > -1e-9
    assert bent.mean() < 0.5
    assert np.array_equal(loaded.root_positions[:, [0, 2]], original.root_positions[:, [0, 2]])
    assert np.allclose(loaded.root_positions[:, 1], original.root_positions[:, 1] - floor.height, atol=1e-12)
    assert np.array_equal(loaded.skeleton.offsets, original.skeleton.offsets)
    assert loaded.skeleton.channels == original.skeleton.channels

    jump = empty_db.info("16_01_jump")
    assert jump.core == (0.5, 2.0) and jump.verbs == ("跳ぶ", "ジャンプする")
    assert all(i.cyclic for i in empty_db.search("走る")) and not jump.cyclic


def test_one_malformed_file_in_a_batch_imports_nothing(empty_db, tmp_path):
    good = cmu("02_03_run")
    lines = good.read_text().splitlines()
    truncated = tmp_path / "truncated_run.bvh"
    truncated.write_text("\n".join(lines[: len(lines) - 20]) + "\n")  # 20 frame lines missing
    with pytest.raises(ClipValidationError) as err:
        empty_db.import_bvh([good, truncated, cmu("16_35_run")],
                            ImportOptions(("走る",), drop_first=True, character="cmu"))
    msg = str(err.value)
    assert str(truncated) in msg and "truncated" in msg and "nothing was imported" in msg
    assert empty_db.clips() == [] and empty_db.verbs() == [] and empty_db.characters() == []

    with pytest.raises(ClipValidationError,
                       match=r"02_03_run.bvh: core 0..9 s must satisfy .*duration \(1.442 s\).*nothing was imported"):
        empty_db.import_bvh([good], ImportOptions(("走る",), core=(0, 9), drop_first=True))
    missing = tmp_path / "nowhere.bvh"
    with pytest.raises(ClipValidationError, match="nowhere.bvh: no such file"):
        empty_db.import_bvh([good, missing], ImportOptions(("走る",), drop_first=True))
    assert empty_db.clips() == []


def test_another_performer_joins_the_same_character(empty_db):
    # CMU subjects share the hierarchy but not the proportions: the second is retargeted onto the first's skeleton.
    notes = []
    empty_db.import_bvh([cmu("02_03_run"), cmu("127_07_run")],
                        ImportOptions(("走る",), character="cmu", drop_first=True),
                        notify=lambda path, msg: notes.append((path, msg)))
    a, b = empty_db.load("02_03_run"), empty_db.load("127_07_run")
    assert np.array_equal(a.skeleton.offsets, b.skeleton.offsets)
    src = read_bvh(cmu("127_07_run"), drop_first=True)
    assert not np.allclose(src.skeleton.offsets, a.skeleton.offsets, atol=0.01)
    assert [m for p, m in notes if p.endswith("127_07_run.bvh") and m.startswith("retargeted")]


def test_postures_of_real_captures_are_classified_on_import(empty_db, tmp_path):
    """Sitting down on a step stool, getting up, squatting, walking: what the classifier makes of real data."""
    from text2anim.motiondb import classify_posture
    from text2anim.output.bvh_write import write_bvh

    sit = read_bvh(cmu("14_31_sit"), drop_first=True)  # sits at ~2 s, stands up at ~7.5 s
    write_bvh(sit.between(0.0, 5.0), tmp_path / "sit_down.bvh")
    write_bvh(sit.between(5.0, 9.0), tmp_path / "stand_up.bvh")
    infos = empty_db.import_bvh([tmp_path / "sit_down.bvh", tmp_path / "stand_up.bvh", cmu("02_01_walk")],
                                ImportOptions(("動く",), character="cmu", drop_first=False))
    assert [(i.name, i.start_posture, i.end_posture) for i in infos] == [
        ("sit_down", "standing", "seated"), ("stand_up", "seated", "standing"), ("02_01_walk", "standing", "standing")]
    squat = read_bvh(cmu("14_06_squat"), drop_first=True)
    assert classify_posture(squat, int(10.0 * squat.fps)) == "crouched"  # hips low, over the feet
    assert classify_posture(squat, int(20.0 * squat.fps)) == "standing"
    told = empty_db.import_bvh([tmp_path / "sit_down.bvh"],
                               ImportOptions(("座る",), character="cmu", names=("told",), start_posture="standing",
                                             end_posture="crouched"))
    assert (told[0].start_posture, told[0].end_posture) == ("standing", "crouched")

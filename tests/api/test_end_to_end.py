"""Text to animation through the real pipeline and the built-in library, as a user runs it."""
from __future__ import annotations

import importlib.util
import json

import numpy as np
import pytest

import text2anim
from cli_run import assert_clean_error, text2anim as run
from text2anim.core import read_bvh
from text2anim.core.bodyparts import body_map
from text2anim.core.metrics import SKATING_MARGIN, against_limits, quality, skating_ratio
from text2anim.motiondb.library import builtin_clips

EXAMPLE = "太郎は走って、ボールを蹴る。そして喜ぶ。"


@pytest.fixture(scope="module")
def example(library_db):
    return text2anim.animate(EXAMPLE, db=library_db)


def test_plan_cli_prints_the_papers_table(library_db):
    proc = run("plan", EXAMPLE, "--db", library_db)
    assert proc.returncode == 0, proc.stderr
    assert "[要素 2]" in proc.stdout and "接続形式  Transition" in proc.stdout
    assert "接続形式  Connection" in proc.stdout and "前要素    要素 2" in proc.stdout


def test_plan_json_follows_the_contract(library_db):
    proc = run("plan", EXAMPLE, "--json", "--db", library_db)
    assert proc.returncode == 0, proc.stderr
    table = json.loads(proc.stdout)
    assert [(e["verb"], e["method"], e["prev"]) for e in table["elements"]] == [
        ("走る", "initial", None), ("蹴る", "transition", 1), ("喜ぶ", "connection", 2)]
    run_, kick, cheer = table["elements"]
    assert run_["start"] == 0 and run_["start"] < kick["start"] < run_["end"] <= kick["end"]
    assert cheer["start"] == pytest.approx(kick["end"], abs=1e-3)


def test_example_animation_is_one_clean_motion(example):
    (name, motion), = example.motions.items()
    assert name == "太郎" and motion.fps == 30
    last = example.table.elements[-1]
    # the time table's length, and the time the joins took to slow down where the clips' own
    # accelerations ask for it (synthesis.join.joinpass: braking steps, reported per join as added_s)
    added = sum(j.metrics.get("post", {}).get("added_s", 0.0) for j in example.result.joins)
    assert motion.duration == pytest.approx(last.end + added, abs=0.2)
    assert skating_ratio(motion) <= clips_skating(e.clip for e in example.table.elements) + 0.01
    # No teleport: the hips never move more than a sprint's distance in one frame.
    step = np.linalg.norm(np.diff(motion.positions[:, 0], axis=0), axis=1)
    assert step.max() < 10 / motion.fps
    # The kick happens: one foot rises well above the other while the kick element plays.
    kick = example.result.elements[example.table.elements[1].id]  # as played
    frames = slice(int(kick.start * 30), int(kick.end * 30))
    from text2anim.core.bodyparts import body_map
    feet = body_map(motion.skeleton).feet
    y = motion.positions[frames][:, [feet["left"][0], feet["right"][0]], 1]
    assert np.abs(y[:, 0] - y[:, 1]).max() > 0.2


def test_report_has_every_join_with_metrics(example):
    report = example.report
    assert [(j["first"], j["second"], j["method"]) for j in report["joins"]][:2] == [
        (1, 2, "transition"), (2, 3, "connection")]
    for j in report["joins"]:
        assert j["intervals"] and all(iv["begin"] <= iv["end"] for iv in j["intervals"])
        assert j["metrics"]["skating_ratio"] <= j["metrics"]["source_skating_ratio"] + SKATING_MARGIN


def test_cli_writes_bvh_viewer_and_report(tmp_path, library_db):
    out = tmp_path / "anim.bvh"
    proc = run(EXAMPLE, "-o", out, "--html", tmp_path / "anim.html", "--report", tmp_path / "r.json",
               "--db", library_db)
    assert proc.returncode == 0, proc.stderr
    m = read_bvh(out)
    assert m.n_frames > 60 and m.fps == pytest.approx(30)
    assert "<canvas" in (tmp_path / "anim.html").read_text()
    assert json.loads((tmp_path / "r.json").read_text())["joins"]


def test_same_text_same_bytes(tmp_path, library_db):
    a, b = tmp_path / "a.bvh", tmp_path / "b.bvh"
    assert run(EXAMPLE, "-o", a, "--db", library_db).returncode == 0
    assert run(EXAMPLE, "-o", b, "--db", library_db).returncode == 0
    assert a.read_bytes() == b.read_bytes()


def test_two_actors_get_two_files_apart(tmp_path, library_db):
    anim = text2anim.animate("太郎が歩くと同時に花子が走る。", db=library_db)
    files = anim.save_bvh(tmp_path / "x.bvh")
    assert sorted(f.name for f in files) == ["x_太郎.bvh", "x_花子.bvh"]
    taro, hanako = (anim.motions[n].positions[0, 0] for n in ("太郎", "花子"))
    assert np.linalg.norm((taro - hanako)[[0, 2]]) >= 1.0


@pytest.mark.parametrize("args, fragment", [
    (("",), "empty"),
    (("宇宙遊泳する。",), "宇宙遊泳する"),
    (("走る。", "-o", "/nonexistent-dir/x.bvh"), "does not exist"),
    # without the postgres extra the message says the driver is missing; with it, that no server answers
    (("走る。", "--db", "postgresql://nobody@127.0.0.1:1/none"),
     "cannot connect" if importlib.util.find_spec("psycopg2") or importlib.util.find_spec("psycopg")
     else "which is not installed: pip install 'text2anim[postgres]'"),
])
def test_bad_input_one_message_no_file(tmp_path, library_db, args, fragment):
    extra = () if "--db" in args else ("--db", library_db)
    proc = run(*args, *extra, cwd=tmp_path)
    assert_clean_error(proc, fragment)
    assert list(tmp_path.iterdir()) == []


def test_skip_unknown_animates_the_rest(tmp_path, library_db):
    proc = run("走って、宇宙遊泳する。そして喜ぶ。", "--skip-unknown", "-o", tmp_path / "a.bvh", "--db", library_db)
    assert proc.returncode == 0, proc.stderr
    assert "skipped 宇宙遊泳する" in proc.stderr
    assert (tmp_path / "a.bvh").exists()


def test_a_chain_of_actions_plays_every_action(library_db):
    """走り、跳び、転ぶ: the jump is delayed for room after the run; the fall scheduled after it follows it
    instead of being dropped (it was: 'not executed', and the actor stood until the end)."""
    anim = text2anim.animate("太郎は走り、跳び、転ぶ。", db=library_db)
    assert not anim.report["warnings"] and not anim.report["skipped"]
    (motion,) = anim.motions.values()
    els = anim.report["elements"]
    assert all(v.get("executed", True) for v in els.values())
    jump, fall = els["2"], els["3"]
    assert fall["core"][0] >= jump["core"][1] - 1e-9  # cores in the order written, not overlapping
    hips = motion.positions[:, 0, 1]
    end = int(fall["core"][1] * motion.fps)
    assert hips[end - 1] < 0.5 * hips[0]  # the fall is played: the hips end near the floor


def test_a_wait_is_standing_not_a_frozen_stride(library_db):
    anim = text2anim.animate("走る。3秒後に歩く。", db=library_db)
    (motion,) = anim.motions.values()
    run, walk = (e for e in anim.table.elements if e.id not in anim.planned.fillers)
    assert walk.start == pytest.approx(run.end + 3)
    from text2anim.core.contacts import detect_contacts
    c = detect_contacts(motion)
    # the second before the last 0.5 s: the join into the captured walk (a stride at 1.3 m/s)
    # shifts the weight forward over those last 0.5 s, as a person setting off does
    mid = slice(int((walk.start - 1.5) * 30), int((walk.start - 0.5) * 30))
    assert c.left[mid].all() and c.right[mid].all()  # both feet down while waiting
    hips_speed = np.linalg.norm(np.diff(motion.positions[mid, 0], axis=0), axis=1) * 30
    assert hips_speed.max() < 0.3
    bar = clips_skating(e.clip for e in anim.table.elements) + 0.01
    assert all(j["metrics"]["skating_ratio"] <= bar for j in anim.report["joins"])
    assert skating_ratio(motion) <= bar


def test_an_actor_who_finishes_early_stands_until_the_end(library_db):
    anim = text2anim.animate("太郎は走る。3秒後に花子が歩く。", db=library_db)
    taro, hanako = anim.motions["太郎"], anim.motions["花子"]
    assert taro.n_frames == hanako.n_frames
    hips = taro.positions[-15:, 0]
    assert np.linalg.norm(hips[-1] - hips[0]) < 0.1


def test_an_actor_waiting_for_a_longer_join_keeps_its_own_time(library_db):
    """花子's walk into the sit takes 2 s more than scheduled; 太郎, done earlier, waits at rest instead of
    having his run and stop played up to half speed (which stood him on one foot in a slowed step, and
    moved his frames away from the report's times)."""
    from text2anim.motiondb import MotionDB

    anim = text2anim.animate("太郎は走る。花子が歩く。そして座る。", db=library_db)
    taro = anim.motions["太郎"]
    assert taro.n_frames == anim.motions["花子"].n_frames
    (run,) = [r for r in anim.report["time_table"] if r["actor"] == "太郎" and r["clip"] == "run"]
    t0, t1 = anim.report["elements"][str(run["id"])]["core"]
    with MotionDB.open(library_db) as db:
        clip = db.load("run")

    def speed(m, a: float, b: float) -> float:
        xz = m.root_positions[int(round(a * m.fps)):int(round(b * m.fps)) + 1, [0, 2]]
        return float(np.linalg.norm(np.diff(xz, axis=0), axis=1).sum() / (b - a))

    assert speed(taro, t0, t1) == pytest.approx(speed(clip, 0.0, (clip.n_frames - 1) / clip.fps), rel=0.05)
    joins = [j for j in anim.report["joins"] if j["second"] in {r["id"] for r in anim.report["time_table"]
                                                                 if r["actor"] == "太郎"}]
    assert joins and all(all(j["quality"]["transition"]["meets"].values()) for j in joins)


@pytest.mark.parametrize("text, clip", [("スキップする。", "skip"), ("歩く。", "walk"), ("下がる。", "walk_back")])
def test_a_looping_clip_alone_plays_as_recorded(library_db, text, clip):
    """A clip that already loops is not 'corrected' at its seam (the skip's landing once made it skate).

    The captured walk is built to loop (its seam blended into the frames before the cycle); the
    captured run's seam is still corrected by the engine: see test_capture_library.py."""
    from text2anim.motiondb import MotionDB

    with MotionDB.open(library_db) as db:
        source = db.load(clip)
    (motion,) = text2anim.animate(text, db=library_db).motions.values()
    n = min(motion.n_frames, source.n_frames)
    # The body's shape, seen from its hips (placement on the ground may turn and move it).
    here = np.linalg.norm(motion.positions[:n] - motion.positions[:n, :1], axis=-1)
    there = np.linalg.norm(source.positions[:n] - source.positions[:n, :1], axis=-1)
    np.testing.assert_allclose(here, there, atol=2e-3)
    assert skating_ratio(motion) <= skating_ratio(source) + 0.01


def clips_skating(names) -> float:
    """The largest GMD skating ratio (30 fps) of the built-in clips ``names``: since issue 12 most are
    CMU capture, whose swing toes pass below 5 cm (the bar an output is held to is this + 0.01,
    issue 11's criterion against the sources)."""
    from text2anim.motiondb.library import builtin_clips

    recs = {r.name: r.motion for r in builtin_clips()}
    return max(skating_ratio(recs[n.removesuffix("~mirrored")]) for n in names)


@pytest.mark.parametrize("text", ["花子はくるくるまわる。", "手を叩きながらスキップする。", "ボールを投げると同時に走る。"])
def test_the_sentences_that_broke_the_jerk_limit_meet_the_builtin_limits(library_db, text):
    """Issue 11: every corpus sentence that animates meets the built-in limits. These three had not, on
    jerk: the keyframed turn's 0.16 s steps and the skip's hop (the swing's clearance rose in one
    frame) and the captured pitch composed on a run (played 1.26 times faster than recorded)."""
    anim = text2anim.animate(text, db=library_db)
    for m in anim.motions.values():
        assert all(against_limits(quality(m)).values()), quality(m)


def test_a_composed_capture_is_not_played_faster_than_recorded(library_db):
    """The captured pitch laid on a run keeps at least its own duration (jerk grows with the cube of a
    speed-up), and its throwing hand is no jerkier than in the pitch itself."""
    anim = text2anim.animate("ボールを投げると同時に走る。", db=library_db)
    (join,) = [j for j in anim.result.joins if j.blend == "composition"]
    assert join.metrics["stretch"] >= 1.0
    (pitch,) = [c.motion for c in builtin_clips() if c.name == "throw"]

    def hand_jerk(m):
        hand = body_map(m.skeleton).hands["right"]
        return np.linalg.norm(np.diff(m.positions[:, hand], n=3, axis=0), axis=-1).max() * m.fps ** 3

    assert hand_jerk(anim.motions["default"]) <= hand_jerk(pitch)


def test_a_fast_run_is_faster_but_no_jerkier_than_a_body_moves(library_db):
    """速く走る plays the run 1.5 times as fast: its joints' jerk (which grows with the speed cubed) reached 93 %
    of the built-in limit on the built-in body and passed it on a 24-joint rig. The cycle is lengthened by a
    frame at a time until its jerk is within 90 % of the limit: still clearly faster than a plain run."""
    from text2anim.core.metrics import BUILTIN_LIMITS, at_rate
    from text2anim.synthesis.join.timing import JERK_ROOM

    def hips_speed(m) -> float:
        xz = at_rate(m, 30.0).root_positions[:, [0, 2]]
        return float(np.linalg.norm(np.diff(xz, axis=0), axis=1).mean() * 30.0)

    fast = text2anim.animate("太郎は速く走る。", db=library_db).motions["太郎"]
    plain = text2anim.animate("太郎は走る。", db=library_db).motions["太郎"]
    assert quality(fast).jerk_p99 <= JERK_ROOM * BUILTIN_LIMITS["jerk_p99"]
    assert hips_speed(fast) > 1.3 * hips_speed(plain)


def test_the_report_says_how_the_text_was_read(example, library_db):
    """A typo repaired and a pronoun read as its person are in the report as on stderr; a text read as
    written adds no field."""
    anim = text2anim.animate("花子は歩るいて、止まった。彼女は座った。", db=library_db)
    assert anim.report["notes"] == ["read 歩るいて as 歩いて (a verb's okurigana)",
                                    "read 彼女 as 花子 (the last woman named)"]
    assert list(anim.motions) == ["花子"]
    assert "notes" not in example.report

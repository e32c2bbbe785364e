"""Posture continuity: clips whose postures meet, and bridges where none can.

On the real database seeded with the built-in library (``library_db``), through
:func:`scheduler.postures.choose`, :func:`~scheduler.postures.bridges` and
:func:`scheduler.arrangement.arrange` with the pipeline's own stages (the
analyser, the scheduler, the API's clip search, the synthesis engine). ``arrange``
is applied here as :func:`scheduler.schedule` applies it (:func:`plan_with_postures`,
without the fillers of the waits).
"""
from __future__ import annotations

import itertools

import numpy as np
import pytest

from text2anim import nlp
from text2anim.clip_search import DatabaseClips
from text2anim.core.metrics import skating_ratio
from text2anim.motiondb import ClipRecord, MotionDB, classify_posture
from text2anim.motiondb.library import build_all
from text2anim.pipeline import Planned
from text2anim.scheduler import plan
from text2anim.scheduler.arrangement import arrange
from text2anim.scheduler.picker import Picker
from text2anim.scheduler.postures import BRIDGE_VERBS, POSTURES, bridges, choose, matching, mismatches

#: The sentences the lead saw in contact sheets, and the clips they must play (bridges included).
SENTENCES = {
    "しゃがんで、立ち上がる。": ["crouch_down", "stand_from_crouch"],
    "転んで、起き上がる。": ["fall", "get_up"],
    "座って、歩く。": ["sit_down", "stand_up", "walk"],
    "座って、立ち上がる。": ["sit_down", "stand_up"],
    "ひざまずいて、立ち上がる。": ["kneel", "stand_from_kneel"],
    "ひざまずいて、歩く。": ["kneel", "stand_from_kneel", "walk"],
}


@pytest.fixture(scope="module")
def db(library_db):
    with MotionDB.open(library_db) as opened:
        yield opened


def names(clips):
    return [None if c is None else c.name for c in clips]


def plan_with_postures(text: str, db: MotionDB, fps: float = 30.0) -> tuple[Planned, object]:
    """The steps of :func:`scheduler.schedule` up to the fillers: plan, arrange, plan again."""
    analysis = nlp.analyze(text)
    source = DatabaseClips(db)
    picker = Picker(source)
    table = plan(analysis, picker, fps)
    arranged = arrange(analysis, table, picker.chosen, source)
    if arranged.changed:
        analysis = arranged.analysis
        picker = Picker(source)
        table = plan(analysis, arranged.finder(picker), fps)
    return Planned(analysis, table, dict(picker.chosen)), arranged


def sequence(planned: Planned, actor=None):
    """The actor's whole-body elements in playing order."""
    return [e for e in sorted(planned.table.elements, key=lambda e: (e.start, e.id))
            if e.actor == actor and e.method != "composition"]


# ------------------------------------------------------------------ choose
@pytest.mark.parametrize("verb, default", [
    ("しゃがむ", "crouch"), ("かがむ", "crouch"), ("しゃがみ込む", "crouch_down"),
    ("立ち上がる", "stand_up"), ("起き上がる", "get_up"), ("立つ", "stand_from_crouch"), ("座る", "sit_down"),
    ("ひざまずく", "kneel"), ("膝をつく", "kneel"),
])
def test_what_a_lone_verb_finds_first(db, verb, default):
    """The database's default clip of each posture verb (what a motion gets when nothing is around it)."""
    assert db.search(verb)[0].name == default


@pytest.mark.parametrize("verbs, expected", [
    (("しゃがむ", "立ち上がる"), ["crouch_down", "stand_from_crouch"]),
    (("転ぶ", "起き上がる"), ["fall", "get_up"]),
    (("転ぶ", "立ち上がる"), ["fall", "get_up"]),
    (("座る", "立ち上がる"), ["sit_down", "stand_up"]),
    (("座る", "立つ"), ["sit_down", "stand_up"]),
    (("しゃがむ", "立つ"), ["crouch_down", "stand_from_crouch"]),
    (("しゃがむ", "立つ", "座る", "立ち上がる"), ["crouch_down", "stand_from_crouch", "sit_down", "stand_up"]),
    (("ひざまずく", "立ち上がる"), ["kneel", "stand_from_kneel"]),
    # a standing gesture after kneeling or sitting is played there: the actor rises from it afterwards
    (("ひざまずく", "祈る", "立ち上がる"), ["kneel", "pray", "stand_from_kneel"]),
    (("座る", "本を読む", "立ち上がる"), ["sit_down", "read", "stand_up"]),
    # nothing to gain: every motion keeps its best clip (the lone しゃがむ goes down and comes back up)
    (("しゃがむ",), ["crouch"]),
    (("しゃがむ", "歩く"), ["crouch", "walk"]),
    (("しゃがむ", "ボールを拾う"), ["crouch", "pick_up"]),
    (("立ち上がる",), ["stand_up"]),
    (("起き上がる",), ["get_up"]),
    (("歩く", "走る", "止まる"), ["walk", "run", "stop"]),
    # no candidate can meet: the best clips stay, a bridge will be needed
    (("座る", "歩く"), ["sit_down", "walk"]),
])
def test_choose_makes_postures_meet_when_the_candidates_allow(db, verbs, expected):
    cands = [db.search(*v.split("を")[::-1]) if "を" in v else db.search(v) for v in verbs]
    picks = choose(cands)
    assert names(picks) == expected
    if verbs != ("座る", "歩く"):
        assert mismatches(picks) == []


def test_choose_keeps_the_shape_and_passes_through_motions_without_candidates(db):
    crouch, up = db.search("しゃがむ"), db.search("立ち上がる")
    assert names(choose({7: crouch, 3: [], 9: up}).values()) == ["crouch_down", None, "stand_from_crouch"]
    assert list(choose({7: crouch, 3: [], 9: up})) == [7, 3, 9]
    assert choose([]) == [] and choose({}) == {}
    # the posture before the first motion counts when given
    assert names(choose([up], initial="lying")) == ["get_up"]
    assert names(choose([up], initial="crouched")) == ["stand_from_crouch"]
    assert names(choose([up])) == ["stand_up"]
    with pytest.raises(ValueError, match="unknown posture 'sitting'"):
        choose([up], initial="sitting")


def _brute_force(cands):
    best = None
    for combo in itertools.product(*[list(enumerate(c)) for c in cands]):
        clips = [c for _, c in combo]
        key = (len(mismatches(clips)), tuple(k for k, _ in combo))
        if best is None or key < best[0]:
            best = (key, clips)
    return best[1]


def test_choose_is_the_optimum_of_an_exhaustive_search(db):
    """Every sequence of up to three of these verbs: the programme finds what trying all combinations finds."""
    verbs = ("しゃがむ", "立ち上がる", "座る", "転ぶ", "起き上がる", "歩く", "立つ", "ひざまずく", "祈る")
    cands = {v: db.search(v) for v in verbs}
    for n in (1, 2, 3):
        for seq in itertools.product(verbs, repeat=n):
            lists = [cands[v] for v in seq]
            assert names(choose(lists)) == names(_brute_force(lists)), seq


# ----------------------------------------------------------------- bridges
@pytest.mark.parametrize("before, after, expected", [
    ("seated", "standing", ["stand_up"]),
    ("crouched", "standing", ["stand_from_crouch"]),
    ("lying", "standing", ["get_up"]),
    ("standing", "seated", ["sit_down"]),
    ("standing", "crouched", ["crouch_down"]),
    ("seated", "crouched", ["stand_up", "crouch_down"]),
    ("lying", "seated", ["get_up", "sit_down"]),
    ("crouched", "seated", ["stand_from_crouch", "sit_down"]),
    ("standing", "standing", []),
    ("standing", "lying", ["lie_down"]),  # 横になる (issue 14: clips/everyday.json)
    ("kneeling", "standing", ["stand_from_kneel"]),
    ("standing", "kneeling", ["kneel"]),
    ("kneeling", "seated", ["stand_from_kneel", "sit_down"]),
])
def test_bridges_from_the_library(db, before, after, expected):
    chain = bridges(before, after, DatabaseClips(db))
    assert names(chain) == expected
    if chain:
        assert chain[0].start_posture == before and chain[-1].end_posture == after
        assert all(a.end_posture == b.start_posture for a, b in zip(chain, chain[1:]))
    assert names(bridges(before, after, DatabaseClips(db), max_clips=1)) == (expected if len(expected) <= 1 else [])


def test_bridges_refuse_unknown_postures(db):
    with pytest.raises(ValueError, match="unknown posture 'sitting'"):
        bridges("sitting", "standing", DatabaseClips(db))


def test_the_scheduler_knows_the_databases_postures_in_its_order():
    """The scheduler reads no motiondb module: its posture words are :data:`BRIDGE_VERBS`' keys."""
    from text2anim.motiondb.types import POSTURES as STORED

    assert POSTURES == tuple(BRIDGE_VERBS) == STORED


@pytest.fixture(scope="module")
def db_with_bob(tmp_path_factory):
    """The built-in library plus bob's clips: his own way to stand up from a chair, and a seated idle."""
    url = f"sqlite:///{tmp_path_factory.mktemp('bob') / 'motions.sqlite'}"
    with MotionDB.open(url) as db:
        up = db.record("stand_up")
        sit = db.load("sit_down")
        seated = sit.frames(sit.n_frames - 30)  # the last second of sit_down: sitting still
        db.add([ClipRecord("bob_stand_up", up.motion, ("立ち上がる",), character="bob", core=up.core),
                ClipRecord("seated_wait", seated, ("待つ",), character="bob")])
        assert db.info("seated_wait").start_posture == "seated"  # classified from the frames
    return url


def test_bridges_prefer_the_characters_own_clips(db_with_bob):
    with MotionDB.open(db_with_bob) as opened:
        db = DatabaseClips(opened)
        assert names(bridges("seated", "standing", db, character="default")) == ["stand_up"]
        assert names(bridges("seated", "standing", db, character="bob")) == ["bob_stand_up"]
        # bob has no way to crouch: the chain borrows the default character's clip after his own
        assert names(bridges("seated", "crouched", db, character="bob")) == ["bob_stand_up", "crouch_down"]


def test_matching_finds_a_clip_that_keeps_the_posture(db, db_with_bob):
    db = DatabaseClips(db)
    assert matching(db, "待つ", "standing").name == "wait"
    assert matching(db, "待つ", "seated").name == "wait_seated"  # the captured seated idle (issue 12)
    assert matching(db, "待つ", "kneeling").name == "wait_kneeling"
    assert matching(db, "待つ", "lying") is None  # none lying: the pose is held
    assert matching(db, "まだない動詞", "standing") is None
    with MotionDB.open(db_with_bob) as opened:
        bob = DatabaseClips(opened)
        assert matching(bob, "待つ", "seated").name == "seated_wait"
        assert matching(bob, "待つ", "standing").name == "wait"
    with pytest.raises(ValueError):
        matching(db, "待つ", "floor")


# ----------------------------------------------------------------- arrange
@pytest.mark.parametrize("text", sorted(SENTENCES))
def test_sentences_play_clips_whose_postures_meet(db, text):
    planned, arranged = plan_with_postures(text, db)
    seq = sequence(planned)
    assert [e.clip for e in seq] == SENTENCES[text]
    infos = [planned.clips[e.id] for e in seq]
    assert mismatches(infos) == []
    # every join off the feet: the next clip starts where the previous one ended (joint positions, root
    # x/z removed); standing joins are the synthesis engine's business (a walk starts mid-stride)
    for a, b in zip(seq, seq[1:]):
        if planned.clips[a.id].end_posture == "standing":
            continue
        end, start = (db.load(planned.clips[e.id]) for e in (a, b))
        pa = end.positions[-1] - end.root_positions[-1] * [1, 0, 1]
        pb = start.positions[0] - start.root_positions[0] * [1, 0, 1]
        assert np.abs(pa - pb).max() < 0.05, (a.clip, b.clip)


def test_without_the_hook_the_joins_were_broken(db):
    """What the lead saw: the first clip of each motion, as the pipeline picks it today."""
    for text in ("しゃがんで、立ち上がる。", "座って、歩く。"):
        analysis = nlp.analyze(text)
        picker = Picker(DatabaseClips(db))
        plan(analysis, picker, 30.0)
        assert mismatches([picker.chosen[m.id] for m in analysis.motions]) == [1]


def test_a_bridge_is_a_motion_of_its_own_between_its_neighbours(db):
    planned, arranged = plan_with_postures("座って、歩く。", db)
    (bridge,) = arranged.bridges
    sit, up, walk = sequence(planned)
    assert up.id == bridge and up.verb == "立ち上がる" and up.clip == "stand_up"
    assert up.prev == sit.id and walk.prev == up.id
    assert up.start == pytest.approx(sit.end) and walk.start == pytest.approx(up.end)
    assert walk.method == "transition"  # the link the text made (て-form) now leads from the bridge
    spec = next(m for m in planned.analysis.motions if m.id == bridge)
    walk_spec = next(m for m in planned.analysis.motions if m.id == walk.id)
    assert spec.span == (walk_spec.span[0],) * 2 and spec.actor is None
    assert planned.clips[bridge].name == "stand_up"


def test_a_delay_is_spent_in_the_posture_before_the_bridge(db):
    planned, arranged = plan_with_postures("太郎は座る。3秒後に歩く。", db)
    sit, up, walk = sequence(planned, "太郎")
    assert [sit.clip, up.clip, walk.clip] == ["sit_down", "stand_up", "walk"]
    assert up.start == pytest.approx(sit.end + 3.0)  # sits for 3 s, then stands up
    assert walk.start == pytest.approx(up.end)


def test_a_bridge_waits_for_the_other_actor_as_the_motion_did(db):
    """太郎 falls; 花子 waves; then 太郎 walks: he gets up when 花子 is done (where 歩く would have started)."""
    planned, arranged = plan_with_postures("太郎は転ぶ。花子が手を振ると、太郎は歩く。", db)
    fall, up, walk = sequence(planned, "太郎")
    (wave,) = sequence(planned, "花子")
    assert [fall.clip, up.clip, walk.clip] == ["fall", "get_up", "walk"]
    assert up.verb == "起き上がる" and up.start == pytest.approx(wave.end) and walk.start == pytest.approx(up.end)
    planned, _ = plan_with_postures("座る。歩く。", db)  # two sentences, no word linking them
    assert [e.clip for e in sequence(planned)] == ["sit_down", "stand_up", "walk"]


def test_several_changes_of_posture_in_a_row(db):
    planned, arranged = plan_with_postures("座る。立ち上がって、しゃがむ。そして立つ。", db)
    assert [e.clip for e in sequence(planned)] == ["sit_down", "stand_up", "crouch_down", "stand_from_crouch"]
    assert arranged.bridges == ()
    planned, arranged = plan_with_postures("座って、しゃがむ。", db)  # seated -> standing before crouching
    assert [e.clip for e in sequence(planned)] == ["sit_down", "stand_up", "crouch"]


def test_texts_without_a_posture_change_are_left_alone(db):
    for text in ("歩いて、走る。", "しゃがんで、ボールを拾う。", "座ったまま手を振る。", "ジャンプする前にしゃがむ。"):
        analysis = nlp.analyze(text)
        source = DatabaseClips(db)
        picker = Picker(source)
        table = plan(analysis, picker, 30.0)
        arranged = arrange(analysis, table, picker.chosen, source)
        assert not arranged.changed and arranged.bridges == () and arranged.analysis is analysis, text


def test_two_actors_are_arranged_separately(db):
    planned, _ = plan_with_postures("花子は座って、歩く。太郎はしゃがんで、立ち上がる。", db)
    assert [e.clip for e in sequence(planned, "花子")] == ["sit_down", "stand_up", "walk"]
    assert [e.clip for e in sequence(planned, "太郎")] == ["crouch_down", "stand_from_crouch"]


# --------------------------------------------------------------- animation
@pytest.mark.parametrize("text", ["しゃがんで、立ち上がる。", "転んで、起き上がる。", "座って、歩く。", "ひざまずいて、歩く。"])
def test_the_animation_changes_posture_where_the_clips_do(db, text):
    """Synthesised through the real engine: at each element's start the character is in its clip's posture."""
    from text2anim.synthesis.constraint.engine import synthesize
    from text2anim.tracks import build_tracks

    fps = 30.0
    planned, _ = plan_with_postures(text, db, fps)
    result = synthesize(build_tracks(planned, db, fps), fps)
    (motion,) = result.motions.values()
    assert skating_ratio(motion) <= clips_skating(e.clip for e in planned.table.elements) + 0.01  # GMD, 30 fps
    for e in sequence(planned):
        info = planned.clips[e.id]
        played = result.elements[e.id]
        # the time table's start: a looping clip's played start also counts the lead-in the engine
        # blends from (0.7 s of the captured walk), while the clip before is still finishing
        start = int(round(max(played.start, e.start) * fps))
        assert classify_posture(motion, start) == info.start_posture, (e.clip, played.start, e.start)
    assert classify_posture(motion, motion.n_frames - 1) == "standing"


def test_built_in_postures_are_stored(db):
    for b in build_all(30.0):
        info = db.info(b.record.name)
        assert (info.start_posture, info.end_posture) == (b.start_posture, b.end_posture)


def clips_skating(names) -> float:
    """The largest GMD skating ratio (30 fps) of the built-in clips ``names``: since issue 12 most are
    CMU capture, whose swing toes pass below 5 cm (the bar an output is held to is this + 0.01,
    issue 11's criterion against the sources)."""
    from text2anim.motiondb.library import builtin_clips

    recs = {r.name: r.motion for r in builtin_clips()}
    return max(skating_ratio(recs[n.removesuffix("~mirrored")]) for n in names)

"""The seed-003 engine on real captures (CMU): transition, connection, composition, timing, actors.

Clips (30 fps output): a gait cycle cut from ``16_15_walk`` and one from
``16_35_run`` (both cyclic), ``10_03_kick`` up to 2.8 s (it ends standing,
core: the kick, 0.7–1.5 s), and the right-hand wave of ``14_24_wave``
(11.55–12.95 s, declared ``right_arm``).
"""
from __future__ import annotations

import json
from functools import lru_cache

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from text2anim.core import read_bvh
from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import detect_contacts, foot_tracks
from text2anim.synthesis.constraint.engine import hips_frame, synthesize
from text2anim.core.metrics import SKATING_MARGIN, skating_ratio
from text2anim.scene import default_spots
from text2anim.synthesis.tracks import Clip, Element, Track
from text2anim.synthesis.join.cycles import find_cycle
from text2anim.synthesis.join.timing import prepare

from shared_data import cmu, requires_cmu

pytestmark = requires_cmu
FPS = 30


@lru_cache(maxsize=None)
def clips() -> dict[str, Clip]:
    walk = read_bvh(cmu("16_15_walk"), drop_first=True)
    a, b = find_cycle(walk)
    run = read_bvh(cmu("16_35_run"), drop_first=True)
    c, d = find_cycle(run)
    kick = read_bvh(cmu("10_03_kick"), drop_first=True).between(0, 2.8)
    wave = read_bvh(cmu("14_24_wave"), drop_first=True).between(11.55, 12.95)
    return {
        "walk": Clip("walk", walk[a:b], (0.0, (b - a) / walk.fps), cyclic=True),
        "run": Clip("run", run[c:d], (0.0, (d - c) / run.fps), cyclic=True),
        "kick": Clip("kick", kick, (0.7, 1.5)),
        "wave": Clip("wave", wave, (0.3, 1.1), body_part="right_arm"),
    }


def one(*elements, fps=FPS, **kw):
    res = synthesize([Track(None, tuple(elements))], fps=fps, **kw)
    return res, res.motions[None]


def landings(m, lo, hi):
    """Sides of the foot landings in frames [lo, hi), in time order."""
    c = detect_contacts(m)
    out = []
    for side in ("left", "right"):
        out += [(a, side) for a, _ in c.intervals(side) if lo <= a < hi and a > 0]
    return [s for _, s in sorted(out)]


def assert_clean_join(j, jerk_factor=1.5, skating=None):
    """``skating``: the GMD ratio the blend may reach where it is above its sources' (a measured ceiling)."""
    m = j.metrics
    bound = max(m["source_skating_ratio"] + SKATING_MARGIN, skating or 0.0)
    assert m["skating_ratio"] <= bound, j
    assert m["region"]["skating_ratio"] <= bound, j
    # a foot in contact in the blend moves no faster than feet in contact do in the source clips
    assert m["max_slide_cm_s"] <= max(m["source_max_slide_cm_s"], 15.0) + 1.0
    assert m["jerk_max"] <= jerk_factor * m["source_jerk_max"]


@pytest.mark.parametrize("fps", [30, 60])
def test_walk_to_run_transition(fps):
    C = clips()
    res, m = one(Element(1, C["walk"], 0.0, 3.0, "initial"), Element(2, C["run"], 2.6, 5.0, "transition", prev=1),
                 fps=fps)
    (j,) = res.joins
    assert (j.method, j.blend) == ("transition", "transition")
    assert_clean_join(j)
    w0, w1 = (round(x * fps) for x in (j.intervals[0].begin, j.intervals[0].end))
    assert skating_ratio(m[w0:w1]) == 0.0
    # the steps keep alternating through the join
    sides = landings(m, w0 - fps, w1 + fps)
    assert len(sides) >= 3 and all(a != b for a, b in zip(sides, sides[1:]))
    # it walks, then runs: the root's speed after the join is the run's
    speed = np.linalg.norm(np.diff(m.root_positions[:, [0, 2]], axis=0), axis=1) * fps
    assert speed[w1 + fps // 3:].mean() > 1.6 * speed[: w0 - fps // 3].mean()
    # cores are kept to within a centimetre: the join post-pass (synthesis.join.joinpass) stops at the run's core
    # start, but its legs are re-solved by IK up to there (measured 0.66-0.72 cm)
    assert res.elements[1].core_fidelity_cm < 1.0 and res.elements[2].core_fidelity_cm < 1.0


def test_locked_foot_stays_put_during_the_blend():
    C = clips()
    elements = (Element(1, C["walk"], 0.0, 3.0, "initial"), Element(2, C["run"], 2.6, 5.0, "transition", prev=1))
    res, m = one(*elements)
    _, m_free = one(*elements, lock_feet=False)
    lock = res.joins[0].metrics["foot_locks"][0]
    side = lock["side"]
    a, b = round(lock["begin"] * FPS), round(lock["end"] * FPS)

    def drift(motion):
        """Horizontal travel of the foot's lowest point while it is flat on the ground (within 1.5 cm of its
        height at a)."""
        tr = foot_tracks(motion)[side]
        rows = np.arange(a, b)
        low = motion.positions[rows, tr.joint[a:b]]
        down = tr.height[a:b] < tr.height[a] + 0.015
        return np.linalg.norm((low - low[0])[down][:, [0, 2]], axis=-1).max()

    # within 2 cm (was 1.5): the join post-pass retimes the blend and the lock's last frame, mapped onto
    # the retimed frames, can catch the heel lifting (measured 1.6 cm). The run's hips outrun the planted
    # foot: the lock ends there (footlock.reachable_locks) and the foot rolls off over the lock's last
    # retimed frames (2.4 cm up, moving 3 cm): flat means within 1.5 cm
    assert drift(m) < 0.02 < drift(m_free)


def test_run_to_kick_is_a_connection_at_the_footstep():
    C = clips()
    kick = C["kick"]
    res, m = one(Element(1, C["run"], 0.0, 2.0, "initial"),
                 Element(2, kick, 1.7, 1.7 + kick.motion.duration, "transition", prev=1))
    (j,) = res.joins
    assert j.method == "transition" and j.blend == "footstep"
    assert_clean_join(j)
    assert j.metrics["same_state"] and j.metrics["support"] in ("left", "right")
    assert abs(j.metrics["shift_s"]) < 0.35
    assert res.elements[2].core_fidelity_cm < 0.5
    # the join's support foot: the kick continues from where the run's foot is planted
    assert j.metrics["other_foot_gap_cm"] < 40


def test_connection_with_a_delay_holds_the_end_pose_then_starts():
    C = clips()
    kick, walk = C["kick"], C["walk"]
    end = kick.motion.duration
    res, m = one(Element(1, kick, 0.0, end, "initial"), Element(2, walk, end + 1.0, end + 4.0, "connection", prev=1))
    (j,) = res.joins
    assert j.method == "connection" and j.intervals[0].kind.startswith("pose")
    assert_clean_join(j)
    # during the delay the kick's end pose stands: feet and hips still, the chest breathing (issue 12: no
    # frozen pose) by at most a few cm/s
    a, b = round((end + 0.3) * FPS), round((end + 0.6) * FPS)
    bm = body_map(m.skeleton)
    legs = [0] + [j for side in ("left", "right") for j in bm.feet[side]]
    speed = np.linalg.norm(np.diff(m.positions[a:b], axis=0), axis=-1) * FPS
    assert speed[:, legs].max() < 0.01 and 0.005 < speed.max() < 0.05
    assert np.allclose(m.positions[a, legs], m.positions[b, legs], atol=2e-3)  # the post-pass filters the hold's edges
    # and after the join the character walks
    w1 = round(j.intervals[0].end * FPS)
    travel = np.linalg.norm(m.root_positions[w1 + 30, [0, 2]] - m.root_positions[w1, [0, 2]])
    assert travel > 0.6
    assert res.elements[1].core_fidelity_cm < 0.5 and res.elements[2].core_fidelity_cm < 0.5


def test_walk_and_wave_composition():
    C = clips()
    walk, wave = C["walk"], C["wave"]
    res, m = one(Element(1, walk, 0.0, 4.0, "initial"),
                 Element(2, wave, 0.5, 0.5 + wave.motion.duration, "composition", prev=1, body_part="right_arm"))
    _, base = one(Element(1, walk, 0.0, 4.0, "initial"))
    (j,) = res.joins
    assert j.method == "composition" and [i.part for i in j.intervals] == ["right_arm", "right_arm"]
    # the arm is laid on the looped walk, whose own feet skate on 2 of the 30 frames around it (GMD rule,
    # either foot; the walk cycle as a whole: 0.03): a ceiling, issue 11
    assert_clean_join(j, skating=0.07)
    t0, t1 = (round(x * FPS) for x in j.metrics["switch_s"])
    bm = body_map(m.skeleton)
    hand = bm.hands["right"]
    # the right hand follows the wave clip's hand around the hips in the core (fully switched frames)
    blend_in = round((j.intervals[0].end - j.intervals[0].begin) * FPS)
    blend_out = round((j.intervals[1].end - j.intervals[1].begin) * FPS)
    k = np.arange(t0 + blend_in, t1 - blend_out)
    src = round(j.metrics["clip_s"][0] * FPS) + (k - t0) * (
        (j.metrics["clip_s"][1] - j.metrics["clip_s"][0]) * FPS / (t1 - t0))
    donor = prepare(Element(2, wave, 0.5, 0.5 + wave.motion.duration, "composition"), FPS).motion
    core = (src >= 0.3 * FPS) & (src <= 1.1 * FPS)
    assert core.sum() >= 5
    k, src = k[core], np.round(src[core]).astype(int)
    got = hips_frame(m.positions[k][:, [hand]], m.positions[k, 0], m.pose.rotations[k, 0])
    want = hips_frame(donor.positions[src][:, [hand]], donor.positions[src, 0], donor.pose.rotations[src, 0])
    assert np.linalg.norm(got - want, axis=-1).max() < 0.08
    # ... while it is far from where the walk's hand is
    walk_hand = hips_frame(base.positions[k][:, [hand]], base.positions[k, 0], base.pose.rotations[k, 0])
    assert np.linalg.norm(walk_hand - want, axis=-1).min() > 0.3
    # the legs are the walk's, contacts and all
    legs = list(bm.joints("lower"))
    assert np.allclose(m.positions[:, legs], base.positions[:, legs], atol=1e-9)
    cm, cb = detect_contacts(m), detect_contacts(base)
    assert np.array_equal(cm.left, cb.left) and np.array_equal(cm.right, cb.right)
    # sway: the torso and head move off the walk inside the composition only, by a residual of a few degrees
    spine = list(bm.joints("torso"))
    dev = np.degrees((Rotation.from_quat(m.rotations[:, spine].reshape(-1, 4)).inv()
                      * Rotation.from_quat(base.rotations[:, spine].reshape(-1, 4))).magnitude()).reshape(len(m), -1)
    assert dev[t0:t1].max() > 0.5 and dev[t0:t1].max() <= 15.0
    assert dev[:t0].max() < 1e-6 and dev[t1:].max() < 1e-6
    assert j.metrics["sway_max_deg"] > 0.5
    # without sway transfer the torso is the walk's
    res_ns, m_ns = one(Element(1, walk, 0.0, 4.0, "initial"),
                       Element(2, wave, 0.5, 0.5 + wave.motion.duration, "composition", prev=1,
                               body_part="right_arm"), sway=False)
    assert np.allclose(m_ns.rotations[:, spine], base.rotations[:, spine])


def test_tamama_holds_the_base_end_pose_while_the_part_plays():
    C = clips()
    kick, wave = C["kick"], C["wave"]
    end = kick.motion.duration
    res, m = one(Element(1, kick, 0.0, end + 2.0, "initial", hold=True),
                 Element(2, wave, end, end + wave.motion.duration, "composition", prev=1, body_part="right_arm"))
    legs = list(body_map(m.skeleton).joints("lower"))
    a, b = round((end + 0.3) * FPS), round((end + 1.4) * FPS)
    assert np.abs(np.diff(m.positions[a:b][:, legs], axis=0)).max() < 1e-6  # the held pose stands
    hand = body_map(m.skeleton).hands["right"]
    assert np.abs(np.diff(m.positions[a:b, hand], axis=0)).max() * FPS > 0.5  # the hand waves


def test_speed_two_halves_the_duration():
    C = clips()
    kick = C["kick"]
    d = kick.motion.duration
    res, m = one(Element(1, kick, 0.0, d / 2, "initial", speed=2.0))
    assert m.n_frames == pytest.approx(d / 2 * FPS, abs=1)
    slow = prepare(Element(1, kick, 0.0, d, "initial"), FPS).motion
    fast = prepare(Element(1, kick, 0.0, d / 2, "initial", speed=2.0), FPS).motion
    assert fast.n_frames == pytest.approx(slow.n_frames / 2, abs=1)
    assert np.allclose(fast.positions[10], slow.positions[20], atol=0.02)  # the same pose, twice as early
    assert res.elements[1].core[1] == pytest.approx(1.5 / 2, abs=1 / FPS)


def test_looping_a_walk_travels_on_without_a_pop():
    C = clips()
    walk = C["walk"]
    res, m = one(Element(1, walk, 0.0, 5.0, "initial"))
    assert m.n_frames == 5 * FPS
    cyc = prepare(Element(1, walk, 0.0, walk.motion.duration, "initial"), FPS).motion
    per_second = np.linalg.norm(cyc.root_positions[-1, [0, 2]] - cyc.root_positions[0, [0, 2]]) / (
        (cyc.n_frames - 1) / FPS)
    travel = np.linalg.norm(m.root_positions[-1, [0, 2]] - m.root_positions[0, [0, 2]])
    assert travel == pytest.approx(5 * per_second, rel=0.1)
    steps = np.linalg.norm(np.diff(m.positions, axis=0), axis=-1).max(axis=1)
    n = cyc.n_frames
    seams = [k * n - 1 for k in range(1, 5) if k * n - 1 < len(steps)]
    assert max(steps[seams]) < 1.5 * np.percentile(steps, 95)
    assert skating_ratio(m) <= skating_ratio(walk.motion) + SKATING_MARGIN  # no more than the captured cycle


def test_repeated_kick_is_two_kicks_joined():
    C = clips()
    kick = C["kick"]
    d = kick.motion.duration
    res, m = one(Element(1, kick, 0.0, 2 * d, "initial", repeat=2))
    (j,) = res.joins
    assert (j.first, j.second, j.blend) == (1, 1, "repeat")
    assert_clean_join(j)
    assert res.elements[1].core_fidelity_cm < 0.5  # both repetitions' cores kept
    # the kicking foot rises high twice
    foot = body_map(m.skeleton).feet["right"][0]
    y = m.positions[:, foot, 1]
    high = y > y.min() + 0.3
    assert len(np.flatnonzero(np.diff(high.astype(int)) == 1)) == 2


def test_two_actors_start_on_their_spots_apart_and_output_is_deterministic():
    C = clips()
    spots = default_spots(["太郎", "花子"])  # the staging's default: side by side
    tracks = [Track("太郎", (Element(1, C["walk"], 0.0, 2.0, "initial"),), spots[0].origin, spots[0].heading),
              Track("花子", (Element(2, C["run"], 0.0, 2.0, "initial"),), spots[1].origin, spots[1].heading)]
    res = synthesize(tracks, FPS)
    a, b = res.motions["太郎"], res.motions["花子"]
    assert np.linalg.norm(a.root_positions[0, [0, 2]] - b.root_positions[0, [0, 2]]) >= 1.0
    again = synthesize(tracks, FPS)
    for k in res.motions:
        assert np.array_equal(res.motions[k].rotations, again.motions[k].rotations)
        assert np.array_equal(res.motions[k].root_positions, again.motions[k].root_positions)


def test_report_is_json():
    C = clips()
    res, _ = one(Element(1, C["walk"], 0.0, 3.0, "initial"), Element(2, C["run"], 2.6, 5.0, "transition", prev=1),
                 Element(3, C["wave"], 0.5, 1.9, "composition", prev=1, body_part="right_arm"))
    text = json.dumps(res.report())
    back = json.loads(text)
    assert [j["method"] for j in back["joins"]] == ["transition", "composition"]
    for j in back["joins"]:
        assert {"first", "second", "method", "blend", "intervals", "metrics"} <= set(j)
        assert {"skating_ratio", "jerk_max", "jerk_rms", "source_jerk_max", "core_fidelity_cm"} <= set(j["metrics"])

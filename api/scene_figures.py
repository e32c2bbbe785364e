"""Figures of a placed scene, measured on the output (the actors' final motions and the things as drawn),
never on the scene stage's own bookkeeping: what ``benchmarks/bench_scene.py`` prints and
``tests/scene/test_scene_corpus.py`` holds, for the checks of ``tests/corpus/scene_corpus.jsonl``.

=========== ============================================================== =========================
check       figure                                                         passes when
=========== ============================================================== =========================
approach    hips to hips (m) at the end of the actor's row; to a place:    0.3-1.6 m, facing within
            to its marker                                                  :data:`FACING_DEG`
faces       the actor's heading error towards the target (deg), mean over  < :data:`FACING_DEG`
            the middle half of the row (heading from hips and thighs)
sync        the two actors' reach instants apart (s: each one's hand       < :data:`SYNC_S`, the wrists
            furthest out in front of the hips, in the rows' overlap), and  < :data:`HANDS_M` apart
            how far apart their hands are then (but in a hug)
holds       the thing's centre to the holding hand's wrist (m, worst       < :data:`HOLD_M`
            frame of the row; the wrists' midpoint for a two-hand thing)
launch      the thing's first fast frame (a kick: its sharpest speed-up)   < :data:`LAUNCH_S`
            to the striking foot's or hand's closest frame to it (s)
catch       the thing to the catcher's wrists' midpoint when it stops      < :data:`CATCH_M`
            flying (m)
seat        the seat's centre to the hips over the floor (m) where they    < 0.2 m, hips 0-0.3 m
            sit, and the hips above the seat's top                          above the top
present     the person is one of the scene's actors                        yes
together    the two actors' rows start apart (s; 0 with ``"sync": false``:   < :data:`SYNC_S`, within
            one joins a walk the other carries on, 近づいて、一緒に歩く)    :data:`TOGETHER_M` at its
                                                                           middle and end, never
                                                                           within :data:`CLEAR_M`
leaves      the distance grows over the row (m)                            > 0.5 m
behind      the angle of the actor around the target from where it faces   > 120°
reaches     the hand to the door at the row's nearest frame (m)            < 0.15 m
apart       a thing lying still on the floor to the hips of someone who    > :data:`APART_M`
            does not handle it, over the floor (m, nearest frame)
at          the hips to the thing's box over the floor (m) at the end of   < :data:`AT_M`, facing it
            the row (机の前に座る: the body at its front; ``"facing":       within 45°
            false``: 木の下に座る, the back to it)
hand_in_    the first one's right wrist to the other's left (m, worst       < :data:`HANDS_M`
hand        frame of the middle half of the rows' overlap: 手をつなぐ)
rests       the thing's bottom to what it is put on (m: the floor, 床に      < :data:`REST_M`, over the
            下ろす, or a thing's top, テーブルの上に置く) at the row's end   thing's top
free        the thing to the nearer wrist over the row (m; a thing not      > :data:`FREE_M`
            drawn is free): 空を見上げる holds no sky
round       the turns the hips sweep round the thing over the row (laps:    >= 0.9 of ``laps``, never
            木の周りを三周歩く), and their nearest distance to its centre   within :data:`ROUND_M` of
                                                                           its side
clear       the nearest the actor's hips come to the target's over the    > :data:`CLEAR_M`
            row, over the floor (m): 受け取って、走り去った runs off, not
            through the giver
returns     the hips at the end of the row to where the actor started,    < :data:`RETURN_FRACTION`
            over the floor, as a fraction of the farthest they went by
            then (廊下を行ったり来たりした: back where they set off)
=========== ============================================================== =========================
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.spatial.transform import Rotation

from text2anim.core.bodyparts import body_map
from text2anim.core.conventions import path_and_heading
from text2anim.core.ground import wrap_angle

from .placed import played_rows

FACING_DEG = 20.0
SYNC_S = 0.1
HANDS_M = 0.2  # m between the wrists: two palms that touch hold them about 16 cm apart
HOLD_M = 0.10
LAUNCH_S = 0.1
CATCH_M = 0.15
APART_M = 0.5  # m: a ball within half a metre of someone's hips lies at their feet
AT_M = 0.6  # m: hips within this of a thing's box are at it (a chair's depth between them and a desk)
REST_M = 0.03  # m between a thing put down and what it rests on
FREE_M = 0.3  # m: a thing further than this from both wrists is not in the hand
ROUND_M = 0.2  # m between the hips and the side of a thing walked round
TOGETHER_M = 2.0  # m: two who walk or dance together stay this close (walking apart ends metres away)
CLEAR_M = 0.3  # m, hips to hips: closer, two bodies are inside each other
RETURN_FRACTION = 0.5  # of the farthest distance gone: nearer the start than this has come back


@dataclass(frozen=True)
class Figure:
    """One check's figure: its ``value`` (in ``unit``), whether it ``passed``, and a readable ``note``."""

    check: str
    value: float
    unit: str
    passed: bool
    note: str = ""


def figures(anim, checks: list[dict]) -> list[Figure]:
    """The figure of each check (the ``scene`` list of a corpus line) on the animation ``anim``; a check's
    verb is the row's, or the verb as written where a stand-in plays (``--fallback nearest``)."""
    asked = {f.id: f.written for f in anim.planned.fallbacks}
    rows = [replace(r, verb=asked.get(r.id, r.verb)) for r in played_rows(anim.table, anim.result)]
    props = {p.name: p for p in anim.props()}
    return [_one(anim, rows, props, c) for c in checks]


def _one(anim, rows, props, c: dict) -> Figure:
    kind = c["check"]
    try:
        return _MEASURES[kind](anim, rows, props, c)
    except _Missing as why:
        return Figure(kind, float("nan"), "", False, str(why))


class _Missing(Exception):
    """What a check needs is not in the animation (no such row, actor or thing)."""


def _row(rows, actor, verb):
    for r in rows:
        if r.actor == actor and r.verb == verb and r.method != "composition":
            return r
    for r in rows:
        if r.actor == actor and r.verb == verb:
            return r
    raise _Missing(f"no row of {actor} {verb}")


def _motion(anim, actor):
    if actor not in anim.motions:
        raise _Missing(f"{actor} is not in the scene")
    return anim.motions[actor]


def _played(anim, rows, c: dict):
    """The check's row (its actor's, of its verb), that actor's motion, and the row's first and last frames."""
    r = _row(rows, c["actor"], c["verb"])
    m = _motion(anim, c["actor"])
    return r, m, _frame(anim, r.start, m), _frame(anim, r.end, m)


def _thing(props, c: dict):
    """The check's thing as drawn (:class:`output.viewer.types.Prop`)."""
    if c["thing"] not in props:
        raise _Missing(f"{c['thing']} is not in the scene")
    return props[c["thing"]]


def _frame(anim, t: float, m) -> int:
    return int(np.clip(round(t * anim.fps), 0, m.n_frames - 1))


def _floor(p):
    return np.array([p[0], 0.0, p[2]])


def _facing_error(m, f: int, point) -> float:
    _, heading = path_and_heading(m)
    hips = m.root_positions[f]
    want = np.arctan2(point[0] - hips[0], point[2] - hips[2])
    return float(np.degrees(abs(wrap_angle(heading[f] - want))))


def _approach(anim, rows, props, c):
    r = _row(rows, c["actor"], c["verb"])
    m = _motion(anim, c["actor"])
    f = _frame(anim, r.end, m) if r.end * anim.fps < m.n_frames else m.n_frames - 1
    hips = _floor(m.root_positions[f])
    if c["target"] in anim.motions:
        other = _floor(anim.motions[c["target"]].root_positions[f])
    elif c["target"] in props:
        other = _floor(props[c["target"]].positions[f])
    else:
        raise _Missing(f"{c['target']} is not in the scene")
    d = float(np.linalg.norm(hips - other))
    err = _facing_error(m, f, other)
    return Figure("approach", d, "m", 0.3 <= d <= 1.6 and err < 30.0, f"facing {err:.0f}° off")


def _faces(anim, rows, props, c):
    r, m, f0, f1 = _played(anim, rows, c)
    other = _motion(anim, c["target"])
    q = max(1, (f1 - f0) // 4)
    frames = range(f0 + q, max(f0 + q + 1, f1 - q))
    sent = _launched(anim, props, r, m, f0, f1)
    if sent is not None:  # a throw or a kick: the body turns in the wind-up; the chest faces them as it leaves
        e = _chest_error(m, sent, other.root_positions[sent])
        return Figure("faces", e, "deg", e < FACING_DEG, "the chest, when the thing leaves")
    e = float(np.mean([_facing_error(m, f, other.root_positions[f]) for f in frames]))
    return Figure("faces", e, "deg", e < FACING_DEG)


def _chest_error(m, f: int, point) -> float:
    """The heading error at frame ``f`` of the chest (the line across the shoulders, its forward normal)."""
    bm, parents = body_map(m.skeleton), m.skeleton.parents
    shoulder = {s: parents[parents[bm.hands[s]]] for s in ("left", "right")}  # the upper arm's joint
    left = m.positions[f, shoulder["left"]] - m.positions[f, shoulder["right"]]
    heading = np.arctan2(-left[2], left[0])  # forward = left x up
    hips = m.root_positions[f]
    want = np.arctan2(point[0] - hips[0], point[2] - hips[2])
    return float(np.degrees(abs(wrap_angle(heading - want))))


def _launched(anim, props, r, m, f0: int, f1: int) -> int | None:
    """The frame a thing the row sends (a throw, a kick: :data:`SENDING`) leaves the actor: a kicked thing's
    first fast frame (it lay still), a thrown one's first frame over 0.25 m from both wrists."""
    if r.verb not in SENDING:
        return None
    left, right = _wrists(m)
    for p in props.values():
        if r.verb in ("投げる", "放る"):
            away = np.minimum(np.linalg.norm(p.positions[f0:f1] - left[f0:f1], axis=1),
                              np.linalg.norm(p.positions[f0:f1] - right[f0:f1], axis=1)) > 0.25
            near = np.nonzero(~away)[0]
            gone = np.nonzero(away & (np.arange(f1 - f0) > (near[0] if len(near) else 0)))[0]
        else:
            gone = np.nonzero(np.linalg.norm(np.gradient(p.positions, 1.0 / anim.fps, axis=0), axis=1)[f0:f1] > 1.0)[0]
        if len(gone):
            return f0 + int(gone[0])
    return None


#: Verbs that send a thing off: the actor faces its recipient when it leaves.
SENDING = frozenset("投げる 放る 蹴る キックする シュートする".split())
#: Verbs whose contact is made with both hands (a hug, a taking): their reach is the wrists' midpoint's.
BOTH_HANDS = frozenset("受け取る 貰う 抱き合う 抱き締める".split())


def _reach(m, f0: int, f1: int, both: bool = False) -> int:
    """The frame in ``[f0, f1)`` where the right wrist (``both``: the wrists' midpoint) is furthest in front of
    the hips."""
    _, heading = path_and_heading(m)
    left, right = _wrists(m)
    wrist = 0.5 * (left + right) if both else right
    rel = wrist[f0:f1] - m.root_positions[f0:f1]
    ahead = rel[:, 0] * np.sin(heading[f0:f1]) + rel[:, 2] * np.cos(heading[f0:f1])
    return f0 + int(np.argmax(ahead))


def _sync(anim, rows, props, c):
    a, b = c["actors"]
    ra = _row(rows, a, c["verb"])
    counterpart = {"渡す": "受け取る", "受け取る": "渡す"}.get(c["verb"], c["verb"])
    rb = _row(rows, b, counterpart)
    ma, mb = _motion(anim, a), _motion(anim, b)
    lo, hi = max(ra.start, rb.start), min(ra.end, rb.end)
    if hi <= lo:
        return Figure("sync", abs(ra.start - rb.start), "s", False, "the two rows do not overlap")
    f0, f1 = _frame(anim, lo, ma), _frame(anim, hi, ma) + 1
    fa, fb = _reach(ma, f0, f1, ra.verb in BOTH_HANDS), _reach(mb, f0, f1, rb.verb in BOTH_HANDS)
    ta, tb = fa / anim.fps, fb / anim.fps
    if c["verb"] in ("抱き合う", "抱き締める"):  # arms around each other: the hands do not meet
        return Figure("sync", abs(ta - tb), "s", abs(ta - tb) < SYNC_S, f"{a} at {ta:.2f} s, {b} at {tb:.2f} s")
    f = (fa + fb) // 2
    apart = float(np.linalg.norm(_hand_point(ma, f, ra.verb in BOTH_HANDS) - _hand_point(mb, f, rb.verb in BOTH_HANDS)))
    return Figure("sync", abs(ta - tb), "s", abs(ta - tb) < SYNC_S and apart < HANDS_M,
                  f"{a} at {ta:.2f} s, {b} at {tb:.2f} s, hands {apart:.2f} m apart")


def _hand_in_hand(anim, rows, props, c):
    a, b = c["actors"]
    ra, rb = _row(rows, a, c["verb"]), _row(rows, b, c["verb"])
    ma, mb = _motion(anim, a), _motion(anim, b)
    lo, hi = max(ra.start, rb.start), min(ra.end, rb.end)
    if hi <= lo:
        return Figure("hand_in_hand", float("inf"), "m", False, "the two rows do not overlap")
    q = 0.25 * (hi - lo)
    f0, f1 = _frame(anim, lo + q, ma), _frame(anim, hi - q, ma) + 1
    worst = float(np.linalg.norm(_wrists(ma)[1][f0:f1] - _wrists(mb)[0][f0:f1], axis=1).max())
    return Figure("hand_in_hand", worst, "m", worst < HANDS_M)


def _hand_point(m, f: int, both: bool):
    """The right wrist (``both``: the wrists' midpoint) at frame ``f``."""
    left, right = _wrists(m)
    return 0.5 * (left[f] + right[f]) if both else right[f]


def _wrists(m):
    bm = body_map(m.skeleton)
    return m.positions[:, bm.hands["left"]], m.positions[:, bm.hands["right"]]


def _holds(anim, rows, props, c):
    r, m, f0, f1 = _played(anim, rows, c)
    p = _thing(props, c)
    left, right = _wrists(m)
    a, b = _HELD_PART.get(r.verb, (1 / 3, 2 / 3))  # taken at the start of a pick, given away in a hand-over, ...
    lo = f0 + int(a * (f1 - f0))
    hi = max(lo + 1, f0 + int(b * (f1 - f0)))
    pos = p.positions[lo:hi]
    d = np.minimum.reduce([np.linalg.norm(pos - w[lo:hi], axis=1) for w in (left, right, 0.5 * (left + right))])
    return Figure("holds", float(d.max()), "m", float(d.max()) < HOLD_M)


#: The part of a row (fractions of it) in which its actor holds the thing: after a pick, before a put or a
#: hand-over, after a taking; the middle third of any other.
_HELD_PART = {**dict.fromkeys(("拾う", "持ち上げる", "拾い上げる", "取る", "持つ"), (0.7, 1.0)),
              **dict.fromkeys(("置く", "下ろす", "降ろす"), (0.0, 0.3)),
              **dict.fromkeys(("渡す", "手渡す", "差し出す"), (0.1, 0.45)),
              **dict.fromkeys(("受け取る", "貰う"), (0.7, 1.0))}


def _launch(anim, rows, props, c):
    r, m, f0, f1 = _played(anim, rows, c)
    p = _thing(props, c)
    v = np.linalg.norm(np.gradient(p.positions, 1.0 / anim.fps, axis=0), axis=1)
    bm = body_map(m.skeleton)
    kick = c["verb"] in ("蹴る", "キックする", "シュートする")
    joints = [bm.feet["left"][1], bm.feet["right"][1]] if kick else [bm.hands["right"], bm.hands["left"]]
    ends = m.positions[:, joints]
    near = np.linalg.norm(ends[f0:f1] - p.positions[f0:f1, None], axis=2).min(axis=1)
    if kick:  # the ball's sharpest speed-up (a dribbled ball rolls to the foot before it)
        contact = f0 + int(np.argmin(near))
        moving = np.nonzero(v[f0:f1] > 1.0)[0]
        if len(moving):
            moving = np.array([int(np.argmax(np.diff(v[f0:f1]))) + 1])
    else:  # a throw: the thing leaves the hand (its distance to the hand starts growing fast)
        away = np.nonzero(near > 0.25)[0]
        moving = away
        contact = f0 + int(away[0]) - 1 if len(away) else f1
    if not len(moving):
        return Figure("launch", float("nan"), "s", False, "the thing never moves")
    dt = abs((f0 + int(moving[0])) - contact) / anim.fps
    return Figure("launch", dt, "s", dt <= LAUNCH_S)


def _catch(anim, rows, props, c):
    _, m, f0, f1 = _played(anim, rows, c)
    p = _thing(props, c)
    left, right = _wrists(m)
    mid = 0.5 * (left + right)
    d = np.linalg.norm(p.positions[f0:f1] - mid[f0:f1], axis=1)
    best = float(d.min())
    return Figure("catch", best, "m", best < CATCH_M)


def _seat(anim, rows, props, c):
    r = _row(rows, c["actor"], c["verb"])
    m = _motion(anim, c["actor"])
    p = _thing(props, c)
    f = _frame(anim, r.start, m) if c["verb"] in ("立ち上がる", "立つ") else min(_frame(anim, r.end, m), m.n_frames - 1)
    hips = m.root_positions[f]
    top = p.positions[f, 1] + (0.0 if p.shape == "chair" else 0.5 * p.size[1])  # a chair's seat: half its height
    d = float(np.hypot(*(hips - p.positions[f])[[0, 2]]))
    above = float(hips[1] - top)
    return Figure("seat", d, "m", d < 0.2 and 0.0 <= above <= 0.3, f"hips {above:.2f} m above the seat")


def _present(anim, rows, props, c):
    ok = c["actor"] in anim.motions
    return Figure("present", float(ok), "", ok)


def _together(anim, rows, props, c):
    a, b = c["actors"]
    ra, rb = _row(rows, a, c["verb"]), _row(rows, b, c["verb"])
    ma, mb = _motion(anim, a), _motion(anim, b)
    f0, f1 = _frame(anim, ra.start, ma), _frame(anim, ra.end, ma)
    gaps = np.hypot(*(ma.root_positions[f0:f1 + 1] - mb.root_positions[f0:f1 + 1])[:, [0, 2]].T)
    d = float(gaps[len(gaps) // 2])
    dt = abs(ra.start - rb.start) if c.get("sync", True) else 0.0  # false: one joins a walk under way
    ok = dt < SYNC_S and d <= TOGETHER_M and gaps[-1] <= TOGETHER_M and gaps.min() >= CLEAR_M
    return Figure("together", dt, "s", bool(ok), f"{d:.2f} m apart, {gaps.min():.2f}-{gaps.max():.2f} m over it")


def _leaves(anim, rows, props, c):
    _, m, f0, f1 = _played(anim, rows, c)
    o = _motion(anim, c["target"])
    d = [float(np.hypot(*(m.root_positions[f] - o.root_positions[f])[[0, 2]])) for f in (f0, f1)]
    return Figure("leaves", d[1] - d[0], "m", d[1] - d[0] > 0.5)


def _behind(anim, rows, props, c):
    r = _row(rows, c["actor"], c["verb"])
    m, o = _motion(anim, c["actor"]), _motion(anim, c["target"])
    f = min(_frame(anim, r.end, m), m.n_frames - 1)
    _, heading = path_and_heading(o)
    rel = m.root_positions[f] - o.root_positions[f]
    angle = float(np.degrees(abs(wrap_angle(np.arctan2(rel[0], rel[2]) - heading[f]))))
    return Figure("behind", angle, "deg", angle > 120.0)


def _reaches(anim, rows, props, c):
    _, m, f0, f1 = _played(anim, rows, c)
    p = _thing(props, c)
    _, right = _wrists(m)
    d = float(np.linalg.norm(_outside(p, right[f0:f1], slice(f0, f1)), axis=1).min())
    return Figure("reaches", d, "m", d < 0.15)


def _outside(p, points: np.ndarray, frames) -> np.ndarray:
    """``(..., 3)`` m: how far ``points`` lie outside thing ``p``'s box along each of its own axes, on ``frames``
    (an index or a slice of its frames, one point each)."""
    local = Rotation.from_quat(p.rotations[frames]).inv().apply(points - p.positions[frames])
    return np.maximum(np.abs(local) - 0.5 * np.array(p.size), 0.0)


def _at(anim, rows, props, c):
    r = _row(rows, c["actor"], c["verb"])
    m = _motion(anim, c["actor"])
    p = _thing(props, c)
    f = min(_frame(anim, r.end, m), m.n_frames - 1)
    d = float(np.hypot(*_outside(p, m.root_positions[f], f)[[0, 2]]))  # over the floor
    err = _facing_error(m, f, p.positions[f])
    facing = err < 45.0 or c.get("facing", True) is False  # 木の下に座る: at its foot, the back to it
    return Figure("at", d, "m", d < AT_M and facing, f"facing {err:.0f}° off")


def _apart(anim, rows, props, c):
    p = _thing(props, c)
    m = _motion(anim, c["actor"])
    n = min(len(p.positions), m.n_frames)
    still = np.linalg.norm(np.gradient(p.positions[:n], 1.0 / anim.fps, axis=0), axis=1) < 0.05
    still &= p.positions[:n, 1] < max(p.size)  # lying on the floor
    if not still.any():
        return Figure("apart", float("nan"), "m", False, "the thing never lies still on the floor")
    d = float(np.hypot(*(p.positions[:n] - m.root_positions[:n])[still][:, [0, 2]].T).min())
    return Figure("apart", d, "m", d > APART_M)


def _rests(anim, rows, props, c):
    r = _row(rows, c["actor"], c["verb"])
    m = _motion(anim, c["actor"])
    p = _thing(props, c)
    f = min(_frame(anim, r.end, m), m.n_frames - 1)
    bottom = p.positions[f, 1] - 0.5 * p.size[1]
    if c["on"] == "floor":
        return Figure("rests", abs(bottom), "m", abs(bottom) < REST_M, "on the floor")
    under = _thing(props, {"thing": c["on"]})
    top = under.positions[f, 1] + 0.5 * under.size[1]
    off = float(np.hypot(*_outside(under, p.positions[f], f)[[0, 2]]))
    return Figure("rests", abs(bottom - top), "m", abs(bottom - top) < REST_M and off < 0.01,
                  f"on {c['on']}, {off:.2f} m off its top")


def _free(anim, rows, props, c):
    _, m, f0, f1 = _played(anim, rows, c)
    if c["thing"] not in props:
        return Figure("free", float("inf"), "m", True, "not drawn")
    p = props[c["thing"]]
    d = min(float(np.linalg.norm(p.positions[f0:f1] - w[f0:f1], axis=1).min()) for w in _wrists(m))
    return Figure("free", d, "m", d > FREE_M)


def _round(anim, rows, props, c):
    _, m, f0, f1 = _played(anim, rows, c)
    p = _thing(props, c)
    rel = m.root_positions[f0:f1] - p.positions[f0:f1]
    swept = float(np.abs(np.sum(wrap_angle(np.diff(np.arctan2(rel[:, 0], rel[:, 2]))))) / (2.0 * np.pi))
    near = float(np.hypot(rel[:, 0], rel[:, 2]).min())
    clear = near - 0.5 * max(p.size[0], p.size[2]) >= ROUND_M
    return Figure("round", swept, "laps", swept >= 0.9 * c["laps"] and clear, f"nearest {near:.2f} m")


def _clear(anim, rows, props, c):
    _, m, f0, f1 = _played(anim, rows, c)
    o = _motion(anim, c["target"])
    n = min(f1 + 1, o.n_frames)
    d = float(np.hypot(*(m.root_positions[f0:n] - o.root_positions[f0:n])[:, [0, 2]].T).min())
    return Figure("clear", d, "m", d > CLEAR_M)


def _returns(anim, rows, props, c):
    _, m, _, f1 = _played(anim, rows, c)
    away = np.hypot(*(m.root_positions[:f1 + 1] - m.root_positions[0])[:, [0, 2]].T)
    ratio = float(away[-1] / max(away.max(), 1e-9))
    return Figure("returns", ratio, "", ratio < RETURN_FRACTION, f"farthest {away.max():.2f} m")


_MEASURES = {"approach": _approach, "faces": _faces, "sync": _sync, "holds": _holds, "launch": _launch,
             "catch": _catch, "seat": _seat, "present": _present, "together": _together, "leaves": _leaves,
             "behind": _behind, "reaches": _reaches,
             "apart": _apart, "at": _at, "hand_in_hand": _hand_in_hand, "rests": _rests, "free": _free,
             "round": _round, "returns": _returns, "clear": _clear}
CHECKS = tuple(_MEASURES)

"""The things of a text over time: where each one is at every frame, from what the actors do to it.

A thing is named by the rows (a row's ``object``, or its target when that is a thing: a seat, a table, a
place). Its story is read from those rows in time order, each at an instant of the actor's own motion
(:mod:`scene.bodies`), never at a fixed time:

==================== ====================================================================================
verb (lemma)         what happens to the thing
==================== ====================================================================================
kick (:data:`KICK`)  it rests on the floor where the kicking foot strikes (the foot's fastest frame) and
                     leaves it then, faster than the foot, on a ballistic path; it lands, bounces, rolls;
                     one already on the floor rolls to the foot before the strike
dribble              it rolls on the floor ahead of the feet (:data:`DRIBBLE_AHEAD`) while the row plays
throw                it is in the throwing hand until the release (the hand's fastest frame); it flies to
                     the catcher's hands at their catch (both hands furthest out) when one catches it,
                     else on with the hand's speed, lands and rolls; thrown to someone who does not catch
                     it, it strikes them and drops at their feet
pick (拾う, 持ち上げる) it lies on the floor under the hand at its lowest frame, then is held; so does a thing
                     taken (取る, 持つ) that is nowhere yet by a hand that goes down for it; 机の上のペンを取る:
                     on the desk under the hand
put (置く, 下ろす)     it is held until the hand's lowest frame, then rests there (on the table it is put on;
                     on the floor: 床に下ろす; beside what it is put by: 窓のそばに置く, which stands beyond it)
give (渡す)           it is in the giver's hand until the hand is furthest out, then in the receiver's
open (開ける, 閉める)  a door in front of the hand at its furthest reach swings open (or shut) on its hinge;
                     knocked on (ノックする), it stays shut; pushed or pulled (押す, 引く), it swings open.
                     It stands where it is first handled; later rows swing it from there
push (押す)           it slides on the floor ahead of the hips while the row plays, and on while the pusher
                     walks or carries (台車を押して、倉庫まで運んだ)
look (見る, 待つ)     it stands :data:`SIGHT_M` ahead of the actor, not in the hand (バスを待つ, 花を見る); the sky
                     and what is above (:data:`shapes.UNDRAWN`: 空を見上げる) is said, not drawn
drink (水を飲む)       nothing new: the drink is in the cup the drinker holds, if any
any other            it is held (one hand or both, :mod:`scene.shapes`) while the row plays
seat (座る on it)     it stands under the hips where they sit, from the start; a sitter with no seat named
                     (座った, 花子の横に座った) sits on a chair (said): a sitting clip's hips are at its height
beside (机の前に座る)  it stands where the body ends beside it, from the start: ahead of the body (前, 後ろ,
                     近く, and a goal with no side: ドアまで歩く), or to its side (隣, 横, 左, 右); one sat in
                     front of is sat at on a chair
around (木の周りを歩く) it stands in the middle of the loops the walk was steered into (:mod:`scene.circling`)
place (駅まで走る)     a marker on the floor where the walk ends
route (公園を歩く)     a marker on the floor halfway along the walk (a を-place of a verb that travels,
                     with no shape of its own: gone through, not carried)
==================== ====================================================================================

Held things follow the hand: its grip point (:func:`scene.bodies.hand`) and turn; a thing between both
hands keeps level, turned with the hips. Gravity :data:`G`; bounces lose :data:`RESTITUTION` of their
vertical speed and roll to a stop with :data:`ROLL_DECELERATION`.
"""
from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from scipy.spatial.transform import Rotation

from text2anim.core.contact_instant import contact_instant
from text2anim.core.fk import matrix_to_quat
from text2anim.core.motion import Motion
from text2anim.nlp.lexicon import DRINKS, GROUND_NOUNS, LOCOMOTION_VERBS, MOVING_VERBS
from text2anim.scheduler.types import Element

from . import bodies, circling
from .shapes import PLACE, UNDRAWN, Shape, shape_of
from .types import Kick, Thing

G = 9.81  # m/s²
RESTITUTION = 0.45
ROLL_DECELERATION = 2.0  # m/s²: a ball on grass
#: A kicked ball leaves faster than the foot that strikes it (a ball's mass is small against the leg's).
KICK_GAIN = 1.3
KICK = frozenset("蹴る キックする シュートする 蹴り上げる 蹴飛ばす 蹴り返す".split())
THROW = frozenset("投げる 放る 放り投げる 投げ渡す パスする 投げ返す".split())
CATCH = frozenset("取る 捕る キャッチする 受け止める 捕まえる".split())
PICK = frozenset("拾う 拾い上げる 持ち上げる 抱え上げる".split())
#: Verbs that take a thing into the hand: one that lies nowhere yet is picked up (机の上のペンを取る).
TAKE = frozenset("取る 手に取る 持つ 掴む つかむ 取り上げる 取り出す".split())
#: Verbs that push or pull: a door pushed or pulled swings open; any other thing pushed slides on the floor.
PUSH_PULL = frozenset("押す 引く 引っ張る".split())
PUSH = frozenset("押す".split())
#: m at the built-in body's size: between the hips and the near side of a thing pushed along the floor.
PUSH_GAP = 0.45
PUT = frozenset("置く 下ろす 降ろす 落とす 積む 乗せる 載せる".split())
GIVE = frozenset("渡す 手渡す 差し出す".split())
RECEIVE = frozenset("受け取る 貰う".split())
OPEN = frozenset("開ける 開く".split())
CLOSE = frozenset("閉める 閉じる 締める".split())
KNOCK = frozenset("ノックする".split())
SIT = frozenset("座る 腰掛ける 着席する".split())
#: What one sits on when the text names no seat (a sitting clip's hips are at a chair's height).
SEAT_STAND_IN = "椅子"
DRIBBLE = frozenset("ドリブルする".split())
#: Verbs done towards a thing without touching it: its object stands ahead of the actor, not in the hand
#: (花を見る, バスを待つ).
SIGHT = frozenset("""見る 眺める 見つめる 見回す 見上げる 見下ろす 覗く 覗き込む 探す 見つける 見失う 待つ 呼ぶ
    指さす 指差す 見送る 睨む""".split())
#: m at a person's size: how far ahead a thing looked at or waited for stands.
SIGHT_M = 1.5
#: m at the built-in body's size: a dribbled ball's distance ahead of the hips
DRIBBLE_AHEAD = 0.5
#: m at the built-in body's size: the room between the hips and the near side of a thing beside the body
BESIDE_GAP = 0.3
#: A door's swing, degrees.
DOOR_SWING = 80.0


class _Path:
    """One thing's frames while its story is read: each event writes from its frame to the end."""

    def __init__(self, name: str, shape: Shape, known: bool, n: int, scale: float):
        self.name, self.shape, self.known, self.scale = name, shape, known, scale
        w, h, d = shape.size
        self.size: tuple[float, float, float] = (w * scale, h * scale, d * scale)
        self.pos = np.full((n, 3), np.nan)
        self.rot = np.tile([0.0, 0.0, 0.0, 1.0], (n, 1))
        self.events: list[tuple[float, str]] = []
        self.holder: tuple[str | None, str] | None = None  # (actor, "right" / "both") while held
        self.at_feet: str | None = None  # who dribbles it (ドリブルして、シュートする: the kick's ball)
        self.sitters: list[tuple[np.ndarray, float]] = []  # (hips, heading) of each who sits on it
        self.sat_by: str | None = None  # the first who sits on it
        self.pushed_by: str | None = None  # who pushes it along the floor (台車を押して、運んだ)
        self.hinge: tuple[np.ndarray, float, float] | None = None  # a door's hinge, heading and angle so far

    @property
    def half(self) -> float:
        return 0.5 * self.size[1]

    def rest(self, f: int, point: np.ndarray, yaw: float = 0.0) -> None:
        self.pos[f:] = point
        self.rot[f:] = Rotation.from_euler("y", yaw).as_quat()
        self.holder = None

    def placed(self) -> bool:
        return not np.isnan(self.pos[-1, 0])


def things(rows: Sequence[Element], motions: dict[str | None, Motion], scale: dict[str | None, float],
           fps: float) -> tuple[tuple[Thing, ...], list[str]]:
    """The things of ``rows`` (played times) around the placed ``motions``; and what could not be placed or
    is drawn as a stand-in, one sentence each."""
    n = max(m.n_frames for m in motions.values())
    paths: dict[str, _Path] = {}
    said: list[str] = []
    for r in sorted(rows, key=lambda r: (r.start, r.verb in RECEIVE, r.id)):  # a hand-over before its taking
        if r.actor not in motions:
            continue
        named = _named(r, motions)
        if r.verb in SIT and not any(how == "seat" for _, how in named):  # 座った, 花子の横に座った: not on air
            seat = _seat_for(paths, r.actor)
            named.append((seat, "seat"))
            said.append(f"{seat}: no seat named for {_who(r.actor)} {r.verb}; a chair stands under the hips")
        if not any(how == "handled" for _, how in named) and r.verb in THROW | PUT | GIVE | KICK:
            held = next((q for q in paths.values() if q.holder is not None and q.holder[0] == r.actor), None)
            if held is None and r.verb in KICK:  # ドリブルして、シュートする: the ball at the feet
                held = next((q for q in paths.values() if q.at_feet == r.actor), None)
            named += [(held.name, "handled")] if held is not None else []  # 拾って、投げる: what the hand holds
        if not any(how == "handled" for _, how in named) and r.verb in LOCOMOTION_VERBS | MOVING_VERBS:
            pushed = next((q for q in paths.values() if q.pushed_by == r.actor), None)
            named += [(pushed.name, "handled")] if pushed is not None else []  # 台車を押して歩く: it comes along
        for name, how in named:
            if how == "sight" and name in UNDRAWN:  # 空を見上げる: the sky is no box ahead on the floor
                if name not in paths:
                    said.append(f"{name}: looked at ({r.verb}), not drawn")
                continue
            cup = _cup_held(paths, r.actor) if how == "handled" and name in DRINKS else None
            if cup is not None:  # コップを手に取って、水を飲む: the water is in the cup
                cup.events.append((r.start, f"{_who(r.actor)} drinks {name} from it"))
                continue
            if name not in paths:
                shape, known = (PLACE, False) if how in ("place", "route") else shape_of(name.split(" ")[0])
                paths[name] = _Path(name, shape, known, n, scale.get(r.actor, 1.0))
            _event(paths[name], how, r, rows, motions, fps)
    out = []
    for p in paths.values():
        if not p.placed():
            said.append(f"{p.name}: the text names it, but no motion says where it is; left out of the scene")
            continue
        first = int(np.argmax(~np.isnan(p.pos[:, 0])))
        p.pos[:first] = p.pos[first]
        p.rot[:first] = p.rot[first]
        if not p.known:
            said.append(f"{p.name}: " + ("a place, shown as a marker on the floor" if p.shape is PLACE
                                         else "no shape of its own, shown as a box"))
        out.append(Thing(p.name, p.shape.shape, p.size, p.shape.color, p.pos, p.rot, tuple(p.events), p.known))
    return tuple(out), said


def _seat_for(paths: dict[str, _Path], actor: str | None) -> str:
    """The stand-in chair of ``actor``: 椅子, or 椅子 2, 椅子 3, ... when others already sit on one."""
    k = 1
    while True:
        name = SEAT_STAND_IN if k == 1 else f"{SEAT_STAND_IN} {k}"
        p = paths.get(name)
        if p is None or p.sat_by in (None, actor):
            return name
        k += 1


def _cup_held(paths: dict[str, _Path], actor: str | None) -> _Path | None:
    return next((q for q in paths.values() if q.holder is not None and q.holder[0] == actor
                 and q.shape.shape == "cup"), None)


def _named(r: Element, motions) -> list[tuple[str, str]]:
    """The things row ``r`` names and how: ``handled`` (its object), ``sight`` (the object of a look or a
    wait: ahead), ``seat``, ``table``, ``place``, ``beside``, ``by`` (what a thing is put beside), ``around``,
    ``route``; the ground (床に下ろす) is no thing."""
    out = []
    side = r.target_side
    if r.target and r.target not in motions and r.target not in GROUND_NOUNS:
        if r.target_role == "support" or (r.target_role == "source" and shape_of(r.target)[0].shape in
                                          ("chair", "bench")):
            out.append((r.target, "seat"))
        elif r.target_role == "destination":
            out.append((r.target, "table" if side in (None, "on") else "by"))
        elif r.target_role == "source" and side == "on":  # 机の上のペンを取る: the desk under the hand
            out.append((r.target, "table"))
        elif r.target_role in ("goal", "at", "source") and not shape_of(r.target)[1]:
            out.append((r.target, "place"))
        elif r.target_role == "goal" and side == "around":
            out.append((r.target, "around"))
        elif r.target_role == "goal" and side != "on":  # ドアまで歩く: it stands ahead where the walk ends
            out.append((r.target, "beside"))
            if r.verb in SIT and side is not None:
                out.append((SEAT_STAND_IN, "seat"))  # 机の前に座る: on a chair at it
        elif r.target_role in ("goal", "at"):
            out.append((r.target, "table"))
    if r.object and r.object not in motions and r.verb in LOCOMOTION_VERBS and not shape_of(r.object)[1]:
        out.append((r.object, "route"))  # 公園を歩く: the park is walked through, not carried
    elif r.object and r.object not in motions and r.verb in SIGHT:
        out.append((r.object, "sight"))  # バスを待つ: ahead, not in the hand
    elif r.object and r.object not in motions:  # after the table it may be put on
        out.append((r.object, "handled"))
    return out


def _who(actor: str | None) -> str:
    return actor if actor is not None else "the default character"


def _frames(r: Element, fps: float, n: int) -> tuple[int, int]:
    f0 = int(np.clip(round(r.start * fps), 0, n - 1))
    return f0, int(np.clip(round(r.end * fps), f0 + 1, n))


def _event(p: _Path, how: str, r: Element, rows: Sequence[Element], motions, fps: float) -> None:
    m = motions[r.actor]
    f0, f1 = _frames(r, fps, m.n_frames)
    t = f0 / fps
    if how == "seat":
        p.sat_by = p.sat_by or r.actor
        _seat(p, m, f0 if r.target_role == "source" else f1 - 1)
        p.events.append((t, f"{_who(r.actor)} " + ("rises from it" if r.target_role == "source" else "sits on it")))
    elif how == "table":
        _table(p, m, f0, f1)
    elif how == "beside":
        _beside(p, m, f1 - 1, r.target_side, _turns_to_someone(r, rows, motions))
        p.events.append(((f1 - 1) / fps, f"{_who(r.actor)} is at its {r.target_side or 'front'} side"))
    elif how == "by":
        _by(p, m, f0, f1, r.object)
        p.events.append((t, f"{_who(r.actor)} puts {r.object or 'a thing'} by it"))
    elif how == "around":  # the walk was steered into loops round it (scene.circling)
        middle, _ = circling.centre(m, f0, f1)
        p.rest(0, middle + [0.0, p.half, 0.0])
        p.events.append((t, f"{_who(r.actor)} goes round it"))
    elif how == "route":
        path, _ = bodies.hips_path(m)
        p.rest(0, path[(f0 + f1) // 2] + [0.0, p.half, 0.0])
        p.events.append((t, f"{_who(r.actor)} goes through it"))
    elif how == "sight":
        if not p.placed():
            path, heading = bodies.hips_path(m)
            mid = (f0 + f1) // 2
            p.rest(0, path[mid] + SIGHT_M * p.scale * bodies.forward(heading[mid]) + [0.0, p.half, 0.0],
                   float(heading[mid]))
        p.events.append((t, f"{_who(r.actor)} {r.verb} it"))
    elif how == "place":
        path, heading = bodies.hips_path(m)
        f = f1 - 1 if r.target_role != "source" else f0
        p.rest(0, path[f] + 0.6 * bodies.forward(heading[f]) + [0.0, p.half, 0.0])
        p.events.append((f / fps, f"{_who(r.actor)} " + ("leaves it" if r.target_role == "source" else "reaches it")))
    elif r.verb in KICK:
        _kick(p, r, m, motions, f0, f1, fps)
    elif r.verb in DRIBBLE:
        _dribble(p, r, m, f0, f1)
        p.events.append((t, f"dribbled by {_who(r.actor)}"))
    elif r.verb in THROW:
        _throw(p, r, m, rows, motions, f0, f1, fps)
    elif r.verb in PICK or (r.verb in TAKE and not p.placed() and _reaches_down(m, p, f0, f1)):
        grab = bodies.lowest(_grip(m, p), f0, f1)
        if not p.placed():  # it lay where the hand finds it: on the floor, or on the desk it is taken from
            point = _on_floor(_grip(m, p)[grab], p)
            if r.target_role == "source" and r.target_side == "on" and r.target not in GROUND_NOUNS:
                point[1] += _table_top(bodies.hand(m, "right")[bodies.lowest(bodies.hand(m, "right"), f0, f1), 1])
            p.rest(0, point)
        else:  # one already on its way (a pass) is met by the hand as it comes
            _meet(p, _grip(m, p), grab, int(MEET_S * fps))
        _hold(p, r.actor, m, grab)
        p.events.append((grab / fps, f"{_who(r.actor)} picks it up"))
    elif r.verb in PUT:
        if p.holder is None or p.holder[0] != r.actor:
            _hold(p, r.actor, m, f0)
        grip = _grip(m, p)
        let_go = bodies.lowest(grip, f0, f1)
        point = _on_floor(grip[let_go], p)
        on_table = r.target_role == "destination" and r.target_side in (None, "on") and r.target not in GROUND_NOUNS
        if on_table:  # on the table :func:`_table` puts under the hand
            point[1] += _table_top(bodies.hand(m, "right")[bodies.lowest(bodies.hand(m, "right"), f0, f1), 1])
        p.rest(let_go, point, float(bodies.hips_path(m)[1][let_go]))
        floor = " on the floor" if r.target in GROUND_NOUNS else ""
        p.events.append((let_go / fps, f"{_who(r.actor)} puts it down{floor}"))
    elif r.verb in GIVE:
        _give(p, r, m, motions, f0, f1, fps)
    elif r.verb in RECEIVE:
        if p.holder is None or p.holder[0] != r.actor:  # no one handed it over: taken at the reach
            _hold(p, r.actor, m, _instant(m, "both_hands", "reach", f0, f1))
            p.events.append((t, f"{_who(r.actor)} takes it"))
    elif r.verb in OPEN or r.verb in CLOSE or _knocks(r, p) or (r.verb in PUSH_PULL and p.shape.shape == "door"):
        opening = _opening_after(r, rows, p)
        also = None if opening is None else bodies.hand(m, "right")[_instant(m, "right_hand", "reach",
                                                                             *_frames(opening, fps, m.n_frames))]
        _door(p, r, m, f0, f1, fps, opening is None, also)
    elif (r.verb in PUSH and p.shape.shape != "door") or (
            p.pushed_by == r.actor and r.verb in LOCOMOTION_VERBS | MOVING_VERBS):
        _push(p, r, m, f0, f1)
        p.events.append((t, f"pushed by {_who(r.actor)}"))
    elif p.holder is None or p.holder[0] != r.actor:
        _hold(p, r.actor, m, 0 if not p.placed() else f0)
        p.events.append((t, f"{_who(r.actor)} holds it"))


# ---------------------------------------------------------------- held


#: s: a thing handed over passes from the giver's grip into the taker's over this long.
HAND_OVER_S = 0.15
#: s: a hand reaching for a thing that still moves (a rolling ball) closes on it over this long.
MEET_S = 0.4


def _meet(p: _Path, grip: np.ndarray, f: int, n: int) -> None:
    """The thing's frames before ``f`` eased from its own path into the ``grip`` ``(T, 3)`` over ``n``
    frames, so a hand takes it where it is, without a jump."""
    lo = max(0, f - n)
    if f <= lo:
        return
    u = (np.arange(lo, f) - lo + 1) / (f - lo + 1)
    w = (u * u * (3.0 - 2.0 * u))[:, None]
    p.pos[lo:f] = (1.0 - w) * p.pos[lo:f] + w * grip[lo:f]


#: m at the built-in body's size: a hand lower than this reaches down for a thing (about the knees).
REACH_DOWN = 0.55


def _reaches_down(m: Motion, p: _Path, f0: int, f1: int) -> bool:
    """Does the hand go down for the thing in frames ``[f0, f1)`` (a take that picks it up: 手に取る), rather
    than stay up (写真を撮る: the camera is held from the start)?"""
    grip = _grip(m, p)
    return float(grip[bodies.lowest(grip, f0, f1), 1]) < REACH_DOWN * p.scale


def _grip(m: Motion, p: _Path) -> np.ndarray:
    return bodies.hands(m) if p.shape.grip == "both" else bodies.hand(m, "right")


def _hold(p: _Path, actor: str | None, m: Motion, f: int) -> None:
    """``p`` in ``actor``'s hand(s) from frame ``f``: at the grip, turned with the hand (one hand) or with the
    hips (both hands, level)."""
    grip = _grip(m, p)
    p.pos[f:] = grip[f:]
    if p.shape.grip == "both":
        p.rot[f:] = Rotation.from_euler("y", bodies.hips_path(m)[1][f:, None]).as_quat()
    else:
        hand_rot = m.pose.rotations[:, _hand_joint(m)]
        rel = hand_rot[f].T  # the thing keeps the turn it had when taken: level at the grab
        p.rot[f:] = matrix_to_quat(hand_rot[f:] @ rel)
    p.holder = (actor, p.shape.grip)


def _hand_joint(m: Motion) -> int:
    from text2anim.core.bodyparts import body_map

    return body_map(m.skeleton).hands["right"]


def _on_floor(point: np.ndarray, p: _Path) -> np.ndarray:
    return np.array([point[0], p.half, point[2]])


# ---------------------------------------------------------------- flights


def _instant(m: Motion, effector: str, kind: str, f0: int, f1: int) -> int:
    """:func:`core.contact_instant.contact_instant` within frames ``[f0, f1)``."""
    return contact_instant(m, effector, kind, (f0 / m.fps, (max(f1, f0 + 1) - 1) / m.fps))


def kicks(rows: Sequence[Element], motions: dict[str | None, Motion], fps: float) -> list[Kick]:
    """The kicks of things on the floor among ``rows`` (played times): who, with which foot, from which frame,
    striking at which (:func:`strike`)."""
    out = []
    for r in rows:
        if r.verb in KICK and r.object is not None and r.actor in motions:
            m = motions[r.actor]
            f0, f1 = _frames(r, fps, m.n_frames)
            side, hit = strike(m, f0, f1)
            out.append(Kick(r.actor, side, f0, hit))
    return out


def strike(m: Motion, f0: int, f1: int) -> tuple[str, int]:
    """A kick's kicking foot (its toe the faster) and the frame it strikes in ``[f0, f1)``."""
    side = max(("left", "right"), key=lambda s: float(bodies.speed(bodies.toe(m, s)[f0:f1], m.fps).max()))
    return side, _instant(m, f"{side}_foot", "strike", f0, f1)


def release(m: Motion, f0: int, f1: int) -> int:
    """A throw's release in ``[f0, f1)``: the right hand flying out from the shoulder fastest."""
    return _instant(m, "right_hand", "release", f0, f1)


def reach_instant(r: Element, m: Motion, effector: str, fps: float) -> float:
    """When row ``r``'s ``effector`` reaches out (:func:`core.contact_instant.contact_instant`), s."""
    f0, f1 = _frames(r, fps, m.n_frames)
    return _instant(m, effector, "reach", f0, f1) / fps


def send_instant(r: Element, m: Motion, fps: float) -> tuple[float, float] | None:
    """When row ``r`` sends a thing off (a kick's strike, a throw's release), s, and where the chest faces
    then (rad); ``None`` for other verbs."""
    f0, f1 = _frames(r, fps, m.n_frames)
    if r.verb in KICK:
        f = strike(m, f0, f1)[1]
    elif r.verb in THROW:
        f = release(m, f0, f1)
    else:
        return None
    return f / fps, bodies.chest_heading(m, f)


def _kick(p: _Path, r: Element, m: Motion, motions, f0: int, f1: int, fps: float) -> None:
    side, hit = strike(m, f0, f1)
    toe = bodies.toe(m, side)
    heading = float(bodies.hips_path(m)[1][hit])
    start = _on_floor(toe[hit] + 0.5 * p.size[0] * bodies.forward(heading), p)
    if p.holder is None and not p.placed():
        p.rest(0, start)
        p.events.append((0.0, "on the floor"))
    elif p.holder is None and np.hypot(*(p.pos[hit] - start)[[0, 2]]) > 0.5:  # on the floor away: it rolls there
        w = np.linspace(0.0, 1.0, hit - f0 + 1)[:, None]
        p.pos[f0:hit + 1] = (1.0 - w) * p.pos[f0] + w * start
        p.pos[hit:] = start
    p.at_feet = None
    v = np.gradient(toe, 1.0 / fps, axis=0)[hit] * KICK_GAIN
    horizontal = float(np.clip(np.hypot(v[0], v[2]), 4.0, 7.0))  # a kick about, not a shot at goal
    aim = _aim(r, motions, p.pos[hit], hit, heading)
    lift = float(np.clip(v[1], 0.5, 3.0))
    to = _receiver_at(r, motions, hit)
    if to is not None:  # a pass: along the ground, rolling to a stop at the receiver's feet
        d = max(float(np.hypot(*(to - p.pos[hit])[[0, 2]])) - 0.3, 0.5)
        horizontal, lift = float(np.sqrt(2.0 * ROLL_DECELERATION * d)), 0.3
    v = np.array([horizontal * np.sin(aim), lift, horizontal * np.cos(aim)])
    _fly(p, hit, p.pos[hit], v, fps)
    p.events.append((hit / fps, f"kicked by {_who(r.actor)}"))


def _dribble(p: _Path, r: Element, m: Motion, f0: int, f1: int) -> None:
    """The ball on the floor :data:`DRIBBLE_AHEAD` ahead of the hips over frames ``[f0, f1)``, left there after."""
    path, heading = bodies.hips_path(m)
    h = heading[f0:f1]
    ahead = path[f0:f1] + DRIBBLE_AHEAD * p.scale * np.stack([np.sin(h), np.zeros_like(h), np.cos(h)], axis=1)
    p.pos[f0:] = ahead[-1] + [0.0, p.half, 0.0]
    p.pos[f0:f1] = ahead + [0.0, p.half, 0.0]
    p.holder, p.at_feet = None, r.actor


def _push(p: _Path, r: Element, m: Motion, f0: int, f1: int) -> None:
    """The thing on the floor ahead of the hips (:data:`PUSH_GAP` to its near side) over frames ``[f0, f1)``,
    turned as they face, left there after: pushed along (台車を押す, and on with the pusher's walk or carry)."""
    path, heading = bodies.hips_path(m)
    h = heading[f0:f1]
    reach = PUSH_GAP * p.scale + 0.5 * p.size[2]
    ahead = path[f0:f1] + reach * np.stack([np.sin(h), np.zeros_like(h), np.cos(h)], axis=1) + [0.0, p.half, 0.0]
    p.pos[f0:] = ahead[-1]
    p.pos[f0:f1] = ahead
    p.rot[f0:] = Rotation.from_euler("y", float(h[-1])).as_quat()
    p.rot[f0:f1] = Rotation.from_euler("y", h[:, None]).as_quat()
    p.holder, p.pushed_by = None, r.actor


def _throw(p: _Path, r: Element, m: Motion, rows, motions, f0: int, f1: int, fps: float) -> None:
    if p.holder is None or p.holder[0] != r.actor:
        _hold(p, r.actor, m, 0 if not p.placed() else f0)
    hand = bodies.hand(m, "right")
    let_go = release(m, f0, f1)
    start = hand[let_go]
    catch = _catcher(p, r, rows, motions, let_go, fps)
    if catch is not None:
        who, fc, point = catch
        dt = (fc - let_go) / fps
        v = (point - start - 0.5 * np.array([0.0, -G, 0.0]) * dt * dt) / dt
        _fly(p, let_go, start, v, fps, until=fc)
        p.events.append((let_go / fps, f"thrown by {_who(r.actor)}"))
        _hold(p, who, motions[who], fc)
        p.events.append((fc / fps, f"caught by {who}"))
        return
    v = np.gradient(hand, 1.0 / fps, axis=0)[let_go]
    heading = float(bodies.hips_path(m)[1][let_go])
    speed = max(float(np.hypot(v[0], v[2])), 5.0)
    aim = _aim(r, motions, start, let_go, heading)
    _fly(p, let_go, start, np.array([speed * np.sin(aim), float(np.clip(v[1], 1.0, 4.0)), speed * np.cos(aim)]), fps)
    p.events.append((let_go / fps, f"thrown by {_who(r.actor)}"))
    hit = _reaches_body(p, r, motions, let_go)
    if hit is not None:  # thrown to someone who does not catch it: it strikes them and drops at their feet
        back = p.pos[hit - 1] - p.pos[hit]
        back[1] = 0.0
        _fly(p, hit, p.pos[hit], 0.5 * back / max(float(np.linalg.norm(back)), 1e-9), fps)
        p.events.append((hit / fps, f"drops at {r.target}'s feet"))


#: m at the built-in body's size: a flying thing this near a person's hips, over the floor, meets their body.
BODY_RADIUS = 0.25


def _reaches_body(p: _Path, r: Element, motions, after: int) -> int | None:
    """The first frame after ``after`` at which the thing flying to row ``r``'s recipient meets their body (within
    :data:`BODY_RADIUS` of their hips over the floor, below their head), or ``None``."""
    if r.target not in motions or r.target_role != "recipient":
        return None
    hips = bodies.hips_path(motions[r.target])[0]
    n = min(len(p.pos), len(hips))
    for f in range(after + 1, n):
        if np.hypot(*(p.pos[f] - hips[f])[[0, 2]]) < BODY_RADIUS * p.scale and p.pos[f, 1] < 1.8 * p.scale:
            return f
    return None


def _catcher(p: _Path, r: Element, rows, motions, after: int, fps: float):
    """The catch that ends a throw: (who, frame, where the hands meet the thing), or ``None``. The thrower's own
    catch after the throw ends it too (高く投げて、自分でキャッチした: the ball goes up and comes down to them)."""
    for q in rows:
        if (q.verb in CATCH and q.actor in motions and q.object in (p.name, None)
                and (q.actor != r.actor or q.start >= r.start)):
            m = motions[q.actor]
            f0, f1 = _frames(q, fps, m.n_frames)
            both = bodies.hands(m)
            fc = _instant(m, "both_hands", "reach", f0, f1)
            if fc > after + int(0.2 * fps):
                return q.actor, fc, both[fc]
    return None


def _receiver_at(r: Element, motions, f: int) -> np.ndarray | None:
    """Where the row's recipient stands at frame ``f`` (their hips over the floor), ``None`` without one."""
    if r.target in motions and r.target_role in ("recipient", "addressee", "goal"):
        other = bodies.hips_path(motions[r.target])[0]
        return other[min(f, len(other) - 1)]
    return None


def _aim(r: Element, motions, start: np.ndarray, f: int, heading: float) -> float:
    """The heading a thing is sent at: towards the row's recipient when there is one, else ``heading``."""
    to = _receiver_at(r, motions, f)
    return bodies.heading_to(start, to) if to is not None else heading


def _fly(p: _Path, f: int, start: np.ndarray, v: np.ndarray, fps: float, until: int | None = None) -> None:
    """A ballistic flight from frame ``f``: lands, bounces, rolls to a stop (or ends at ``until``). A ball
    turns as it rolls: about the level axis across its way (which a flight, its bounces and its roll keep),
    by the ground it covers over its radius."""
    n = len(p.pos) if until is None else until + 1
    if n <= f:
        return
    p.pos[f:n] = _ballistic(start, v, n - f, fps, p.half)
    way = p.pos[n - 1] - p.pos[f]
    way[1] = 0.0
    if p.shape.shape == "sphere" and np.linalg.norm(way) > 1e-9:
        axis = np.cross([0.0, 1.0, 0.0], way / np.linalg.norm(way))
        rolled = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p.pos[f:n, :][:, [0, 2]], axis=0), axis=1))])
        p.rot[f:n] = (Rotation.from_rotvec(np.outer(rolled / p.half, axis)) * Rotation.from_quat(p.rot[f])).as_quat()
    else:
        p.rot[f:n] = p.rot[f]
    p.holder = None


def _ballistic(start: np.ndarray, v: np.ndarray, n: int, fps: float, radius: float) -> np.ndarray:
    """``n`` frames ``(n, 3)`` of a thing of ``radius`` thrown from ``start`` at ``v`` (m/s): gravity, bounces
    losing :data:`RESTITUTION` of their vertical speed, a roll slowing by :data:`ROLL_DECELERATION`. Four
    steps a frame, in plain floats (a frame's arithmetic is a few operations: numpy's would cost more)."""
    x, y, z = (float(c) for c in start)
    vx, vy, vz = (float(c) for c in v)
    sub = 4
    h = 1.0 / (fps * sub)
    out = np.empty((n, 3))
    for k in range(n):
        out[k] = (x, y, z)
        for _ in range(sub):
            grounded = y <= radius + 1e-6 and abs(vy) < 0.5
            if grounded:
                y, vy = radius, 0.0
                flat = math.hypot(vx, vz)
                scale = max(0.0, flat - ROLL_DECELERATION * h) / flat if flat > 1e-9 else 0.0
                vx, vz = vx * scale, vz * scale
            else:
                vy -= G * h
            x, y, z = x + vx * h, y + vy * h, z + vz * h
            if y < radius and not grounded:
                y, vy, vx, vz = radius, -vy * RESTITUTION, vx * 0.85, vz * 0.85
    return out


# ---------------------------------------------------------------- hand-over, seats, tables, doors


def _give(p: _Path, r: Element, m: Motion, motions, f0: int, f1: int, fps: float) -> None:
    if p.holder is None or p.holder[0] != r.actor:
        _hold(p, r.actor, m, 0 if not p.placed() else f0)
    contact = _instant(m, "right_hand", "reach", f0, f1)
    taker = r.target if r.target in motions else None
    if taker is None:
        return
    given = p.pos.copy()
    _hold(p, taker, motions[taker], contact)
    n = min(int(HAND_OVER_S * fps), len(p.pos) - contact)  # from one grip into the other, not a jump
    w = ((np.arange(n) + 1) / (n + 1))[:, None]
    p.pos[contact:contact + n] = (1.0 - w) * given[contact:contact + n] + w * p.pos[contact:contact + n]
    p.events.append((contact / fps, f"handed from {_who(r.actor)} to {taker}"))


def _seat(p: _Path, m: Motion, f: int) -> None:
    """A seat under the hips at frame ``f``: its top a hand's breadth below the hip joints, its centre a
    little behind them (the thighs lie on its front half), turned as the hips face. Several who sit on it
    (太郎と花子はベンチに座った) share it: it stands under the middle of their hips, as long as their row."""
    p.sitters.append((np.array(m.root_positions[f]), float(bodies.hips_path(m)[1][f])))
    hips = np.mean([h for h, _ in p.sitters], axis=0)
    heading = p.sitters[0][1]
    top = max(0.2 * p.scale, float(min(h[1] for h, _ in p.sitters)) - 0.1 * p.scale)
    w, h, d = p.size
    h = 2.0 * top if p.shape.shape == "chair" else top  # a chair's seat at half its height (output.viewer.types)
    across = max(float(np.hypot(*(a - b)[[0, 2]])) for a, _ in p.sitters for b, _ in p.sitters)
    p.size = (max(w, across + 0.5 * p.scale), h, d)
    centre = hips - 0.05 * bodies.forward(heading)
    p.rest(0, np.array([centre[0], 0.5 * h, centre[2]]), heading)


def _table(p: _Path, m: Motion, f0: int, f1: int) -> None:
    """A table whose near edge is under where the hand puts a thing down (its lowest frame)."""
    grip = bodies.hand(m, "right")
    f = bodies.lowest(grip, f0, f1)
    heading = float(bodies.hips_path(m)[1][f])
    w, h, d = p.size
    top = _table_top(grip[f, 1])
    p.size = (w, top, d)
    centre = grip[f] + (0.5 * d - 0.1) * bodies.forward(heading)
    p.rest(0, np.array([centre[0], 0.5 * top, centre[2]]), heading)


def _turns_to_someone(r: Element, rows: Sequence[Element], motions) -> bool:
    """Does the actor of ``r``, standing at the front of a thing (黒板の前に立って), then act towards a person
    (生徒たちにお辞儀する)? Then the body faces them, its back to the thing."""
    return r.target_side == "front" and any(
        q.actor == r.actor and q.id != r.id and q.start >= r.start and q.target in motions
        and q.target_role in ("addressee", "recipient", "patient", "partner") for q in rows)


def _beside(p: _Path, m: Motion, f: int, side: str | None, back: bool = False) -> None:
    """A thing standing where the body is at frame ``f`` beside it: ahead of the hips, its near side
    :data:`BESIDE_GAP` from them (the body at its front, 前, faces it), or to the body's right or left
    (隣, 横, 右, 左), or behind it (``back``; 下: at the foot of a tree), turned as the body faces."""
    path, heading = bodies.hips_path(m)
    h = float(heading[f])
    w, _, d = p.size
    gap = BESIDE_GAP * p.scale
    if side in ("beside", "right", "left"):
        across = -np.pi / 2 if side in ("beside", "right") else np.pi / 2
        centre = path[f] + (gap + 0.5 * w) * bodies.forward(h + across)
    elif side == "under" or back:  # 木の下に座る: at its foot, the trunk at the back; 黒板の前で話す
        centre = path[f] - (gap + 0.5 * d) * bodies.forward(h)
    else:
        centre = path[f] + (gap + 0.5 * d) * bodies.forward(h)
    p.rest(0, centre + [0.0, p.half, 0.0], h)


def _by(p: _Path, m: Motion, f0: int, f1: int, thing: str | None) -> None:
    """A thing a held thing is put beside (窓のそばに置く): standing beyond where the hand puts it down (its
    lowest frame), room for that thing between, turned as the body faces."""
    grip = bodies.hand(m, "right")
    f = bodies.lowest(grip, f0, f1)
    heading = float(bodies.hips_path(m)[1][f])
    room = (shape_of(thing)[0].size[2] if thing else 0.3) * p.scale
    centre = grip[f] + (room + BESIDE_GAP * p.scale * 0.5 + 0.5 * p.size[2]) * bodies.forward(heading)
    p.rest(0, np.array([centre[0], p.half, centre[2]]), heading)


def _table_top(hand_y: float) -> float:
    """A table's top (m) for a thing put down by a hand at ``hand_y``: just below the hand."""
    return float(np.clip(hand_y - 0.05, 0.3, 1.1))


def _knocks(r: Element, p: _Path) -> bool:
    """ドアをノックする, ドアを叩く: a door knocked on."""
    return r.verb in KNOCK or (r.verb == "叩く" and p.shape.shape == "door")


def _opening_after(r: Element, rows: Sequence[Element], p: _Path) -> Element | None:
    """The opening of door ``p`` by the same actor after a push or pull ``r`` (ドアを引いて開ける: one act, the
    pull takes the handle, the opening swings it), if any."""
    if r.verb not in PUSH_PULL:
        return None
    return next((q for q in rows if q.actor == r.actor and q.id != r.id and q.start >= r.start and q.verb in OPEN
                 and q.object == p.name), None)


def _door(p: _Path, r: Element, m: Motion, f0: int, f1: int, fps: float, swings: bool = True,
          also: np.ndarray | None = None) -> None:
    """A door in front of the right hand at its furthest reach, its hinge on the hand's far side, where it is
    first handled (a door held, the goal of a walk, is placed anew; with ``also``, the hand at the opening a
    pull leads to, it stands at the nearer of the two reaches, the further one on its handle); it swings open
    (or shut) from the reach to the row's end, from the angle it had, unless it does not ``swings`` (a pull
    before an opening)."""
    reach = _instant(m, "right_hand", "reach", f0, f1)
    fresh = p.hinge is None or p.holder is not None
    if fresh:
        heading = float(bodies.hips_path(m)[1][reach])
        hand = bodies.hand(m, "right")[reach]
        if also is not None and float(np.dot(also - hand, bodies.forward(heading))) < 0.0:
            hand = also
        handle = hand + 0.05 * bodies.forward(heading)
        hinge = handle + (p.size[0] - 0.1) * bodies.forward(heading + np.pi / 2)
        hinge[1] = 0.0
        p.hinge = (hinge, heading, np.radians(DOOR_SWING) if r.verb in CLOSE else 0.0)  # ドアを閉める: it was open
    assert p.hinge is not None  # placed above when fresh
    hinge, heading, was = p.hinge
    opening, knocked = r.verb in OPEN or r.verb in PUSH_PULL, _knocks(r, p)
    to = was if knocked or not swings else np.radians(DOOR_SWING) if opening else 0.0
    n = len(p.pos)
    ramp = np.clip((np.arange(reach, n) - reach) / max(1, f1 - reach), 0.0, 1.0)
    angles = was + (to - was) * (3 - 2 * ramp) * ramp * ramp
    p.hinge = (hinge, heading, float(to))
    w, h, _ = p.size
    centre_local = -0.5 * w * bodies.forward(heading + np.pi / 2) + [0.0, 0.5 * h, 0.0]
    if fresh:  # it stood there from the start (a door walked up to is where the hand finds it)
        p.pos[:reach] = hinge + Rotation.from_euler("y", was).apply(centre_local)
        p.rot[:reach] = Rotation.from_euler("y", heading + was).as_quat()
    p.pos[reach:] = hinge + Rotation.from_euler("y", angles[:, None]).apply(centre_local)
    p.rot[reach:] = Rotation.from_euler("y", heading + angles[:, None]).as_quat()
    p.holder = None
    if knocked or to != was or not swings:
        done = "knocked on" if knocked else "taken by the handle" if not swings else "opened" if opening else "shut"
        p.events.append((reach / fps, f"{done} by {_who(r.actor)}"))

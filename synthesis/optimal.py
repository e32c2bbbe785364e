"""Motion synthesis with optimal blending (paper 000, Oshita): the default joiner of consecutive motions.

For each pair of consecutive whole-body elements on a track (§4, "各前後の要素動作の組に対して本手法を繰り返し適用"):

1. **method** (§4.1, §4.2.5, :mod:`synthesis.method_select`): transition,
   connection, adaptation with or without a step, from the foot–ground
   constraints of the two clips around their cores on the track;
2. **ranges** (§4.2, eqs. (1)–(9), :mod:`synthesis.blend_ranges`): lower and
   upper body blend separately, each in its range;
3. **search** (§4.3, eqs. (10)–(15), :mod:`synthesis.blend_search`): ``t0``,
   ``t1`` of every interval minimise eq. (10) over all pairs at once, the
   weights from the user's ``smoothness`` ``W``;
4. **placement**: the next motion is turned and slid so its support foot
   stands on the previous motion's and both face the same way
   (:func:`synthesis.align.align_through_foot`, as paper [6] / seed 003 do);
   for an adaptation the next lower body is fitted to the previous feet
   (:mod:`synthesis.adaptation`, §4.2.3) and S0 is searched again on it;
5. **weights** (§4.4, :mod:`synthesis.weights`): Hermite curves with eq. (16)
   slopes; motion–pose / pose–motion blends by the three cases of §4.4.2;
6. **rendering**: per frame, the lower body blends its two sources with the
   lower weight, the upper body its two with the upper weight (slerp,
   :mod:`synthesis.blend`); planted feet are locked and released by the
   seed engine's :func:`synthesis.transition.apply_join` (IK, §4.3.2 of 003).

Every blend lasts at least :data:`MIN_BLEND` s (a shorter pose change reads as
a pop).

**Cores** (§4.2.5): when the two cores overlap on the track the later motion
cannot keep its core; it is **not executed** — a warning says so and the
report has a join with ``blend: "not_executed"``; the next element joins the
one before. Cores overlapping by less than :data:`CORE_TOLERANCE` s (a frame of
contact-label noise between the scheduler's step times and ours) touch. A looped clip is all core except the step a join uses
(:func:`~synthesis.method_select.cyclic_core_end`); a looped next clip may
enter at another phase of its cycle to make a transition possible
(``phase_s``).

**Feet** (the paper's foot constraints made exact): planted feet are locked by
the seed engine's IK (:func:`synthesis.transition.apply_join`). Three choices
of this module keep that from fighting the blend:

- a foot that a held pose plants somewhere else than the other side does
  (more than :data:`STEP_GAP`) steps across in the air over the middle of the
  blend instead of staying locked where the first motion left it
  (:func:`_planted`);
- the next motion is moved by the few centimetres between its own support foot
  and where the lock leaves that foot after the blend (:func:`settle`), so the
  lock hands over without bending a leg inside the next core;
- a join whose blend would still skate is rendered again — without the step,
  with S0's weight eased to zero slope at its ends, placed by the roots
  mid-blend (motion–motion), then with the next-best intervals of eq. (10) —
  and the first clean rendering is kept (``fallback`` in the report).

**Room** (choice where the paper assumes suitable times): when the given start
time leaves the lower-body blend less than :data:`MIN_ROOM` s (for a
connection: less than the step it blends), the next element is delayed by the
shortfall, at most :data:`MAX_SHIFT` s (``shift_s`` in the report; partial
elements laid on it move with it; later elements keep their times). Ranges
still too narrow are widened into the core with a warning.

Units: frames on the track internally, seconds in the report. Deterministic.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from .adaptation import adapt, pin_feet
from .align import Rigid, align_through_foot, headings, to_heading_frame
from text2anim.core.bodyparts import body_map
from .assemble import Laid, assemble
from .blend import blend, ease, sample
from .blend_ranges import Bounds, Range, after, ranges
from .blend_search import Found, Weights, best, evaluate, evaluate_motions, preset
from text2anim.core.contacts import FootContacts, detect_contacts
from .engine import Placed, Result, skating_frames, spread_actors
from .method_select import (Choice, cyclic_core_begin, cyclic_core_end, phase_for, select, steps,
                            support_by_gap)
from text2anim.core.motion import Motion, concatenate
from .plan import BlendInterval, Element, JoinReport, Track
from .posedist import distance, features, part_joints
from .switching import foot_points
from .track import Incoming, TrackState, extend, lay_elements
from .transition import PLANTED_WEIGHT, Join, apply_join
from .weights import hermite_weights, plan_partial, slope

MIN_BLEND = 0.2  # s: the shortest blend interval (shorter pose changes read as pops)
MIN_ROOM = 0.25  # s: the least room the lower-body range should leave
MAX_SHIFT = 0.5  # s: the most an element is delayed for room
CORE_TOLERANCE = 0.1  # s: cores overlapping by less than this are taken as touching (a frame of contact noise)
SAME_FEET_CM = 1.0
RUNNERS_UP = 5  # next-best lower-body intervals tried when the best one's join would skate  # cm: an adaptation moving no foot further needs no return step (S3)


@dataclass(frozen=True)
class Interval:
    """A blend interval as carried out: ``name``/``part``/``kind``, frames ``t0``..``t1`` (track), the
    weight of the second source per frame ``(t1 - t0 + 1,)``, sources, the §4.4 ``case``
    (``hermite``, or ``a``/``b``/``c`` of §4.4.2), the search's result and the range searched."""

    name: str
    part: str
    kind: str
    t0: int
    t1: int
    weights: np.ndarray
    src: tuple[str, str]
    case: str
    found: Found
    range: Range
    slopes: tuple[float, float]


@dataclass
class Plan:
    """What :func:`plan_join` decided for one join."""

    inc: Incoming
    choice: Choice
    intervals: dict
    rigid: Rigid
    support: str | None
    placed: Motion
    adapted: Motion | None
    shift: int = 0
    phase: int = 0
    warnings: list = field(default_factory=list)
    info: dict = field(default_factory=dict)
    alternatives: list = field(default_factory=list)

    def cost(self) -> dict:
        """eq. (10)'s weighted terms summed over the searched intervals (the report's ``cost``)."""
        out = {"time": 0.0, "pose": 0.0, "velocity": 0.0}
        for iv in self.intervals.values():
            for k, v in iv.found.terms().items():
                out[k] += v
        out = {k: round(v, 4) for k, v in out.items()}
        out["total"] = round(sum(out.values()), 4)
        return out


@dataclass(frozen=True)
class Skip:
    """A join not carried out: the later element is not executed, and why."""

    reason: str


# ------------------------------------------------------------------------------------------- planning
def _sources(tr: Motion, inc: Incoming, adapted: Motion | None):
    """Source name → (motion, track frame of its frame 0)."""
    return {"A": (tr, 0), "B": (inc.motion, inc.offset),
            "Bad": (adapted if adapted is not None else inc.motion, inc.offset)}


class _Features:
    """Kovar features of the join's sources, joints per part looked up once."""

    def __init__(self, tr: Motion, inc: Incoming, adapted: Motion | None = None):
        self.src = _sources(tr, inc, adapted)
        self.joints = {p: part_joints(tr, p) for p in ("lower", "upper")}

    def __call__(self, name: str, part: str, frames) -> np.ndarray:
        motion, off = self.src[name]
        return features(motion, self.joints[part], np.asarray(frames) - off)


def _grid(r: Range, feats: _Features, fps: float, weights: Weights, min_len: int):
    """eq. (10) over every candidate pair of the range (:mod:`synthesis.blend_search`)."""
    if r.kind == "motion-motion":
        f0 = np.arange(r.t0[0], r.t0[1] + 2)
        f1 = np.arange(r.t1[0], r.t1[1] + 2)
        return evaluate_motions(feats(r.src[0], r.part, f0), feats(r.src[1], r.part, f0),
                                feats(r.src[0], r.part, f1), feats(r.src[1], r.part, f1), r.t0, r.t1, fps, weights,
                                r.p_len, min_len)
    f_from = feats(r.src[0], r.part, np.arange(r.t0[0], r.t0[1] + 2))
    f_to = feats(r.src[1], r.part, np.arange(r.t1[0] - 1, r.t1[1] + 1))
    return evaluate(f_from, f_to, r.t0, r.t1, fps, weights, r.p_len, min_len)


def _search(r: Range, feats: _Features, fps: float, weights: Weights, min_len: int) -> Found:
    """The global minimum of eq. (10) over the range."""
    return best(_grid(r, feats, fps, weights, min_len), weights, min_len)


def _runners_up(r: Range, feats: _Features, fps: float, weights: Weights, min_len: int, k: int) -> list[Found]:
    """The ``k`` next-best pairs of eq. (10) after the minimum, in order of cost (ties: earlier first)."""
    g = _grid(r, feats, fps, weights, min_len)
    flat = g.cost.ravel()
    order = np.argsort(flat, kind="stable")
    order = order[np.isfinite(flat[order])][1:k + 1]
    out = []
    for o in order:
        i, j = np.unravel_index(int(o), g.cost.shape)
        out.append(Found(int(g.t0[i]), int(g.t1[j]), float(g.Qt[i, j]), float(g.D[i, j]), float(g.Qv[i, j]),
                         float(g.V0[i, j]), float(g.V1[i, j]), float(g.cost[i, j]), weights))
    return out


def _ends(feats: _Features, r: Range, t0: int, t1: int, fps: float) -> tuple[float, float, float]:
    """``D(t0, t1)`` and the eq. (14) speeds ``V(t0)``, ``V(t1)`` of an interval (m, m/s)."""
    fa = feats(r.src[0], r.part, [t0, t0 + 1])
    fb = feats(r.src[1], r.part, [t1 - 1, t1])
    D = distance(fa[0], fb[1])
    return D, (D - distance(fa[1], fb[1])) * fps, (D - distance(fa[0], fb[0])) * fps


def _weights(name: str, r: Range, found: Found, feats: _Features, fps: float, min_len: int) -> Interval:
    """§4.4: the weight curve of a searched interval (and the §4.4.2 case, which may move an end)."""
    t0, t1, kind = found.t0, found.t1, r.kind
    case = "hermite"
    D, V0, V1 = found.D, found.V0, found.V1
    if kind == "motion-motion":  # eq. (16) from the start and end poses (the search compared the pairs)
        D, V0, V1 = _ends(feats, r, t0, t1, fps)
    if kind in ("motion-pose", "pose-motion"):
        frames = np.arange(t0, t1 + 1)
        if kind == "motion-pose":  # the moving first source against the end pose
            d = np.linalg.norm(feats(r.src[0], r.part, frames) - feats(r.src[1], r.part, [t1]), axis=-1).mean(-1)
        else:  # the start pose against the moving second source
            d = np.linalg.norm(feats(r.src[0], r.part, [t0]) - feats(r.src[1], r.part, frames), axis=-1).mean(-1)
        pp = plan_partial(kind, d, min_len)
        case, kind = pp.case, pp.kind
        if (pp.begin, pp.end) != (0, t1 - t0):
            t0, t1 = t0 + pp.begin, t0 + pp.end
            D, V0, V1 = _ends(feats, r, t0, t1, fps)
    T = (t1 - t0) / fps
    m0, m1 = slope(V0, D, T), slope(V1, D, T)  # eq. (16), 0 on reversal
    w = hermite_weights(t1 - t0, m0, m1)
    return Interval(name, r.part, kind, t0, t1, w, r.src, case, found, r, (m0, m1))


def _supported(choice: Choice, contacts: FootContacts, latest: int) -> Choice:
    """A connection's step begins (eq. (3): ``t_s0,begin = t_p0,begin``) when its foot is in the air *and*
    the support foot is down: in a run both feet are off the ground as one lifts, and a lower body frozen
    or blended from that instant has no foot to stand on. The first such frame of ``P0`` (no later than
    ``latest``); ``P0`` as it was when there is none (a jump)."""
    p0 = choice.p0
    c = contacts.of(choice.support)
    f = np.arange(p0.begin, min(p0.end, latest + 1))
    f = f[(f < len(c)) & c[np.clip(f, 0, len(c) - 1)]]
    if len(f) == 0 or f[0] == p0.begin:
        return choice
    return replace(choice, p0=replace(p0, begin=int(f[0])))


def _geometry(tr_contacts: FootContacts, prev: Placed, inc: Incoming, floor: int, min_len: int):
    a_steps = [s for s in steps(tr_contacts) if s.begin >= prev.offset]
    c0 = (prev.offset + prev.core[0], prev.offset + prev.core[1])
    a_end = prev.offset + prev.stop
    c0_end = c0[1]
    if prev.cyclic:  # a loop's core ends at its last step — or where the next motion is scheduled to start
        c0_end = min(cyclic_core_end(a_steps, prev.offset + prev.lead, a_end, c0), max(inc.first, c0[0] + 1))
    b_steps = steps(inc.contacts, inc.offset)
    c1 = (inc.offset + inc.core[0], inc.offset + inc.core[1])
    if inc.cyclic:
        c1 = (cyclic_core_begin(b_steps, inc.first, c1), c1[1])
    choice = select(a_steps, b_steps, c0_end, c1, floor=floor, b_first=inc.first, min_frames=min_len)
    if choice.method == "motion_connection":
        choice = _supported(choice, tr_contacts, c1[0] - min_len)
    bounds = Bounds(c0_end, c1, a_end, inc.first, inc.end, floor, min_len)
    return choice, bounds, a_steps


def _planted_near(contacts: FootContacts, side: str, lo: int, hi: int, target: int, offset: int = 0):
    """The frame in ``[lo, hi]`` (track) nearest ``target`` where ``side`` is down (``contacts`` index = frame -
    ``offset``), or ``None``."""
    c = contacts.of(side)
    f = np.arange(max(lo, offset), min(hi, offset + len(c) - 1) + 1)
    if len(f) == 0:
        return None
    f = f[c[f - offset]]
    return int(f[np.argmin(np.abs(f - target))]) if len(f) else None


def _alignment(choice: Choice, s0: Found, tr: Motion, tr_contacts: FootContacts, inc: Incoming):
    """``(support, ta, tb)``: the foot (or ``None``: roots) and the track frames of A and B put together."""
    sup = choice.support
    if choice.method == "motion_transition":
        lo, hi = max(s0.t0, inc.first), s0.t1
        mid = (lo + hi) // 2
        both = tr_contacts.of(sup)[np.clip(np.arange(lo, hi + 1), 0, tr.n_frames - 1)]
        ib = np.clip(np.arange(lo, hi + 1) - inc.offset, 0, inc.motion.n_frames - 1)
        both = both & inc.contacts.of(sup)[ib]
        frames = np.arange(lo, hi + 1)[both]
        if len(frames):
            f = int(frames[np.argmin(np.abs(frames - mid))])
            return sup, f, f
        return None, mid, mid  # no foot down in both: the roots meet in the middle of the blend
    if choice.method == "motion_connection":
        ta = _planted_near(tr_contacts, sup, choice.p0.begin - 2, s0.t1, s0.t1)
        tb = _planted_near(inc.contacts, sup, inc.first, inc.offset + inc.core[1], s0.t1, inc.offset)
        if ta is None or tb is None:
            return None, s0.t1, s0.t1
        return sup, ta, tb
    # adaptation: the previous motion's feet where its lower body starts blending, the next's pose at S0's end
    ta, tb = s0.t0, s0.t1
    if sup is None:
        fa = foot_points(tr)
        fb = foot_points(inc.motion)
        ha = headings(tr, 0.5)[ta]
        hb = headings(inc.motion, 0.5)[tb - inc.offset]
        pa = {s: to_heading_frame(fa[s][ta][None, None, :], np.array([ha]))[0, 0, [0, 2]] for s in fa}
        pb = {s: to_heading_frame(fb[s][tb - inc.offset][None, None, :], np.array([hb]))[0, 0, [0, 2]] for s in fb}
        sup = support_by_gap(pa, pb)
    return sup, ta, tb


def plan_join(tr: Motion, prev: Placed, inc: Incoming, fps: float, weights: Weights, floor: int = 0,
              min_blend: float = MIN_BLEND, allow_shift: bool = True) -> Plan | Skip:
    """Method, ranges, search, placement and weights of one join (no frames written).

    Args:
        tr: the track so far, holding ``prev`` (extended, held, at least to the next element's last frame).
        prev: the previous element as laid.
        inc: the next element.
        weights: eq. (10)'s weights (:func:`synthesis.blend_search.preset`).
        floor: no blend starts before this track frame (the previous join's end; eq. (17)'s current time).
        allow_shift: delay the next element for room (see the module docstring).
    """
    L = max(2, int(round(min_blend * fps)))
    tr_contacts = detect_contacts(tr)
    warnings: list[str] = []
    choice, bounds, a_steps = _geometry(tr_contacts, prev, inc, floor, L)
    phase = 0
    if inc.cyclic and choice.p0 is not None:  # a loop may enter at the phase whose step lifts with P0's
        off = phase_for(choice.p0, steps(inc.contacts), inc.offset, inc.first)
        if off is not None and inc.end - off <= inc.motion.n_frames and off != inc.offset:
            moved = inc.at_phase(off)
            c2, b2, _ = _geometry(tr_contacts, prev, moved, floor, L)
            if c2.method == "motion_transition":
                phase, inc, choice, bounds = off - inc.offset, moved, c2, b2
    if bounds.c1[0] < bounds.c0_end - int(round(CORE_TOLERANCE * fps)):
        return Skip(f"element {inc.element.id} ({inc.element.clip.name}) is not executed: its core "
                    f"({bounds.c1[0] / fps:.2f} s) would begin before the core of element {prev.element.id} "
                    f"ends ({bounds.c0_end / fps:.2f} s); schedule it later to perform it (paper 000 §4.2.5)")
    shift = 0
    rs = ranges(choice, bounds)
    if allow_shift:
        s0 = rs[0]
        need = max(L, int(round(MIN_ROOM * fps)), s0.p_len if choice.method == "motion_connection" else 0)
        have = s0.t1[1] - s0.t0[0]
        if have < need:
            shift = min(need - have, int(round(MAX_SHIFT * fps)))
            inc = inc.moved(shift)
            choice, bounds, _ = _geometry(tr_contacts, prev, inc, floor, L)
            rs = ranges(choice, bounds)
    for k, r in enumerate(rs):
        if not r.feasible(L):
            rs[k] = r.relax(L)
            warnings.append(f"join {prev.element.id}→{inc.element.id}: the cores leave no room for the "
                            f"{r.part}-body blend {r.name}; it overlaps a core")
    byname = {r.name: r for r in rs}
    feats = _Features(tr, inc)
    found = {"S0": _search(byname["S0"], feats, fps, weights, L), "S1": _search(byname["S1"], feats, fps, weights, L)}
    support, ta, tb = _alignment(choice, found["S0"], tr, tr_contacts, inc)
    ta = int(np.clip(ta, 0, tr.n_frames - 1))
    tb_own = int(np.clip(tb - inc.offset, 0, inc.motion.n_frames - 1))
    rigid = align_through_foot(tr, ta, inc.motion, tb_own, support)
    placed = rigid.apply(inc.motion)
    adapted = None
    info: dict = {}
    if choice.method.startswith("motion_adaptation"):
        fa, fb = foot_points(tr), foot_points(placed)
        offsets = {s: fa[s][ta] - fb[s][tb_own] for s in ("left", "right")}
        if support is not None:
            offsets[support] = np.zeros(3)
        adapted = adapt(placed, offsets)
        info["adapt_offsets"] = offsets
        info["adapt_offset_cm"] = {s: round(100 * float(np.hypot(v[0], v[2])), 2) for s, v in offsets.items()}
        feats = _Features(tr, inc, adapted)
        found["S0"] = _search(byname["S0"], feats, fps, weights, L)  # S0 again, onto the adapted lower body
        if "S3" in byname and max(info["adapt_offset_cm"].values()) < SAME_FEET_CM:
            del byname["S3"]  # the feet already agree: nothing to return from (S2 runs to the end, eq. (9))
            info["return"] = "not needed: the feet already stand as the next motion has them"
        if "S3" in byname:
            byname["S3"] = after(byname["S3"], found["S0"].t1, L)
            if not byname["S3"].feasible(L):
                byname["S3"] = byname["S3"].relax(L)
            found["S3"] = _search(byname["S3"], feats, fps, weights, L)
    intervals = {n: _weights(n, byname[n], f, feats, fps, L) for n, f in found.items()}
    alternatives = []
    if adapted is None:  # the next-best lower-body intervals, tried in turn if the best one's join skates
        alternatives = [_weights("S0", byname["S0"], f, feats, fps, L)
                        for f in _runners_up(byname["S0"], feats, fps, weights, L, RUNNERS_UP)]
    info.update({
        "support": support, "align_frames_s": [ta / fps, tb / fps],
        "p0_s": None if choice.p0 is None else [choice.p0.begin / fps, choice.p0.end / fps, choice.p0.side],
        "p1_s": None if choice.p1 is None else [choice.p1.begin / fps, choice.p1.end / fps, choice.p1.side],
        "cores_s": [bounds.c0_end / fps, bounds.c1[0] / fps],
        "weight_cases": {n: iv.case for n, iv in intervals.items()},
        "slopes": {n: [round(iv.slopes[0], 3), round(iv.slopes[1], 3)] for n, iv in intervals.items()},
        "ranges_s": {n: {"eq": r.eq, "t0": [r.t0[0] / fps, r.t0[1] / fps], "t1": [r.t1[0] / fps, r.t1[1] / fps]}
                     for n, r in byname.items()},
        "shift_s": shift / fps, "phase_s": phase / fps,
        "weights": {"time": weights.time, "pose": weights.pose, "velocity": weights.velocity},
    })
    if adapted is not None:
        s2_end = intervals["S3"].t0 if "S3" in intervals else inc.end
        info["adapted_s"] = [intervals["S0"].t1 / fps, s2_end / fps]  # eq. (7) / (9): S2
    return Plan(inc, choice, intervals, rigid, support, placed, adapted, shift, phase, warnings, info, alternatives)


def _public(info: dict) -> dict:
    """The plan's notes as they go into the report (plain JSON values)."""
    return {k: v for k, v in info.items() if k != "adapt_offsets"}


# ------------------------------------------------------------------------------------------ rendering
def _schedule(iv: Interval, frames: np.ndarray):
    """Per track frame: the first source's frame, the second source's frame, the second's weight."""
    w = np.interp(frames, np.arange(iv.t0, iv.t1 + 1), iv.weights, left=0.0, right=1.0)
    moving_from = iv.kind.startswith("motion")
    moving_to = iv.kind.endswith("motion")
    fa = np.where((frames < iv.t0) | moving_from, frames, iv.t0).astype(np.float64)
    fb = np.where((frames > iv.t1) | moving_to, frames, iv.t1).astype(np.float64)
    return fa, fb, w


def _b_side(plan: Plan) -> Motion:
    """The lower body's second source on the next motion's frames: the placed motion, or for an adaptation
    the adapted one (S2, eqs. (7)/(9)), returned to its own over S3 (eq. (8)).

    The return fades the adaptation's deformation by the S3 weight (§4.4.2 cases (a)/(b)): the motion's own
    movement plays through it and the support foot stays put. Case (c) is the literal pose–pose blend of
    the adapted pose at ``t0`` and the motion's pose at ``t1``, planted feet pinned.
    """
    if plan.adapted is None:
        return plan.placed
    if "S3" not in plan.intervals:
        return plan.adapted
    iv = plan.intervals["S3"]
    off = plan.inc.offset
    a, b = iv.t0 - off, iv.t1 - off
    if iv.kind == "pose-motion":
        scale = np.ones(plan.placed.n_frames)
        scale[a:b + 1] = 1.0 - iv.weights
        scale[b + 1:] = 0.0
        return adapt(plan.placed, plan.info["adapt_offsets"], scale)
    n = b - a + 1
    frozen = sample(plan.adapted, np.full(n, float(a)))
    own = plan.placed[a:b + 1] if iv.kind.endswith("motion") else sample(plan.placed, np.full(n, float(b)))
    seg = blend(frozen, own, iv.weights)
    ref = plan.placed[a:b + 1]
    c = plan.inc.contacts
    seg = pin_feet(seg, ref, {s: c.of(s)[a:b + 1] for s in ("left", "right")})
    return concatenate([p for p in (plan.adapted[:a], seg, plan.placed[b + 1:]) if p.n_frames])


def _contacts_at(c: FootContacts, idx: np.ndarray) -> dict:
    i = np.clip(np.round(idx).astype(int), 0, len(c.left) - 1)
    return {"left": c.left[i], "right": c.right[i]}


#: m: a foot the two sides of a lower-body blend plant further apart than this has to step across
STEP_GAP = 0.06
#: the weights between which such a foot is in the air (it lifts from the first side's place once the
#: second has this share, and lands on the second's when it has that share)
STEP_WEIGHTS = (0.25, 0.75)


def _planted(a_comp: Motion, b_comp: Motion, ca: dict, cb: dict, w: np.ndarray, step: bool = True) -> dict:
    """Per foot, whether it is held on the ground on each frame of the window (for the foot locks).

    A foot is down where the side that holds at least :data:`~synthesis.transition.PLANTED_WEIGHT` of the
    blend has it down (the seed engine's rule) — except where the two sides plant it more than
    :data:`STEP_GAP` apart: one foot cannot stand in two places, so it stays on the first side's place
    until the second side has :data:`STEP_WEIGHTS` [0] of the blend, crosses in the air, and lands on
    the second side's place once that has [1] (a frozen pose planted somewhere else would otherwise hold
    the foot where the first motion left it, and let it go with a snap long after the blend). Only when
    a side is a held pose (``step``): where both motions play (a gait transition) their planted feet
    follow each other's rhythm and the seed engine's rule holds.
    """
    feet = body_map(a_comp.skeleton).feet
    pa, pb = a_comp.positions, b_comp.positions
    out = {}
    for s in ("left", "right"):
        ankle = feet[s][0]
        apart = (np.hypot(*(pa[:, ankle] - pb[:, ankle])[:, [0, 2]].T) > STEP_GAP) & step
        on_a = ca[s] & (1.0 - w >= PLANTED_WEIGHT) & ~(apart & (w > STEP_WEIGHTS[0]))
        on_b = cb[s] & (w >= PLANTED_WEIGHT) & ~(apart & (w < STEP_WEIGHTS[1]))
        out[s] = on_a | on_b
    return out


def render(tr: Motion, plan: Plan, lock: bool = True, step: bool = True):
    """Write a planned join onto the track: returns ``(track, locks, (w0, w1))``.

    The lower body of every frame of the window blends its two sources with the lower weight, the upper
    body its two with the upper weight; :func:`synthesis.transition.apply_join` then writes the window and
    the next motion after it and locks the planted feet (its blend is given the upper body already blended
    on both sides, so only the lower weight is left to it).
    """
    inc = plan.inc
    off = inc.offset
    ivs = plan.intervals
    w0 = min(iv.t0 for iv in ivs.values())
    w1 = max(iv.t1 for iv in ivs.values()) + 1
    frames = np.arange(w0, w1)
    bside = _b_side(plan)
    faL, fbL, wL = _schedule(ivs["S0"], frames)
    if "S3" in ivs:  # after S0 the lower body is the second source alone (adapted, then back, inside bside)
        fbL = np.where(frames > ivs["S0"].t1, frames, fbL)
    faU, fbU, wU = _schedule(ivs["S1"], frames)
    a_low, b_low = sample(tr, faL), sample(bside, fbL - off)
    up = blend(sample(tr, faU), sample(bside, fbU - off), wU)
    upper = part_joints(tr, "upper")

    def with_upper(m: Motion) -> Motion:
        r = m.rotations.copy()
        r[:, upper] = up.rotations[:, upper]
        return m.replace(rotations=r)

    a_comp, b_comp = with_upper(a_low), with_upper(b_low)
    tr_c = detect_contacts(tr)
    b_c = detect_contacts(bside)
    ca = _contacts_at(tr_c, faL)
    cb = _contacts_at(b_c, fbL - off)
    tail = bside[w1 - off:]
    placed_b = concatenate([b_comp, tail]) if tail.n_frames else b_comp
    b_contacts = FootContacts(tr.fps, *(np.concatenate([cb[s], b_c.of(s)[w1 - off:]]) for s in ("left", "right")))
    planted = _planted(a_comp, b_comp, ca, cb, wL, step=step and ivs["S0"].kind != "motion-motion")
    join = Join(plan.choice.method, plan.rigid, w0, (w0, w1), frames.astype(np.float64),
                np.arange(w1 - w0, dtype=np.float64), wL, planted, ca)
    track = concatenate([p for p in (tr[:w0], a_comp) if p.n_frames])
    out, locks = apply_join(track, placed_b, b_contacts, join, lock=lock)
    return out, locks, (w0, w1)


#: m: a support foot the locks leave further than this from the next motion's own is re-placed (settle)
SETTLE = 0.005


def settle(out: Motion, locks, window: tuple[int, int], plan: Plan) -> Plan | None:
    """The plan with the next motion slid so that its support foot stands where the join's lock left it.

    A foot locked through the blend follows the planted sources' weighted movement (a heel rolling
    off in the first motion, a landing in the next), so where the lock lets it go, after the blend, can
    differ by a few centimetres from where the next motion itself has that foot — and the release would
    then bend the next motion's leg inside its core. Moving the next motion by that difference lets its own
    foot take over exactly: a slide on the ground, and a lift or drop where the two clips stand on
    different floors (captures of two people played on one skeleton: the next clip's feet may float or
    sink by centimetres, the locked foot stands on the first clip's floor). Connections and transitions only (an adaptation's
    feet are the first motion's by construction). ``None`` when nothing needs to move.
    """
    if plan.adapted is not None or not locks:
        return None
    after = [lk for lk in locks if lk.end > window[1]]
    mine = [lk for lk in after if lk.side == plan.support] or after
    if not mine:
        return None
    lk = max(mine, key=lambda x: x.end)
    f = lk.end - 1
    own = f - plan.inc.offset
    if not 0 <= own < plan.placed.n_frames:
        return None
    ankle, toe = body_map(out.skeleton).feet[lk.side]
    d = out.positions[f, ankle] - plan.placed.positions[own, ankle]
    # the height from the foot's lowest point: a locked flat foot against the next clip's raised heel
    # (a dancer on the ball of the foot) is the same floor, not a sinking clip
    d[1] = out.positions[f, [ankle, toe], 1].min() - plan.placed.positions[own, [ankle, toe], 1].min()
    if np.linalg.norm(d) < SETTLE:
        return None
    rigid = plan.rigid.then(Rigid(0.0, (float(d[0]), float(d[2]))))
    placed = rigid.apply(plan.inc.motion)
    placed = placed.replace(root_positions=placed.root_positions + np.array([0.0, d[1], 0.0]))
    info = dict(plan.info, settled_cm=[round(100 * float(x), 2) for x in d])
    return replace(plan, rigid=rigid, placed=placed, info=info)


# ---------------------------------------------------------------------------------------------- engine
def report_of(prev: Placed, inc: Incoming, plan: Plan, fps: float, locks) -> JoinReport:
    """The join's :class:`~synthesis.plan.JoinReport` (timetable.md §2)."""
    e = inc.element
    method = "connection" if inc.rep > 0 else e.method
    order = {"S0": 0, "S1": 1, "S3": 2}
    intervals = tuple(BlendInterval(iv.part, iv.kind, iv.t0 / fps, iv.t1 / fps)
                      for iv in sorted(plan.intervals.values(), key=lambda iv: order[iv.name]))
    info = _public(plan.info)
    if inc.rep > 0:
        info["repetition"] = inc.rep
    if locks:
        info["foot_locks"] = [{"side": lk.side, "begin": lk.begin / fps, "end": lk.end / fps,
                               "release_end": lk.release_end / fps} for lk in locks]
    return JoinReport(prev.element.id, e.id, method, plan.choice.method, intervals, plan.cost(), info,
                      tuple(plan.warnings))


def _eased(plan: Plan) -> Plan:
    """The plan with the lower-body blend S0's weight eased (quintic, zero slope and curvature at both ends)
    instead of eq. (16)'s Hermite — see :func:`_carry_out`."""
    iv = plan.intervals["S0"]
    w = ease(np.linspace(0.0, 1.0, iv.t1 - iv.t0 + 1), "smooth")
    return replace(plan, intervals={**plan.intervals, "S0": replace(iv, weights=w, case=iv.case + "+eased")})


def _roots_mid(tr: Motion, plan: Plan) -> Plan:
    """A motion–motion blend's next motion placed by the roots where the weight passes one half (instead of
    through the support foot): two roots moving at different speeds are then apart by as much at the end
    of the blend as at its start, in opposite directions, and the mix does not surge."""
    iv = plan.intervals["S0"]
    tm = iv.t0 + int(np.argmin(np.abs(iv.weights - 0.5)))
    own = int(np.clip(tm - plan.inc.offset, 0, plan.inc.motion.n_frames - 1))
    rigid = align_through_foot(tr, int(np.clip(tm, 0, tr.n_frames - 1)), plan.inc.motion, own, None)
    info = dict(plan.info, align_frames_s=[tm / tr.fps, tm / tr.fps], support=None)
    return replace(plan, rigid=rigid, placed=rigid.apply(plan.inc.motion), support=None, info=info)


def _skating(motion: Motion, lo: int, hi: int) -> float:
    """Skating ratio (both feet low and fast, :func:`synthesis.engine.skating_frames`) over ``[lo, hi)``."""
    sk = skating_frames(motion)
    return float(sk[max(lo, 0):hi].mean()) if hi > lo else 0.0


def _carry_out(tr: Motion, plan: Plan, lock: bool):
    """Render a plan — and make sure the join does not skate.

    The plan is rendered as the paper has it (eq. (16) weights, a foot held by a frozen pose stepping
    across, :func:`_planted`), then settled (:func:`settle`). If its blend still skates (a run
    pulled into a standing pose: the mixed hips overshoot where the two motions' roots are far apart and
    the weight is steep at an end), the join is rendered again without the step, then with S0's weight
    eased to zero slope at both ends, then both; the first that does not skate is kept (else the one that
    skates least), and the report says which (``fallback``). When none of those is clean, the same is
    tried with the next-best lower-body intervals of eq. (10) (:data:`RUNNERS_UP` of them): the search's
    minimum subject to the join keeping its feet. Deterministic.
    """
    best = None
    variants = [("", True, False), ("no_step", False, False), ("eased", True, True), ("eased_no_step", False, True)]
    if plan.intervals["S0"].kind == "motion-motion":
        variants.append(("roots_mid", False, False))
    candidates = [("", plan)] + [(f"next_best_{k + 1}", replace(plan, intervals={**plan.intervals, "S0": iv}))
                                 for k, iv in enumerate(plan.alternatives)]
    for cname, cand in candidates:
        for vname, step, eased in variants:
            p = _eased(cand) if eased else (_roots_mid(tr, cand) if vname == "roots_mid" else cand)
            out, locks, window = render(tr, p, lock, step)
            moved = settle(out, locks, window, p)
            if moved is not None:  # placed where the locked foot stands: the next motion's own step needs no release
                p = moved
                out, locks, window = render(tr, p, lock, step)
            sk = _skating(out, window[0], window[1]) if lock else 0.0  # the blend (the clips' own skating after
            # it, a jump's landing, is not the join's to fix)
            name = "+".join(x for x in (cname, vname) if x)
            if name:
                p = replace(p, info=dict(p.info, fallback=name))
            if best is None or sk < best[0]:
                best = (sk, p, out, locks, window)
            if sk == 0.0:
                _, p, out, locks, window = best
                return p, out, locks, window
    _, p, out, locks, window = best
    return p, out, locks, window


def join_next(state: TrackState, inc: Incoming, fps: float, weights: Weights, lock: bool = True,
              min_blend: float = MIN_BLEND, allow_shift: bool = True) -> Plan | Skip:
    """Join ``inc`` to the track's last element (plan, render, report); a :class:`Skip` leaves the track as it was."""
    prev = state.placed[-1]
    tr = extend(state.motion, inc.offset + inc.motion.n_frames, state.floor)
    plan = plan_join(tr, prev, inc, fps, weights, state.floor, min_blend, allow_shift)
    e = inc.element
    if isinstance(plan, Skip):
        state.skipped[e.id] = plan.reason
        state.warnings.append(plan.reason)
        rep = JoinReport(prev.element.id, e.id, "connection" if inc.rep > 0 else e.method, "not_executed", (),
                         None, {}, (plan.reason,))
        state.joins.append((rep, None, prev, None, []))
        return plan
    inc = plan.inc
    plan, out, locks, window = _carry_out(tr, plan, lock)
    region_end = max([window[1]] + [lk.release_end for lk in locks])
    state.motion = out
    state.floor = window[1]
    if plan.shift:  # this element only: later ones keep their scheduled times
        state.delays.append((e.id, plan.shift / fps))
    core = inc.core
    if inc.cyclic:  # a looped clip is all core: the join is taken out of it
        core = (max(core[0], region_end - inc.offset), core[1])
    if prev.cyclic:
        prev.core = (prev.core[0], min(prev.core[1], window[0] - prev.offset))
    shown = replace(e, start=inc.first / fps, end=inc.end / fps) if (plan.shift or plan.phase) else e
    p = Placed(shown, plan.placed, inc.offset, core, inc.contacts, inc.cyclic, plan.rigid, inc.rep, inc.lead,
               inc.stop)
    state.placed.append(p)
    state.warnings.extend(plan.warnings)
    rep = report_of(prev, inc, plan, fps, locks)
    ivs = plan.intervals
    main = (min(ivs[n].t0 for n in ("S0", "S1")), max(ivs[n].t1 for n in ("S0", "S1")) + 1)
    # S0/S1 blend the two motions: their jerk and skating are the join's; the return to the next motion's own
    # lower body (S3) plays that motion's own step, its figures are in the region's
    state.joins.append((rep, (main, (window[0], region_end)), prev, p, []))
    return plan


def lay_track(track: Track, whole: Sequence[Element], fps: float, weights: Weights, lock: bool = True,
              min_blend: float = MIN_BLEND) -> Laid:
    """The whole-body elements of one track joined by optimal blending (see the module docstring)."""
    return lay_elements(track, whole, fps, lambda state, inc: join_next(state, inc, fps, weights, lock, min_blend))


def synthesize_optimal(tracks: Sequence[Track], fps: float = 30.0, smoothness: float = 0.5, *,
                       lock_feet: bool = True, sway: bool = True, spread: bool = True,
                       min_blend: float = MIN_BLEND) -> Result:
    """Tracks → one motion per actor by optimal blending (paper 000), compositions as the seed engine does.

    Args:
        tracks: one :class:`~synthesis.plan.Track` per actor.
        fps: output frame rate.
        smoothness: ``W`` of §4.3, 0 (time first: short blends) to 1 (smoothness first).
        lock_feet: lock planted feet during blends.
        sway: transfer the sway of composed clips.
        spread: give actors sharing one origin :func:`~synthesis.engine.default_origins`.
        min_blend: the shortest blend interval, seconds.

    Returns the same :class:`~synthesis.engine.Result` as :func:`synthesis.engine.synthesize`; each join's
    report has ``blend`` (the §4.1 method), ``intervals`` (lower/upper, kinds), ``cost`` (eq. (10) terms).
    """
    weights = preset(smoothness)
    if spread:
        tracks = spread_actors(tracks)

    def lay(track: Track, whole):
        return lay_track(track, whole, fps, weights, lock_feet, min_blend)

    return assemble(tracks, fps, lay, sway, post=lock_feet)

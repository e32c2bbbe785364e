"""Motion connection (動作接続, paper 003 §4.3): Connection and Transition joins.

Both joins take the track built so far (the first motion ``A`` is on it) and
the next element's prepared clip ``B``, and decide a :class:`Join`: where
``B`` is placed (a :class:`~core.ground.Rigid` through the support foot
and a frame offset on the track), the blend window, which frame of each
motion every window frame shows (a time warp for transitions) and the blend
weights. :func:`synthesis.join.apply.apply_join` (the join layer every engine shares) then writes it and
locks the feet.

**Connection** (§4.3.1–4.3.2): switching frames ``a`` near the end of ``A``
(after its core) and ``b`` near the start of ``B`` (before its core) with the
same foot contact, at least one foot down in both
(:func:`synthesis.constraint.switching.find_switch`); ``B`` is aligned through that
foot. With a delay (``B`` starts later than :data:`HOLD_GAP` s after ``A``
ends) ``A``'s pose at ``a`` stands until the blend, which is centred on ``b``
where ``B`` is scheduled. Without one, ``B`` is moved in time so that ``b``
falls on ``a`` (``shift_s`` in the report; ``phase_s`` for a looped ``B``,
which enters at another phase but still ends when scheduled) and the blend is
centred there.
Either way both motions play their own frames through the blend — a clip
only ever holds its first or last frame, easing into and out of it
(:func:`synthesis.join.timing.soft_clip`), never a frame in mid-motion — and the
blend never enters a core unless the cores leave no room for
:data:`MIN_BLEND` s (a warning then says so). A looped ``B`` may start at
any phase, so only where the switch falls costs time.

**Transition** of two cyclic motions (walk → run): the key frames of both,
foot lift and foot land (:func:`synthesis.join.gait.steps`); a swing of the
same foot is taken in each, both near the scheduled overlap; both swings
are time-warped onto one of their mean length and blended lift to land.
``B`` is aligned through the stance foot at the lift (its root when that
foot is not down in both) and continues from its landing frame: a looped
clip simply enters at another phase (``phase_s``). A transition of motions
that are not both cyclic (run → kick) is a connection at the footstep:
switching frames as for a connection, chosen nearest to the scheduled
overlap, and a blend as long as the overlap (at least :data:`MIN_BLEND` s).

Feet: locked and lifted as for every engine (:mod:`synthesis.join.apply`).

Choices where the paper is silent (constants below): connection blend
:data:`CONNECTION_BLEND` s, at least :data:`MIN_BLEND` s for any blend;
switching frames searched in the last/first :data:`SEARCH` s; weights of the
``smooth`` profile (:data:`synthesis.join.apply.PROFILE`); clips ease into a held frame
over :data:`synthesis.join.timing.KNEE` s.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.motion import Motion

from ..join.align import align_through_foot
from ..join.apply import PROFILE, Join, contacts_at, planted_in_blend
from ..join.blend import ramp
from ..join.gait import steps
from ..join.placed import Placed
from ..join.timing import KNEE, soft_clip
from .switching import find_switch

CONNECTION_BLEND = 0.5  # s
HOLD_GAP = 0.1  # s: a connection whose second motion starts later than this after the first ends holds a pose
HOLD_LIFTED_COST = 0.2  # s-equivalent: a held pose should have both feet down when A has such a frame
MIN_BLEND = 0.3  # s
SEARCH = 1.0  # s searched for switching frames at the end of A / start of B


def _blend_kind(src: np.ndarray) -> str:
    return "pose" if len(src) < 2 or np.ptp(src) < 1e-9 else "motion"


def connection(track: Motion, a: Placed, b: Placed, fps: float, overlap: bool = False,
               blend_seconds: float = CONNECTION_BLEND, floor: int = 0) -> Join:
    """A Connection (or, with ``overlap``, a transition at the footstep) of ``a`` and ``b``.

    ``track`` holds ``A`` (``a.motion`` is ``A`` as placed, its frame 0 at track frame
    ``a.offset``); ``b.offset`` is where ``B``'s frame 0 would be as scheduled.
    Nothing before track frame ``floor`` (the end of the join into ``A``) is rewritten.

    Two cases:

    - **a delay** (``B`` starts more than :data:`HOLD_GAP` s after ``A`` ends): ``A``
      plays to ``a`` — its last frame, unless an earlier one in its last second
      has both feet down (:data:`HOLD_LIFTED_COST`) or that one has no planted
      foot in common with ``B``'s start — and that pose stands; ``b`` is
      searched near ``B``'s start for the same contact; the blend is centred on
      ``b`` where ``B`` is scheduled, ``B`` playing its own frames through it.
    - **no delay, or an overlap** (a footstep): ``a`` and ``b`` are searched
      together and ``B`` is moved in time so that ``b`` falls on ``a``; the
      blend is centred there, both motions playing their own frames through it
      (no pose is frozen mid-motion; a clip only holds its first or last frame).
    """
    warnings = []
    nA, nB = a.stop, b.motion.n_frames
    search = max(2, int(round(SEARCH * fps)))
    gap = b.first - a.end
    hold_mode = not overlap and gap > HOLD_GAP * fps
    # after A's core and before B's (a looped clip is all core: its last / first second then), leaving
    # room for half a blend on the core's side; failing a common planted foot there, closer to the cores,
    # then anywhere in the last / first second
    half = int(round(0.5 * blend_seconds * fps))
    a_core = 0 if a.cyclic else a.core[1] - 1
    a_floor = floor - a.offset + (0 if hold_mode else half)
    b_core = nB if b.cyclic else b.core[0] + 1
    levels = []
    for a_room, b_room in ((half, half), (0, 0), (None, None)):
        a_lim = max(0, a_floor) if a_room is None else max(a_core + a_room, a_floor, 0)
        a_lo = min(max(nA - search, a_lim), nA - 1)
        b_lim = nB if b_room is None else b_core - b_room
        b_hi = max(b.lead + 1, min(b.lead + search, b_lim, nB))
        levels.append(((a_lo, nA), (b.lead, b_hi)))

    def time_cost(ai, bj):
        if hold_mode:  # A's pose at a stands (frames after a are dropped); B's frames before b still play;
            # a pose with a foot in the air is a poor one to stand in
            lifted = ~(a.contacts.left[ai] & a.contacts.right[ai])
            return (nA - 1 - ai) / fps + (bj - b.lead) / fps + HOLD_LIFTED_COST * lifted
        ta, tb = a.offset + ai, b.offset + bj
        if b.cyclic:  # a loop may start at any phase: only where the switch falls matters
            return np.abs(ta - b.first) / fps + 0 * bj
        return np.abs(tb - ta - max(gap, 0)) / fps  # how far B moves from its schedule

    sw = None
    for a_range, b_range in levels:
        found = find_switch(a.motion, a.contacts, a_range, b.motion, b.contacts, b_range, time_cost)
        sw = sw or found
        if found.support is not None:
            sw = found
            break
    assert sw is not None  # levels is never empty
    ta = a.offset + sw.a
    rigid = align_through_foot(track, ta, b.motion, sw.b, sw.support)
    if hold_mode:
        offset, centre = b.offset, b.offset + sw.b
        L = blend_seconds
    else:
        offset, centre = ta - sw.b, ta
        L = float(np.clip((a.end - b.first) / fps, MIN_BLEND, blend_seconds)) if overlap else blend_seconds
    span = max(int(round(L * fps)), 2)
    w0 = int(round(centre - span / 2))
    w1 = w0 + span
    lo = a.offset + (0 if a.cyclic else a.core[1])  # never blend inside a core (a looped clip's: its whole cycles)
    hi = offset + (nB if b.cyclic else b.core[0])
    c0, c1 = max(w0, lo, floor), min(w1, hi)
    shortest = max(int(round(MIN_BLEND * fps)), 2)
    if c1 - c0 >= min(shortest, span):
        w0, w1 = c0, c1
    else:  # a blend this short would be a pop: it goes into the core instead
        w0 = max(w0, floor)
        w1 = max(w1, w0 + shortest)
        warnings.append("the cores leave no room for a blend; it overlaps a core")
    w0 = max(w0, 0)
    w1 = max(w1, w0 + 2)
    a_stop = sw.a + 1 if hold_mode else a.motion.n_frames  # a delay ends A at its switching frame
    # A is re-timed from where it starts easing to its last frame (never frozen mid-motion)
    k = KNEE * fps
    a_from = int(np.clip(np.floor(a.offset + a_stop - 1 - k), min(floor, w0), w0))
    src_a_all = a.offset + soft_clip(np.arange(a_from, w1) - a.offset, 0, a_stop - 1, k)
    pre = src_a_all[:w0 - a_from]
    src_a = src_a_all[w0 - a_from:]
    frames = np.arange(w0, w1)
    src_b = soft_clip(frames - offset, 0, nB - 1, k)
    w = ramp(w1 - w0, PROFILE)
    ca = contacts_at(a.contacts, src_a - a.offset)
    cb = contacts_at(b.contacts, src_b)
    kind = f"{_blend_kind(src_a)}-{_blend_kind(src_b)}"
    info = {"switch_first_s": ta / fps, "switch_second_s": (offset + sw.b) / fps, "support": sw.support,
            "same_state": sw.exact, "other_foot_gap_cm": 100 * sw.other_gap,
            "phase_s" if b.cyclic else "shift_s": (offset - b.offset) / fps,
            "held_s": max(0, w0 - (a.offset + nA)) / fps if hold_mode else 0.0}
    return Join("footstep" if overlap else "connection", rigid, offset, (w0, w1), src_a, src_b, w,
                planted_in_blend(ca, cb, w), ca, (("whole", kind, w0, w1),), tuple(warnings), info, pre)


def transition(track: Motion, a: Placed, b: Placed, fps: float, floor: int = 0) -> Join:
    """A Transition: cyclic ``a`` → cyclic ``b`` blended over one time-warped swing; a footstep
    connection when either is not cyclic or no swing of the same foot exists in both."""
    if not (a.cyclic and b.cyclic):
        return connection(track, a, b, fps, overlap=True, floor=floor)
    sa = [s for s in steps(a.contacts) if floor <= a.offset + s.begin < track.n_frames]
    sb = steps(b.contacts)
    pairs = [(x, y) for x in sa for y in sb if x.side == y.side]
    if not pairs:
        return connection(track, a, b, fps, overlap=True, floor=floor)
    s2 = b.first  # the scheduled overlap starts here; both lifts should be near it

    def cost(p):
        x, y = p
        t_a = abs(a.offset + x.begin - s2) / fps
        t_b = abs(b.offset + y.begin - s2) / fps
        warp = abs(np.log(x.frames / y.frames))
        return t_a + t_b + 0.5 * warp

    x, y = min(pairs, key=cost)
    D = max(2, int(round(0.5 * (x.frames + y.frames))))
    stance = "left" if x.side == "right" else "right"
    t_lift = a.offset + x.begin
    sup_a = a.contacts.of(stance)[x.begin]
    sup_b = b.contacts.of(stance)[y.begin]
    rigid = align_through_foot(track, t_lift, b.motion, y.begin, stance if (sup_a and sup_b) else None)
    u = np.arange(D) / D  # the time warp: both swings run from lift (u = 0) towards landing (u = 1)
    src_a = t_lift + u * x.frames
    src_b = y.begin + u * y.frames
    w0, w1 = t_lift, t_lift + D
    offset = w1 - y.end  # B continues from its landing frame
    w = ramp(D, PROFILE)
    ca = contacts_at(a.contacts, src_a - a.offset)
    cb = contacts_at(b.contacts, src_b)
    info = {"key_frames_first_s": ((a.offset + x.begin) / fps, (a.offset + x.end) / fps),
            "key_frames_second_s": (y.begin / fps, y.end / fps), "swing_foot": x.side,
            "phase_s": (offset - b.offset) / fps, "warp_first": D / x.frames, "warp_second": D / y.frames}
    return Join("transition", rigid, offset, (w0, w1), src_a, src_b, w, planted_in_blend(ca, cb, w), ca,
                (("whole", "motion-motion", w0, w1),), (), info)

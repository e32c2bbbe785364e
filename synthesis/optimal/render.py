"""Step 6, rendering: a planned join written onto the track, lower and upper body blended by their own
weights (slerp), planted feet held (a foot two held poses plant apart steps across), locks by
:func:`synthesis.join.apply.apply_join` (a rendering in two steps: :func:`prepare`, then :func:`finish`)."""
from __future__ import annotations

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import FootContacts, detect_contacts
from text2anim.core.motion import Motion, concatenate

from .adaptation import adapt, pin_feet
from ..join.blend import blend, sample
from .posedist import part_joints
from ..join.apply import PLANTED_WEIGHT, Blended, Join, blend_join, contacts_at, lock_join
from .weights import hermite_weights
from .records import Interval, Plan


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

    The return fades the adaptation's deformation over S3 (§4.4.2 cases (a)/(b)): the motion's own
    movement plays through it and the support foot stays put. Both ends of that fade play the motion's own
    movement (the deformation held through S2, none after), so what eq. (16) matches there is the
    deformation's own speed, 0: the fade is the Hermite curve with zero slopes at both ends (S3's eq. (16)
    weights, taken from the speeds of the whole poses, would start and stop moving the hips by the
    deformation with a jump in their velocity: a root pop at S3's ends, inside the next motion's core).
    The hips' path through the return is then bent by the join post-pass (:mod:`synthesis.join.hipspath`,
    a departure from eq. (8) written there). Case (c) is the literal pose–pose blend of the adapted pose at ``t0`` and the motion's pose at ``t1``,
    planted feet pinned.
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
        scale[a:b + 1] = 1.0 - hermite_weights(b - a, 0.0, 0.0)  # eq. (16) with the deformation's speed, 0
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


#: m: a foot the two sides of a lower-body blend plant further apart than this has to step across
STEP_GAP = 0.06
#: the weights between which such a foot is in the air (it lifts from the first side's place once the
#: second has this share, and lands on the second's when it has that share)
STEP_WEIGHTS = (0.25, 0.75)


def _planted(a_comp: Motion, b_comp: Motion, ca: dict, cb: dict, w: np.ndarray, step: bool = True) -> dict:
    """Per foot, whether it is held on the ground on each frame of the window (for the foot locks).

    A foot is down where the side that holds at least :data:`~synthesis.join.apply.PLANTED_WEIGHT` of the
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


class Parts:
    """What the renderings of one join share (:func:`synthesis.optimal.repair.carry_out` renders a join up
    to ~16 times: variants of the lower-body weights, the steps, the placement): every sampled, blended or
    composed motion of :func:`prepare` and :func:`blended`, made once per distinct input and reused (the
    same objects, so their kinematics are computed once too). Keys name their inputs by value, and the
    motions among them by the motion itself (immutable, compared by identity: the key holds it, so it
    lives as long as this cache); one cache per track ``tr``."""

    def __init__(self) -> None:
        self._made: dict = {}

    def get(self, key: tuple, make):
        """The value made for ``key`` (``make()`` the first time)."""
        hit = self._made.get(key)
        if hit is None:
            hit = self._made[key] = make()
        return hit

    def sample(self, motion: Motion, frames: np.ndarray) -> Motion:
        """:func:`synthesis.join.blend.sample` of a motion this cache holds (or the track)."""
        f = np.asarray(frames, dtype=np.float64)
        return self.get(("sample", motion, f.tobytes()), lambda: sample(motion, f))


def _bside_of(plan: Plan, parts: Parts) -> Motion:
    """:func:`_b_side`, once per placed motion, adaptation and S3."""
    s3 = plan.intervals.get("S3")
    key = ("bside", plan.placed, plan.adapted,
           None if s3 is None else (s3.t0, s3.t1, s3.kind, np.asarray(s3.weights).tobytes()))
    return parts.get(key, lambda: _b_side(plan))


def prepare(tr: Motion, plan: Plan, step: bool = True, tr_contacts: FootContacts | None = None,
            parts: Parts | None = None):
    """What :func:`render` hands :func:`synthesis.join.apply.apply_join`: ``(track, placed_b, b_contacts,
    join)`` — the window's two sides composed and the feet it holds (the cheap part of a rendering:
    :func:`render`'s output is a function of these alone). ``parts``: what earlier renderings on ``tr``
    made (:class:`Parts`)."""
    parts = Parts() if parts is None else parts
    inc = plan.inc
    off = inc.offset
    ivs = plan.intervals
    w0 = min(iv.t0 for iv in ivs.values())
    w1 = max(iv.t1 for iv in ivs.values()) + 1
    frames = np.arange(w0, w1)
    bside = _bside_of(plan, parts)
    faL, fbL, wL = _schedule(ivs["S0"], frames)
    if "S3" in ivs:  # after S0 the lower body is the second source alone (adapted, then back, inside bside)
        fbL = np.where(frames > ivs["S0"].t1, frames, fbL)
    faU, fbU, wU = _schedule(ivs["S1"], frames)
    a_low, b_low = parts.sample(tr, faL), parts.sample(bside, fbL - off)
    ua, ub = parts.sample(tr, faU), parts.sample(bside, fbU - off)
    up = parts.get(("blend", ua, ub, wU.tobytes()), lambda: blend(ua, ub, wU))
    upper = part_joints(tr, "upper")

    def with_upper(m: Motion) -> Motion:
        def make() -> Motion:
            r = m.rotations.copy()
            r[:, upper] = up.rotations[:, upper]
            return m.replace(rotations=r)
        return parts.get(("upper", m, up), make)

    a_comp, b_comp = with_upper(a_low), with_upper(b_low)
    tr_c = tr_contacts if tr_contacts is not None else detect_contacts(tr)
    b_c = detect_contacts(bside)  # kept in bside's cache
    ca = contacts_at(tr_c, faL)
    cb = contacts_at(b_c, fbL - off)
    planted = _planted(a_comp, b_comp, ca, cb, wL, step=step and ivs["S0"].kind != "motion-motion")
    tail_from = w1 - off

    def make_placed_b() -> Motion:
        tail = bside[tail_from:]
        return concatenate([b_comp, tail]) if tail.n_frames else b_comp  # (both poses known: so is its)
    placed_b = parts.get(("placed_b", b_comp, bside, tail_from), make_placed_b)
    b_contacts = FootContacts(tr.fps, *(np.concatenate([cb[s], b_c.of(s)[w1 - off:]]) for s in ("left", "right")))
    join = Join(plan.choice.method, plan.rigid, w0, (w0, w1), frames.astype(np.float64),
                np.arange(w1 - w0, dtype=np.float64), wL, planted, ca)
    track = parts.get(("track", a_comp, w0),
                      lambda: concatenate([p for p in (tr[:w0], a_comp) if p.n_frames]))
    return track, placed_b, b_contacts, join


def finish(prepared, lock: bool = True, blended: Blended | None = None, lift: bool = True):
    """:func:`render` from :func:`prepare` 's output (and its :func:`blended` when the caller has it):
    ``(track, locks, (w0, w1))``; ``lift=False``: the swings not yet lifted
    (:func:`synthesis.join.apply.lift_join` finishes it; the locked feet are final already)."""
    track, placed_b, b_contacts, join = prepared
    if blended is None:
        blended = blend_join(track, placed_b, join)
    out, locks = lock_join(blended, b_contacts, join, lift) if lock else (blended.out, [])
    return out, locks, join.window


def blended(prepared, parts: Parts | None = None) -> Blended:
    """The join of :func:`prepare` 's output written, its feet not yet locked: the root is already final.
    ``parts``: the :class:`Parts` that prepared it (its samples of the two sides are reused)."""
    track, placed_b, _, join = prepared
    if parts is None:
        return blend_join(track, placed_b, join)
    # the blend asks nothing of the feet the join holds: renderings that differ only in those (the step)
    # share it
    key = ("blended", track, placed_b, join.window, join.offset, join.src_a.tobytes(), join.src_b.tobytes(),
           np.asarray(join.weights).tobytes(), None if join.pre is None else join.pre.tobytes())
    return parts.get(key, lambda: blend_join(track, placed_b, join, parts.sample))


def render(tr: Motion, plan: Plan, lock: bool = True, step: bool = True, tr_contacts: FootContacts | None = None):
    """Write a planned join onto the track: returns ``(track, locks, (w0, w1))``. ``tr_contacts``: the
    track's foot contacts when the caller has them (:func:`carry_out` renders one track several times).

    The lower body of every frame of the window blends its two sources with the lower weight, the upper
    body its two with the upper weight; :func:`synthesis.join.apply.apply_join` then writes the window and
    the next motion after it and locks the planted feet (its blend is given the upper body already blended
    on both sides, so only the lower weight is left to it). In two steps, :func:`prepare` and :func:`finish`.
    """
    return finish(prepare(tr, plan, step, tr_contacts), lock)

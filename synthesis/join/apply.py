"""A join decided as a blend window (:class:`Join`), and written into the track (:func:`apply_join`).

Every engine decides a join its own way — paper 003's Connection and Transition
(:mod:`synthesis.constraint.connection`), optimal blending's intervals (:mod:`synthesis.optimal.render`), the
baselines' fixed crossfades — as the same record: where the next motion ``B`` is placed, the blend window,
which frame of each motion every window frame shows, and the weights. Writing it is shared:
:func:`blend_join` (the track up to the window, the blend, then all of placed ``B``) and :func:`lock_join`
(planted feet locked by :mod:`synthesis.join.footlock`, paper 003 §4.3.2; feet the blend carries through the
air lifted clear of the floor, :func:`lift_join`).

A foot counts as planted in the blend where a motion holding at least :data:`PLANTED_WEIGHT` of the weight
has it down (:func:`planted_in_blend`), and past the blend where ``B`` has it down; planted runs that touch
the blend are locked and released in the air. Frames are track frames unless said.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import FootContacts, runs
from text2anim.core.ground import Rigid
from text2anim.core.motion import Motion, concatenate

from .blend import blend, sample
from .footlock import FootLocks, Lock, lift_swings, lock_feet, plan_locks, reachable_locks
from .timing import hold

#: The weight profile of joins' blends and of the feet's locks (:mod:`synthesis.join.blend`).
PROFILE = "smooth"
#: In a blend a foot counts as planted when a motion holding at least this weight has it on the ground.
PLANTED_WEIGHT = 0.25


@dataclass(frozen=True)
class Join:
    """What an engine decided about one join (all frames are track frames unless said).

    Attributes:
        kind: paper 003's ``connection``, ``transition`` (cyclic, time-warped) or ``footstep`` (a transition
            joined as a connection at the footstep); optimal blending's §4.1 method; ``pose`` / ``crossfade``.
        rigid: the move that places ``B``.
        offset: the track frame of ``B``'s frame 0.
        window: ``[w0, w1)`` the blend.
        src_a: ``(n,)`` fractional track frames ``A`` shows in the window.
        src_b: ``(n,)`` fractional frames of (placed) ``B`` in the window.
        weights: ``(n,)`` weight of ``B``, or ``(n, J)`` per joint (e.g. lower and upper body
            blended over different spans); the feet follow joint 0's (the hips').
        planted: per side, ``(n,)`` whether the foot is down in the motion that dominates the window.
        planted_a: per side, ``(n,)`` whether it is down in ``A`` as shown in the window.
        intervals: ``(part, kind, begin, end)`` frames for the report.
        pre: fractional track frames ``A`` shows just before the window, where it eases into
            its held last frame (``None``: the track is kept as it is up to the window).
        warnings: what could not be honoured.
        info: the engine's notes for the report (switching frames, shift, phase...).
    """

    kind: str
    rigid: Rigid
    offset: int
    window: tuple[int, int]
    src_a: np.ndarray
    src_b: np.ndarray
    weights: np.ndarray
    planted: dict
    planted_a: dict
    intervals: tuple = ()
    warnings: tuple[str, ...] = ()
    info: dict = field(default_factory=dict)
    pre: np.ndarray | None = None

    @property
    def retimed_from(self) -> int:
        """First track frame the join rewrites: ``A`` eases to its end over ``pre`` before the window."""
        return self.window[0] - (0 if self.pre is None else len(self.pre))


def contacts_at(contacts: FootContacts, frames: np.ndarray) -> dict[str, np.ndarray]:
    """Per side, whether the foot is down at the (fractional, rounded, clipped) ``frames``, ``(n,)`` bool."""
    idx = np.clip(np.round(frames).astype(int), 0, len(contacts.left) - 1)
    return {"left": contacts.left[idx], "right": contacts.right[idx]}


def planted_in_blend(ca: dict, cb: dict, w: np.ndarray) -> dict:
    """Per side, ``(n,)``: the foot is down in a motion that holds at least :data:`PLANTED_WEIGHT` of the
    blend (``w`` the weight of ``B``; ``ca``, ``cb`` the contacts of ``A`` and ``B`` over the window)."""
    return {s: (ca[s] & (1.0 - w >= PLANTED_WEIGHT)) | (cb[s] & (w >= PLANTED_WEIGHT)) for s in ("left", "right")}


def apply_join(track: Motion, placed_b: Motion, b_contacts: FootContacts, join: Join,
               lock: bool = True) -> tuple[Motion, list[Lock]]:
    """Write a join: the track up to the window, the blend, then all of placed ``B``; feet locked.

    Returns the new track (it ends with ``B``'s last frame) and the locks applied. In two steps:
    :func:`blend_join` and :func:`lock_join`.
    """
    blended = blend_join(track, placed_b, join)
    if not lock:
        return blended.out, []
    return lock_join(blended, b_contacts, join)


@dataclass(frozen=True)
class Blended:
    """A join written but its feet not yet locked (:func:`blend_join`): ``out`` the new track; ``a_w``,
    ``b_line`` the first source over the window and the second from the window on (for the locks' targets).
    Locking changes only joint rotations: ``out``'s root positions are the final track's."""

    out: Motion
    a_w: Motion
    b_line: Motion


def blend_join(track: Motion, placed_b: Motion, join: Join, sampler=sample) -> Blended:
    """The first half of :func:`apply_join`: the track up to the window, the blend, then all of placed ``B``.
    ``sampler``: :func:`synthesis.join.blend.sample` or one that remembers what it sampled."""
    w0, w1 = join.window
    if w0 > track.n_frames:  # B starts after everything so far: hold the last frame until then
        track = hold(track, w0)
    a_w = sampler(track, join.src_a)
    b_w = sampler(placed_b, join.src_b)
    mix = blend(a_w, b_w, join.weights)
    for m in (a_w, b_w, mix):  # the window's kinematics (the locks ask for them): the tracks concatenated
        m.pose  # from these and known poses below then know theirs without redoing every frame's
    parts = [mix]
    head = track[:w0]
    if join.pre is not None and len(join.pre):
        head = concatenate([p for p in (track[:join.retimed_from], sample(track, join.pre)) if p.n_frames])
    if w1 - join.offset < 0:  # the window ends before B's first frame: B's first pose bridges the rest
        parts.append(sample(placed_b, np.zeros(join.offset - w1)))
    parts.append(placed_b[max(0, w1 - join.offset):])
    b_line = concatenate([b_w] + parts[1:])  # B alone over [w0, end)
    out = concatenate([p for p in [head] + parts if p.n_frames])
    return Blended(out, a_w, b_line)


def lock_join(blended: Blended, b_contacts: FootContacts, join: Join, lift: bool = True) -> tuple[Motion, list[Lock]]:
    """The second half of :func:`apply_join`: the planted feet of a :func:`blend_join` locked, swings lifted
    (:func:`lift_join`; ``lift=False`` leaves that to the caller: a locked foot is the same either way)."""
    out, a_w, b_line = blended.out, blended.a_w, blended.b_line
    w0, w1 = join.window
    n = out.n_frames
    nb = n - w0
    after = np.arange(w1, n) - join.offset
    ok = (after >= 0) & (after < len(b_contacts.left))
    planted, src_planted = {}, {}
    for s in ("left", "right"):
        m = np.zeros(n, dtype=bool)
        m[w0:w1] = join.planted[s]
        m[w1:][ok] = b_contacts.of(s)[after[ok]]
        planted[s] = m
        pb = np.zeros(nb, dtype=bool)
        pb[:w1 - w0] = contacts_at(b_contacts, join.src_b)[s]
        pb[w1 - w0:] = m[w1:]
        src_planted[s] = pb
    locks = plan_locks(planted, (w0, w1), n)
    feet = body_map(out.skeleton).feet
    a_pose, b_pose = a_w.pose, b_line.pose
    wa = np.zeros(nb)
    wl = join.weights if join.weights.ndim == 1 else join.weights[:, 0]
    wa[:w1 - w0] = 1.0 - wl
    wb = 1.0 - wa
    a_contacts = {s: np.zeros(nb, dtype=bool) for s in ("left", "right")}
    for s in ("left", "right"):
        a_contacts[s][:w1 - w0] = join.planted_a[s]
    feet_locks = {}
    for side in ("left", "right"):
        mine = [lk for lk in locks if lk.side == side]
        if not mine:
            continue
        ankle = feet[side][0]
        pa = np.zeros((nb, 3))
        ra = np.tile(np.eye(3), (nb, 1, 1))
        pa[:w1 - w0] = a_pose.positions[:, ankle]
        ra[:w1 - w0] = a_pose.rotations[:, ankle]
        feet_locks[side] = FootLocks(mine, [pa, b_pose.positions[:, ankle]], [ra, b_pose.rotations[:, ankle]],
                                     [wa * a_contacts[side], wb * src_planted[side]])
    if feet_locks:
        feet_locks = reachable_locks(out, feet_locks, w0)
        locks = [lk for side in ("left", "right") if side in feet_locks for lk in feet_locks[side].locks]
    out = lock_feet(out, feet_locks, w0, PROFILE)
    return (lift_join(out, locks, join.window) if lift else out), locks


def lift_join(out: Motion, locks: list[Lock], window: tuple[int, int]) -> Motion:
    """The last step of :func:`lock_join`: feet the blend ``[w0, w1)`` or a release carries through the air
    (not locked) kept clear of the floor (:func:`synthesis.join.footlock.lift_swings`)."""
    w0, w1 = window
    n = out.n_frames
    swings = []
    for side in ("left", "right"):
        air = np.zeros(n, dtype=bool)
        air[w0:w1] = True
        for lk in locks:
            if lk.side == side:
                air[lk.end:lk.release_end] = True
        for lk in locks:
            if lk.side == side:
                air[lk.begin:lk.end] = False
        swings += [(side, int(lo), int(hi)) for lo, hi in runs(air)]
    return lift_swings(out, swings)

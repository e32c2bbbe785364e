"""Preparing a clip for its place on a track: speed, looping, repeats, holding and trimming.

The time table (``docs/timetable.md`` §1) gives every element a played length
``end - start``; this module turns the element's clip into exactly that many
frames at the output frame rate:

- **speed** is a time scale: the clip is resampled (slerp) as if recorded at
  ``fps * speed``; its core scales with it. A cyclic clip played faster than
  recorded is slowed a frame per cycle at a time until its jerk is within
  :data:`JERK_ROOM` of the built-in limit (:func:`cycle_at_speed`).
- a **cyclic** clip (its last frame flows into its first) is **looped** to the
  length: each cycle is moved rigidly by the cycle's own root travel and turn,
  so a loop of a walk walks on instead of jumping back. Any mismatch between
  the end of the cycle and its start is spread over the cycle, so the seam
  has no pop (:mod:`synthesis.join.cycles`).
- any other clip is played whole and then its last pose is **held**, or it is
  **trimmed** to the length — from its tail, never inside its core; a core
  longer than the length is kept whole (the element then overruns; a warning
  says so).
- **repeats** of a non-cyclic whole-body clip are its repetitions, each an element of its own
  share of the time, joined by the engine as connections (:func:`repetitions`, the one place repeats
  are handled); a cyclic clip simply loops to the whole length, a partial one plays once.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from text2anim.core.kept import Kept
from text2anim.core.motion import Motion

from ..tracks import Element
from .blend import sample
from .cycles import loop, make_cyclic


def at_speed(motion: Motion, speed: float, fps: float) -> Motion:
    """``motion`` played ``speed`` times as fast, sampled at ``fps`` (time scaling by resampling)."""
    if not speed > 0:
        raise ValueError(f"speed must be positive, got {speed}")
    return motion.replace(fps=motion.fps * speed).resample(fps)


def hold(motion: Motion, n_frames: int) -> Motion:
    """``motion`` extended to ``n_frames`` by repeating its last frame (or cut to it)."""
    n = motion.n_frames
    if n_frames <= n:
        return motion[:n_frames]
    # the motion, then its last frame repeated: only the repeats' kinematics is new (Motion.then)
    return motion.then(take_frames(motion[n - 1:], np.zeros(n_frames - n, dtype=int)))


#: Seconds over which a clip coming to its last frame (or leaving its first) eases to a stop
#: instead of freezing in one frame: its velocity falls linearly to zero over twice this.
KNEE = 0.2


def soft_clip(x: np.ndarray, lo: float, hi: float, knee: float) -> np.ndarray:
    """``np.clip(x, lo, hi)`` with rounded corners: within ``knee`` of a bound the curve bends
    quadratically (slope 1 → 0), so a clip played up to a held frame slows down to it.

    Identity for ``lo + knee <= x <= hi - knee`` (it never changes which frame plays there).
    """
    x = np.asarray(x, dtype=np.float64)
    if knee <= 0 or hi - lo < 2 * knee:
        return np.clip(x, lo, hi)
    out = np.clip(x, lo, hi)
    up = (x > hi - knee) & (x < hi + knee)
    out[up] = hi - (hi + knee - x[up]) ** 2 / (4 * knee)
    down = (x > lo - knee) & (x < lo + knee)
    out[down] = lo + (x[down] - lo + knee) ** 2 / (4 * knee)
    return out


def ease_hold(motion: Motion, n_frames: int, knee: float = KNEE) -> Motion:
    """``motion`` extended to ``n_frames`` by holding its last pose, easing into it (see :func:`soft_clip`)."""
    n = motion.n_frames
    if n_frames <= n:
        return motion[:n_frames]
    k = knee * motion.fps
    start = max(0, int(np.floor(n - 1 - k)))
    src = soft_clip(np.arange(start, n_frames, dtype=np.float64), 0, n - 1, k)
    return motion[:start].then(sample(motion, src)) if start else sample(motion, src)


def ease_lead(motion: Motion, n_frames: int, knee: float = KNEE) -> Motion:
    """``n_frames`` of ``motion``'s first pose before it, easing out of it (the mirror of :func:`ease_hold`)."""
    if n_frames <= 0:
        return motion
    k = knee * motion.fps
    stop = min(motion.n_frames, int(np.ceil(k)) + 1)
    src = soft_clip(np.arange(-n_frames, stop, dtype=np.float64), 0, motion.n_frames - 1, k)
    return sample(motion, src).then(motion[stop:])


def take_frames(motion: Motion, idx: np.ndarray) -> Motion:
    """The frames ``idx`` ``(N,)`` of ``motion``, in that order (repeats allowed)."""
    return Motion(motion.skeleton, motion.fps, motion.root_positions[idx], motion.rotations[idx],
                  None if motion.translations is None else motion.translations[idx])


def trim(motion: Motion, n_frames: int, core: tuple[int, int]) -> tuple[Motion, int]:
    """Cut ``motion`` to ``n_frames`` from its tail, never inside ``core`` (frames).

    Returns the cut motion and the number of frames it is still too long
    (0 unless the core itself does not fit).
    """
    keep = max(n_frames, core[1], 1)
    return motion[:keep], max(0, keep - n_frames)


@dataclass(frozen=True)
class Prepared:
    """An element's clip at the output frame rate and played length.

    Attributes:
        motion: the frames, in the clip's own placement (not yet moved onto the track).
        core: ``[begin, end)`` frames of the core interval in ``motion``.
        cycle: frames per cycle for a looped clip, else 0.
        lead: frames of loop added before the element's start (``margin``), 0 otherwise.
        played: frames of the clip actually played before any hold (the rest repeats the last frame).
        warnings: what could not be honoured (a core longer than the played length).
    """

    motion: Motion
    core: tuple[int, int]
    cycle: int = 0
    played: int = 0
    warnings: tuple[str, ...] = ()
    lead: int = 0


def cycle_frames(motion: Motion, speed: float, fps: float) -> Motion:
    """One cycle of a cyclic clip at ``speed``, sampled at ``fps`` with a whole number of frames.

    The period (the clip's frame count over its frame rate, over ``speed``)
    is rounded to whole output frames and the clip is sampled (slerp) at
    that spacing, so looping keeps the clip's exact tempo to within a frame.
    """
    return _cycle(motion, _cycle_length(motion, speed, fps), fps)


def _cycle_length(motion: Motion, speed: float, fps: float) -> int:
    """Frames (at least 3) of one cycle of a cyclic clip at ``speed``, sampled at ``fps``."""
    return max(3, int(round(motion.n_frames / motion.fps / speed * fps)))


def _cycle(motion: Motion, n_cycle: int, fps: float) -> Motion:
    """One cycle of a cyclic clip over ``n_cycle`` frames at ``fps`` (slerp)."""
    return sample(motion, np.arange(n_cycle) * (motion.n_frames / n_cycle)).replace(fps=fps)


#: share of the built-in jerk limit (core.metrics.BUILTIN_LIMITS) a cycle played faster than recorded may reach:
#: the joins beside it and a rig with fewer quiet joints read a few per cent more
JERK_ROOM = 0.9


def cycle_at_speed(motion: Motion, speed: float, fps: float) -> Motion:
    """:func:`cycle_frames`, lengthened a frame at a time (never slower than the clip's own speed) while its
    joints' jerk p99 (30 fps, the cycle looped) is above :data:`JERK_ROOM` of the built-in limit: a clip
    played ``s`` times faster jerks ``s³`` times as much, and 速く走る played the run 1.5 times as fast, its
    jerk at 93 % of the limit on the built-in body and over it on a 24-joint rig."""
    from text2anim.core.metrics import BUILTIN_LIMITS, quality

    cycle = cycle_frames(motion, speed, fps)
    own = _cycle_length(motion, 1.0, fps)
    while cycle.n_frames < own:
        looped = loop(make_cyclic(cycle), 2 * cycle.n_frames, 0)
        if quality(looped).jerk_p99 <= JERK_ROOM * BUILTIN_LIMITS["jerk_p99"]:
            break
        cycle = _cycle(motion, cycle.n_frames + 1, fps)
    return cycle


def repetitions(elements: Sequence[Element]) -> list[tuple[Element, int]]:
    """Whole-body elements in time order, each with its repetition number: a repeated non-cyclic one as
    its ``repeat`` repetitions, each of ``(end - start) / repeat`` s, joined to the one before by a
    connection; any other element once, as repetition 0."""
    out = []
    for e in sorted(elements, key=lambda e: (e.start, e.id)):
        n = max(1, int(e.repeat))
        if e.clip.cyclic or n == 1:
            out.append((e, 0))
            continue
        step = (e.end - e.start) / n
        for k in range(n):
            sub = replace(e, start=e.start + k * step, end=e.start + (k + 1) * step, repeat=1,
                          method=e.method if k == 0 else "connection", prev=e.prev if k == 0 else e.id)
            out.append((sub, k))
    return out


#: the last preparations made (:func:`prepare`), by clip, speed, rate, length and margin: a warm process lays the
#: same elements again (the studio re-animates the whole text at every pause in typing), and what is derived from a
#: prepared motion (its pose, its foot contacts) is kept with it (~0.5-1 MB each). An entry holds its clip's motion,
#: so the motion's ``id`` in its key names no other motion while it is kept.
PREPARED: Kept[tuple[Motion, Prepared, int]] = Kept(16)


def prepare(element: Element, fps: float, margin: bool = False) -> Prepared:
    """The element's clip made ready for the track: speed, loop or hold/trim to ``end - start``.

    Repeats are not this function's: a repeated whole-body element comes here as its
    :func:`repetitions`. With ``margin`` a cyclic clip gets one more cycle before its start and after its
    end (``lead`` frames before): a transition may then enter it at any phase. The last :data:`PREPARED`
    preparations are kept (the same motion object for the same request).
    """
    clip = element.clip
    speed = float(element.speed)
    if not speed > 0:
        raise ValueError(f"element {element.id}: speed must be positive, got {speed}")
    length = element.end - element.start
    n_target = max(1, int(round(length * fps)))
    key = (id(clip.motion), speed, float(fps), n_target, bool(margin), tuple(clip.core), bool(clip.cyclic))
    known = PREPARED.known(key)
    if known is None or known[0] is not clip.motion:
        known = PREPARED.put(key, (clip.motion, *_prepared(clip, speed, fps, n_target, margin)))
    _, prep, over = known
    if over:
        return replace(prep, warnings=(
            f"element {element.id}: its core ({(clip.core[1] - clip.core[0]) / speed:.2f} s) does not "
            f"fit in {length:.2f} s; the core is kept and the element runs {over / fps:.2f} s longer",))
    return prep


def _prepared(clip, speed: float, fps: float, n_target: int, margin: bool) -> tuple[Prepared, int]:
    """:func:`prepare` of a clip at ``speed`` to ``n_target`` frames: the preparation (without warnings) and the
    frames by which a trimmed core overruns (0 when it fits)."""
    if clip.cyclic and clip.motion.n_frames >= 3:
        # kept with the clip's motion: a text that walks 31 times loops the same cycle 31 times
        m = clip.motion.cache.get(("cyclic at speed", speed, float(fps)),
                                  lambda: make_cyclic(cycle_at_speed(clip.motion, speed, fps)))
    else:
        m = at_speed(clip.motion, speed, fps)
    n_src = m.n_frames
    c0 = int(np.clip(round(clip.core[0] / speed * fps), 0, max(n_src - 1, 0)))
    c1 = int(np.clip(round(clip.core[1] / speed * fps), c0 + 1, n_src))
    if clip.cyclic and n_src >= 3:
        lead = n_src if margin else 0
        out = loop(m, n_target + 2 * lead, -lead)
        full = max(1, n_target // n_src)
        core = (lead + min(c0, n_target - 1), lead + min(n_target, (full - 1) * n_src + c1))
        return Prepared(out, core, n_src, n_target, (), lead), 0
    over = 0
    if n_target >= n_src:
        out, played = hold(m, n_target), n_src
    else:
        out, over = trim(m, n_target, (c0, c1))
        played = out.n_frames
    return Prepared(out, (c0, min(c1, out.n_frames)), 0, played, ()), over

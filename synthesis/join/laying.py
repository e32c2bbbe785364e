"""Laying one actor's track: the state of the track so far, the element coming in, the loop over elements.

Every joiner of whole-body motions (paper 003's, optimal blending, the pose and crossfade baselines) lays a
track the same way (:func:`lay_elements`): each element (a repeated non-cyclic one as its repetitions,
:func:`synthesis.join.timing.repetitions`) is prepared (:func:`incoming`: speed, loop with a margin
cycle, hold or trim); the first is placed at the track's origin and heading (:func:`place_first`), each
next one is joined to the track so far by the joiner's own ``join(state, incoming)``, which decides and
writes the join and commits it (:func:`synthesis.join.commit.commit`). Frames on the track; seconds only
in the report.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from text2anim.core.cancel import checkpoint
from text2anim.core.contacts import contacts_of, detect_contacts, lowest_tracks
from text2anim.core.kept import value_digest
from text2anim.core.motion import Motion, concatenate
from text2anim.core.skeleton import Skeleton

from ..tracks import Element, Track
from .align import place_at
from .blend import sample
from .laid import Laid, LaidJoin
from .placed import Placed, on_skeleton
from .timing import KNEE, ease_hold, ease_lead, hold, prepare, repetitions, soft_clip, take_frames


@dataclass
class TrackState:
    """A track being laid: the frames so far, the elements placed, the joins, the earliest frame a new
    blend may start (``floor``), and the elements a join moved in time (``delays``: ``(id, s)``).

    The frames are kept as pieces end to end (:meth:`lay`), put together when :attr:`motion` is read: a join
    lays the track before its blend and its rendering, and the next join extends those (:func:`extended`)
    without first putting them together, so a long track is copied once a join, not twice."""

    placed: list[Placed] = field(default_factory=list)
    joins: list[LaidJoin] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    skipped: dict[int, str] = field(default_factory=dict)
    floor: int = 0
    delays: list[tuple[int, float]] = field(default_factory=list)
    skeleton: Skeleton | None = None
    pieces: tuple[Motion, ...] = ()
    #: the frames' :func:`core.contacts.lowest_tracks` ``(heights, speeds)`` when known (:func:`laid_feet`)
    feet: tuple[np.ndarray, np.ndarray] | None = None
    #: a digest of everything the state was made from (:func:`lay_elements`: the track's origin, heading and rate,
    #: then each incoming element in order, the one being joined included, without its labels:
    #: :meth:`Placed.unlabelled`): with a joiner's options it determines the join but for the labels, so a joiner
    #: may keep its answers by it; empty for a state laid otherwise
    chain: bytes = b""

    @property
    def motion(self) -> Motion | None:
        """The frames so far (``None`` before the first element is placed)."""
        if len(self.pieces) > 1:
            self.pieces = (concatenate(list(self.pieces)),)
        return self.pieces[0] if self.pieces else None

    @motion.setter
    def motion(self, motion: Motion | None) -> None:
        self.lay(() if motion is None else (motion,))

    def lay(self, pieces: Sequence[Motion], feet: tuple[np.ndarray, np.ndarray] | None = None) -> None:
        """The frames so far are ``pieces`` end to end (empty ones left out; put together when read);
        ``feet``: their :func:`core.contacts.lowest_tracks` when the caller has them."""
        self.pieces = tuple(p for p in pieces if p.n_frames)
        self.feet = feet

    def laid(self) -> Motion:
        """The frames so far (a join is only made once the first element is placed)."""
        if self.motion is None:
            raise ValueError("no element is laid on the track yet")
        return self.motion


def incoming(e: Element, rep: int, fps: float, state: TrackState) -> Placed:
    """Prepare an element for the track (speed, loop with a margin cycle, hold/trim): where it is scheduled,
    not yet placed in space (``rigid`` ``None``)."""
    prep = prepare(e, fps, margin=e.clip.cyclic)
    state.warnings.extend(prep.warnings)
    prep, state.skeleton, note = on_skeleton(prep, state.skeleton, e)
    if note and rep == 0:
        state.warnings.append(note)
    lead = prep.lead
    start = int(round(e.start * fps))
    motion = prep.motion
    # found once for a prepared motion and kept with it, as the preparation is kept (timing.PREPARED), and the
    # motion itself goes on the track: what a join computes from it (its features, its placement) is kept with it
    contacts = detect_contacts(motion)
    return Placed(e, motion, start - lead, prep.core, contacts, e.clip.cyclic, lead, prep.motion.n_frames - lead, rep)


def place_first(state: TrackState, inc: Placed, origin, heading: float) -> None:
    """The first element of a track, at its origin and heading, its first pose held until it starts."""
    rigid = place_at(inc.motion, origin, heading, frame=inc.lead)
    m = rigid.apply(inc.motion)
    state.motion = ease_lead(m[inc.lead:], inc.first)
    state.placed.append(replace(inc, motion=m, rigid=rigid))


def extend(tr: Motion, n: int, floor: int) -> Motion:
    """The track held to ``n`` frames: eased into its last pose when the easing starts at or after
    ``floor`` (frames before it are final), else simply held."""
    if tr.n_frames >= n:
        return tr
    if tr.n_frames - 1 - KNEE * tr.fps >= floor:
        return ease_hold(tr, n)
    return hold(tr, n)


def extended(state: TrackState, n: int) -> Motion:
    """:func:`extend` of the track so far to ``n`` frames, with ``state.floor``, bit for bit, but put together
    from its pieces (:meth:`TrackState.lay`) once: a track eased or held past a last piece that holds the
    easing is that piece's frames resampled (:func:`synthesis.join.blend.sample` with the piece's origin,
    the track's fractions) after the pieces before it. Where the track's feet are kept (``state.feet``), the
    extension's are theirs and its new frames' (:func:`_fed`), and so are its contacts."""
    pieces = state.pieces
    if len(pieces) < 2:
        return extend(state.laid(), n, state.floor)
    total = sum(p.n_frames for p in pieces)
    last = pieces[-1]
    origin = total - last.n_frames
    if total >= n:
        return extend(state.laid(), n, state.floor)
    if total - 1 - KNEE * last.fps < state.floor:  # held (hold): the last frame repeated
        return concatenate([*pieces, take_frames(last[last.n_frames - 1:], np.zeros(n - total, dtype=int))])
    k = KNEE * last.fps  # eased (ease_hold): the frames from ``start`` on resampled
    start = max(0, int(np.floor(total - 1 - k)))
    if start < origin:
        return extend(state.laid(), n, state.floor)
    src = soft_clip(np.arange(start, n, dtype=np.float64), 0, total - 1, k)
    head = [*pieces[:-1], last[:start - origin]]
    eased = sample(last, src, origin)
    tr = concatenate([p for p in head if p.n_frames] + [eased])
    if state.feet is not None and start - origin >= 2:
        _fed(tr, state.feet, start, concatenate([last[start - origin - 2:start - origin], eased]))
    return tr


def _fed(tr: Motion, kept: tuple[np.ndarray, np.ndarray], k: int, seam: Motion) -> None:
    """``tr``'s :func:`core.contacts.lowest_tracks` and contacts (kept in its cache) from ``kept``, those of a
    track whose first ``k`` frames are ``tr``'s, and ``seam``, ``tr``'s frames from ``k - 2`` on: a frame's
    height is its own, its speed its neighbours' (``k - 1``'s reads ``k``), so only ``seam``'s frames are
    measured. The same bits as measuring ``tr`` (a difference of two frames, a percentile and runs)."""
    feet = _spliced(kept, k, seam)
    tr.cache.put("lowest_tracks", feet)
    tr.cache.put("contacts", contacts_of(*feet, tr.fps))


def laid_feet(tr: Motion, c0: int, rendered: Motion) -> tuple[np.ndarray, np.ndarray] | None:
    """The :func:`core.contacts.lowest_tracks` of ``tr[:c0]`` then ``rendered`` (a join laid on ``tr``,
    :meth:`TrackState.lay`), from ``tr``'s (measured once if not kept) and ``rendered``'s; ``None`` for a
    rendering from the track's first two frames."""
    if c0 < 2 or not rendered.n_frames:
        return None
    kept = tr.cache.get("lowest_tracks", lambda: lowest_tracks(tr))
    return _spliced(kept, c0, concatenate([tr[c0 - 2:c0], rendered]))


def _spliced(kept: tuple[np.ndarray, np.ndarray], k: int, seam: Motion) -> tuple[np.ndarray, np.ndarray]:
    """The :func:`core.contacts.lowest_tracks` of a track whose first ``k`` frames have ``kept`` and whose
    frames from ``k - 2`` on are ``seam``: heights ``(T,)`` from frame ``k`` on and speeds ``(T - 1,)`` from
    ``k - 1`` on are ``seam``'s (a speed reads the frame after it)."""
    y, v = lowest_tracks(seam)
    return np.concatenate([kept[0][:k], y[2:]]), np.concatenate([kept[1][:k - 1], v[1:]])


def lay_elements(track: Track, whole: Sequence[Element], fps: float,
                 join: Callable[[TrackState, Placed], object]) -> Laid:
    """The whole-body elements of one track laid in time order: the first placed, each next one joined by
    ``join(state, incoming)`` (which updates ``state``; ``state.chain`` names the track so far and ``incoming``)."""
    state = TrackState(chain=value_digest(track.origin, track.heading, fps))
    for e, rep in repetitions(whole):
        checkpoint()  # an abandoned animation stops before its next join
        inc = incoming(e, rep, fps, state)
        state.chain = value_digest(state.chain, inc.unlabelled())
        if not state.pieces:  # (reading ``state.motion`` would put the pieces together)
            place_first(state, inc, track.origin, track.heading)
            continue
        join(state, inc)
    return Laid(state.laid(), state.placed, state.joins, state.warnings, state.skipped, state.delays)


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

from text2anim.core.cancel import checkpoint
from text2anim.core.contacts import detect_contacts
from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton

from ..tracks import Element, Track
from .align import place_at
from .laid import Laid, LaidJoin
from .placed import Placed, on_skeleton
from .timing import KNEE, ease_hold, ease_lead, hold, prepare, repetitions


@dataclass
class TrackState:
    """A track being laid: the frames so far, the elements placed, the joins, the earliest frame a new
    blend may start (``floor``), and the elements a join moved in time (``delays``: ``(id, s)``)."""

    motion: Motion | None = None
    placed: list[Placed] = field(default_factory=list)
    joins: list[LaidJoin] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    skipped: dict[int, str] = field(default_factory=dict)
    floor: int = 0
    delays: list[tuple[int, float]] = field(default_factory=list)
    skeleton: Skeleton | None = None

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


def lay_elements(track: Track, whole: Sequence[Element], fps: float,
                 join: Callable[[TrackState, Placed], object]) -> Laid:
    """The whole-body elements of one track laid in time order: the first placed, each next one joined by
    ``join(state, incoming)`` (which updates ``state``)."""
    state = TrackState()
    for e, rep in repetitions(whole):
        checkpoint()  # an abandoned animation stops before its next join
        inc = incoming(e, rep, fps, state)
        if state.motion is None:
            place_first(state, inc, track.origin, track.heading)
            continue
        join(state, inc)
    return Laid(state.laid(), state.placed, state.joins, state.warnings, state.skipped, state.delays)


"""Automatic start times for online use, paper 000 §5: ``Timeline.append(clip, now)``.

While the animation plays, motions are appended one by one; each starts as
early as it can after what is already scheduled, and nothing already shown —
no frame before the playing time ``now`` — ever changes. :meth:`Timeline.append`:

1. the method and the steps to use come from the last motion on the timeline
   and the new one (:mod:`synthesis.optimal.method_select`, via
   :func:`synthesis.optimal.plan_join`);
2. the new motion is placed **tentatively** so that its core begins
   :data:`GAP` seconds after the later of the last motion's core end and
   ``now`` ("両要素動作のブレンドに用いる区間に一定時間の間隔を空けて"), and the
   blend intervals are searched with the extra constraint of eq. (17)::

       t_current < t_s,begin,   t_current < t_s,end                          (17)

   (every new blend interval begins after ``now``: the search's floor);
3. where the new motion would then play on its own before its core — frames
   no blend uses — that span is **closed**: the motion is moved earlier by it
   (never so far that its core would begin before the last core ends or
   before ``now``) and the intervals are searched again;
4. the join is written (:func:`synthesis.optimal.join_next`): the track before
   the first new blend is left as it is, frame for frame.

``now`` is in seconds on the timeline's clock; ``None`` means "not playing
yet" (only the previous joins bound the new blends). A ``now`` inside the
easing into the last motion's final pose commits that pose first (the player
has shown it), so appending still changes nothing before ``now``.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from text2anim.core.contacts import detect_contacts
from text2anim.core.methods import Method
from text2anim.core.motion import Motion

from ..assemble import finish_whole
from ..join.gait import steps
from ..join.laying import TrackState, extend, incoming, place_first
from ..join.timing import KNEE
from ..optimal import MIN_BLEND, Skip, join_next, plan_join
from ..result import Result
from ..tracks import Clip, Element
from .blend_search import preset
from .method_select import cyclic_core_end

#: s between the last core's end (or now) and the new core's start, where a new motion is first placed.
GAP = 0.5


class Timeline:
    """One actor's motion, grown by :meth:`append` while it plays (paper 000 §5).

    Args:
        fps: frame rate of the motion.
        smoothness: ``W`` of §4.3 (0 time first, 1 smoothness first).
        origin, heading: where the actor stands at time 0 (x, z metres; radians about +Y).
        lock_feet: lock planted feet during blends.
    """

    def __init__(self, fps: float = 30.0, smoothness: float = 0.5, origin: tuple[float, float] = (0.0, 0.0),
                 heading: float = 0.0, lock_feet: bool = True, gap: float = GAP, min_blend: float = MIN_BLEND):
        self.fps = float(fps)
        self.weights = preset(smoothness)
        self.origin, self.heading = origin, float(heading)
        self.lock_feet = lock_feet
        self.gap = gap
        self.min_blend = min_blend
        self.state = TrackState()
        self.elements: list[Element] = []
        self._finished: Motion | None = None
        self._ids = 0

    # ------------------------------------------------------------------------------------------ views
    @property
    def motion(self) -> Motion:
        """The animation so far (the last motion held on its final pose once it ends)."""
        if self.state.motion is None:
            raise ValueError("the timeline is empty")
        if self._finished is None:
            self._finished = finish_whole(self.state.motion, self.state.placed, self.elements)
        return self._finished

    @property
    def duration(self) -> float:
        return self.motion.duration if self.state.motion is not None else 0.0

    @property
    def joins(self) -> list:
        """The :class:`~synthesis.result.JoinReport` of every join so far (without metrics)."""
        return [j.report for j in self.state.joins]

    def result(self) -> Result:
        """The timeline as a :class:`~synthesis.result.Result` (joins measured as the engines do)."""
        from ..assemble import measure
        from ..join.laid import Laid
        from ..tracks import Track

        laid = Laid(self.motion, self.state.placed, list(self.state.joins), list(self.state.warnings),
                    dict(self.state.skipped))
        reps, els = measure(Track(None, tuple(self.elements)), laid, [], self.fps)
        from ..played import placed_paths

        return Result({None: self.motion}, reps, self.fps, els, tuple(self.state.warnings),
                      {None: placed_paths(self.state.placed, self.motion.n_frames)})

    # ----------------------------------------------------------------------------------------- append
    def _element(self, clip: Clip, start: int, speed: float, duration: float | None, method: Method) -> Element:
        length = duration if duration is not None else clip.motion.duration / speed
        prev = self.elements[-1].id if self.elements else None
        return Element(self._ids + 1, clip, start / self.fps, start / self.fps + length, method, prev, speed)

    def _commit(self, now_f: int) -> None:
        """Make what the player has shown up to ``now_f`` the track itself (the easing into the last pose)."""
        last = self.state.placed[-1]
        ease_from = last.offset + last.stop - 1 - int(np.ceil(KNEE * self.fps))
        if now_f >= ease_from:
            done = self.motion
            self.state.motion = done
            self.state.placed[-1] = replace(last, stop=min(last.stop, done.n_frames - last.offset))

    def append(self, clip: Clip, now: float | None = None, *, speed: float = 1.0,
               duration: float | None = None) -> Element:
        """Add ``clip`` as early as it can start after the timeline's last motion (see the module docstring).

        ``now`` (s): the playing time; no blend of this motion begins at or before it, and no frame
        before it changes. ``speed`` scales the clip's time; ``duration`` (s) loops a cyclic clip to that
        length (default: the clip's own length). Returns the element as placed.
        """
        fps = self.fps
        now_f = -1 if now is None else int(np.floor(now * fps + 1e-9))
        self._finished = None
        if self.state.motion is None:
            e = self._element(clip, max(0, now_f + 1), speed, duration, "initial")
            place_first(self.state, incoming(e, 0, fps, self.state), self.origin, self.heading)
            self._ids += 1
            self.elements.append(e)
            return e
        self._commit(now_f)
        self.state.floor = max(self.state.floor, now_f + 1)  # eq. (17): every new blend begins after now
        floor = self.state.floor
        prev = self.state.placed[-1]
        c0 = (prev.offset + prev.core[0], prev.offset + prev.core[1])
        c0_end = c0[1]
        if prev.cyclic:
            tr_steps = [s for s in steps(detect_contacts(self.state.motion)) if s.begin >= prev.offset]
            c0_end = cyclic_core_end(tr_steps, prev.offset + prev.lead, prev.offset + prev.stop, c0)
        probe = incoming(self._element(clip, 0, speed, duration, "connection"), 0, fps, self.state)
        L = max(2, int(round(self.min_blend * fps)))
        earliest = max(c0_end, floor) + L  # the new core may not begin before this
        start = max(c0_end, floor) + int(round(self.gap * fps)) - probe.core[0]  # tentative placement

        def planned(start_f: int):
            inc = incoming(self._element(clip, start_f, speed, duration, "connection"), 0, fps, self.state)
            tr = extend(self.state.laid(), inc.offset + inc.motion.n_frames, floor)
            return inc, plan_join(tr, prev, inc, fps, self.weights, floor, self.min_blend, allow_shift=False)

        inc, plan = planned(start)
        if not isinstance(plan, Skip):  # close the span the new motion would play unblended before its core
            last_blend = max(iv.t1 for iv in plan.intervals.values())
            gap = (plan.inc.offset + plan.inc.core[0]) - last_blend
            room = (plan.inc.offset + plan.inc.core[0]) - earliest
            close = min(gap, room)
            if close > 0:
                inc2, plan2 = planned(start - close)
                if not isinstance(plan2, Skip):
                    start, inc, plan = start - close, inc2, plan2
        e = inc.element
        self._ids += 1
        plan = join_next(self.state, inc, fps, self.weights, self.lock_feet, self.min_blend, allow_shift=False)
        if isinstance(plan, Skip):
            return e
        if plan.phase:
            e = replace(e, start=plan.inc.first / fps, end=plan.inc.end / fps)
        self.elements.append(e)
        return e

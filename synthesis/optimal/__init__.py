"""Motion synthesis with optimal blending (paper 000, Oshita): the default joiner of consecutive motions.

For each pair of consecutive whole-body elements on a track (§4, "各前後の要素動作の組に対して本手法を繰り返し適用"):

1. **method** (§4.1, §4.2.5, :mod:`.geometry` on :mod:`.method_select`): transition,
   connection, adaptation with or without a step, from the foot–ground
   constraints of the two clips around their cores on the track;
2. **ranges** (§4.2, eqs. (1)–(9), :mod:`.blend_ranges`): lower and
   upper body blend separately, each in its range;
3. **search** (§4.3, eqs. (10)–(15), :mod:`.search` on :mod:`.blend_search`): ``t0``,
   ``t1`` of every interval minimise eq. (10) over all pairs at once, the
   weights from the user's ``smoothness`` ``W``;
4. **placement**: the next motion is turned and slid so its support foot
   stands on the previous motion's and both face the same way
   (:mod:`.placement`, :func:`synthesis.join.align.align_through_foot`, as paper [6] / seed 003 do);
   for an adaptation the next lower body is fitted to the previous feet
   (:mod:`.adaptation`, §4.2.3) and S0 is searched again on it;
5. **weights** (§4.4, :mod:`.curves` on :mod:`.weights`): Hermite curves with eq. (16)
   slopes; motion–pose / pose–motion blends by the three cases of §4.4.2;
6. **rendering** (:mod:`.render`): per frame, the lower body blends its two sources with the
   lower weight, the upper body its two with the upper weight (slerp,
   :mod:`synthesis.join.blend`); planted feet are locked and released by the
   join layer's :func:`synthesis.join.apply.apply_join` (IK, §4.3.2 of 003).

Steps 1–5 are :func:`~.planner.plan_join` (records in :mod:`.records`); a join is carried out by
:func:`~.join.join_next`, which renders until the join does not skate (:mod:`.repair`), and committed to the
track as every engine's is (:func:`synthesis.join.commit.commit`). The pose distance of eq. (13)
(:mod:`.posedist`) also serves the ``pose`` baseline; :mod:`.timeline` appends motions online (§5).

Every blend lasts at least :data:`MIN_BLEND` s (a shorter pose change reads as
a pop).

**Cores** (§4.2.5): when the two cores overlap on the track the later motion
cannot keep its core; it is **not executed** — a warning says so and the
report has a join with ``blend: "not_executed"``; the next element joins the
one before. Cores overlapping by less than :data:`CORE_TOLERANCE` s (a frame of
contact-label noise between the scheduler's step times and ours) touch. A looped clip is all core except the step a join uses
(:func:`~synthesis.optimal.method_select.cyclic_core_end`); a looped next clip may
enter at another phase of its cycle to make a transition possible
(``phase_s``).

**Feet** (the paper's foot constraints made exact): planted feet are locked by
the join layer's IK (:func:`synthesis.join.apply.apply_join`). Three choices
of this engine keep that from fighting the blend:

- a foot that a held pose plants somewhere else than the other side does
  (more than :data:`STEP_GAP`) steps across in the air over the middle of the
  blend instead of staying locked where the first motion left it
  (:mod:`.render`);
- the next motion is moved by the few centimetres between its own support foot
  and where the lock leaves that foot after the blend (:func:`.placement.settle`), so the
  lock hands over without bending a leg inside the next core;
- a join whose blend would still skate is rendered again — without the step,
  with S0's weight eased to zero slope at its ends, placed by the roots
  mid-blend (motion–motion), then with the next-best intervals of eq. (10),
  each eased and without the step — and the first clean rendering is kept
  (``fallback`` in the report).

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

from ..assemble import assemble
from ..result import Result
from ..tracks import Track
from .blend_search import preset
from .join import join_next, lay_track, report_of
from .placement import SETTLE, settle
from .planner import CORE_TOLERANCE, MAX_SHIFT, MIN_BLEND, MIN_ROOM, RUNNERS_UP, SAME_FEET_CM, plan_join
from .records import Interval, Plan, Skip
from .render import STEP_GAP, STEP_WEIGHTS, render

__all__ = ["CORE_TOLERANCE", "MAX_SHIFT", "MIN_BLEND", "MIN_ROOM", "RUNNERS_UP", "SAME_FEET_CM", "SETTLE",
           "STEP_GAP", "STEP_WEIGHTS", "Interval", "Plan", "Skip", "join_next", "lay_track", "plan_join", "render",
           "report_of", "settle", "synthesize_optimal"]


def synthesize_optimal(tracks: Sequence[Track], fps: float = 30.0, smoothness: float = 0.5, *,
                       lock_feet: bool = True, sway: bool = True,
                       min_blend: float = MIN_BLEND, finished: bool = True) -> Result:
    """Tracks → one motion per actor by optimal blending (paper 000), compositions as every engine lays them.

    Args:
        tracks: one :class:`~synthesis.tracks.Track` per actor, each at its staged origin and heading.
        fps: output frame rate.
        smoothness: ``W`` of §4.3, 0 (time first: short blends) to 1 (smoothness first).
        lock_feet: lock planted feet during blends.
        sway: transfer the sway of composed clips.
        min_blend: the shortest blend interval, seconds.
        finished: ``False`` leaves the motions before :func:`synthesis.finish.finish` (the caller finishes them).

    Returns the same :class:`~synthesis.result.Result` as :func:`synthesis.constraint.engine.synthesize`; each join's
    report has ``blend`` (the §4.1 method), ``intervals`` (lower/upper, kinds), ``cost`` (eq. (10) terms).
    """
    weights = preset(smoothness)

    def lay(track: Track, whole):
        return lay_track(track, whole, fps, weights, lock_feet, min_blend)

    return assemble(tracks, fps, lay, sway, post=lock_feet, finished=finished)

"""A join rendered until it does not skate (nor pop, where another rendering does not): the paper's
rendering first, then without the step, with S0's weight eased, placed by the roots, and with the
next-best intervals of eq. (10), eased and without the step (:func:`carry_out`)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from text2anim.core.contacts import FootContacts, detect_contacts
from text2anim.core.metrics import SOURCE_FACTOR, root_pop, toe_joints, toe_skating_pairs
from text2anim.core.motion import Motion

from ..join.align import align_through_foot
from ..join.apply import lift_join
from ..join.blend import ease
from ..join.footlock import Lock
from ..join.measure import skating_exceeds
from .placement import settle
from .records import Plan
from .render import Parts, blended, finish, prepare


def _eased(plan: Plan) -> Plan:
    """The plan with the lower-body blend S0's weight eased (quintic, zero slope and curvature at both ends)
    instead of eq. (16)'s Hermite — see :func:`carry_out`."""
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


def _skating(out: Motion, base: Motion, window: tuple[int, int], locks) -> float:
    """GMD skating ratio (either foot, :func:`synthesis.join.measure.skating_frames`) of a rendering ``out``
    over its blend window ``[w0, w1)``. ``base``: the rendering before its feet were locked, the same frames
    outside ``[w0, the locks' last release)``: only those frames' kinematics are computed (a rendering that is
    not kept never needs the rest)."""
    lo, hi = window
    n = out.n_frames
    if n < 2 or hi <= max(lo, 0):
        return 0.0
    edited = max([hi] + [lk.release_end for lk in locks])
    toes = toe_joints(out)
    feet = base.positions[:, toes].copy()  # (T, 2, 3)
    feet[lo:edited] = out[lo:edited].positions[:, toes]
    sk = np.zeros(n, dtype=bool)  # per frame, as skating_frames
    sk[:n - 1] = toe_skating_pairs(feet, out.fps)
    return float(sk[max(lo, 0):hi].mean())


#: the renderings of a join's plan, in the order tried (:func:`carry_out`): ``(name, step, eased)``
VARIANTS = (("", True, False), ("no_step", False, False), ("eased", True, True), ("eased_no_step", False, True))
#: the renderings of each runner-up's (:func:`carry_out`): eased and without the step alone. Over the
#: corpora's and golden sentences' 597 joins, 25 runner-up renderings did not skate; 24 of them were, or
#: rendered the same as, that variant; tried in all four, a join whose every rendering skates (10 of the
#: 32-motion text's 93) rendered 24 times instead of 9
RUNNER_UP_VARIANTS = (("eased_no_step", False, True),)
#: frames around the blend window whose root pop is the join's (:func:`_window_pop`)
POP_MARGIN = 3


def _window_pop(out: Motion, window: tuple[int, int]) -> float:
    """Root pop (m/s², :func:`core.metrics.quality` at the track's rate) of the blend window and
    :data:`POP_MARGIN` frames around: the root's alone, so the same before the feet are locked (locks turn
    joints, never the root)."""
    return root_pop(out[max(0, window[0] - POP_MARGIN):min(out.n_frames, window[1] + POP_MARGIN)])


def _held(prepared) -> bytes:
    """The feet a prepared rendering holds (:func:`.render.prepare`), as bytes to compare."""
    planted = prepared[3].planted
    return b"".join(np.asarray(planted[s], dtype=bool).tobytes() for s in ("left", "right"))


def _shifted(plan: Plan, by: int) -> Plan:
    """The plan on a track whose frames are ``by`` later (its blend intervals, runners-up and the next
    motion's offset moved; what a rendering reads of a plan: the rest is not in frames)."""
    def moved(iv):
        return replace(iv, t0=iv.t0 + by, t1=iv.t1 + by)
    return replace(plan, inc=replace(plan.inc, offset=plan.inc.offset + by),
                   intervals={k: moved(iv) for k, iv in plan.intervals.items()},
                   alternatives=[moved(iv) for iv in plan.alternatives])


def _first_rendered(tr: Motion, plan: Plan) -> int:
    """The first track frame any rendering of ``plan`` reads or writes (:func:`carry_out`): the earliest
    blend interval's start, its runners-up' included, less :data:`POP_MARGIN`. Every frame before it is
    the track's own in every rendering (a join writes from its window on, the feet's locks start there)."""
    t0 = min(iv.t0 for iv in [*plan.intervals.values(), *plan.alternatives])
    return int(np.clip(t0 - POP_MARGIN, 0, tr.n_frames))


def carry_out(tr: Motion, plan: Plan, lock: bool, own: float = 0.0, own_pop: float = float("inf")):
    """Render a plan — and make sure the join does not skate, nor pop where another rendering would not.

    The plan is rendered as the paper has it (eq. (16) weights, a foot held by a frozen pose stepping
    across, :func:`_planted`), then settled (:func:`settle`). If its blend skates (a run
    pulled into a standing pose: the mixed hips overshoot where the two motions' roots are far apart and
    the weight is steep at an end) or its hips pop, the join is rendered again without the step, then with
    S0's weight eased to zero slope at both ends, then both (and placed by the roots' midpoint for a
    motion–motion blend). "Skates" is the benchmark's rule: the blend's GMD ratio above ``own`` (the two
    source clips' larger ratio) + 0.01; "pops": the window's root pop above 1.2 x ``own_pop`` (the
    sources' larger, :func:`core.metrics.against_sources`). The first rendering that does neither is kept,
    else of those that do not skate the one that pops least, else the one that skates least; the report
    says which (``fallback``). When every rendering skates, the next-best lower-body intervals of eq. (10)
    (:data:`RUNNERS_UP` of them) are tried, each rendered eased and without the step
    (:data:`RUNNER_UP_VARIANTS`): the search's minimum subject to the join keeping its feet. Deterministic. Returns ``(plan, c0, rendered, locks, window)``: the track is ``tr[:c0]`` then
    ``rendered`` (its pose known: the two end to end know theirs), the locks and window in the track's frames.

    The renderings are of the track from :func:`_first_rendered` on (every frame before it is the same in
    all of them): each is a few hundred frames however long the track, and the track is not put together
    here: a long track laid join after join is copied once a join, not twice
    (:meth:`synthesis.join.laying.TrackState.lay`).
    """
    c0 = _first_rendered(tr, plan)
    whole_c = detect_contacts(tr)  # the whole track's (its thresholds are; laying.extended keeps them), then cut
    p, out, locks, window = _carry_out(tr, tr[c0:], c0, plan, lock, own, own_pop,
                                       FootContacts(whole_c.fps, whole_c.left[c0:], whole_c.right[c0:]))
    if c0:
        out.pose  # (its window's kinematics): the track's pose is then joined from the pieces' (slices know theirs)
        locks = [replace(lk, begin=lk.begin + c0, end=lk.end + c0, release_end=lk.release_end + c0) for lk in locks]
        window = (window[0] + c0, window[1] + c0)
    return p, c0, out, locks, window


def _carry_out(whole: Motion, tr: Motion, c0: int, plan: Plan, lock: bool, own: float, own_pop: float,
               tr_c: FootContacts) -> tuple[Plan, Motion, list[Lock], tuple[int, int]]:
    """:func:`carry_out` on ``tr``, the track ``whole`` from frame ``c0`` on (``tr_c``: its foot contacts):
    the plans are ``whole``'s, the renderings, locks and window ``tr``'s."""
    best = None
    parts = Parts()  # what the renderings share (render.Parts)
    variants = list(VARIANTS)
    if plan.intervals["S0"].kind == "motion-motion":
        variants.append(("roots_mid", False, False))
    candidates = [("", plan)] + [(f"next_best_{k + 1}", replace(plan, intervals={**plan.intervals, "S0": iv}))
                                 for k, iv in enumerate(plan.alternatives)]
    # A rendering is a function of its plan and the feet it holds (render.prepare); "without the step" holds
    # the same feet as with it where no foot has to step across (always in a motion-motion blend): such a
    # variant is the rendering before it again, no better, and is not rendered twice (nor measured).
    # Locking the feet (the costly half of a rendering) turns joints, never the root: a rendering's pop is
    # known before it, and one that pops more than a best that does not skate cannot win (its key is
    # larger whatever it skates) — it is not locked (``None`` in ``seen``); where settle may still place
    # it again, it is locked (settle asks where the locks leave the foot) but neither lifted nor measured.
    # One that pops as much (a best that pops: one that does not ended the search) could win only by
    # skating less, both within the bound: it is not measured either (the variants without the step share
    # their blend, so their root and pop, with the one before; over the corpora's and golden sentences'
    # 597 joins such a tie decided none, and 78 renderings were lifted and measured for it).
    seen: dict = {}

    def popping(bl, prepared) -> float:  # how far the window's pop is over the sources' (the root's: final)
        return max(0.0, _window_pop(bl.out, prepared[3].window) - SOURCE_FACTOR * own_pop)

    def hopeless(over: float) -> bool:
        return best is not None and not best[0][0] and over >= best[0][1]

    for cname, cand in candidates:
        for vname, step, eased in (RUNNER_UP_VARIANTS if cname else variants):
            p_whole = _eased(cand) if eased else (_roots_mid(whole, cand) if vname == "roots_mid" else cand)
            p = _shifted(p_whole, -c0)
            first = prepare(tr, p, step, tr_c, parts)
            key: tuple = (cname, eased, vname == "roots_mid", _held(first))
            again = key in seen
            if not again:
                bl = blended(first, parts)
                over = popping(bl, first)
                if (p.adapted is not None or not lock) and hopeless(over):  # settle moves nothing: final
                    seen[key] = None
                    continue
                # settled from the locked feet alone (a swing lift moves no locked foot); the swings are
                # lifted only on a rendering that is kept, not on one that settle places again
                out, locks, window = finish(first, lock, bl, lift=False)
                moved = settle(out, locks, window, p)
                if moved is None and hopeless(over):  # final as it stands, and cannot win
                    seen[key] = None
                    continue
                if moved is None and lock:
                    out = lift_join(out, locks, window)
                seen[key] = (out, locks, window, moved, bl.out, over)
            if seen[key] is None:
                continue
            out, locks, window, moved, base, over = seen[key]
            if moved is not None:  # placed where the locked foot stands: the next motion's own step needs no release
                p = moved  # settle moves the next motion in space, not in time
                p_whole = replace(moved, inc=p_whole.inc, intervals=p_whole.intervals, alternatives=p_whole.alternatives)
                second = prepare(tr, p, step, tr_c, parts)
                key = (key, _held(second))
                again = key in seen
                if not again:
                    bl = blended(second, parts)
                    over = popping(bl, second)
                    seen[key] = None if hopeless(over) else (*finish(second, lock, bl), None, bl.out, over)
                if seen[key] is None:
                    continue
                out, locks, window, _, base, over = seen[key]
            if again:  # the same rendering as an earlier variant's: its key is that one's, which did not pass
                continue
            sk = _skating(out, base, window, locks) if lock else 0.0  # the blend (the clips' own skating after
            # it, a jump's landing, is not the join's to fix)
            name = "+".join(x for x in (cname, vname) if x)
            if name:
                p_whole = replace(p_whole, info=dict(p_whole.info, fallback=name))
            skates = skating_exceeds(sk, own)
            key = (skates, 0.0 if skates else over, sk)
            if best is None or key < best[0]:
                best = (key, p_whole, out, locks, window)
            if key[:2] == (False, 0.0):
                break
        if best is not None and not best[0][0]:  # a rendering that does not skate: the runners-up are for feet, not for pops
            break
    assert best is not None  # there is always the plan itself
    _, p, out, locks, window = best
    return p, out, locks, window

"""A join rendered until it does not skate (nor pop, where another rendering does not): the paper's
rendering first, then without the step, with S0's weight eased, placed by the roots, and with the
next-best intervals of eq. (10) (:func:`carry_out`)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from text2anim.core.contacts import detect_contacts
from text2anim.core.metrics import SOURCE_FACTOR, root_pop, toe_joints, toe_skating_pairs
from text2anim.core.motion import Motion

from ..join.align import align_through_foot
from ..join.apply import lift_join
from ..join.blend import ease
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


def _window_pop(out: Motion, window: tuple[int, int]) -> float:
    """Root pop (m/s², :func:`core.metrics.quality` at the track's rate) of the blend window and 3 frames
    around: the root's alone, so the same before the feet are locked (locks turn joints, never the root)."""
    return root_pop(out[max(0, window[0] - 3):min(out.n_frames, window[1] + 3)])


def _held(prepared) -> bytes:
    """The feet a prepared rendering holds (:func:`.render.prepare`), as bytes to compare."""
    planted = prepared[3].planted
    return b"".join(np.asarray(planted[s], dtype=bool).tobytes() for s in ("left", "right"))


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
    says which (``fallback``). When every rendering skates, the same is tried with the next-best lower-body
    intervals of eq. (10) (:data:`RUNNERS_UP` of them): the search's minimum subject to the join keeping
    its feet. Deterministic.
    """
    best = None
    tr_c = detect_contacts(tr)  # the track before the join: the same for every rendering
    parts = Parts()  # and what the renderings share (render.Parts)
    variants = [("", True, False), ("no_step", False, False), ("eased", True, True), ("eased_no_step", False, True)]
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
    seen: dict = {}

    def popping(bl, prepared) -> float:  # how far the window's pop is over the sources' (the root's: final)
        return max(0.0, _window_pop(bl.out, prepared[3].window) - SOURCE_FACTOR * own_pop)

    def hopeless(over: float) -> bool:
        return best is not None and not best[0][0] and over > best[0][1]

    for cname, cand in candidates:
        for vname, step, eased in variants:
            p = _eased(cand) if eased else (_roots_mid(tr, cand) if vname == "roots_mid" else cand)
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
                p = moved
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
                p = replace(p, info=dict(p.info, fallback=name))
            skates = skating_exceeds(sk, own)
            key = (skates, 0.0 if skates else over, sk)
            if best is None or key < best[0]:
                best = (key, p, out, locks, window)
            if key[:2] == (False, 0.0):
                break
        if best is not None and not best[0][0]:  # a rendering that does not skate: the runners-up are for feet, not for pops
            break
    assert best is not None  # there is always the plan itself
    _, p, out, locks, window = best
    return p, out, locks, window

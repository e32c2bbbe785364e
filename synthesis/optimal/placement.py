"""Placement: the next motion turned and slid so its support foot stands on the previous motion's
(:func:`alignment`, as paper [6] / seed 003 do), then moved by what the foot locks leave (:func:`settle`)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import FootContacts
from text2anim.core.ground import Rigid, headings, to_heading_frame
from text2anim.core.motion import Motion

from ..join.gait import foot_points_at
from ..join.placed import Placed
from .blend_search import Found
from .method_select import Choice, support_by_gap
from .records import Plan


def _planted_near(contacts: FootContacts, side: str, lo: int, hi: int, target: int, offset: int = 0):
    """The frame in ``[lo, hi]`` (track) nearest ``target`` where ``side`` is down (``contacts`` index = frame -
    ``offset``), or ``None``."""
    c = contacts.of(side)
    f = np.arange(max(lo, offset), min(hi, offset + len(c) - 1) + 1)
    if len(f) == 0:
        return None
    f = f[c[f - offset]]
    return int(f[np.argmin(np.abs(f - target))]) if len(f) else None


def alignment(choice: Choice, s0: Found, tr: Motion, tr_contacts: FootContacts, inc: Placed):
    """``(support, ta, tb)``: the foot (or ``None``: roots) and the track frames of A and B put together."""
    sup = choice.support
    if choice.method == "motion_transition":
        assert sup is not None  # a transition is chosen for steps of one foot
        lo, hi = max(s0.t0, inc.first), s0.t1
        mid = (lo + hi) // 2
        both = tr_contacts.of(sup)[np.clip(np.arange(lo, hi + 1), 0, tr.n_frames - 1)]
        ib = np.clip(np.arange(lo, hi + 1) - inc.offset, 0, inc.motion.n_frames - 1)
        both = both & inc.contacts.of(sup)[ib]
        frames = np.arange(lo, hi + 1)[both]
        if len(frames):
            f = int(frames[np.argmin(np.abs(frames - mid))])
            return sup, f, f
        return None, mid, mid  # no foot down in both: the roots meet in the middle of the blend
    if choice.method == "motion_connection":
        assert sup is not None and choice.p0 is not None  # a connection steps with P0 on its support foot
        ta = _planted_near(tr_contacts, sup, choice.p0.begin - 2, s0.t1, s0.t1)
        tb = _planted_near(inc.contacts, sup, inc.first, inc.offset + inc.core[1], s0.t1, inc.offset)
        if ta is None or tb is None:
            return None, s0.t1, s0.t1
        return sup, ta, tb
    # adaptation: the previous motion's feet where its lower body starts blending, the next's pose at S0's end
    ta, tb = s0.t0, s0.t1
    if sup is None:
        fa = foot_points_at(tr, ta)
        fb = foot_points_at(inc.motion, tb - inc.offset)
        ha = headings(tr, 0.5)[ta]
        hb = headings(inc.motion, 0.5)[tb - inc.offset]
        pa = {s: to_heading_frame(fa[s][None, None, :], np.array([ha]))[0, 0, [0, 2]] for s in fa}
        pb = {s: to_heading_frame(fb[s][None, None, :], np.array([hb]))[0, 0, [0, 2]] for s in fb}
        sup = support_by_gap(pa, pb)
    return sup, ta, tb


#: m: a support foot the locks leave further than this from the next motion's own is re-placed (settle)
SETTLE = 0.005


def settle(out: Motion, locks, window: tuple[int, int], plan: Plan) -> Plan | None:
    """The plan with the next motion slid so that its support foot stands where the join's lock left it.

    A foot locked through the blend follows the planted sources' weighted movement (a heel rolling
    off in the first motion, a landing in the next), so where the lock lets it go, after the blend, can
    differ by a few centimetres from where the next motion itself has that foot — and the release would
    then bend the next motion's leg inside its core. Moving the next motion by that difference *on the
    ground* lets its own foot take over: a slide, never a lift or a drop. Every clip stands on one floor
    (y = 0: the built-in library's and every import's, found from its own contacts), so a locked foot left
    above or below the next motion's own says how far the lock held it off the floor, not where the next
    motion stands: lifting the next motion to it floated a walk after a run 2-2.5 cm (CMU pairs, issue 46;
    47 cm when a lock could not hold a foot down at all). Connections and transitions only (an adaptation's
    feet are the first motion's by construction). ``None`` when nothing needs to move.
    """
    if plan.adapted is not None or not locks:
        return None
    # a foot put down again where a lock could not hold it (Lock.at) stands where the join chose, not where
    # either clip stands: it places nothing
    after = [lk for lk in locks if lk.end > window[1] and lk.at is None]
    mine = [lk for lk in after if lk.side == plan.support] or after
    if not mine:
        return None
    lk = max(mine, key=lambda x: x.end)
    f = lk.end - 1
    own = f - plan.inc.offset
    if not 0 <= own < plan.placed.n_frames:
        return None
    ankle = body_map(out.skeleton).feet[lk.side][0]
    at = out[f:f + 1].positions[0]  # the kinematics of that frame alone
    d = at[ankle] - plan.placed.positions[own, ankle]
    d[1] = 0.0  # on the ground (above)
    if np.linalg.norm(d) < SETTLE:
        return None
    rigid = plan.rigid.then(Rigid(0.0, (float(d[0]), float(d[2]))))
    placed = rigid.apply(plan.inc.motion)
    info = dict(plan.info, settled_cm=[round(100 * float(x), 2) for x in d])
    return replace(plan, rigid=rigid, placed=placed, info=info)

"""Switching frames from foot–ground contact (paper 003 §4.3.1) and gait key frames (§4.3.2).

Connection: near the end of the first motion and near the start of the
second, frames with the *same contact state* are searched; the states need
not agree completely, but at least one foot must be on the ground in both
(the support foot the second motion is aligned through). The paper does not
rank the candidates; this module does, with three terms it documents
(:func:`find_switch`):

1. a state that differs in the other foot costs :data:`PARTIAL_STATE_COST`;
2. the time the switch drops or shifts (seconds, see below);
3. how far the *other* foot would have to travel during the blend after the
   support feet are put together and the headings matched (metres ×
   :data:`OTHER_FOOT_COST`): a planted foot that has to move is a slide or an
   extra step, a swinging one a hurried shuffle, so the candidate that needs
   the least wins.

Pose similarity is deliberately *not* used, as the paper says: the switch is
chosen so that the feet can be kept still.

Transition of cyclic motions: the key frames are *foot lift* (a foot leaves
the ground) and *foot land* (it touches down), the :func:`synthesis.join.gait.steps` of both motions.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from text2anim.core.contacts import FootContacts
from text2anim.core.ground import headings, to_heading_frame
from text2anim.core.motion import Motion

from ..join.gait import foot_points
PARTIAL_STATE_COST = 0.3  # s-equivalent: prefer the full state when it costs less than 0.3 s of motion
OTHER_FOOT_COST = 1.0  # per metre the other planted foot would have to move


@dataclass(frozen=True)
class Switch:
    """Switching frames of a connection.

    ``a`` is the frame of the first motion, ``b`` of the second; ``support``
    the foot (``left``/``right``) in contact in both through which the second
    is aligned, ``None`` when neither foot is down in either (a jump); ``exact``
    whether the whole contact state agrees; ``cost`` the ranking score;
    ``other_gap`` the distance (m) between the other foot's places in the two
    motions after alignment.
    """

    a: int
    b: int
    support: str | None
    exact: bool
    cost: float
    other_gap: float = 0.0


def planted_for(contacts: FootContacts, side: str) -> np.ndarray:
    """For every frame, how many frames from it on the ``side`` foot stays on the ground (0 in the air), ``(T,)``."""
    c = contacts.of(side)
    n = len(c)
    idx = np.where(~c, np.arange(n), n)
    next_off = np.minimum.accumulate(idx[::-1])[::-1]
    return next_off - np.arange(n)


def find_switch(first: Motion, cf: FootContacts, a_range: tuple[int, int],
                second: Motion, cs: FootContacts, b_range: tuple[int, int],
                time_cost) -> Switch:
    """The best pair of switching frames.

    Args:
        first, cf: the first motion and its contacts; ``a`` is searched in ``a_range`` ``[lo, hi)``.
        second, cs: the second motion and its contacts; ``b`` in ``b_range``.
        time_cost: ``f(a (Na,1), b (1,Nb)) -> (Na, Nb)`` seconds: what a pair costs in time
            (frames dropped, or how far the pair is from the scheduled overlap).

    Candidates have at least one foot on the ground in both frames; when there
    is none, the pair of smallest time cost is taken with ``support=None``
    (both motions airborne: aligned at the root).
    """
    a = np.arange(*a_range)
    b = np.arange(*b_range)
    if len(a) == 0 or len(b) == 0:
        raise ValueError("empty switching range")
    tc = np.asarray(time_cost(a[:, None], b[None, :]), dtype=np.float64)
    la, ra = cf.left[a][:, None], cf.right[a][:, None]
    lb, rb = cs.left[b][None, :], cs.right[b][None, :]
    both_l, both_r = la & lb, ra & rb
    exact = (la == lb) & (ra == rb)
    valid = both_l | both_r
    if not valid.any():
        i, j = np.unravel_index(np.argmin(tc), tc.shape)
        return Switch(int(a[i]), int(b[j]), None, bool(exact[i, j]), float(tc[i, j]))
    # Where the other foot would have to go: in each frame's heading frame, the vector from the
    # support foot to the other foot; after alignment the two vectors should coincide.
    fa, fb = foot_points(first), foot_points(second)
    ha, hb = headings(first, 0.5)[a], headings(second, 0.5)[b]
    rel = {}
    for sup, oth in (("left", "right"), ("right", "left")):
        va = to_heading_frame((fa[oth][a] - fa[sup][a])[:, None, :], ha)[:, 0, [0, 2]]
        vb = to_heading_frame((fb[oth][b] - fb[sup][b])[:, None, :], hb)[:, 0, [0, 2]]
        rel[sup] = np.linalg.norm(va[:, None, :] - vb[None, :, :], axis=-1)
    # support: the foot planted in both; when both are, the one the second motion keeps down longer
    keep_l = planted_for(cs, "left")[b][None, :]
    keep_r = planted_for(cs, "right")[b][None, :]
    sup_left = both_l & (~both_r | (keep_l >= keep_r))
    gap = np.where(sup_left, rel["left"], rel["right"])
    cost = tc + PARTIAL_STATE_COST * (~exact) + OTHER_FOOT_COST * gap
    cost = np.where(valid, cost, np.inf)
    i, j = np.unravel_index(np.argmin(cost), cost.shape)
    return Switch(int(a[i]), int(b[j]), "left" if sup_left[i, j] else "right", bool(exact[i, j]),
                  float(cost[i, j]), float(gap[i, j]))

"""§4.1 and §4.2.5: the join's method from the foot–ground constraints around the two cores on the track,
and the bounds its blend ranges (§4.2) must keep (:mod:`synthesis.optimal.method_select`)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from text2anim.core.contacts import FootContacts

from ..join.gait import steps
from ..join.placed import Placed
from .blend_ranges import Bounds
from .method_select import Choice, cyclic_core_begin, cyclic_core_end, select


def _supported(choice: Choice, contacts: FootContacts, latest: int) -> Choice:
    """A connection's step begins (eq. (3): ``t_s0,begin = t_p0,begin``) when its foot is in the air *and*
    the support foot is down: in a run both feet are off the ground as one lifts, and a lower body frozen
    or blended from that instant has no foot to stand on. The first such frame of ``P0`` (no later than
    ``latest``); ``P0`` as it was when there is none (a jump)."""
    p0 = choice.p0
    assert p0 is not None and choice.support is not None  # a connection steps with P0 on its support foot
    c = contacts.of(choice.support)
    f = np.arange(p0.begin, min(p0.end, latest + 1))
    f = f[(f < len(c)) & c[np.clip(f, 0, len(c) - 1)]]
    if len(f) == 0 or f[0] == p0.begin:
        return choice
    return replace(choice, p0=replace(p0, begin=int(f[0])))


def geometry(tr_contacts: FootContacts, prev: Placed, inc: Placed, floor: int, min_len: int):
    a_steps = steps(tr_contacts, start=max(prev.offset, 0))
    c0 = (prev.offset + prev.core[0], prev.offset + prev.core[1])
    a_end = prev.offset + prev.stop
    c0_end = c0[1]
    if prev.cyclic:  # a loop's core ends at its last step — or where the next motion is scheduled to start
        c0_end = min(cyclic_core_end(a_steps, prev.offset + prev.lead, a_end, c0), max(inc.first, c0[0] + 1))
    b_steps = steps(inc.contacts, inc.offset)
    c1 = (inc.offset + inc.core[0], inc.offset + inc.core[1])
    if inc.cyclic:
        c1 = (cyclic_core_begin(b_steps, inc.first, c1), c1[1])
    choice = select(a_steps, b_steps, c0_end, c1, floor=floor, b_first=inc.first, min_frames=min_len)
    if choice.method == "motion_connection":
        choice = _supported(choice, tr_contacts, c1[0] - min_len)
    bounds = Bounds(c0_end, c1, a_end, inc.first, inc.end, floor, min_len)
    return choice, bounds, a_steps

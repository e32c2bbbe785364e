"""§4.4: the weight curve of a searched blend interval (Hermite, eq. (16) slopes; §4.4.2's cases)."""
from __future__ import annotations

import numpy as np

from .blend_ranges import Range
from .blend_search import Found
from .records import Interval
from .search import Features, ends
from .weights import hermite_weights, plan_partial, slope


def interval_weights(name: str, r: Range, found: Found, feats: Features, fps: float, min_len: int) -> Interval:
    """§4.4: the weight curve of a searched interval (and the §4.4.2 case, which may move an end)."""
    t0, t1, kind = found.t0, found.t1, r.kind
    case = "hermite"
    D, V0, V1 = found.D, found.V0, found.V1
    if kind == "motion-motion":  # eq. (16) from the start and end poses (the search compared the pairs)
        D, V0, V1 = ends(feats, r, t0, t1, fps)
    if kind in ("motion-pose", "pose-motion"):
        frames = np.arange(t0, t1 + 1)
        if kind == "motion-pose":  # the moving first source against the end pose
            d = np.linalg.norm(feats(r.src[0], r.part, frames) - feats(r.src[1], r.part, [t1]), axis=-1).mean(-1)
        else:  # the start pose against the moving second source
            d = np.linalg.norm(feats(r.src[0], r.part, [t0]) - feats(r.src[1], r.part, frames), axis=-1).mean(-1)
        pp = plan_partial(kind, d, min_len)
        case, kind = pp.case, pp.kind
        if (pp.begin, pp.end) != (0, t1 - t0):
            t0, t1 = t0 + pp.begin, t0 + pp.end
            D, V0, V1 = ends(feats, r, t0, t1, fps)
    T = (t1 - t0) / fps
    m0, m1 = slope(V0, D, T), slope(V1, D, T)  # eq. (16), 0 on reversal
    w = hermite_weights(t1 - t0, m0, m1)
    return Interval(name, r.part, kind, t0, t1, w, r.src, case, found, r, (m0, m1))

"""§4.3, eqs. (10)–(15): the blend interval ``t0``, ``t1`` that minimises eq. (10) over a range.

The features (Kovar's point clouds, :mod:`synthesis.optimal.posedist`) of the join's sources are looked up per
body part once (:class:`Features`); :mod:`synthesis.optimal.blend_search` evaluates every candidate pair.
A blend of the legs into a held pose never ends on a frame where the second source is off its floor
(:func:`core.hang.off_its_floor`), and a blend between two poses not within :data:`AIR_AHEAD` before it
leaves it (each unless it leaves no blend that fits): a standing pose blended into
a run's flight, or its toe-off, lifts both feet with the hips level, a body hanging in the air
(``core.hang``); blended into the stance, one foot stays down while the other swings, as a run starts.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.hang import off_its_floor
from text2anim.core.motion import Motion

from ..join.placed import Placed
from .blend_ranges import Range
from .blend_search import Found, Weights, best, evaluate, evaluate_motions
from .posedist import distance, features, part_joints


#: s: where it has the choice, a blend of the legs between two poses does not end this close before the second
#: source leaves its floor: blended from standing into a run's toe-off, both feet rose together and the flight hung (0.25 s)
AIR_AHEAD = 0.1


def _sources(tr: Motion, inc: Placed, adapted: Motion | None):
    """Source name → (motion, track frame of its frame 0)."""
    return {"A": (tr, 0), "B": (inc.motion, inc.offset),
            "Bad": (adapted if adapted is not None else inc.motion, inc.offset)}


class Features:
    """Kovar features of the join's sources, joints per part looked up once."""

    def __init__(self, tr: Motion, inc: Placed, adapted: Motion | None = None):
        self.src = _sources(tr, inc, adapted)
        self.joints = {p: part_joints(tr, p) for p in ("lower", "upper")}

    def __call__(self, name: str, part: str, frames) -> np.ndarray:
        motion, off = self.src[name]
        return features(motion, self.joints[part], np.asarray(frames) - off)

    def airborne(self, name: str, frames) -> np.ndarray:
        """Bool of the shape of ``frames``: whether source ``name`` is off its own floor at these track frames
        (:func:`core.hang.off_its_floor`; frames outside it count as down)."""
        motion, off = self.src[name]
        air = motion.cache.get(("off_its_floor",), lambda: off_its_floor(motion))
        i = np.asarray(frames) - off
        ok = (i >= 0) & (i < len(air))
        return np.where(ok, air[np.clip(i, 0, len(air) - 1)], False)


def grid(r: Range, feats: Features, fps: float, weights: Weights, min_len: int):
    """eq. (10) over every candidate pair of the range (:mod:`synthesis.optimal.blend_search`)."""
    if r.kind == "motion-motion":
        f0 = np.arange(r.t0[0], r.t0[1] + 2)
        f1 = np.arange(r.t1[0], r.t1[1] + 2)
        return evaluate_motions(feats(r.src[0], r.part, f0), feats(r.src[1], r.part, f0),
                                feats(r.src[0], r.part, f1), feats(r.src[1], r.part, f1), r.t0, r.t1, fps, weights,
                                r.p_len, min_len)
    f_from = feats(r.src[0], r.part, np.arange(r.t0[0], r.t0[1] + 2))
    f_to = feats(r.src[1], r.part, np.arange(r.t1[0] - 1, r.t1[1] + 1))
    g = evaluate(f_from, f_to, r.t0, r.t1, fps, weights, r.p_len, min_len)
    if r.part == "lower":
        # a blend of the legs never ends on a pose in the air, nor (where it has the choice) a blend between two
        # poses just before one: it would lift both feet together into the take-off
        ahead = max(1, int(round(AIR_AHEAD * fps))) if r.kind == "pose-pose" else 0
        air = feats.airborne(r.src[1], g.t1[None, :] + np.arange(ahead + 1)[:, None])  # (ahead + 1, N1)
        for mask in (air.any(axis=0), air[0]):
            if mask.any() and np.isfinite(g.cost[:, ~mask]).any():  # unless that leaves no blend
                g.cost[:, mask] = np.inf
                break
    return g


def search(r: Range, feats: Features, fps: float, weights: Weights, min_len: int) -> Found:
    """The global minimum of eq. (10) over the range."""
    return best(grid(r, feats, fps, weights, min_len), weights, min_len)


def runners_up(g, weights: Weights, k: int) -> list[Found]:
    """The ``k`` next-best pairs of eq. (10) after the minimum of the evaluated :func:`grid` ``g``, in order
    of cost (ties: earlier first)."""
    flat = g.cost.ravel()
    order = np.argsort(flat, kind="stable")
    order = order[np.isfinite(flat[order])][1:k + 1]
    out = []
    for o in order:
        i, j = np.unravel_index(int(o), g.cost.shape)
        out.append(Found(int(g.t0[i]), int(g.t1[j]), float(g.Qt[i, j]), float(g.D[i, j]), float(g.Qv[i, j]),
                         float(g.V0[i, j]), float(g.V1[i, j]), float(g.cost[i, j]), weights))
    return out


def ends(feats: Features, r: Range, t0: int, t1: int, fps: float) -> tuple[float, float, float]:
    """``D(t0, t1)`` and the eq. (14) speeds ``V(t0)``, ``V(t1)`` of an interval (m, m/s)."""
    fa = feats(r.src[0], r.part, [t0, t0 + 1])
    fb = feats(r.src[1], r.part, [t1 - 1, t1])
    D = distance(fa[0], fb[1])
    return D, (D - distance(fa[1], fb[1])) * fps, (D - distance(fa[0], fb[0])) * fps

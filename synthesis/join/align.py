"""Placing a clip on a track: at the track's origin (:func:`place_at`) or through the support foot
(:func:`align_through_foot`, paper 003 §4.3: the next motion is turned about +Y and slid over the ground
so that, at the switching frames, its support foot stands where the previous motion's does and its body
faces the same way). Both are a :class:`core.ground.Rigid`; :func:`moved_by` applies one, kept with the clip.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.ground import Rigid, headings, match
from text2anim.core.motion import Motion


def place_at(motion: Motion, origin: tuple[float, float], heading: float, frame: int = 0,
             smooth: float = 0.5) -> Rigid:
    """The move that puts ``motion``'s root over ``origin`` (x, z) facing ``heading`` (smoothed over
    ``smooth`` seconds, see :func:`headings`) at ``frame``."""
    h = headings(motion, smooth)[frame]
    return match(motion.root_positions[frame], h, np.array([origin[0], 0.0, origin[1]]), heading)


def align_through_foot(prev: Motion, a: int, nxt: Motion, b: int, side: str | None,
                       smooth: float = 0.5) -> Rigid:
    """Move ``nxt`` so its frame ``b`` continues ``prev``'s frame ``a`` (paper 003 §4.3).

    The heading (smoothed over ``smooth`` seconds) of ``nxt`` at ``b`` is turned
    onto ``prev``'s at ``a`` and the ``side`` foot's lowest joint of ``nxt``
    at ``b`` is put over the same foot of ``prev`` at ``a``. ``side=None``
    (no foot on the ground in either) aligns the roots instead.
    """
    ha = headings(prev, smooth)[a]
    hb = headings(nxt, smooth)[b]
    if side is None:
        pa, pb = prev.root_positions[a], nxt.root_positions[b]
    else:
        ankle, toe = body_map(prev.skeleton).feet[side]
        pa = prev[a:a + 1].positions[0, [ankle, toe]].mean(axis=0)  # (that frame's kinematics alone)
        pb = nxt.positions[b, [ankle, toe]].mean(axis=0)
    return match(pb, hb, pa, ha)


def moved_by(motion: Motion, rigid: Rigid) -> Motion:
    """``rigid.apply(motion)``, the last such kept with ``motion`` (by the move's exact bits): a warm process plans
    the same join again (the studio at every pause in typing) and gets the same placed motion, with the
    kinematics and the features computed from it the first time."""
    key = (rigid.yaw.hex(), tuple(float(x).hex() for x in rigid.offset))
    known = motion.cache.known("align.moved")
    if known is not None and known[0] == key:
        return known[1]
    return motion.cache.put("align.moved", (key, rigid.apply(motion)))[1]

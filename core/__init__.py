"""The motion core: skeletons, motions and their derived data, BVH and glTF reading, contacts, metrics, IK.

Units and conventions: metres, seconds, Y up, right-handed; quaternions
``(x, y, z, w)`` as scipy uses them. This package knows nothing of
Japanese and imports no stage: every stage may use it. The writers and pictures (BVH, GLB, VRMA,
the HTML viewer, plots, contact sheets) are :mod:`text2anim.output`.

The names below are imported on first use, so ``import text2anim.core.bodyparts``
does not pay for scipy.
"""
from __future__ import annotations

from .lazy import lazy_attribute

_LAZY = {
    "BVHError": "bvh", "parse_bvh": "bvh", "read_bvh": "bvh",
    "Motion": "motion", "Pose": "fk", "concatenate": "motion",
    "Skeleton": "skeleton",
}

__all__ = sorted(_LAZY)


def __getattr__(name: str):
    return lazy_attribute(__name__, _LAZY, name)

"""Motion core and synthesis: skeletons, motions, BVH, contacts, metrics, joining clips.

Units and conventions: metres, seconds, Y up, right-handed; quaternions
``(x, y, z, w)`` as scipy uses them. This package knows nothing of Japanese.
"""
from .bvh import BVHError, format_bvh, parse_bvh, read_bvh, write_bvh
from .motion import Motion, Pose, concatenate
from .skeleton import Skeleton

__all__ = ["BVHError", "Motion", "Pose", "Skeleton", "concatenate", "format_bvh", "parse_bvh", "read_bvh", "write_bvh"]

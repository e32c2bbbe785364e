"""The canonical skeleton of the built-in library.

CMU joint names and hierarchy (the 31 joints of the cgspeed BVH release, so
:func:`core.bodyparts.body_map` works unchanged), human proportions of a
1.70 m adult, metres, Y up, facing +Z. The rest pose is a T-pose with every
joint's axes aligned with the world: arms along +-X (palms down), legs
straight down, feet flat and pointing +Z. Channels are CMU-style: the root
has XYZ position + ZYX rotation, every other joint ZYX rotation.

Heights in the rest pose with the root at :data:`REST_ROOT_HEIGHT` (0.94 m),
measured from the bare sole: ankle 0.075, ball of the foot (toe joint) 0.02,
hip joints 0.88, chest (Spine1) 1.22, shoulders 1.37, neck base 1.42, skull
base 1.54, top of the head 1.70 m. The skeleton is exactly left/right symmetric.

The character stands on a shoe sole :data:`SHOE_SOLE` (1.8 cm) thick: the
library's floor convention (:data:`core.floor.FOOT_CLEARANCE`) puts a planted
toe joint 3.8 cm above the floor, where the calibrated floors of the CMU
capture sessions put it (subjects in shoes). Keyframed poses are written from
the bare sole and lifted by :data:`SHOE_SOLE` when generated.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from text2anim.core.floor import FOOT_CLEARANCE
from text2anim.core.skeleton import Skeleton

#: Root height of the rest pose (straight legs, feet flat on y = 0).
REST_ROOT_HEIGHT = 0.94
#: Height of the toe joint (ball of the foot) above the bare sole.
TOE_HEIGHT = 0.02
#: Shoe sole under the bare sole (m): a planted toe joint is FOOT_CLEARANCE above the floor.
SHOE_SOLE = FOOT_CLEARANCE - TOE_HEIGHT
#: Ankle joint centre above the bare sole.
ANKLE_HEIGHT = 0.075

# name, parent, offset from parent (metres); left side only, the right is mirrored.
_LEFT_LEG = (
    ("LHipJoint", "Hips", (0.0, 0.0, 0.0)),
    ("LeftUpLeg", "LHipJoint", (0.09, -0.06, 0.0)),
    ("LeftLeg", "LeftUpLeg", (0.0, -0.40, 0.0)),
    ("LeftFoot", "LeftLeg", (0.0, -0.405, 0.0)),
    ("LeftToeBase", "LeftFoot", (0.0, -(ANKLE_HEIGHT - TOE_HEIGHT), 0.13)),
)
_TORSO = (
    ("LowerBack", "Hips", (0.0, 0.0, 0.0)),
    ("Spine", "LowerBack", (0.0, 0.10, 0.0)),
    ("Spine1", "Spine", (0.0, 0.18, 0.0)),
    ("Neck", "Spine1", (0.0, 0.0, 0.0)),
    ("Neck1", "Neck", (0.0, 0.20, 0.0)),
    ("Head", "Neck1", (0.0, 0.12, 0.01)),
)
_LEFT_ARM = (
    ("LeftShoulder", "Spine1", (0.0, 0.0, 0.0)),
    ("LeftArm", "LeftShoulder", (0.18, 0.15, 0.0)),
    ("LeftForeArm", "LeftArm", (0.29, 0.0, 0.0)),
    ("LeftHand", "LeftForeArm", (0.25, 0.0, 0.0)),
    ("LeftFingerBase", "LeftHand", (0.0, 0.0, 0.0)),
    ("LeftHandIndex1", "LeftFingerBase", (0.08, 0.0, 0.0)),
    ("LThumb", "LeftHand", (0.0, 0.0, 0.0)),
)
_END_SITES = {
    "LeftToeBase": (0.0, 0.0, 0.06),
    "Head": (0.0, 0.16, 0.0),
    "LeftHandIndex1": (0.07, 0.0, 0.0),
    "LThumb": (0.03, 0.0, 0.04),
}


def _right(name: str) -> str:
    if name.startswith("Left"):
        return "Right" + name[4:]
    if name.startswith("L") and name[1].isupper():
        return "R" + name[1:]
    return name


def _mirrored(rows):
    return tuple((_right(n), _right(p), (-o[0], o[1], o[2])) for n, p, o in rows)


# CMU order: Hips, left leg, right leg, torso+head, left arm, right arm.
_ROWS = (("Hips", None, (0.0, 0.0, 0.0)),) + _LEFT_LEG + _mirrored(_LEFT_LEG) + _TORSO[:4] + _TORSO[4:] \
    + _LEFT_ARM + _mirrored(_LEFT_ARM)


@lru_cache(maxsize=1)
def canonical_skeleton() -> Skeleton:
    """The built-in library's skeleton (31 CMU joints, 1.70 m, metres, Y up, facing +Z)."""
    names = tuple(r[0] for r in _ROWS)
    parents = np.array([-1 if p is None else names.index(p) for _, p, _ in _ROWS], dtype=np.int64)
    offsets = np.array([o for _, _, o in _ROWS], dtype=np.float64)
    ends = dict(_END_SITES)
    for n, o in list(ends.items()):
        if _right(n) != n:
            ends[_right(n)] = (-o[0], o[1], o[2])
    end_sites = tuple((names.index(n), np.array(o)) for n, o in ends.items())
    end_sites = tuple(sorted(end_sites, key=lambda e: e[0]))
    return Skeleton(names, parents, offsets, end_sites)

"""Known rigs: which joint of a skeleton plays which humanoid role.

Roles are the VRM humanoid bone names (``hips``, ``spine``, ``chest``,
``upperChest``, ``neck``, ``head``, ``leftShoulder``, ``leftUpperArm``,
``leftLowerArm``, ``leftHand``, ``leftUpperLeg``, ``leftLowerLeg``,
``leftFoot``, ``leftToes`` and the ``right*`` ones). Retargeting
(:mod:`core.retarget`) carries motion from role to role; joints with no role
(fingers, twist bones, CMU's ``LHipJoint``, an extra spine or neck joint)
are left at their rest rotation relative to their parent.

A rig is recognised by its joint names (:data:`RIGS`: CMU/cgspeed and the
built-in skeleton, Mixamo, VRM, SMPL's 22 body joints, the Unreal
mannequin); names are compared without a namespace prefix (``mixamorig:``)
and without case. ``--map FILE`` gives the rest: a JSON object
``{role: joint name}`` (see :func:`load_joint_map`) laid over the best
matching known rig.
"""
from __future__ import annotations

import json
from pathlib import Path

from .inputs import read_input
from .skeleton import Skeleton

_SIDED = ("Shoulder", "UpperArm", "LowerArm", "Hand", "UpperLeg", "LowerLeg", "Foot", "Toes")
#: Every role, parents before children.
ROLES = ("hips", "spine", "chest", "upperChest", "neck", "head") + tuple(
    f"{side}{part}" for side in ("left", "right") for part in _SIDED)
#: Roles every rig must place (VRM 1.0's required humanoid bones).
REQUIRED = ("hips", "spine", "head") + tuple(
    f"{side}{part}" for side in ("left", "right")
    for part in ("UpperArm", "LowerArm", "Hand", "UpperLeg", "LowerLeg", "Foot"))
#: The role each role hangs from (its nearest possible ancestor role).
ROLE_PARENT = {
    "spine": "hips", "chest": "spine", "upperChest": "chest", "neck": "upperChest", "head": "neck",
    **{f"{s}Shoulder": "upperChest" for s in ("left", "right")},
    **{f"{s}UpperArm": f"{s}Shoulder" for s in ("left", "right")},
    **{f"{s}LowerArm": f"{s}UpperArm" for s in ("left", "right")},
    **{f"{s}Hand": f"{s}LowerArm" for s in ("left", "right")},
    **{f"{s}UpperLeg": "hips" for s in ("left", "right")},
    **{f"{s}LowerLeg": f"{s}UpperLeg" for s in ("left", "right")},
    **{f"{s}Foot": f"{s}LowerLeg" for s in ("left", "right")},
    **{f"{s}Toes": f"{s}Foot" for s in ("left", "right")},
}


def _sided(left: dict[str, str], right_of) -> dict[str, str]:
    out = dict(left)
    for role, name in left.items():
        if role.startswith("left"):
            out["right" + role[4:]] = right_of(name)
    return out


_CMU = _sided({
    "hips": "Hips", "spine": "LowerBack", "chest": "Spine", "upperChest": "Spine1", "neck": "Neck",
    "head": "Head", "leftShoulder": "LeftShoulder", "leftUpperArm": "LeftArm", "leftLowerArm": "LeftForeArm",
    "leftHand": "LeftHand", "leftUpperLeg": "LeftUpLeg", "leftLowerLeg": "LeftLeg", "leftFoot": "LeftFoot",
    "leftToes": "LeftToeBase"}, lambda n: "Right" + n[4:])
_MIXAMO = {**{r: n for r, n in _CMU.items() if r not in ("spine", "chest", "upperChest")},
           "spine": "Spine", "chest": "Spine1", "upperChest": "Spine2"}
_VRM = {r: r for r in ROLES}
_SMPL = _sided({
    "hips": "pelvis", "spine": "spine1", "chest": "spine2", "upperChest": "spine3", "neck": "neck",
    "head": "head", "leftShoulder": "left_collar", "leftUpperArm": "left_shoulder", "leftLowerArm": "left_elbow",
    "leftHand": "left_wrist", "leftUpperLeg": "left_hip", "leftLowerLeg": "left_knee", "leftFoot": "left_ankle",
    "leftToes": "left_foot"}, lambda n: "right" + n[4:])
_UNREAL = _sided({
    "hips": "pelvis", "spine": "spine_01", "chest": "spine_02", "upperChest": "spine_03", "neck": "neck_01",
    "head": "head", "leftShoulder": "clavicle_l", "leftUpperArm": "upperarm_l", "leftLowerArm": "lowerarm_l",
    "leftHand": "hand_l", "leftUpperLeg": "thigh_l", "leftLowerLeg": "calf_l", "leftFoot": "foot_l",
    "leftToes": "ball_l"}, lambda n: n[:-1] + "r")

#: Known rigs: role -> joint name (compared without namespace and case).
RIGS: dict[str, dict[str, str]] = {"cmu": _CMU, "mixamo": _MIXAMO, "vrm": _VRM, "smpl": _SMPL, "unreal": _UNREAL}


class RigError(ValueError):
    """A skeleton whose humanoid roles cannot be placed; the message names the missing ones."""

    user_facing = True


def _key(name: str) -> str:
    return name.rsplit(":", 1)[-1].lower()


def load_joint_map(path: str | Path) -> dict[str, str]:
    """Read a ``--map`` file: a JSON object ``{role: joint name}``; roles are :data:`ROLES`."""
    try:
        data = json.loads(read_input(path, "joint map", RigError).decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise RigError(f"{path}: not a JSON joint map ({exc})") from None
    if not isinstance(data, dict) or not all(isinstance(k, str) and isinstance(v, str) for k, v in data.items()):
        raise RigError(f'{path}: a joint map is a JSON object of role -> joint name, e.g. {{"hips": "pelvis"}}')
    unknown = sorted(set(data) - set(ROLES))
    if unknown:
        raise RigError(f"{path}: unknown roles {', '.join(unknown)}; roles are {', '.join(ROLES)}")
    return dict(data)


def _place(skel: Skeleton, table: dict[str, str]) -> dict[str, int]:
    index = {_key(n): j for j, n in enumerate(skel.names)}
    return {role: index[_key(name)] for role, name in table.items() if _key(name) in index}


def rig_roles(skel: Skeleton, joint_map: dict[str, str] | None = None) -> tuple[str, dict[str, int]]:
    """``(rig name, {role: joint index})`` for ``skel``.

    The known rig that places the most required roles (then the most roles) is taken; ``joint_map`` entries
    (``{role: joint name}``) are laid over it. Raises :class:`RigError` naming
    the required roles that stay unplaced, and any joint of the map the
    skeleton lacks.
    """
    placed = {name: _place(skel, t) for name, t in RIGS.items()}
    closest = min(placed, key=lambda n: (-sum(r in placed[n] for r in REQUIRED), -len(placed[n]), n))
    roles = dict(placed[closest])
    best = closest
    if joint_map:
        missing = [n for n in joint_map.values() if _key(n) not in {_key(x) for x in skel.names}]
        if missing:
            raise RigError(f"the joint map names joints this skeleton lacks: {', '.join(missing)}")
        roles.update(_place(skel, joint_map))
        best = closest + "+map" if placed[closest] else "map"
    unplaced = [r for r in REQUIRED if r not in roles]
    if unplaced:
        listed = ", ".join(f"{r} (e.g. {RIGS[closest].get(r, r)!r})" for r in unplaced)
        raise RigError(f"cannot place these joints of the rig (closest known rig: {closest}): {listed}; "
                       "give them with --map FILE, a JSON object of role -> joint name")
    return best, dict(sorted(roles.items(), key=lambda kv: ROLES.index(kv[0])))

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
mannequin, cgspeed's Daz-friendly CMU, Daz Genesis, 3ds Max Biped, the
Bandai Namco research set, Rokoko, Blender Rigify's ``DEF-`` bones); names are compared without a namespace prefix (``mixamorig:``)
and without case. ``--map FILE`` gives the rest: a JSON object
``{role: joint name}`` (see :func:`load_joint_map`) laid over the best
matching known rig.
"""
from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

from .rig_error import RigError
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

# cgspeed's "Daz-friendly" CMU conversion (lButtock, a hip joint, has no role).
_DAZ = _sided({
    "hips": "hip", "spine": "abdomen", "chest": "chest", "neck": "neck", "head": "head",
    "leftShoulder": "lCollar", "leftUpperArm": "lShldr", "leftLowerArm": "lForeArm", "leftHand": "lHand",
    "leftUpperLeg": "lThigh", "leftLowerLeg": "lShin", "leftFoot": "lFoot", "leftToes": "lToe"}, lambda n: "r" + n[1:])
# Daz Genesis 3/8: bend joints carry the role, twist joints are extras.
_GENESIS = _sided({
    "hips": "hip", "spine": "abdomenLower", "chest": "abdomenUpper", "upperChest": "chestLower", "neck": "neckLower",
    "head": "head", "leftShoulder": "lCollar", "leftUpperArm": "lShldrBend", "leftLowerArm": "lForearmBend",
    "leftHand": "lHand", "leftUpperLeg": "lThighBend", "leftLowerLeg": "lShin", "leftFoot": "lFoot",
    "leftToes": "lToe"}, lambda n: "r" + n[1:])
_BIPED = _sided({  # 3ds Max Biped
    "hips": "Bip01 Pelvis", "spine": "Bip01 Spine", "chest": "Bip01 Spine1", "upperChest": "Bip01 Spine2",
    "neck": "Bip01 Neck", "head": "Bip01 Head", "leftShoulder": "Bip01 L Clavicle",
    "leftUpperArm": "Bip01 L UpperArm", "leftLowerArm": "Bip01 L Forearm", "leftHand": "Bip01 L Hand",
    "leftUpperLeg": "Bip01 L Thigh", "leftLowerLeg": "Bip01 L Calf", "leftFoot": "Bip01 L Foot",
    "leftToes": "Bip01 L Toe0"}, lambda n: n.replace(" L ", " R "))
_BANDAI = _sided({  # Bandai Namco Research motion dataset
    "hips": "Hips", "spine": "Spine", "chest": "Chest", "neck": "Neck", "head": "Head",
    "leftShoulder": "Shoulder_L", "leftUpperArm": "UpperArm_L", "leftLowerArm": "LowerArm_L",
    "leftHand": "Hand_L", "leftUpperLeg": "UpperLeg_L", "leftLowerLeg": "LowerLeg_L", "leftFoot": "Foot_L",
    "leftToes": "Toes_L"}, lambda n: n[:-1] + "R")
_ROKOKO = _sided({
    "hips": "Hips", "spine": "Spine1", "chest": "Spine2", "upperChest": "Spine4", "neck": "Neck", "head": "Head",
    "leftShoulder": "LeftShoulder", "leftUpperArm": "LeftArm", "leftLowerArm": "LeftForeArm",
    "leftHand": "LeftHand", "leftUpperLeg": "LeftThigh", "leftLowerLeg": "LeftShin", "leftFoot": "LeftFoot",
    "leftToes": "LeftToe"}, lambda n: "Right" + n[4:])
_RIGIFY = _sided({  # Blender Rigify's deform bones
    "hips": "DEF-spine", "spine": "DEF-spine.001", "chest": "DEF-spine.002", "upperChest": "DEF-spine.003",
    "neck": "DEF-spine.004", "head": "DEF-spine.006", "leftShoulder": "DEF-shoulder.L",
    "leftUpperArm": "DEF-upper_arm.L", "leftLowerArm": "DEF-forearm.L", "leftHand": "DEF-hand.L",
    "leftUpperLeg": "DEF-thigh.L", "leftLowerLeg": "DEF-shin.L", "leftFoot": "DEF-foot.L",
    "leftToes": "DEF-toe.L"}, lambda n: n[:-1] + "R")

#: Known rigs: role -> joint name (compared without namespace and case).
RIGS: dict[str, dict[str, str]] = {
    "cmu": _CMU, "mixamo": _MIXAMO, "vrm": _VRM, "smpl": _SMPL, "unreal": _UNREAL, "daz": _DAZ,
    "genesis": _GENESIS, "biped": _BIPED, "bandai": _BANDAI, "rokoko": _ROKOKO, "rigify": _RIGIFY}


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


def _place(names: tuple[str, ...], table: dict[str, str]) -> dict[str, int]:
    index = {_key(n): j for j, n in enumerate(names)}
    return {role: index[_key(name)] for role, name in table.items() if _key(name) in index}


def closest_rig(names: tuple[str, ...]) -> tuple[str, dict[str, int]]:
    """``(rig name, {role: joint index})`` of the known rig that places the most required roles, then the most roles."""
    closest, placed = _closest_rig(names)
    return closest, dict(placed)


@lru_cache(maxsize=64)
def _closest_rig(names: tuple[str, ...]) -> tuple[str, tuple[tuple[str, int], ...]]:
    """:func:`closest_rig`, kept per skeleton: every join's balance asks it of the same names (3 ms a warm call)."""
    placed = {name: _place(names, t) for name, t in RIGS.items()}
    closest = min(placed, key=lambda n: (-sum(r in placed[n] for r in REQUIRED), -len(placed[n]), n))
    return closest, tuple(placed[closest].items())


def rig_roles(skel: Skeleton, joint_map: dict[str, str] | None = None) -> tuple[str, dict[str, int]]:
    """``(rig name, {role: joint index})`` for ``skel``.

    The known rig that places the most required roles (then the most roles) is taken; ``joint_map`` entries
    (``{role: joint name}``) are laid over it. Raises :class:`RigError` naming
    the required roles that stay unplaced, and any joint of the map the
    skeleton lacks.
    """
    closest, found = closest_rig(skel.names)
    roles = dict(found)
    best = closest
    if joint_map:
        missing = [n for n in joint_map.values() if _key(n) not in {_key(x) for x in skel.names}]
        if missing:
            raise RigError(f"the joint map names joints this skeleton lacks: {', '.join(missing)}")
        roles.update(_place(skel.names, joint_map))
        best = closest + "+map" if found else "map"
    unplaced = [r for r in REQUIRED if r not in roles]
    if unplaced and not joint_map:  # no name table knows it: read the limbs from the skeleton's shape
        from .skeleton_shape import infer_roles

        try:
            shape = infer_roles(skel)  # the names where they place roles; the shape the required ones they miss
            merged = {**roles, **{r: shape[r] for r in unplaced if r in shape}} if roles else shape
            return ("shape" if not roles else closest + "+shape"), dict(
                sorted(merged.items(), key=lambda kv: ROLES.index(kv[0])))
        except RigError as exc:
            why = f"; read by its shape: {exc}"
    else:
        why = ""
    if unplaced:
        listed = ", ".join(f"{r} (e.g. {RIGS[closest].get(r, r)!r})" for r in unplaced)
        raise RigError(f"cannot place these joints of the rig (closest known rig: {closest}): {listed}{why}; "
                       "give them with --map FILE, a JSON object of role -> joint name")
    return best, dict(sorted(roles.items(), key=lambda kv: ROLES.index(kv[0])))

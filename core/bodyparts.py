"""Body-part groups from joint names.

Names are matched after dropping a namespace prefix (``mixamorig:``) and
separators; side comes from ``Left``/``Right`` anywhere, or a lone ``L``/``R``
prefix or suffix (``LHipJoint``, ``hand.L``, ``Hand_R``). A joint whose name
says nothing (an end effector, a finger, Unreal's ``ball_l``) takes its parent's
group. A sided hip (SMPL's ``left_hip``) is the top of that leg. Covered:
CMU/cgspeed, Mixamo, the built-in skeleton (CMU names), VRM humanoid bone
names, SMPL's 22 joints and the Unreal mannequin (see :mod:`core.rigs` for
which joint plays which role in retargeting).
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Literal, get_args

if TYPE_CHECKING:  # only named: `text2anim plan` reads the body parts without loading numpy
    from .skeleton import Skeleton

#: The groups a partial action may be declared for, plus the whole halves.
#: A body-part group: what a partial action is declared for (``ClipRecord.body_part``) and what a
#: composition takes from its clip.
BodyPart = Literal["lower", "upper", "right_arm", "left_arm", "both_arms", "head", "torso", "right_leg", "left_leg"]
#: Every :data:`BodyPart`, in this order.
GROUPS: tuple[BodyPart, ...] = get_args(BodyPart)

_KEYWORDS = (  # first match wins, so "forearm" is an arm before anything else
    ("head", ("neck", "head", "jaw", "eye", "nose", "skull")),
    ("arm", ("shoulder", "clavicle", "collar", "arm", "elbow", "hand", "wrist", "finger", "thumb",
             "index", "middle", "ring", "pinky", "palm")),
    ("leg", ("upleg", "thigh", "leg", "knee", "shin", "calf", "foot", "ankle", "toe", "hipjoint", "heel")),
    ("torso", ("spine", "chest", "back", "abdomen", "torso", "waist", "belly")),
    ("hips", ("hips", "hip", "pelvis", "root")),
)


class BodyMapError(ValueError):
    """A skeleton whose joints cannot all be placed in body parts."""

    user_facing = True


def _strip(name: str) -> str:
    return name.rsplit(":", 1)[-1]


def side_of(name: str) -> str | None:
    """``"left"``, ``"right"`` or ``None`` from a joint name."""
    n = _strip(name)
    low = n.lower()
    if "left" in low:
        return "left"
    if "right" in low:
        return "right"
    # L_Arm, Arm_L, l_arm, and VRoid's J_Bip_L_UpperArm
    # Biped's "Bip01 L Thigh", Daz's lThigh
    if re.match(r"^[Ll](?=[A-Z_.\- ])", n) or re.search(r"[_.\- ][Ll]($|[_.\- ])", n):
        return "left"
    if re.match(r"^[Rr](?=[A-Z_.\- ])", n) or re.search(r"[_.\- ][Rr]($|[_.\- ])", n):
        return "right"
    return None


def kind_of(name: str) -> str | None:
    """``head``, ``arm``, ``leg``, ``torso``, ``hips`` or ``None`` from a joint name."""
    low = re.sub(r"[^a-z0-9]", "", _strip(name).lower())
    for kind, words in _KEYWORDS:
        if any(w in low for w in words):
            return kind
    return None


@dataclass(frozen=True)
class BodyMap:
    """Joint indices per body part, and the end effectors metrics and synthesis use.

    ``groups`` maps each name of :data:`GROUPS` (and ``hips``) to a sorted tuple of joint indices.
    ``feet`` maps ``left``/``right`` to ``(ankle, toe)`` (toe may equal ankle when the skeleton has none).
    """

    groups: dict[str, tuple[int, ...]]
    feet: dict[str, tuple[int, int]]
    hands: dict[str, int]
    head: int
    chest: int
    hips: int = 0

    def joints(self, part: str) -> tuple[int, ...]:
        try:
            return self.groups[part]
        except KeyError:
            raise BodyMapError(f"unknown body part {part!r}; known: {', '.join(GROUPS)}") from None


def _first(names: tuple[str, ...], members: tuple[int, ...], words: tuple[str, ...]) -> int | None:
    """The first of ``members`` whose joint name contains one of ``words`` (case and punctuation ignored)."""
    for j in members:
        low = re.sub(r"[^a-z0-9]", "", _strip(names[j]).lower())
        if any(w in low for w in words):
            return j
    return None


def _role_label(role: str) -> tuple[str, str | None]:
    """``(kind, side)`` of a humanoid role (:data:`core.rigs.ROLES`)."""
    side = "left" if role.startswith("left") else "right" if role.startswith("right") else None
    part = role[len(side):].lower() if side else role
    if part in ("hips",):
        return "hips", None
    if part in ("spine", "chest", "upperChest"):
        return "torso", None
    if part in ("neck", "head"):
        return "head", None
    return ("leg" if part in ("upperleg", "lowerleg", "foot", "toes") else "arm"), side


@lru_cache(maxsize=64)
def _body_map(names: tuple[str, ...], parents: tuple[int, ...], known: tuple[tuple[str, int], ...] = ()) -> BodyMap:
    from .rigs import REQUIRED, closest_rig  # numpy-free callers of this module never get here

    found = dict(known) if known else closest_rig(names)[1]
    # A known rig's joints take the part of their role (Rigify's DEF-spine.006 is the head, whatever it says).
    roles = {j: role for role, j in found.items()} if all(r in found for r in REQUIRED) else {}
    skel_parents = parents
    labels: list[str | None] = []
    unplaced = []
    for j, name in enumerate(names):
        kind = "hips" if j == 0 else kind_of(name)
        side = side_of(name)
        if j in roles:
            kind, side = _role_label(roles[j])
        if kind == "hips" and j != 0 and side is not None:
            kind = "leg"  # left_hip (SMPL), LeftHip: the thigh's joint
        if kind in ("arm", "leg"):
            if side is None:
                p = skel_parents[j]
                inherited = labels[p] if p >= 0 else None
                if inherited and inherited.startswith(("left_", "right_")) and inherited.endswith(kind):
                    labels.append(inherited)
                    continue
                unplaced.append(name)
                labels.append(None)
                continue
            labels.append(f"{side}_{kind}")
        elif kind is not None:
            labels.append(kind)
        else:
            p = skel_parents[j]
            inherited = labels[p] if p >= 0 else None
            if inherited is None or (inherited in ("hips", "torso") and not roles):
                unplaced.append(name)
            labels.append(inherited)  # a known rig's extra joint (lButtock, a twist bone) is part of its parent's
    if unplaced:
        raise BodyMapError("cannot place these joints in body parts (no known name pattern): " + ", ".join(unplaced))
    groups: dict[str, list[int]] = {g: [] for g in (*GROUPS, "hips")}
    for j, lab in enumerate(labels):
        assert lab is not None  # every joint is placed, else raised above
        groups[lab].append(j)
    groups["both_arms"] = groups["left_arm"] + groups["right_arm"]
    groups["lower"] = groups["hips"] + groups["left_leg"] + groups["right_leg"]
    groups["upper"] = groups["torso"] + groups["head"] + groups["both_arms"]
    frozen = {g: tuple(sorted(v)) for g, v in groups.items()}
    missing = [g for g in ("left_leg", "right_leg", "left_arm", "right_arm", "head") if not frozen[g]]
    if missing:
        raise BodyMapError("the skeleton has no joints for: " + ", ".join(missing))

    feet, hands = {}, {}
    for side in ("left", "right"):
        leg = frozen[f"{side}_leg"]
        ankle = found.get(f"{side}Foot") if roles else _first(names, leg, ("foot", "ankle"))
        if ankle is None:
            raise BodyMapError(f"no {side} foot/ankle joint among: " + ", ".join(names[j] for j in leg))
        toe = found.get(f"{side}Toes") if roles else None
        toe = toe if toe is not None else _first(names, leg, ("toe",))
        if toe is None:
            kids = [j for j in leg if parents[j] == ankle]
            toe = kids[0] if kids else ankle
        feet[side] = (ankle, toe)
        arm = frozen[f"{side}_arm"]
        hand = found.get(f"{side}Hand") if roles else _first(names, arm, ("hand", "wrist"))
        hands[side] = hand if hand is not None else arm[-1]
    head = found.get("head") if roles else _first(names, frozen["head"], ("head",))
    head = head if head is not None else frozen["head"][-1]
    neck = frozen["head"][0]
    chest = parents[neck] if parents[neck] in frozen["torso"] else (frozen["torso"][-1] if frozen["torso"] else 0)
    return BodyMap(frozen, feet, hands, head, chest)


def body_map(skeleton: Skeleton) -> BodyMap:
    """The :class:`BodyMap` of ``skeleton``; raises :class:`BodyMapError` naming unplaceable joints.

    Joints are placed by name (known rigs' tables, then name patterns); a skeleton no name places is
    read by its shape (:func:`core.skeleton_shape.infer_roles`), and refused when that finds no human."""
    parents = tuple(skeleton.parents.tolist())
    try:
        return _body_map(skeleton.names, parents)
    except BodyMapError as by_name:
        from .rig_error import RigError
        from .skeleton_shape import infer_roles

        try:
            roles = tuple(sorted(infer_roles(skeleton).items()))
        except RigError as exc:
            raise BodyMapError(f"{by_name}; read by its shape: {exc}") from None
        return _body_map(skeleton.names, parents, roles)


def mirror_index(skeleton: Skeleton) -> list[int]:
    """For each joint, the index of its left/right counterpart (itself for centre joints)."""
    names = skeleton.names
    out = []
    for n in names:
        swapped = re.sub(r"Left|Right|left|right|LEFT|RIGHT", lambda m: {"left": "right", "right": "left"}[m.group(0).lower()].capitalize()
                         if m.group(0)[0].isupper() else {"left": "right", "right": "left"}[m.group(0)], n)
        if swapped == n:
            base = _strip(n)
            prefix = n[: len(n) - len(base)]
            m = re.match(r"^([LR])(?=[A-Z_.\-])", base)
            if m:
                swapped = prefix + ("R" if m.group(1) == "L" else "L") + base[1:]
            else:
                m = re.search(r"([_.\-])([LlRr])$", base)
                if m:
                    s = {"L": "R", "R": "L", "l": "r", "r": "l"}[m.group(2)]
                    swapped = prefix + base[: m.start(2)] + s
        out.append(names.index(swapped) if swapped in names else names.index(n))
    return out

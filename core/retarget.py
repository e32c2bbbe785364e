"""Retargeting: a motion carried from one skeleton onto another.

Inputs: a source :class:`Motion`, a target :class:`Skeleton`, and the joint
mapping between them, found by role (:mod:`core.rigs`: CMU, Mixamo, VRM,
SMPL, Unreal names, or a ``{role: joint}`` map for the rest).

Steps, each vectorised over frames (one numpy step per joint):

1. **Rest alignment.** For every role placed in both skeletons, a rotation
   ``A_r`` turns the target's rest bone onto the source's rest bone: its
   direction (joint to the next role down the chain, e.g. upper arm to lower
   arm) exactly, and the body's forward axis as well as it can (scipy's
   ``align_vectors`` with the first weight infinite). So a T-pose source
   drives an A-pose target, and a target whose bones point other ways at rest
   is handled the same way. Hips: up (hips to head) and left (right hip to
   left hip). A leaf role (hand, head, toes) takes its parent role's ``A``.
   A glTF character's foot whose mesh shows its sole (:mod:`core.soles`) is
   turned by the sole instead: the sole's heel-to-ball line onto the source
   foot's level forward, so a foot the source plants flat stands flat on the
   target's own shoes, whatever the angle of its toe bone (a Mixamo foot,
   whose toe joint is 40° below the ankle's forward, stood 16-20° heel-down
   by its bone); its toe joint is planted at the mesh's own height above the
   sole, and the sole is kept out of the floor (:func:`core.soles.clear_soles`).
2. **World rotations.** BVH rest rotations are the identity, so the source
   joint's world rotation ``G_s`` is its rotation relative to its rest pose;
   the target joint gets ``G_t = G_s A_r`` and its local rotation follows from
   its parent's world rotation. Joints with no role (fingers, twist bones,
   an extra spine or neck joint) keep their rest rotation relative to their
   parent; a role the target lacks (a missing spine joint) is absorbed, since
   the next role down is set in world space.
3. **Hips.** The source hips' position (its floor at ``y = 0``, see
   :mod:`core.floor`) scaled by ``s = L_t / L_s``, the ratio of leg lengths
   (:func:`leg_length`: the hips' standing height): height and travel both.
   A target whose hips are not its root (the Unreal mannequin's ``root``)
   gets the hips' position as that joint's translation.
4. **Re-planting**, on every frame:

   - each foot's goal: its toe joint on the source toe's scaled position
     ``s * p`` (its height unscaled within :data:`GROUND_BAND` of the floor,
     :func:`foot_height`), the foot turned as in step 2, so the ankle goes
     where the target foot's own shape puts it (a rig without toe joints: the
     ankle on the scaled source ankle, raised by the rigs' difference in
     ankle height above the sole);
   - where a leg cannot reach its goal (a straight stance leg on a rig whose
     feet or legs are proportioned otherwise) the hips are lowered just
     enough, smoothly over :data:`DROP_WINDOW`;
   - the spine's first joint is turned (shortest arc) so the top of the chest
     points where the scaled source's is, and each shoulder so its upper arm
     joint does (moved towards the hand's goal when that is out of the arm's
     reach from there); the neck and upper arms keep their step-2 world
     rotations. Rigs that split the spine in other places bend it in other
     places; this puts the arms back where they hang from;
   - two-bone IK (:mod:`core.ik`) puts the ankles on their goals and the
     wrists on the scaled source wrists, and the feet and hands get their
     step-2 world rotations back. The knee and elbow hinges come from the
     target's rest pose: a knee flexes backwards (``forward x thigh``), an
     elbow forwards (``upper arm x forward``); the knee turns towards the thigh's own forward (a pole
     in front of it), so a straight stance leg keeps its twist. An ankle goal near the leg's full
     length is pulled in softly (:func:`soft_reach`, soft IK from 97 % of it): the knee never snaps
     straight for a frame; a fully stretched leg's foot stays up to 1.1 % of the leg short of its goal.

   Feet therefore plant where the scaled source's do and slide no more than
   they do (in proportion ``s``).

Units: metres, Y up; rotations ``(T, J, 4)`` scipy quaternions ``(x, y, z, w)``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import maximum_filter1d, uniform_filter1d
from scipy.spatial.transform import Rotation

from .fk import matrix_to_quat
from .floor import FOOT_CLEARANCE
from .ik import set_world_rotation, two_bone_ik
from .motion import Motion
from .rigs import ROLE_PARENT, ROLES, RigError, rig_roles
from .skeleton import Skeleton
from .soles import Sole, clear_soles

#: The role a role's bone points at, in order of preference (the first placed in both rigs).
AIM = {
    "spine": ("chest", "upperChest", "neck", "head"),
    "chest": ("upperChest", "neck", "head"),
    "upperChest": ("neck", "head"),
    "neck": ("head",),
    **{f"{s}{a}": (f"{s}{b}",) for s in ("left", "right") for a, b in (
        ("Shoulder", "UpperArm"), ("UpperArm", "LowerArm"), ("LowerArm", "Hand"),
        ("UpperLeg", "LowerLeg"), ("LowerLeg", "Foot"), ("Foot", "Toes"))},
}
#: Height (m) below which a toe keeps the source's height above the floor (see :func:`foot_height`):
#: just above the 5 cm under which docs/timetable.md section 3 calls a foot low; the swing above it scales.
GROUND_BAND = 0.06
#: Leg-length ratios within which a body counts as the source's size (the band keeps toe heights) ...
SAME_SIZE = 1.25
#: ... and beyond which toe heights scale like every other length (see :func:`foot_height`).
OTHER_SIZE = 1.5
#: Seconds over which the hips' lowering (where a leg cannot reach) is spread.
DROP_WINDOW = 0.2
_LIMBS = {f"{s}_{k}": (f"{s}{a}", f"{s}{b}", f"{s}{c}") for s in ("left", "right") for k, (a, b, c) in (
    ("leg", ("UpperLeg", "LowerLeg", "Foot")), ("arm", ("UpperArm", "LowerArm", "Hand")))}


@dataclass(frozen=True)
class Mapping:
    """Joint correspondence between two rigs.

    ``source``/``target``: ``{role: joint index}`` of each skeleton; ``rigs``: the
    recognised rig names (``"cmu"``, ``"mixamo+map"``, ...); ``scale``: the
    leg-length ratio target / source.
    """

    source: dict[str, int]
    target: dict[str, int]
    rigs: tuple[str, str]
    scale: float

    @property
    def roles(self) -> tuple[str, ...]:
        """Roles placed in both rigs, parents first."""
        return tuple(r for r in ROLES if r in self.source and r in self.target)


def _lowest_foot(skel: Skeleton, roles: dict[str, int]) -> float:
    """Rest height (m) of the lowest foot point: the ankle and toe joints, and on a foot without a toe joint
    the end sites hanging from its ankle (its toes), as :func:`core.floor.sole_heights` reads a sole."""
    rest = skel.rest_positions()
    low = float(rest[[roles[r] for r in ("leftFoot", "rightFoot", "leftToes", "rightToes") if r in roles], 1].min())
    for side in ("left", "right"):
        if f"{side}Toes" not in roles and f"{side}Foot" in roles:
            tips = [rest[j, 1] + o[1] for j, o in skel.end_sites if j == roles[f"{side}Foot"]]
            low = min([low] + tips)
    return low


def leg_length(skel: Skeleton, roles: dict[str, int]) -> float:
    """Standing height of the hips joint, metres: hips above the hip joints, plus thigh, shin and ankle height.

    Bone lengths rather than the rest pose's extent, so legs that are splayed
    or bent at rest (CMU's rest pose has them apart) count at full length.
    Mean of both legs.
    """
    rest = skel.rest_positions()
    total = 0.0
    for side in ("left", "right"):
        up, knee, ankle = (rest[roles[f"{side}{p}"]] for p in ("UpperLeg", "LowerLeg", "Foot"))
        total += (rest[roles["hips"], 1] - up[1]) + np.linalg.norm(knee - up) + np.linalg.norm(ankle - knee)
    return total / 2 + ankle_height(skel, roles)


def ankle_height(skel: Skeleton, roles: dict[str, int]) -> float:
    """Rest height of the ankles (mean of both) above the lowest foot point (:func:`_lowest_foot`), metres."""
    rest = skel.rest_positions()
    return float(rest[[roles["leftFoot"], roles["rightFoot"]], 1].mean()) - _lowest_foot(skel, roles)


def map_skeletons(source: Skeleton, target: Skeleton, source_map: dict[str, str] | None = None,
                  target_map: dict[str, str] | None = None) -> Mapping:
    """The :class:`Mapping` of two skeletons; :class:`core.rigs.RigError` names the joints neither rig places."""
    try:
        rs, src = rig_roles(source, source_map)
    except RigError as exc:
        raise RigError(f"source skeleton: {exc}") from None
    try:
        rt, tgt = rig_roles(target, target_map)
    except RigError as exc:
        raise RigError(f"target skeleton: {exc}") from None
    ls, lt = leg_length(source, src), leg_length(target, tgt)
    if not (ls > 1e-6 and lt > 1e-6):
        raise RigError("a skeleton's hips are not above its feet in the rest pose (leg length "
                       f"{ls:.3f} m source, {lt:.3f} m target)")
    return Mapping(src, tgt, (rs, rt), lt / ls)


def _unit(v: np.ndarray) -> np.ndarray:
    return v / max(float(np.linalg.norm(v)), 1e-12)


def _body_axes(skel: Skeleton, roles: dict[str, int]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rest ``(up, left, forward)`` unit vectors of a rig."""
    rest = skel.rest_positions()
    up = _unit(rest[roles["head"]] - rest[roles["hips"]])
    left = rest[roles["leftUpperLeg"]] - rest[roles["rightUpperLeg"]]
    left = _unit(left - up * (left @ up))
    return up, left, np.cross(left, up)


def _align(dst: list[np.ndarray], src: list[np.ndarray]) -> Rotation:
    """The rotation taking ``src`` vectors onto ``dst`` (the first exactly)."""
    rot, _ = Rotation.align_vectors(np.array(dst), np.array(src), weights=[np.inf] + [1.0] * (len(dst) - 1))
    return rot


def rest_alignment(source: Skeleton, target: Skeleton, mapping: Mapping,
                   soles: dict[str, Sole] | None = None) -> dict[str, np.ndarray]:
    """``{role: A_r (3, 3)}`` turning the target's rest bone onto the source's (step 1); a foot whose sole
    ``soles[role]`` (:func:`core.soles.sole_lines`) is known is turned by its sole instead
    (:func:`_sole_alignment`)."""
    soles = soles or {}
    ps, pt = source.rest_positions(), target.rest_positions()
    up_s, left_s, fwd_s = _body_axes(source, mapping.source)
    up_t, left_t, fwd_t = _body_axes(target, mapping.target)
    out = {"hips": _align([up_s, left_s], [up_t, left_t]).as_matrix()}
    both = set(mapping.roles)
    for role in mapping.roles[1:]:
        aim = next((a for a in AIM.get(role, ()) if a in both), None)
        parent = ROLE_PARENT[role]
        while parent not in out:
            parent = ROLE_PARENT[parent]
        if role in soles:
            ahead = fwd_s if aim is None else ps[mapping.source[aim]] - ps[mapping.source[role]]
            out[role] = _sole_alignment(ahead, soles[role].line)
            continue
        if aim is None:
            out[role] = out[parent]
            continue
        ds = ps[mapping.source[aim]] - ps[mapping.source[role]]
        dt = pt[mapping.target[aim]] - pt[mapping.target[role]]
        if min(np.linalg.norm(ds), np.linalg.norm(dt)) < 1e-6:
            out[role] = out[parent]
            continue
        out[role] = _align([_unit(ds), fwd_s], [_unit(dt), fwd_t]).as_matrix()
    return out


def _sole_alignment(ahead: np.ndarray, sole: np.ndarray) -> np.ndarray:
    """A foot's ``A_r`` ``(3, 3)`` that lays the target's sole line ``sole`` (heel to ball, rest pose) level
    along ``ahead``'s horizontal (the source foot's forward at rest, where a BVH body stands flat: the
    built-in body's planted feet keep its rest pitch, 23°), its normal up: a foot the source plants flat
    stands flat on the target's own soles, whatever the angle of its toe bone."""
    up = np.array([0.0, 1.0, 0.0])
    level = _unit(ahead - up * (ahead @ up))
    return _align([level, up], [sole, _unit(up - sole * (sole @ up))]).as_matrix()


def _world_to_local(target: Skeleton, world: dict[int, np.ndarray], T: int) -> np.ndarray:
    """Local rotations ``(T, J, 4)`` from the world rotations of the mapped joints (others: rest)."""
    J = target.n_joints
    eye = np.broadcast_to(np.eye(3), (T, 3, 3))
    gw = np.empty((T, J, 3, 3))
    local = np.empty((T, J, 3, 3))
    for j in range(J):
        p = target.parents[j]
        parent_w = gw[:, p] if p >= 0 else eye
        if j in world:
            gw[:, j] = world[j]
            local[:, j] = np.swapaxes(parent_w, -1, -2) @ world[j]
        else:
            gw[:, j] = parent_w
            local[:, j] = eye
    return matrix_to_quat(local)


def _hinge(target: Skeleton, chain: tuple[int, int, int], forward: np.ndarray, leg: bool) -> np.ndarray:
    """Flexion axis of a knee (``forward x thigh``) or an elbow (``upper arm x forward``), rest frame."""
    rest = target.rest_positions()
    d = _unit(rest[chain[1]] - rest[chain[0]])
    axis = np.cross(forward, d) if leg else np.cross(d, forward)
    return _unit(axis)


def retarget(motion: Motion, target: Skeleton, *, source_map: dict[str, str] | None = None,
             target_map: dict[str, str] | None = None, replant: bool = True,
             soles: dict[str, Sole] | None = None) -> Motion:
    """``motion`` played on ``target`` (see the module docstring for the method).

    Args:
        motion: the source clip, its floor at ``y = 0`` (:func:`core.floor.place_on_floor`).
        target: the skeleton to carry it onto (its rest pose in any of T- or A-pose).
        source_map, target_map: ``{role: joint name}`` over the known rigs (``--map``).
        replant: re-place ankles and wrists on the scaled source's by IK (step 4).
        soles: ``{"leftFoot"/"rightFoot": Sole}`` the target's soles from its mesh
            (:func:`core.soles.sole_lines`): those feet are aligned by their soles (step 1) and planted
            with their soles on the floor (step 4).

    Raises :class:`core.rigs.RigError` when a skeleton's roles cannot be placed.
    """
    mapping = map_skeletons(motion.skeleton, target, source_map, target_map)
    A = rest_alignment(motion.skeleton, target, mapping, soles)
    T = motion.n_frames
    Gs = motion.pose.rotations
    world = {mapping.target[r]: Gs[:, mapping.source[r]] @ A[r] for r in mapping.roles}
    rots = _world_to_local(target, world, T)

    s = mapping.scale
    hips_pos = s * motion.positions[:, mapping.source["hips"]]
    hips = mapping.target["hips"]
    trans = None
    if hips == 0:
        root = hips_pos
    else:
        if not target.has_position_channels(hips):
            raise RigError(f"the target's hips joint {target.names[hips]!r} is not its root and has no "
                           "position channels, so it cannot carry the motion's travel")
        root = np.broadcast_to(target.offsets[0], (T, 3)).copy()
        trans = np.broadcast_to(target.offsets, (T,) + target.offsets.shape).copy()
        trans[:, hips] = hips_pos - root  # every joint above the hips sits at rest, unrotated
    out = Motion(target, motion.fps, root, rots, trans)
    if replant and T:
        out = _replant(out, motion, mapping, A, soles or {})
    if soles and T:
        out = clear_soles(out, soles)
    return out


def _aim(motion: Motion, joint: int, end: int, goal: np.ndarray) -> Motion:
    """Turn ``joint`` by the shortest arc (per frame) that points it at ``goal`` ``(T, 3)`` through ``end``."""
    pose = motion.pose
    a = pose.positions[:, joint]
    u, v = pose.positions[:, end] - a, goal - a
    axis = np.cross(u, v)
    sin = np.linalg.norm(axis, axis=-1)
    angle = np.arctan2(sin, np.sum(u * v, axis=-1))
    turn = axis * (angle / np.maximum(sin, 1e-12))[:, None]
    turn[sin < 1e-9] = 0.0
    world = Rotation.from_rotvec(turn).as_matrix() @ pose.rotations[:, joint]
    p = motion.skeleton.parents[joint]
    local = world if p < 0 else np.swapaxes(pose.rotations[:, p], -1, -2) @ world
    rots = motion.rotations.copy()
    rots[:, joint] = matrix_to_quat(local)
    return motion.replace(rotations=rots)


def _aim_torso(out: Motion, source: Motion, mapping: Mapping, world: dict[str, np.ndarray]) -> Motion:
    """The spine aimed so the top of the chest, and each shoulder so its upper arm, sit on the scaled source's.

    The neck and the upper arms then get their world rotations (``world``, step 2) back, so the
    aiming moves where the head and arms hang from but not which way they point.
    """
    both = set(mapping.roles)
    spine = [r for r in ("spine", "chest", "upperChest") if r in both]
    src_pos = source.positions
    if len(spine) >= 2:
        out = _aim(out, mapping.target[spine[0]], mapping.target[spine[-1]],
                   mapping.scale * src_pos[:, mapping.source[spine[-1]]])
        if "neck" in both:
            out = set_world_rotation(out, mapping.target["neck"], matrix_to_quat(world["neck"]))
    rest = out.skeleton.rest_positions()
    for side in ("left", "right"):
        sh, arm, fore, hand = (f"{side}{p}" for p in ("Shoulder", "UpperArm", "LowerArm", "Hand"))
        if not all(r in both for r in (sh, arm, fore, hand)):
            continue
        goal = mapping.scale * src_pos[:, mapping.source[arm]]
        # if the hand's goal is out of the arm's reach from there, slide the goal towards it until it is not
        reach = 0.999 * sum(np.linalg.norm(rest[mapping.target[b]] - rest[mapping.target[a]])
                            for a, b in ((arm, fore), (fore, hand)))
        to_hand = mapping.scale * src_pos[:, mapping.source[hand]] - goal
        dist = np.linalg.norm(to_hand, axis=-1)
        goal = goal + to_hand * (np.maximum(dist - reach, 0.0) / np.maximum(dist, 1e-12))[:, None]
        out = _aim(out, mapping.target[sh], mapping.target[arm], goal)
        out = set_world_rotation(out, mapping.target[arm], matrix_to_quat(world[arm]))
    return out


def foot_height(y: np.ndarray, s: float) -> np.ndarray:
    """A toe's height on the target: as the source's up to :data:`GROUND_BAND`, scaled by ``s`` above it,
    for a body of about the source's size; scaled by ``s`` throughout for a body of another size.

    Contact and the first centimetres of a step are a matter of the ground, not of the body's size:
    scaled by 0.93, a toe skimming at 5.2 cm would scuff at 4.8 cm (and count as skating, docs/timetable.md
    section 3); the swing above the band scales with the legs. Continuous at the band. A 0.2 m or a 20 m
    character is another matter: 4 cm of sole under a 0.2 m body is a quarter of its height (its legs
    could not reach down, it would squat and float), so outside :data:`SAME_SIZE` the band fades out
    (fully gone at :data:`OTHER_SIZE`) and every height scales with the legs.
    """
    w = float(np.clip((np.log(OTHER_SIZE) - abs(np.log(s))) / (np.log(OTHER_SIZE) - np.log(SAME_SIZE)), 0.0, 1.0))
    kept = np.where(y <= GROUND_BAND, y, GROUND_BAND + s * (y - GROUND_BAND))
    return w * kept + (1.0 - w) * s * y


def _limb_goals(out: Motion, source: Motion, mapping: Mapping, world: dict[str, np.ndarray],
                soles: dict[str, Sole]):
    """``[(limb, chain (3,), end-joint goal (T, 3), end world rotation (T, 3, 3))]`` of step 4; a foot with a
    known sole has its toe joint raised or lowered by how far the mesh's toe joint stands above its sole
    (``Sole.toe_height``) rather than :data:`core.floor.FOOT_CLEARANCE`, so that sole, not an assumed
    one, stands on the floor."""
    src_pos = source.positions
    rest_t = out.skeleton.rest_positions()
    lift = ankle_height(out.skeleton, mapping.target) - mapping.scale * ankle_height(source.skeleton, mapping.source)
    parents = out.skeleton.parents
    goals = []
    for name, roles in _LIMBS.items():
        if not all(r in mapping.source and r in mapping.target for r in roles):
            continue
        chain = (mapping.target[roles[0]], mapping.target[roles[1]], mapping.target[roles[2]])
        if parents[chain[1]] != chain[0] or parents[chain[2]] != chain[1]:
            continue  # a twist bone inside the limb: not a two-bone chain, left as rotated
        end_world = world[roles[2]]
        goal = mapping.scale * src_pos[:, mapping.source[roles[2]]]
        toes = roles[2].replace("Foot", "Toes")
        if name.endswith("leg") and toes in mapping.source and toes in mapping.target:
            # the toe where the scaled source's is, the ankle where the foot's own shape puts it
            foot = rest_t[mapping.target[toes]] - rest_t[chain[2]]
            toe = mapping.scale * src_pos[:, mapping.source[toes]]
            toe[:, 1] = foot_height(src_pos[:, mapping.source[toes], 1], mapping.scale)
            if roles[2] in soles:
                toe[:, 1] += soles[roles[2]].toe_height - foot_height(np.array([FOOT_CLEARANCE]), mapping.scale)[0]
            goal = toe - end_world @ foot
        elif name.endswith("leg"):  # no toes: the target's own ankle height above its sole
            goal[:, 1] += lift if roles[2] not in soles else soles[roles[2]].toe_height - mapping.scale * (
                ankle_height(source.skeleton, mapping.source) + FOOT_CLEARANCE)
        goals.append((name, chain, goal, end_world))
    return goals


def _drop_hips(out: Motion, legs, hips: int) -> Motion:
    """Lower the hips on the frames where a leg cannot reach its ankle goal, smoothly (over :data:`DROP_WINDOW` s).

    ``d = max(0, -v_y - sqrt(c^2 - |v_xz|^2))`` per leg, ``v`` hip joint to goal, ``c`` the chain's
    length; the larger leg's ``d``, max-filtered then averaged over the window (so never below it).
    """
    if not legs:
        return out
    pos = out.positions
    drops = []
    for _, (up, mid, end), goal, _ in legs:
        reach = 0.999 * _chain_length(out.skeleton, (up, mid, end))
        v = goal - pos[:, up]
        flat = np.sqrt(np.maximum(reach ** 2 - v[:, 0] ** 2 - v[:, 2] ** 2, 0.0))
        drops.append(np.maximum(-v[:, 1] - flat, 0.0))
    d = np.max(drops, axis=0)
    if not np.any(d > 0):
        return out
    w = max(1, int(round(DROP_WINDOW * out.fps)))
    d = uniform_filter1d(maximum_filter1d(d, w, mode="nearest"), w, mode="nearest")
    if hips == 0:
        root = out.root_positions.copy()
        root[:, 1] -= d
        return out.replace(root_positions=root)
    trans = out.local_translations()
    trans[:, hips, 1] -= d  # the joints above the hips are unrotated (see retarget)
    return out.replace(translations=trans)


#: fraction of a leg's length from which its reach is softened (:func:`soft_reach`)
SOFT_FROM = 0.97


def _chain_length(skel: Skeleton, chain: tuple[int, int, int]) -> float:
    rest = skel.rest_positions()
    return float(np.linalg.norm(rest[chain[1]] - rest[chain[0]]) + np.linalg.norm(rest[chain[2]] - rest[chain[1]]))


def soft_reach(root: np.ndarray, goal: np.ndarray, length: float) -> np.ndarray:
    """Goals ``(T, 3)`` of a two-bone chain from ``root`` ``(T, 3)`` pulled in where they near its ``length``:
    beyond :data:`SOFT_FROM` of it, the distance ``d`` becomes ``s + (L - s)(1 - exp(-(d - s) / (L - s)))``
    (soft IK), so the chain straightens only as the goal goes to infinity. A goal that reaches the chain's
    length a frame at a time otherwise snaps the knee straight for that frame and bends it the next (the
    knee's jerk, 4x the default body's on a Mixamo rig). At full length it falls 1.1 % of the length short."""
    v = goal - root
    d = np.linalg.norm(v, axis=-1)
    s = SOFT_FROM * length
    soft = np.where(d > s, s + (length - s) * (1.0 - np.exp(-(d - s) / (length - s))), d)
    return root + v * (soft / np.maximum(d, 1e-12))[:, None]


def _replant(out: Motion, source: Motion, mapping: Mapping, A: dict[str, np.ndarray],
             soles: dict[str, Sole]) -> Motion:
    """Step 4: hips lowered where a leg cannot reach, chest and shoulders aimed, ankles and wrists onto the
    scaled source's by IK, their world rotations restored."""
    _, _, fwd_t = _body_axes(out.skeleton, mapping.target)
    Gs = source.pose.rotations
    world = {r: Gs[:, mapping.source[r]] @ A[r] for r in mapping.roles}
    goals = _limb_goals(out, source, mapping, world, soles)
    out = _drop_hips(out, [g for g in goals if g[0].endswith("leg")], mapping.target["hips"])
    out = _aim_torso(out, source, mapping, world)
    for name, chain, goal, end_world in goals:
        leg = name.endswith("leg")
        hinge = _hinge(out.skeleton, chain, fwd_t, leg)
        pole = None
        if leg:  # the knee towards the thigh's own forward: with the knee itself as the pole, a nearly straight
            # leg has no bend plane and the IK's twist about the hip-ankle line flips from frame to frame
            pose = out.pose
            pole = pose.positions[:, chain[1]] + 0.5 * np.einsum("tij,j->ti", pose.rotations[:, chain[0]], fwd_t)
            goal = soft_reach(pose.positions[:, chain[0]], goal, _chain_length(out.skeleton, chain))
        out = two_bone_ik(out, chain, goal, pole=pole, hinge=tuple(hinge))
        out = set_world_rotation(out, chain[2], matrix_to_quat(end_world))
    return out

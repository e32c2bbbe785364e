"""VRM Animation (``.vrma``): a glTF binary with the ``VRMC_vrm_animation`` 1.0 extension.

A VRMA file holds no mesh: a node per humanoid bone, named and mapped by its
VRM humanoid bone name, in the *VRM T-pose* (facing +Z, arms along ±X, the
floor at ``y = 0``) with identity rest rotations, and one animation: the hips'
``translation`` (world space: the hips are a scene root) and every bone's
``rotation``. A player (``@pixiv/three-vrm-animation``) turns the rotations
into the avatar's normalized bone rotations, so with identity rest rotations
they are exactly our motion's local rotations relative to the rest pose, and
scales the hips' travel by its avatar's hips height over the file's rest hips
height (VRMC_vrm_animation-1.0 README, "Humanoid", and
``how_to_transform_human_pose.md``).

:func:`vrma_skeleton` makes the T-pose skeleton from a rig's mapped joints
(the built-in skeleton, or the user's VRM avatar so the animation is fitted to
its proportions); the motion is retargeted onto it (:mod:`core.retarget`) and
written by :func:`vrma_bytes`. Units: metres, Y up, quaternions ``(x, y, z, w)``.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.floor import FOOT_CLEARANCE
from text2anim.core.glb import FLOAT, BufferBuilder, pack_glb
from text2anim.core.motion import Motion, unroll_quaternions
from text2anim.core.rigs import ROLE_PARENT, ROLES
from text2anim.core.skeleton import Skeleton

__all__ = ["vrma_skeleton", "vrma_bytes"]

_FEET = ("leftFoot", "rightFoot", "leftToes", "rightToes")


def vrma_skeleton(skel: Skeleton, roles: dict[str, int], *, turn: bool = False, grounded: bool = False) -> Skeleton:
    """The humanoid bones of ``skel`` (``{role: joint}``, :func:`core.rigs.rig_roles`) as a VRMA rest skeleton.

    Joints are named by role, each under its nearest placed ancestor role; positions are
    ``skel``'s rest positions: where they are (``grounded``: a VRM avatar's, which stands on
    ``y = 0``; a player then scales the hips' travel by 1 on that avatar), else with the lowest foot
    joint :data:`core.floor.FOOT_CLEARANCE` above the floor, as our motions stand; with ``turn``
    (a VRM 0.x avatar, which faces -Z) turned half round about +Y. ``offsets[0]`` is the hips'
    rest position.
    """
    placed = [r for r in ROLES if r in roles]
    pos = (skel.rest_positions() + skel.offsets[0])[[roles[r] for r in placed]]
    if turn:
        pos = pos * [-1.0, 1.0, -1.0]
    if not grounded:
        pos = pos - [0.0, min(pos[placed.index(r), 1] for r in _FEET if r in placed) - FOOT_CLEARANCE, 0.0]
    parents = []
    for r in placed:
        p = ROLE_PARENT.get(r)
        while p is not None and p not in placed:
            p = ROLE_PARENT.get(p)
        parents.append(-1 if p is None else placed.index(p))
    offsets = np.array([pos[j] - (pos[p] if p >= 0 else 0.0) for j, p in enumerate(parents)])
    return Skeleton(tuple(placed), np.array(parents), offsets)


def vrma_bytes(motion: Motion) -> bytes:
    """The ``.vrma`` of ``motion`` on a :func:`vrma_skeleton` (its joints named by VRM humanoid bone names)."""
    skel = motion.skeleton
    if motion.n_frames == 0:
        raise ValueError("the motion has no frames")
    unknown = [n for n in skel.names if n not in ROLES]
    if unknown or skel.names[0] != "hips" or motion.translations is not None:
        raise ValueError(f"not a VRMA skeleton (joints {unknown or skel.names[:1]}): see vrma_skeleton")
    b = BufferBuilder()
    nodes = []
    for j, name in enumerate(skel.names):
        node: dict = {"name": name, "translation": [float(v) for v in skel.offsets[j]]}
        kids = skel.children(j)
        if kids:
            node["children"] = kids
        nodes.append(node)
    anim: dict = {"name": "text2anim", "channels": [], "samplers": []}
    times = b.accessor(motion.times, FLOAT, "SCALAR", minmax=True)

    def channel(node: int, path: str, values: np.ndarray, atype: str) -> None:
        anim["samplers"].append({"input": times, "output": b.accessor(values, FLOAT, atype), "interpolation": "LINEAR"})
        anim["channels"].append({"sampler": len(anim["samplers"]) - 1, "target": {"node": node, "path": path}})

    channel(0, "translation", motion.root_positions, "VEC3")
    quats = unroll_quaternions(motion.rotations / np.linalg.norm(motion.rotations, axis=-1, keepdims=True))
    for j in range(skel.n_joints):
        channel(j, "rotation", quats[:, j], "VEC4")
    gl: dict = {
        "asset": {"version": "2.0", "generator": "text2anim"},
        "extensionsUsed": ["VRMC_vrm_animation"],
        "extensions": {"VRMC_vrm_animation": {
            "specVersion": "1.0",
            "humanoid": {"humanBones": {name: {"node": j} for j, name in enumerate(skel.names)}}}},
        "scene": 0, "scenes": [{"name": "text2anim", "nodes": [0]}],
        "nodes": nodes, "animations": [anim], "buffers": [{}],
    }
    return pack_glb(gl, b)

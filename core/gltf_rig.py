"""A user's character from a glTF binary (``.glb``, ``.vrm``): its skeleton in, its animation out.

:func:`read_gltf_rig` reads the skin's joints (the union of every skin's, with
the nodes between them) as a :class:`~core.skeleton.Skeleton` in the scene's
world space: metres, the rest pose being the nodes' own transforms, each offset
the world-space difference of a joint and its parent. Nodes may carry any rest
rotation and uniform scale (an armature scaled by 0.01, Blender's bone axes):
our skeleton's rest rotations are the identity, and the rig keeps each joint's
world rest rotation ``W_j`` to translate back. A VRM file's humanoid bone map
(``VRMC_vrm`` 1.0 or the ``VRM`` 0.x extension) names the roles
(:mod:`core.rigs`) of its joints.

:func:`rig_glb_bytes` writes the input file again with one animation on the
rig's nodes: mesh, skin, materials and extensions kept (the JSON written anew
with the same content, the binary chunk's bytes kept and the animation's
appended); the file's own animations are replaced. A motion on our skeleton has local
rotations ``r_j`` relative to the rest pose; the node's glTF rotation is

    ``q_j = W_p^-1 r_j W_p L_j``  (``W_p`` the parent's world rest rotation, ``L_j`` the node's rest rotation),

the *pose data* conversion of the VRM Animation spec
(``how_to_transform_human_pose.md``); a translated joint's glTF translation is
``W_p^-1 d_j / s_p`` (``d_j`` its offset in our world-aligned frame, ``s_p`` the
parent's world scale), the root's the inverse of its parent's world matrix
applied to its world position.
"""
from __future__ import annotations

import copy
import json
import os
import struct
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from .glb import BufferBuilder, pack_glb
from .gltf_check import check_rig_json
from .inputs import read_input
from .gltf_prune import drop_animations
from .motion import Motion, unroll_quaternions
from .rigs import ROLES, RigError
from .skeleton import POSITION_CHANNELS, Skeleton

__all__ = ["GltfRig", "read_gltf_rig", "rig_glb_bytes", "GLTF_SUFFIXES"]

#: File suffixes read as glTF binaries.
GLTF_SUFFIXES = (".glb", ".vrm")
_FLOAT = 5126
_ROT = ("Zrotation", "Yrotation", "Xrotation")


@dataclass(frozen=True, eq=False)
class GltfRig:
    """A skinned character read from a ``.glb``/``.vrm``.

    Attributes:
        path: the file.
        gl: its glTF JSON; ``bin``: its BIN chunk.
        skeleton: the joints, world-aligned (see the module docstring), metres.
        nodes: the glTF node of each skeleton joint, ``(J,)``.
        rest_world: each joint's world rest rotation ``W_j``, ``(J, 3, 3)``.
        parent_world: the world matrix of the root joint's parent node, ``(4, 4)`` (identity at a scene root).
        scale: each joint's world scale (uniform), ``(J,)``.
        humanoid: ``{role: joint name}`` from the VRM humanoid extension (empty for a plain glTF).
        vrm: ``"1.0"``, ``"0.x"`` or ``None``.
        node_world: every node's rest world matrix, ``(N, 4, 4)`` (the mesh's bind pose: :mod:`core.gltf_mesh`).
    """

    path: Path
    gl: dict
    bin: bytes
    skeleton: Skeleton
    nodes: tuple[int, ...]
    rest_world: np.ndarray
    parent_world: np.ndarray
    scale: np.ndarray
    humanoid: dict[str, str]
    vrm: str | None
    node_world: np.ndarray


def _bad(path: Path, why: str) -> RigError:
    return RigError(f"{path}: {why}")


def read_glb(path: Path) -> tuple[dict, bytes]:
    """The JSON and the BIN chunk (``b""`` if none) of a glTF binary; :class:`RigError` if it is not one."""
    data = read_input(path, "rig", RigError)
    if len(data) < 20 or data[:4] != b"glTF":
        raise _bad(path, "not a glTF binary (.glb/.vrm): it does not start with 'glTF'")
    version, length = struct.unpack_from("<II", data, 4)
    if version != 2 or length > len(data):
        raise _bad(path, f"a glTF binary of version {version} and length {length} ({len(data)} bytes read); "
                         "only complete glTF 2.0 files are read")
    jlen, jtype = struct.unpack_from("<I4s", data, 12)
    if jtype != b"JSON" or 20 + jlen > length:
        raise _bad(path, "the glTF binary's first chunk is not its JSON")
    try:
        gl = json.loads(data[20:20 + jlen].decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise _bad(path, f"the glTF JSON cannot be read ({exc})") from None
    if not isinstance(gl, dict):
        raise _bad(path, "the glTF JSON is not an object")
    blob = b""
    at = 20 + jlen + (-jlen) % 4
    if at + 8 <= length:
        blen, btype = struct.unpack_from("<I4s", data, at)
        if btype == b"BIN\0" and at + 8 + blen <= length:
            blob = data[at + 8:at + 8 + blen]
    return gl, blob


def _local_matrix(node: dict) -> np.ndarray:
    """A node's rest transform ``(4, 4)`` from ``matrix`` (column-major) or TRS."""
    if "matrix" in node:
        return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T
    m = np.eye(4)
    r = Rotation.from_quat(node.get("rotation", [0.0, 0.0, 0.0, 1.0])).as_matrix()
    m[:3, :3] = r * np.array(node.get("scale", [1.0, 1.0, 1.0]), dtype=np.float64)
    m[:3, 3] = node.get("translation", [0.0, 0.0, 0.0])
    return m


def _node_tree(path: Path, nodes: list) -> tuple[np.ndarray, np.ndarray]:
    """Each node's parent ``(N,)`` (-1 at a root) and world matrix ``(N, 4, 4)``."""
    n = len(nodes)
    parent = np.full(n, -1, dtype=np.int64)
    for i, node in enumerate(nodes):
        for c in node.get("children", []):
            if not (isinstance(c, int) and 0 <= c < n) or parent[c] >= 0 or c == i:
                raise _bad(path, f"node {i}'s children do not form a tree (child {c!r})")
            parent[c] = i
    world = np.zeros((n, 4, 4))
    done = np.zeros(n, dtype=bool)
    for i in range(n):
        chain = []
        j = i
        while j >= 0 and not done[j]:
            chain.append(j)
            j = int(parent[j])
            if len(chain) > n:
                raise _bad(path, "the node hierarchy has a cycle")
        for k in reversed(chain):
            p = int(parent[k])
            world[k] = (world[p] if p >= 0 else np.eye(4)) @ _local_matrix(nodes[k])
            done[k] = True
    return parent, world


def _joint_nodes(path: Path, gl: dict, parent: np.ndarray) -> list[int]:
    """The skins' joints and the nodes between them, parents first (depth first in the file's child order).

    Linear in the node count: each node's depth once, the joints under each node summed
    deepest first; the skeleton's root is the deepest node above every joint.
    """
    skins = gl.get("skins") or []
    joints = sorted({int(j) for s in skins for j in s.get("joints", [])})
    if not joints:
        raise _bad(path, "has no skin (no skinned mesh with joints): --rig needs a rigged character")
    n = len(parent)
    depth = np.full(n, -1, dtype=np.int64)
    for i in range(n):
        chain = []
        j = i
        while j >= 0 and depth[j] < 0:
            chain.append(j)
            j = int(parent[j])
        d = depth[j] if j >= 0 else -1
        for k in reversed(chain):
            d += 1
            depth[k] = d
    below = np.zeros(n, dtype=np.int64)  # joints in each node's subtree
    below[joints] = 1
    for k in np.argsort(-depth, kind="stable"):
        if parent[k] >= 0:
            below[parent[k]] += below[k]
    above_all = np.flatnonzero(below == len(joints))
    if above_all.size == 0:
        raise _bad(path, "the skins' joints hang from separate scene roots; a rig has one skeleton")
    root = int(above_all[np.argmax(depth[above_all])])
    keep = below > 0
    gl_nodes = gl["nodes"]
    order, stack = [], [root]
    while stack:
        j = stack.pop()
        order.append(j)
        stack.extend(reversed([c for c in gl_nodes[j].get("children", []) if keep[c]]))
    return order


def _polar(m: np.ndarray) -> tuple[np.ndarray, float]:
    """Rotation and uniform scale of a ``(3, 3)`` matrix (the mean of its column lengths)."""
    s = np.linalg.norm(m, axis=0)
    return Rotation.from_matrix(m / s).as_matrix(), float(s.mean())


def _humanoid(gl: dict, node_joint: dict[int, str]) -> tuple[dict[str, str], str | None]:
    ext = gl.get("extensions") or {}
    pairs: list[tuple[Any, Any]] = []
    version = None
    if isinstance(ext.get("VRMC_vrm"), dict):
        version = "1.0"
        bones = ((ext["VRMC_vrm"].get("humanoid") or {}).get("humanBones") or {})
        pairs = [(k, v.get("node")) for k, v in bones.items() if isinstance(v, dict)]
    elif isinstance(ext.get("VRM"), dict):
        version = "0.x"
        bones = (ext["VRM"].get("humanoid") or {}).get("humanBones") or []
        pairs = [(b.get("bone"), b.get("node")) for b in bones if isinstance(b, dict)]
    return {r: node_joint[n] for r, n in pairs if r in ROLES and n in node_joint}, version


def read_gltf_rig(path: str | os.PathLike) -> GltfRig:
    """The skinned character of a ``.glb``/``.vrm`` (see the module docstring); :class:`RigError` if there is none."""
    path = Path(path)
    gl, blob = read_glb(path)
    nodes = check_rig_json(path, gl)
    parent, world = _node_tree(path, nodes)
    order = _joint_nodes(path, gl, parent)
    index = {n: j for j, n in enumerate(order)}
    names: list[str] = []
    seen: set[str] = set()
    for n in order:
        name = str(nodes[n].get("name") or f"node{n}")
        names.append(name if name not in seen else f"{name}#{n}")
        seen.add(names[-1])
    pos = world[order, :3, 3]
    parents = np.array([-1] + [index[int(parent[n])] for n in order[1:]])
    offsets = pos - np.vstack([np.zeros(3), pos[parents[1:]]])
    lin = world[order, :3, :3]
    finite = np.isfinite(lin).all(axis=(1, 2))
    flat = ~finite | (np.linalg.norm(lin, axis=1) < 1e-9).any(axis=1)
    flat |= np.linalg.det(np.where(finite[:, None, None], lin, np.eye(3))) <= 0  # a mirror is no rotation
    if flat.any():
        raise _bad(path, f"node {order[int(np.argmax(flat))]}'s rest transform is degenerate "
                         "(a zero, negative or non-finite scale)")
    rw, sc = zip(*(_polar(world[n, :3, :3]) for n in order))
    # position channels on the root and down to the first joint that branches (the hips, under a root bone)
    kids = np.bincount(parents[1:], minlength=len(order))
    moving = [0]
    while kids[moving[-1]] == 1:
        moving.append(moving[-1] + 1)  # parents first, depth first: an only child comes right after its parent
    channels = tuple((POSITION_CHANNELS + _ROT) if j in moving else _ROT for j in range(len(order)))
    skel = Skeleton(tuple(names), parents, offsets, (), channels)
    root_parent = int(parent[order[0]])
    humanoid, vrm = _humanoid(gl, dict(zip(order, names)))
    if blob == b"" and gl.get("buffers"):
        raise _bad(path, "keeps its data in external files; export it as a self-contained .glb")
    return GltfRig(path, gl, blob, skel, tuple(order), np.array(rw), world[root_parent] if root_parent >= 0
                   else np.eye(4), np.array(sc), humanoid, vrm, world)


def _node_rotations(rig: GltfRig, motion: Motion) -> np.ndarray:
    """glTF local rotations ``(T, J, 4)`` of the rig's nodes: ``q_j = W_p^-1 r_j W_p L_j``."""
    W = rig.rest_world
    parents = rig.skeleton.parents
    Wp = np.stack([W[p] if p >= 0 else _polar(rig.parent_world[:3, :3])[0] for p in parents])
    L = np.swapaxes(Wp, -1, -2) @ W
    r = Rotation.from_quat(motion.rotations.reshape(-1, 4)).as_matrix().reshape(motion.rotations.shape[:-1] + (3, 3))
    q = np.swapaxes(Wp, -1, -2) @ r @ Wp @ L
    return unroll_quaternions(Rotation.from_matrix(q.reshape(-1, 3, 3)).as_quat().reshape(q.shape[:-2] + (4,)))


def _node_translations(rig: GltfRig, motion: Motion) -> dict[int, np.ndarray]:
    """glTF translations ``{joint: (T, 3)}`` of the root and of the joints with position channels."""
    out = {}
    inv = np.linalg.inv(rig.parent_world)
    out[0] = motion.root_positions @ inv[:3, :3].T + inv[:3, 3]
    skel = rig.skeleton
    if motion.translations is not None:
        d = motion.local_translations()
        for j in range(1, skel.n_joints):
            if skel.has_position_channels(j):
                p = skel.parents[j]
                out[j] = d[:, j] @ rig.rest_world[p] / rig.scale[p]  # row vectors: d W_p == (W_p^T d^T)^T
    return out


def _as_trs(node: dict) -> None:
    """Replace a node's ``matrix`` by TRS (animated nodes must not have a matrix)."""
    if "matrix" not in node:
        return
    m = np.array(node.pop("matrix"), dtype=np.float64).reshape(4, 4).T
    r, s = _polar(m[:3, :3])
    node["translation"] = [float(v) for v in m[:3, 3]]
    node["rotation"] = [float(v) for v in Rotation.from_matrix(r).as_quat()]
    node["scale"] = [s, s, s]


def rig_glb_bytes(rig: GltfRig, motion: Motion, name: str = "text2anim",
                  extra: Callable[[BufferBuilder, dict, dict], None] | None = None) -> bytes:
    """The rig's file with ``motion`` (on ``rig.skeleton``) as its one animation; ``extra(b, gl, animation)``,
    when given, adds more to the file before it is packed (the scene's props, :func:`output.gltf.add_props`)."""
    if not motion.skeleton.same_hierarchy(rig.skeleton):
        raise RigError(f"{rig.path}: the motion is not on this rig's skeleton (a root bone was added? "
                       "--root-motion on a glTF rig needs a root bone above the hips)")
    if motion.n_frames == 0:
        raise ValueError("the motion has no frames")
    gl = copy.deepcopy(rig.gl)
    for n in rig.nodes:
        _as_trs(gl["nodes"][n])
    gl, blob = drop_animations(gl, rig.bin)  # the file's own animations are replaced: their data goes too
    b = BufferBuilder(blob, gl.get("bufferViews"), gl.get("accessors"))
    anim: dict = {"name": name, "channels": [], "samplers": []}
    times = b.accessor(motion.times, _FLOAT, "SCALAR", minmax=True)

    def channel(node: int, path: str, values: np.ndarray, atype: str) -> None:
        anim["samplers"].append({"input": times, "output": b.accessor(values, _FLOAT, atype), "interpolation": "LINEAR"})
        anim["channels"].append({"sampler": len(anim["samplers"]) - 1, "target": {"node": node, "path": path}})

    trans = _node_translations(rig, motion)
    quats = _node_rotations(rig, motion)
    for j, n in enumerate(rig.nodes):
        if j in trans:
            channel(n, "translation", trans[j], "VEC3")
        channel(n, "rotation", quats[:, j], "VEC4")
    gl["animations"] = [anim]
    if not gl.get("buffers"):
        gl["buffers"] = [{}]
    if extra is not None:
        extra(b, gl, anim)
    return pack_glb(gl, b)

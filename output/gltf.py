"""glTF 2.0 binary (``.glb``) export: :func:`write_glb`, :func:`glb_bytes`.

One file holds every actor:

- per actor a group node (the actor's name) over its joint hierarchy, one node
  per joint named as in the skeleton; the nodes' own transforms are the bind
  pose (the skeleton's rest offsets, identity rotations, the root where the
  motion starts);
- per actor a skinned mesh (a box along every bone, including the BVH end
  sites, rigidly bound to the bone's parent joint; a bigger one for the head)
  with the skin's inverse bind matrices, in the actor's viewer colour;
- one animation, ``"text2anim"``: per actor a time accessor (seconds), the root
  joint's ``translation`` and every joint's ``rotation`` (unit quaternions,
  signs made continuous so LINEAR sampling takes the short way), plus
  ``translation`` for every joint when the motion carries local translations;
- per prop (a thing of the scene, :class:`~output.viewer.types.Prop`) a node named
  as the text writes it (ボール, 椅子) at the top of the scene, ``extras.prop`` its
  shape, with a mesh of its shape's parts (:mod:`output.shapes`: a sphere, boxes, a
  chair of seat, legs and back, ...) in a material of its colour; a moving prop gets
  ``translation`` and ``rotation`` channels in the same animation (on its own
  time accessor, the same clock), a still one only its node's transform.
  Without props the file is what it was before props existed, byte for byte.

Units are metres, +Y up, right-handed, as glTF wants; quaternion order
``(x, y, z, w)`` is glTF's too. Binary layout: every buffer view starts on
a 4-byte boundary, vertex attributes are tightly packed, POSITION and the
animation inputs carry ``min``/``max``, the JSON chunk is padded with spaces
and the BIN chunk with zeros. Loads in three.js' GLTFLoader and passes the
Khronos glTF validator without errors or warnings (see ``tests/test_gltf.py``).
"""
from __future__ import annotations

import os
from typing import Any

import numpy as np

from text2anim.core.atomic import atomic_write_bytes
from text2anim.core.glb import (ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, FLOAT, UBYTE, UINT, USHORT, BufferBuilder,
                                 pack_glb)
from text2anim.core.motion import Motion, unroll_quaternions

__all__ = ["add_props", "glb_bytes", "write_glb"]

def _bone_boxes(points: np.ndarray, parents: list[int], radii: np.ndarray):
    """Boxes along bones: positions, normals, joint index per vertex and triangle indices."""
    pos: list[np.ndarray] = []
    nrm: list[np.ndarray] = []
    jnt: list[int] = []
    idx: list[int] = []
    # unit cube faces: normal axis, sign; corners in (u, v) order counter-clockwise seen from outside
    for i, p in enumerate(parents):
        if p < 0:
            continue
        a, b = points[p], points[i]
        d = b - a
        length = float(np.linalg.norm(d))
        if length < 1e-4:
            continue
        z = d / length
        helper = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        x = np.cross(helper, z)
        x /= np.linalg.norm(x)
        y = np.cross(z, x)
        r = float(radii[i])
        # box in the bone frame: x, y in [-r, r], z in [0, length] (a little inset at the ends)
        inset = min(r * 0.5, length * 0.1)
        lo, hi = inset, length - inset
        frame = np.stack([x, y, z], axis=1)  # columns
        for axis in range(3):
            for sign in (-1.0, 1.0):
                n_local = np.zeros(3)
                n_local[axis] = sign
                u_ax, v_ax = [(1, 2), (2, 0), (0, 1)][axis]
                quad = []
                for cu, cv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                    c = np.zeros(3)
                    c[axis] = sign
                    c[u_ax], c[v_ax] = cu, cv
                    local = np.array([c[0] * r, c[1] * r, lo if c[2] < 0 else hi])
                    quad.append(a + frame @ local)
                base = len(pos)
                pos.extend(quad)
                nrm.extend([frame @ n_local] * 4)
                jnt.extend([p] * 4)
                # counter-clockwise when seen from outside: (u, v, n) is right-handed for sign +1
                tri = [0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2]
                idx.extend(base + t for t in tri)
    return (np.array(pos, dtype=np.float64).reshape(-1, 3), np.array(nrm).reshape(-1, 3),
            np.array(jnt, dtype=np.int64), np.array(idx, dtype=np.int64))


def _radii(motion: Motion, parents: list[int], points: np.ndarray) -> np.ndarray:
    skel = motion.skeleton
    h = max(skel.height(), 1e-6)
    lengths = np.array([np.linalg.norm(points[i] - points[p]) if p >= 0 else 0.0 for i, p in enumerate(parents)])
    radii = np.clip(lengths * 0.18, 0.01 * h / 1.7, 0.04 * h / 1.7)
    try:
        from text2anim.core.bodyparts import body_map

        bm = body_map(skel)
    except Exception:  # an unusual skeleton: plain boxes
        return radii
    for i, p in enumerate(parents):
        if p == bm.head:
            radii[i] = 0.085 * h / 1.7
        elif p in bm.groups.get("torso", ()) or p == 0:
            radii[i] *= 1.4
    return radii


def _actor(b: BufferBuilder, gl: dict, name: str, motion: Motion, color: str, multi: bool, animate: bool) -> None:
    skel = motion.skeleton
    J = skel.n_joints
    if motion.n_frames == 0:
        raise ValueError(f"actor {name!r}: the motion has no frames")
    nodes = gl["nodes"]
    first = len(nodes)
    bind_root = motion.root_positions[0].astype(np.float64)
    bind_world = skel.rest_positions() + bind_root  # identity rotations: world = sum of offsets
    for j in range(J):
        node: dict[str, Any] = {"name": skel.names[j]}
        t = bind_root if j == 0 else skel.offsets[j]
        if np.any(t != 0):
            node["translation"] = [float(v) for v in t]
        kids = [first + c for c in skel.children(j)]
        if kids:
            node["children"] = kids
        nodes.append(node)
    group = {"name": name or "actor", "children": [first]}
    nodes.append(group)
    gl["scenes"][0]["nodes"].append(len(nodes) - 1)

    # mesh in bind space
    ends = [bind_world[j] + o for j, o in skel.end_sites]
    points = np.vstack([bind_world, *ends]) if ends else bind_world
    parents = [int(p) for p in skel.parents] + [int(j) for j, _ in skel.end_sites]
    pos, nrm, jnt, idx = _bone_boxes(points, parents, _radii(motion, parents, points))
    if len(pos) == 0:  # a skeleton of points: one small box at the root
        pos, nrm, jnt, idx = _bone_boxes(np.array([bind_world[0], bind_world[0] + [0, 0.05, 0]]), [-1, 0],
                                         np.array([0.0, 0.025]))
    n_vert = len(pos)
    weights = np.zeros((n_vert, 4))
    weights[:, 0] = 1.0
    joints4 = np.zeros((n_vert, 4), dtype=np.int64)
    joints4[:, 0] = jnt
    gl["materials"].append({"name": f"{name or 'actor'} material", "pbrMetallicRoughness": {
        "baseColorFactor": [*_linear(color), 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6}})
    prim = {
        "attributes": {
            "POSITION": b.accessor(pos, FLOAT, "VEC3", target=ARRAY_BUFFER, minmax=True),
            "NORMAL": b.accessor(nrm, FLOAT, "VEC3", target=ARRAY_BUFFER),
            "JOINTS_0": b.accessor(joints4, UBYTE if J < 256 else USHORT, "VEC4", target=ARRAY_BUFFER),
            "WEIGHTS_0": b.accessor(weights, FLOAT, "VEC4", target=ARRAY_BUFFER),
        },
        "indices": b.accessor(idx, USHORT if n_vert < 65535 else UINT, "SCALAR", target=ELEMENT_ARRAY_BUFFER),
        "material": len(gl["materials"]) - 1,
        "mode": 4,
    }
    gl["meshes"].append({"name": name or "actor", "primitives": [prim]})
    ibm = np.tile(np.eye(4), (J, 1, 1))
    ibm[:, :3, 3] = -bind_world
    ibm_colmajor = ibm.transpose(0, 2, 1).reshape(J, 16)  # glTF matrices are column-major
    gl["skins"].append({"name": name or "actor", "joints": list(range(first, first + J)), "skeleton": first,
                        "inverseBindMatrices": b.accessor(ibm_colmajor, FLOAT, "MAT4")})
    nodes.append({"name": f"{name or 'actor'} mesh" if multi or name else "mesh",
                  "mesh": len(gl["meshes"]) - 1, "skin": len(gl["skins"]) - 1})
    gl["scenes"][0]["nodes"].append(len(nodes) - 1)

    if animate:
        _animate(b, gl["animations"][0], first, motion)


def _animate(b: BufferBuilder, anim: dict, first: int, motion: Motion) -> None:
    """Channels of ``motion`` on the joint nodes ``first ...`` (see the module docstring)."""
    J = motion.skeleton.n_joints
    times = b.accessor(motion.times, FLOAT, "SCALAR", minmax=True)

    def channel(node: int, path: str, values: np.ndarray, atype: str):
        anim["samplers"].append({"input": times, "output": b.accessor(values, FLOAT, atype), "interpolation": "LINEAR"})
        anim["channels"].append({"sampler": len(anim["samplers"]) - 1, "target": {"node": node, "path": path}})

    quats = motion.rotations / np.linalg.norm(motion.rotations, axis=-1, keepdims=True)
    quats = unroll_quaternions(quats)
    if motion.translations is None:
        channel(first, "translation", motion.root_positions, "VEC3")
    for j in range(J):
        if motion.translations is not None:
            channel(first + j, "translation", motion.local_translations()[:, j], "VEC3")
        channel(first + j, "rotation", quats[:, j], "VEC4")


def _linear(color: str) -> list[float]:
    """``#rrggbb`` (sRGB) as glTF's linear ``baseColorFactor`` RGB."""
    rgb = [int(color[i:i + 2], 16) / 255 for i in (1, 3, 5)]
    return [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in rgb]


def add_props(b: BufferBuilder, gl: dict, props, anim: dict | None) -> None:
    """Put each :class:`~output.viewer.types.Prop` into the glTF ``gl`` (its buffer ``b``): a node named as the
    prop, at the top of the default scene, with the mesh of its shape (:func:`output.shapes.mesh`) in a material
    of its colour, ``extras.prop`` its shape; its ``translation`` and ``rotation`` channels in ``anim`` (the actors'
    animation) when it moves, else the node's own first-frame transform only. Works on our files and on a
    user's rig alike (lists missing from ``gl`` are created)."""
    from .shapes import mesh

    scene = gl.setdefault("scenes", [{"nodes": []}])[gl.get("scene", 0)].setdefault("nodes", [])
    times: dict[tuple[int, float], int] = {}  # one time accessor per frame count and rate
    for prop in props:
        pos, nrm, idx = mesh(prop.shape, prop.size)
        gl.setdefault("materials", []).append({"name": f"{prop.name} material", "pbrMetallicRoughness": {
            "baseColorFactor": [*_linear(prop.color), 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.7}})
        gl.setdefault("meshes", []).append({"name": prop.name, "primitives": [{
            "attributes": {"POSITION": b.accessor(pos, FLOAT, "VEC3", target=ARRAY_BUFFER, minmax=True),
                           "NORMAL": b.accessor(nrm, FLOAT, "VEC3", target=ARRAY_BUFFER)},
            "indices": b.accessor(idx, USHORT if len(pos) < 65535 else UINT, "SCALAR", target=ELEMENT_ARRAY_BUFFER),
            "material": len(gl["materials"]) - 1, "mode": 4}]})
        quats = prop.unit_rotations
        node: dict[str, Any] = {"name": prop.name, "mesh": len(gl["meshes"]) - 1,
                                "translation": [float(v) for v in prop.positions[0]],
                                "rotation": [float(v) for v in quats[0]], "extras": {"prop": prop.shape}}
        gl["nodes"].append(node)
        n = len(gl["nodes"]) - 1
        scene.append(n)
        if anim is None or prop.is_static:
            continue
        key = (prop.n_frames, float(prop.fps))
        if key not in times:
            times[key] = b.accessor(np.arange(prop.n_frames) / prop.fps, FLOAT, "SCALAR", minmax=True)
        for path, values, atype in (("translation", prop.positions, "VEC3"), ("rotation", quats, "VEC4")):
            anim["samplers"].append({"input": times[key], "output": b.accessor(values, FLOAT, atype),
                                     "interpolation": "LINEAR"})
            anim["channels"].append({"sampler": len(anim["samplers"]) - 1, "target": {"node": n, "path": path}})


def glb_bytes(tracks, animate: bool = True, props=()) -> bytes:
    """The ``.glb`` file of ``tracks`` (a list of :class:`~output.viewer.types.Track`,
    a ``{name: Motion}`` dict or one :class:`~core.motion.Motion`) and the scene's ``props``
    (:class:`~output.viewer.types.Prop`); ``animate=False``: the skinned characters in their bind pose and
    the props where they start, no animation."""
    from .viewer.types import as_props, as_tracks
    from .viewer import PALETTE

    tracks = as_tracks(tracks)
    props = as_props(props)
    for t in tracks:
        for what, arr in (("root positions", t.motion.root_positions), ("rotations", t.motion.rotations)):
            if not np.all(np.isfinite(arr)):
                raise ValueError(f"track {t.name!r}: non-finite {what}")
    b = BufferBuilder()
    gl: dict = {
        "asset": {"version": "2.0", "generator": "text2anim"},
        "scene": 0,
        "scenes": [{"name": "text2anim", "nodes": []}],
        "nodes": [], "meshes": [], "materials": [], "skins": [],
        "animations": [{"name": "text2anim", "channels": [], "samplers": []}],
    }
    for i, t in enumerate(tracks):
        _actor(b, gl, t.name, t.motion, PALETTE[i % len(PALETTE)], len(tracks) > 1, animate)
    add_props(b, gl, props, gl["animations"][0] if animate else None)
    if not animate:
        del gl["animations"]
    gl["buffers"] = [{}]
    return pack_glb(gl, b)


def write_glb(tracks, path: str | os.PathLike, props=()) -> None:
    """Write :func:`glb_bytes` of ``tracks`` and ``props`` to ``path`` atomically
    (:class:`~core.atomic.OutputError` if it cannot be written)."""
    atomic_write_bytes(path, glb_bytes(tracks, props=props))

"""The parts of a glTF JSON the rig reader relies on, checked once before it reads them.

A ``.glb``/``.vrm`` a user hands us may hold anything where the glTF 2.0 schema asks for a
number or a list: a node's children as a dict, a matrix of 15 numbers, a rotation as a
string, a skin joint out of range, a humanoid given as a string. :func:`check_rig_json`
turns each into one :class:`RigError` line naming the field, so the reader itself only
meets the shapes the schema promises. Node count follows the BVH reader's joint limit.
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from .bvh_text import MAX_JOINTS
from .rigs import RigError

#: The most nodes a rig may have (the BVH reader's joint limit).
MAX_NODES = MAX_JOINTS
#: A node's transform fields and their lengths (``matrix`` column-major).
_LENGTHS = {"matrix": 16, "rotation": 4, "translation": 3, "scale": 3}


def _numbers(value: Any, n: int) -> bool:
    return (isinstance(value, list) and len(value) == n
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in value))


def _indices(value: Any, n: int) -> bool:
    return isinstance(value, list) and all(isinstance(v, int) and not isinstance(v, bool) and 0 <= v < n
                                           for v in value)


def _check_node(path: Path, i: int, node: Any, n: int) -> None:
    if not isinstance(node, dict):
        raise RigError(f"{path}: node {i} is not a JSON object")
    if not _indices(node.get("children", []), n):
        raise RigError(f"{path}: node {i}'s children are not a list of node indices below {n}")
    for key, length in _LENGTHS.items():
        if key in node and not _numbers(node[key], length):
            raise RigError(f"{path}: node {i}'s {key} is not {length} finite numbers")
    if "rotation" in node and not any(node["rotation"]):
        raise RigError(f"{path}: node {i}'s rotation is a zero quaternion")
    if "name" in node and not isinstance(node["name"], str):
        raise RigError(f"{path}: node {i}'s name is not a string")


def _check_skins(path: Path, skins: Any, n: int) -> None:
    if not isinstance(skins, list) or not all(isinstance(s, dict) for s in skins):
        raise RigError(f"{path}: skins is not a list of JSON objects")
    for k, skin in enumerate(skins):
        if not _indices(skin.get("joints", []), n):
            raise RigError(f"{path}: skin {k}'s joints are not a list of node indices below {n}")


def _check_humanoid(path: Path, ext: Any) -> None:
    """VRM 1.0 ``humanBones`` a dict of ``{"node": int}``, VRM 0.x a list of ``{"bone": str, "node": int}``."""
    if not isinstance(ext, dict):
        raise RigError(f"{path}: extensions is not a JSON object")
    for key, bones_type in (("VRMC_vrm", dict), ("VRM", list)):
        vrm = ext.get(key)
        if vrm is None:
            continue
        humanoid = vrm.get("humanoid") if isinstance(vrm, dict) else None
        bones = humanoid.get("humanBones") if isinstance(humanoid, dict) else None
        entries = (bones.values() if isinstance(bones, dict) else bones) if isinstance(bones, bones_type) else None
        if entries is None or not all(isinstance(b, dict) and isinstance(b.get("node"), int)
                                      and isinstance(b.get("bone", ""), str) for b in entries):
            raise RigError(f"{path}: the {key} extension's humanoid bones are not as VRM specifies them")


def check_rig_json(path: Path, gl: dict) -> list:
    """``gl``'s nodes after checking every field the rig reader uses; :class:`RigError` names the first bad one."""
    nodes = gl.get("nodes")
    if not isinstance(nodes, list) or not nodes:
        raise RigError(f"{path}: has no nodes: --rig needs a rigged character")
    if len(nodes) > MAX_NODES:
        raise RigError(f"{path}: {len(nodes)} nodes; a rig may have at most {MAX_NODES}")
    for i, node in enumerate(nodes):
        _check_node(path, i, node, len(nodes))
    _check_skins(path, gl.get("skins") or [], len(nodes))
    _check_humanoid(path, gl.get("extensions") or {})
    if not isinstance(gl.get("buffers", []), list):
        raise RigError(f"{path}: buffers is not a list")
    return nodes

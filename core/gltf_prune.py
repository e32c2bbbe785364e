"""A glTF file without its animations: the animations and the data only they used, dropped.

A character written out again with a new animation (:func:`.gltf_rig.rig_glb_bytes`) replaces the
file's own animations; their samplers' accessors, those accessors' buffer views and the bytes of the
binary chunk only those views held would stay in the file unused (a Mixamo X Bot: 752 objects,
2.25 -> 2.47 MB). :func:`drop_animations` removes them, renumbers what is left (every ``bufferView``
reference anywhere in the JSON, extensions included; the accessor references of meshes, skins and
``EXT_mesh_gpu_instancing``) and packs the binary chunk's remaining views in their order, 4-byte aligned.
"""
from __future__ import annotations

import copy
from typing import Any

#: Alignment of a buffer view in the binary chunk (bytes): enough for every component type.
ALIGN = 4


def _accessor_refs(gl: dict) -> list[tuple[dict, Any]]:
    """``(holder, key)`` of every accessor reference outside the animations."""
    refs: list[tuple[dict, Any]] = []
    for mesh in gl.get("meshes", []):
        for prim in mesh.get("primitives", []):
            refs += [(prim["attributes"], k) for k in prim.get("attributes", {})]
            refs += [(prim, "indices")] if "indices" in prim else []
            refs += [(t, k) for t in prim.get("targets", []) for k in t]
    refs += [(skin, "inverseBindMatrices") for skin in gl.get("skins", []) if "inverseBindMatrices" in skin]
    for node in gl.get("nodes", []):
        attrs = node.get("extensions", {}).get("EXT_mesh_gpu_instancing", {}).get("attributes", {})
        refs += [(attrs, k) for k in attrs]
    return refs


def _view_refs(tree: Any, out: list[tuple[dict, str]]) -> list[tuple[dict, str]]:
    """``(holder, "bufferView")`` of every buffer-view reference in ``tree`` (accessors, images, extensions)."""
    if isinstance(tree, dict):
        if isinstance(tree.get("bufferView"), int):
            out.append((tree, "bufferView"))
        for v in tree.values():
            _view_refs(v, out)
    elif isinstance(tree, list):
        for v in tree:
            _view_refs(v, out)
    return out


def drop_animations(gl: dict, blob: bytes) -> tuple[dict, bytes]:
    """``gl`` (a glTF JSON, not changed) and its binary chunk ``blob`` without the animations and the
    accessors, buffer views and bytes that only they used."""
    gl = copy.deepcopy(gl)
    animated = {s[k] for a in gl.pop("animations", []) for s in a.get("samplers", []) for k in ("input", "output")}
    refs = _accessor_refs(gl)
    dropped = animated - {holder[key] for holder, key in refs}
    if not dropped:
        return gl, blob
    used = [i for i in range(len(gl["accessors"])) if i not in dropped]
    new_acc = {old: new for new, old in enumerate(used)}
    for holder, key in refs:
        holder[key] = new_acc[holder[key]]
    gl["accessors"] = [gl["accessors"][i] for i in used]

    views = gl.get("bufferViews", [])
    outside = {k: v for k, v in gl.items() if k != "bufferViews"}
    vrefs = _view_refs(outside, [])
    kept = sorted({holder[key] for holder, key in vrefs})
    new_view = {old: new for new, old in enumerate(kept)}
    for holder, key in vrefs:
        holder[key] = new_view[holder[key]]
    out = bytearray()
    for i in kept:
        view = views[i]
        if view.get("buffer", 0) == 0:
            out.extend(b"\0" * ((-len(out)) % ALIGN))
            start = view.get("byteOffset", 0)
            view["byteOffset"] = len(out)
            out.extend(blob[start:start + view["byteLength"]])
    gl["bufferViews"] = [views[i] for i in kept]
    return gl, bytes(out)

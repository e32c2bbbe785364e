"""A glTF character's skinned vertices in its bind pose, for what the skeleton alone cannot say.

:func:`bind_vertices` reads every skinned primitive's ``POSITION``, ``JOINTS_0`` and ``WEIGHTS_0``
(plain accessors in the binary chunk: float positions; unsigned byte/short joints; float or normalised
unsigned weights) and skins the positions with the nodes' rest transforms (``W_j · IBM_j``), so the
vertices stand where the rest pose puts them: metres, world space, Y up. Everything is checked
before it is read (a view inside the chunk, an accessor inside its view, a joint inside its skin) and
anything else (sparse accessors, external buffers, other component types) is left out rather than
refused: the mesh only refines a rig the skeleton already describes (:mod:`core.soles`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["SkinnedVertices", "bind_vertices", "MAX_VERTICES"]

#: The most vertices read (over all primitives): a detailed character has a few hundred thousand.
MAX_VERTICES = 2_000_000
_COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
_DTYPES = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}


@dataclass(frozen=True)
class SkinnedVertices:
    """``positions`` ``(V, 3)`` metres in the bind pose; ``nodes`` ``(V, 4)`` the glTF node each influence
    names; ``weights`` ``(V, 4)`` summing to 1 per vertex."""

    positions: np.ndarray
    nodes: np.ndarray
    weights: np.ndarray


def _accessor(gl: dict, blob: bytes, index, kind: str, dtypes: tuple[int, ...]) -> np.ndarray | None:
    """Accessor ``index`` as a ``(count, components)`` float64 array (normalised integers to [0, 1]), or
    ``None`` when it is not a plain accessor of ``kind`` and one of ``dtypes`` lying inside ``blob``."""
    accs, views = gl.get("accessors"), gl.get("bufferViews")
    if not (isinstance(index, int) and isinstance(accs, list) and isinstance(views, list) and 0 <= index < len(accs)):
        return None
    acc = accs[index]
    if not isinstance(acc, dict) or acc.get("type") != kind or acc.get("componentType") not in dtypes \
            or "sparse" in acc:
        return None
    view_i, count, ncomp = acc.get("bufferView"), acc.get("count"), _COMPONENTS[kind]
    if not (isinstance(view_i, int) and 0 <= view_i < len(views) and isinstance(count, int) and count >= 0):
        return None
    view = views[view_i]
    if not isinstance(view, dict) or view.get("buffer", 0) != 0:
        return None
    dtype = np.dtype(_DTYPES[acc["componentType"]]).newbyteorder("<")
    size = dtype.itemsize * ncomp
    stride = view.get("byteStride") or size
    start = view.get("byteOffset", 0)
    length = view.get("byteLength")
    at = acc.get("byteOffset", 0)
    if not all(isinstance(v, int) and v >= 0 for v in (stride, start, length, at)) or stride < size:
        return None
    if start + length > len(blob) or (count and at + stride * (count - 1) + size > length):
        return None
    if count == 0:
        return np.zeros((0, ncomp))
    raw = np.ndarray((count, ncomp), dtype=dtype, buffer=blob, offset=start + at, strides=(stride, dtype.itemsize))
    out = raw.astype(np.float64)
    if acc.get("normalized") and dtype.kind == "u":
        out /= np.iinfo(dtype).max
    return out


def bind_vertices(gl: dict, blob: bytes, world: np.ndarray, of: np.ndarray) -> SkinnedVertices:
    """The skinned vertices of the file bound mostly (half their weight or more) to the nodes ``of``, in
    their bind pose (module docstring); ``world`` ``(N, 4, 4)`` is each node's rest world matrix. Empty
    arrays where the file has no such vertex in a skinned primitive it can read."""
    parts: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
    total = 0
    nodes, skins, meshes = gl.get("nodes") or [], gl.get("skins") or [], gl.get("meshes")
    for node in nodes:
        skin_i, mesh_i = node.get("skin"), node.get("mesh")
        if not (isinstance(skin_i, int) and 0 <= skin_i < len(skins) and isinstance(mesh_i, int)
                and isinstance(meshes, list) and 0 <= mesh_i < len(meshes) and isinstance(meshes[mesh_i], dict)):
            continue
        joints = np.asarray(skins[skin_i].get("joints") or [], dtype=np.int64)
        ibm = _accessor(gl, blob, skins[skin_i].get("inverseBindMatrices"), "MAT4", (5126,))
        if joints.size == 0 or (ibm is not None and len(ibm) < len(joints)):
            continue
        if ibm is None:
            ibm = np.tile(np.eye(4), (len(joints), 1, 1))
        else:  # column-major in the file
            ibm = ibm[:len(joints)].reshape(-1, 4, 4).transpose(0, 2, 1)
        skinning = world[joints] @ ibm  # (J, 4, 4): bind space to the rest pose's world
        prims = meshes[mesh_i].get("primitives")
        for prim in prims if isinstance(prims, list) else []:
            attrs = prim.get("attributes") if isinstance(prim, dict) else None
            if not isinstance(attrs, dict):
                continue
            pos = _accessor(gl, blob, attrs.get("POSITION"), "VEC3", (5126,))
            jts = _accessor(gl, blob, attrs.get("JOINTS_0"), "VEC4", (5121, 5123))
            wts = _accessor(gl, blob, attrs.get("WEIGHTS_0"), "VEC4", (5126, 5121, 5123))
            if pos is None or jts is None or wts is None or not len(pos) == len(jts) == len(wts) \
                    or total + len(pos) > MAX_VERTICES or (len(jts) and jts.max() >= len(joints)):
                continue
            total += len(pos)
            w = wts / np.maximum(wts.sum(axis=1, keepdims=True), 1e-12)
            j = jts.astype(np.int64)
            mine = (w * np.isin(joints[j], of)).sum(axis=1) >= 0.5
            w, j, pos = w[mine], j[mine], pos[mine]
            m = sum(w[:, k, None, None] * skinning[j[:, k]] for k in range(4))  # (V, 4, 4) linear blend skinning
            p = np.einsum("vab,vb->va", m[:, :3, :3], pos) + m[:, :3, 3]
            ok = np.isfinite(p).all(axis=1)  # a NaN in a position, a weight or a matrix places nothing
            parts.append((p[ok], joints[j[ok]], w[ok]))
    if not parts:
        return SkinnedVertices(np.zeros((0, 3)), np.zeros((0, 4), dtype=np.int64), np.zeros((0, 4)))
    return SkinnedVertices(*(np.concatenate(x) for x in zip(*parts)))

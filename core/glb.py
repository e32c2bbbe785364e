"""The glTF binary container (``.glb``) every writer of ours packs: :class:`BufferBuilder` (accessors and
buffer views over one growing BIN chunk) and :func:`pack_glb` (the JSON and BIN chunks with their
12-byte header). Shared by the GLB writers (``text2anim.output``) and the user's rig
(:mod:`core.gltf_rig`), which writes its own file back with an animation appended.

Binary layout: every buffer view starts on a 4-byte boundary, the JSON chunk is padded with spaces and
the BIN chunk with zeros.
"""
from __future__ import annotations

import json
import struct

import numpy as np

#: accessor component types and buffer-view targets (glTF 2.0, section 5.1.3 and 5.11.4)
FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
_NP = {FLOAT: "<f4", UBYTE: "u1", USHORT: "<u2", UINT: "<u4"}
_COMPONENTS = {"SCALAR": 1, "VEC3": 3, "VEC4": 4, "MAT4": 16}


class BufferBuilder:
    """Accessors and buffer views over one growing binary buffer (the GLB's BIN chunk)."""

    def __init__(self, data: bytes = b"", views: list[dict] | None = None, accessors: list[dict] | None = None):
        self.bin = bytearray(data)
        self.views: list[dict] = list(views or [])
        self.accessors: list[dict] = list(accessors or [])

    def accessor(self, data: np.ndarray, ctype: int, atype: str, *, target: int | None = None,
                 minmax: bool = False, normalized: bool = False) -> int:
        arr = np.ascontiguousarray(np.asarray(data).astype(_NP[ctype]))
        count = len(arr)
        if arr.size != count * _COMPONENTS[atype]:
            raise ValueError(f"accessor data of shape {arr.shape} is not {count} × {atype}")
        pad = (-len(self.bin)) % 4
        self.bin.extend(b"\0" * pad)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": arr.nbytes}
        if target is not None:
            view["target"] = target
        self.bin.extend(arr.tobytes())
        self.views.append(view)
        acc = {"bufferView": len(self.views) - 1, "componentType": ctype, "count": count, "type": atype}
        if normalized:
            acc["normalized"] = True
        if minmax:
            flat = arr.reshape(count, -1)
            cast = float if ctype == FLOAT else int
            acc["min"] = [cast(v) for v in flat.min(axis=0)]
            acc["max"] = [cast(v) for v in flat.max(axis=0)]
        self.accessors.append(acc)
        return len(self.accessors) - 1


def pack_glb(gl: dict, b: BufferBuilder) -> bytes:
    """The ``.glb`` bytes of the glTF JSON ``gl`` whose buffer 0 is ``b``'s binary (its views and accessors
    appended to ``gl``'s own): the JSON chunk padded with spaces, the BIN chunk with zeros."""
    b.bin.extend(b"\0" * ((-len(b.bin)) % 4))
    gl["buffers"][0]["byteLength"] = len(b.bin)
    gl["bufferViews"] = b.views
    gl["accessors"] = b.accessors
    js = json.dumps(gl, ensure_ascii=False, separators=(",", ":"), allow_nan=False).encode("utf-8")
    js += b" " * ((-len(js)) % 4)
    total = 12 + 8 + len(js) + 8 + len(b.bin)
    return b"".join([
        struct.pack("<4sII", b"glTF", 2, total),
        struct.pack("<I4s", len(js), b"JSON"), js,
        struct.pack("<I4s", len(b.bin), b"BIN\0"), bytes(b.bin),
    ])

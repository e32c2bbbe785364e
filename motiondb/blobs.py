"""Frame data as bytes (a zlib-compressed ``.npy`` array, never a pickle) and skeletons as JSON.

Layout (encoding ``npy-zlib-1``): one little-endian float64 array of shape
``(T, C)`` saved with :func:`numpy.save` (``allow_pickle=False``) and
compressed with zlib. Per frame the columns are:

- ``0:3``: root position, metres;
- ``3:3+4J``: local joint rotations, quaternions ``(x, y, z, w)``, joint-major;
- ``3+4J:3+7J`` (only when the motion has per-joint translations): local
  translations, metres.

So ``C`` is ``3 + 4J`` or ``3 + 7J``; the skeleton (``J``) is stored apart, as the
canonical JSON of :func:`skeleton_json`.
Float64 keeps a stored clip bit-identical to what was imported; the bytes are
deterministic (no time stamps), so the same motion always gives the same blob.
"""
from __future__ import annotations

import io
import json
import zlib

import numpy as np

from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton

from .errors import DBError

ENCODING = "npy-zlib-1"
_LEVEL = 6


def encode_frames(motion: Motion) -> bytes:
    """The motion's frames as ``npy-zlib-1`` bytes."""
    T, J = motion.rotations.shape[:2]
    parts = [motion.root_positions.reshape(T, 3), motion.rotations.reshape(T, 4 * J)]
    if motion.translations is not None:
        parts.append(motion.translations.reshape(T, 3 * J))
    arr = np.ascontiguousarray(np.concatenate(parts, axis=1), dtype="<f8")
    buf = io.BytesIO()
    np.save(buf, arr, allow_pickle=False)
    return zlib.compress(buf.getvalue(), _LEVEL)


def decode_frames(data: bytes, skeleton: Skeleton, fps: float, *, encoding: str = ENCODING,
                  frames: int | None = None, clip: str = "?") -> Motion:
    """A :class:`Motion` from ``npy-zlib-1`` bytes; :class:`DBError` when they do not fit the skeleton."""
    if encoding != ENCODING:
        raise DBError(f"clip {clip!r}: unknown frame encoding {encoding!r} (this text2anim reads {ENCODING})")
    try:
        arr = np.load(io.BytesIO(zlib.decompress(bytes(data))), allow_pickle=False)
    except (zlib.error, ValueError, OSError) as exc:
        raise DBError(f"clip {clip!r}: frame data is damaged ({exc})") from None
    J = skeleton.n_joints
    if arr.ndim != 2 or arr.dtype.kind != "f" or arr.shape[1] not in (3 + 4 * J, 3 + 7 * J):
        raise DBError(f"clip {clip!r}: frame data of shape {arr.shape} does not fit a {J}-joint skeleton")
    if frames is not None and len(arr) != frames:
        raise DBError(f"clip {clip!r}: {len(arr)} frames stored, {frames} recorded")
    T = len(arr)
    arr = arr.astype(np.float64, copy=False)
    root = arr[:, :3]
    rot = arr[:, 3:3 + 4 * J].reshape(T, J, 4)
    trans = arr[:, 3 + 4 * J:].reshape(T, J, 3) if arr.shape[1] == 3 + 7 * J else None
    return Motion(skeleton, fps, root, rot, trans)


def skeleton_json(skel: Skeleton) -> str:
    """Canonical JSON of a skeleton (exact floats), the ``skeletons.definition`` column."""
    return json.dumps({
        "names": list(skel.names),
        "parents": [int(p) for p in skel.parents],
        "offsets": skel.offsets.tolist(),
        "end_sites": [[int(j), o.tolist()] for j, o in skel.end_sites],
        "channels": [list(c) for c in skel.channels],
    }, ensure_ascii=False, sort_keys=True, separators=(",", ":"))


def skeleton_from_json(definition: str) -> Skeleton:
    """The skeleton a :func:`skeleton_json` text describes."""
    d = json.loads(definition)
    return Skeleton(tuple(d["names"]), np.array(d["parents"], dtype=np.int64),
                    np.array(d["offsets"], dtype=np.float64).reshape(-1, 3),
                    tuple((j, np.array(o, dtype=np.float64)) for j, o in d["end_sites"]),
                    tuple(tuple(c) for c in d["channels"]))

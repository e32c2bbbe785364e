"""The built-in library's keyframed clips as shipped arrays (``keyframed.npz``): loading them, and the
hash that says whether they are up to date.

Generating the keyframed clips from ``clips/*.json`` (splines, foot planting by IK, reach, ...)
takes seconds; a new database is seeded from what ``tools/library/build_keyframed.py`` made of them once, as
the captured clips are from ``capture.npz``. The file (a ``.npz`` written with fixed names, order
and timestamps, so the same sources give the same bytes) holds:

- ``_meta``: UTF-8 JSON as ``uint8``: ``{"sources": SOURCES_HASH, "fps": 30.0, "clips": [{"name",
  "verbs", "objects", "core", "body_part", "cyclic", "source", "start_posture", "end_posture"},
  ...], "contacts": {name: [[side, start, stop], ...]}}``: the clips in library order (the keyframed
  clips no captured clip replaces), and the foot contacts (:func:`core.contacts.detect_contacts`,
  frames ``[start, stop)``) of every clip a database is seeded with, the captured ones too, as
  storing them would compute them: seeding needs no forward kinematics (nor scipy);
- per clip ``<name>``: its frames ``(T, 3 + 4J)`` (root position, metres, then the joints' local
  quaternions ``(x, y, z, w)``) as float32, stored byte-plane by byte-plane (``(4, 3 + 4J, T)``
  ``uint8``: byte ``k`` of every value of a channel, frame after frame), which deflates to
  two thirds of the plain float32 (the slowly changing high bytes compress together).

Loading is a ``numpy.load`` and a renormalisation of the quaternions (float32 keeps them
within 1e-7 of the generated ones; :mod:`.capture` does the same), with no import of the
generator (scipy.interpolate, IK).

:func:`sources_hash` hashes the clips' JSON and the generator's modules; the shipped file
records the hash it was built from, and a test compares the two, so a changed JSON file or
generator that was not rebuilt (``python tools/library/build_keyframed.py``) fails.
"""
from __future__ import annotations

import hashlib
import json
from functools import lru_cache
from pathlib import Path

import numpy as np

from text2anim.core.motion import Motion
from text2anim.motiondb.types import ClipDescription, ClipRecord

from .keyframes import ClipDataError
from .skeleton import canonical_skeleton

HERE = Path(__file__).parent
ARRAYS = HERE / "keyframed.npz"
#: Frame rate of the shipped arrays (the database's rate for the built-in clips).
FPS = 30.0
#: The generator's modules (with ``clips/*.json``, what the shipped frames are made from).
GENERATOR = ("__init__.py", "keyframes.py", "keyframe_curves.py", "plant.py", "plant_foot.py",
             "plant_gaps.py", "reach.py", "skeleton.py")


def sources_hash(root: Path = HERE) -> str:
    """SHA-256 (first 32 hex digits) of ``clips/*.json`` and the :data:`GENERATOR` modules under ``root``."""
    h = hashlib.sha256()
    files = sorted((root / "clips").glob("*.json")) + [root / name for name in GENERATOR]
    for path in files:
        h.update(path.relative_to(root).as_posix().encode("utf-8") + b"\0")
        h.update(path.read_bytes() + b"\0")
    return "sha256:" + h.hexdigest()[:32]


def to_planes(frames: np.ndarray) -> np.ndarray:
    """``(T, C)`` frames as float32 byte planes ``(4, C, T)`` ``uint8`` (see the module docstring)."""
    f32 = np.ascontiguousarray(np.asarray(frames, dtype="<f4").T)  # (C, T)
    return np.ascontiguousarray(f32.view(np.uint8).reshape(f32.shape[0], f32.shape[1], 4).transpose(2, 0, 1))


def from_planes(planes: np.ndarray) -> np.ndarray:
    """The ``(T, C)`` float64 frames of :func:`to_planes`' ``(4, C, T)`` planes."""
    f32 = np.ascontiguousarray(planes.transpose(1, 2, 0)).view("<f4")[..., 0]  # (C, T)
    return f32.T.astype(np.float64)


def meta_array(meta: dict) -> np.ndarray:
    """``meta`` as the ``_meta`` array (canonical JSON, UTF-8 bytes)."""
    text = json.dumps(meta, ensure_ascii=False, sort_keys=True, separators=(",", ":"))
    return np.frombuffer(text.encode("utf-8"), dtype=np.uint8)


def _motion(frames: np.ndarray) -> Motion:
    skel = canonical_skeleton()
    J = skel.n_joints
    if frames.ndim != 2 or frames.shape[1] != 3 + 4 * J:
        raise ClipDataError(f"keyframed.npz: frames of shape {frames.shape} do not fit the {J}-joint skeleton")
    rots = frames[:, 3:].reshape(len(frames), J, 4)
    return Motion(skel, FPS, np.array(frames[:, :3]), rots / np.linalg.norm(rots, axis=-1, keepdims=True))


#: Foot contacts per clip name: ``[(side, start, stop), ...]`` (frames, ``[start, stop)``).
Contacts = dict[str, list[tuple[str, int, int]]]


def records_of(meta: dict, planes) -> tuple[ClipRecord, ...]:
    """The keyframed records the ``_meta`` JSON ``meta`` describes, frames from ``planes[name]``."""
    return tuple(ClipRecord(
        name=c["name"], motion=_motion(from_planes(planes[c["name"]])), verbs=tuple(c["verbs"]),
        objects=tuple(c["objects"]), character="default", core=(float(c["core"][0]), float(c["core"][1])),
        body_part=c["body_part"], cyclic=bool(c["cyclic"]), source=c["source"],
        start_posture=c["start_posture"], end_posture=c["end_posture"]) for c in meta["clips"])


@lru_cache(maxsize=1)
def shipped(path: Path = ARRAYS) -> tuple[str, tuple[ClipRecord, ...], Contacts, dict[str, ClipDescription]]:
    """``(sources hash, records, contacts, descriptions)`` of the shipped file: the keyframed clips at
    :data:`FPS` (read-only motions), and the foot contacts and measured descriptions (no actions) of
    every seeded clip."""
    try:
        with np.load(path) as data:
            meta = json.loads(data["_meta"].tobytes().decode("utf-8"))
            records = records_of(meta, data)
        contacts = {name: [(str(side), int(a), int(b)) for side, a, b in rows]
                    for name, rows in meta["contacts"].items()}
        described = {name: ClipDescription.from_dict(d) for name, d in meta["descriptions"].items()}
    except (OSError, KeyError, ValueError) as exc:
        raise ClipDataError(f"{path.name} cannot be read ({exc}): rebuild it "
                            "(python tools/library/build_keyframed.py)") from None
    return str(meta["sources"]), records, contacts, described


def keyframed_records() -> tuple[ClipRecord, ...]:
    """The seeded keyframed clips at :data:`FPS`, from the shipped file (cached, read-only motions)."""
    return shipped()[1]


def seeded_contacts() -> Contacts:
    """The foot contacts of every clip a database is seeded with, by name, as shipped."""
    return shipped()[2]


def seeded_descriptions() -> dict[str, ClipDescription]:
    """The measured descriptions (no actions) of every clip a database is seeded with, by name, as shipped."""
    return shipped()[3]

"""Importing BVH files as clips: the options, and reading and validating the files (nothing stored here).

>>> opts = ImportOptions(verbs=("走る",), character="cmu", drop_first=True)
>>> db.import_bvh(["02_03_run.bvh"], opts)   # reads with read_clips, stores all or nothing

Every file becomes one clip; :func:`read_clips` is the one path a file takes
from disk to a validated :class:`~motiondb.records.PreparedClip`: read, then
:func:`conform`, then validate.

Clips enter the database clean (:func:`conform`):

- **Floor.** Each clip's floor is found from its foot contacts and moved to
  ``y = 0`` (:func:`core.floor.place_on_floor`; a clip with few contacts, such
  as a jump, is put with its feet's lowest reach on the floor).
- **One skeleton per character.** A clip whose skeleton is not its
  character's (another capture subject's bone lengths, or another rig) is
  retargeted onto the character's skeleton (:func:`core.retarget.retarget`:
  rotations carried over relative to each rest pose, hips' height and travel
  scaled by leg length, ankles and wrists re-placed by IK). The character's
  skeleton is the one already in the database, or for a new character the
  first file's of the batch. A skeleton whose joints cannot be mapped is
  refused, naming them; nothing is imported.
"""
from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from text2anim.core.bodyparts import BodyMapError, BodyPart
from text2anim.core.bvh import BVHError, read_bvh
from text2anim.core.clearance import bend_toes, keep_clearance
from text2anim.core.floor import place_on_floor
from text2anim.core.motion import Motion
from text2anim.core.retarget import SAME_SIZE, map_skeletons, retarget
from text2anim.core.rigs import RigError
from text2anim.core.skeleton import Skeleton
from text2anim.core.tpose_blend import BLEND_START, held_blend

from .errors import ClipValidationError
from .records import PreparedClip, prepare_record
from .types import ClipRecord, Posture

#: ``progress(done, total, path)``: called before each file and once at the end (``path`` ``""``).
Progress = Callable[[int, int, str], None]
#: ``notify(path, message)``: what :func:`conform` did to a file (floor moved, retargeted).
Notify = Callable[[str, str], None]
#: Bone offsets closer than this (m) are the same skeleton: no retargeting.
SAME_BONES = 1e-6


@dataclass(frozen=True)
class ImportOptions:
    """How BVH files become clips: the metadata every clip gets and how the files are read.

    Attributes:
        verbs: verb lemmas of every clip, primary first (at least one).
        objects: object nouns of every clip.
        character: the character they belong to.
        core: ``(begin, end)`` seconds to keep; ``None`` the whole clip.
        part: the body part of a partial action (:data:`core.bodyparts.GROUPS`), ``None`` whole body.
        cyclic: the clips loop.
        names: one clip name per file; ``None`` names each clip after its file (``02_01_walk``).
        scale: metres per file unit, or ``"auto"`` (:func:`core.bvh.read_bvh`).
        up: the files' up axis, ``"y"`` or ``"z"`` (:func:`core.bvh.read_bvh`).
        drop_first: drop frame 0 (the T-pose of CMU/cgspeed files), and hold the exporter's blend out of it
            still (:func:`core.tpose_blend.held_blend`).
        replace: overwrite clips of the same names instead of refusing.
        start_posture, end_posture: every clip's postures (:data:`motiondb.types.POSTURES`);
            ``None`` classifies each file's first/last frame.
        style: the style the clips were performed in (:data:`core.styles.STYLES`), ``None`` neutral.
        joint_map: ``{role: joint name}`` (or its items) for the files' joints no known rig names
            (:func:`core.rigs.load_joint_map`), used when a clip is retargeted; it applies to the
            character's skeleton too when that has every joint it names.
    """

    verbs: tuple[str, ...]
    objects: tuple[str, ...] = ()
    character: str = "default"
    core: tuple[float, float] | None = None
    part: BodyPart | None = None
    cyclic: bool = False
    names: tuple[str, ...] | None = None
    scale: float | str = "auto"
    up: str = "y"
    drop_first: bool = False
    replace: bool = False
    start_posture: Posture | None = None
    end_posture: Posture | None = None
    joint_map: tuple[tuple[str, str], ...] | None = None
    style: str | None = None

    def __post_init__(self) -> None:
        if isinstance(self.joint_map, dict):
            object.__setattr__(self, "joint_map", tuple(sorted(self.joint_map.items())))
        # lists (from argparse, callers) become tuples, so the options stay immutable and hashable
        for name in ("verbs", "objects", "names"):
            value = getattr(self, name)
            if value is not None and not isinstance(value, tuple):
                object.__setattr__(self, name, (value,) if isinstance(value, str) else tuple(value))


#: frames x joints: the longest clip an import takes. Finding the floor and retargeting hold a few
#: copies of the clip's world transforms: 20,000 frames of 31 joints import in about 9 s and 650 MB;
#: a 60 MB file (80,840 frames) took 36 s and 2.1 GB.
MAX_CLIP_SAMPLES = 620_000


def _same_skeleton(a: Skeleton, b: Skeleton) -> bool:
    return (a.same_hierarchy(b) and a.channels == b.channels
            and bool(np.allclose(a.offsets, b.offsets, rtol=0.0, atol=SAME_BONES)))


def conform(motion: Motion, target: Skeleton | None, where: str, character: str,
            joint_map: dict[str, str] | None = None) -> tuple[Motion, list[str]]:
    """``motion`` on the floor and on the ``target`` skeleton (``None``: its own), and what was done.

    ``joint_map`` (``{role: joint name}``) places the motion's joints no known rig names, and the
    target's when the target has every joint it names.

    Raises :class:`ClipValidationError` naming ``where`` when the motion has
    no feet to find the floor with or its skeleton cannot be mapped onto ``target``.
    """
    notes = []
    try:
        motion, floor = place_on_floor(motion)
    except BodyMapError as exc:
        raise ClipValidationError(f"{where}: cannot find the floor: {exc}") from None
    if abs(floor.height) >= 0.0005:
        how = "foot contacts" if floor.method == "contacts" else "lowest foot reach (few contacts)"
        notes.append(f"floor moved {'down' if floor.height > 0 else 'up'} {100 * abs(floor.height):.1f} cm "
                     f"(found from its {how})")
    if target is None or _same_skeleton(motion.skeleton, target):
        return bend_toes(motion if target is None else motion.replace(skeleton=target)), notes
    target_map = joint_map if joint_map and set(joint_map.values()) <= set(target.names) else None
    try:
        mapping = map_skeletons(motion.skeleton, target, joint_map, target_map)
        captured, motion = motion, retarget(motion, target, source_map=joint_map, target_map=target_map)
    except RigError as exc:
        raise ClipValidationError(f"{where}: cannot be retargeted onto the skeleton of character "
                                  f"{character!r}: {exc}") from None
    if 1.0 / SAME_SIZE <= mapping.scale <= SAME_SIZE:  # a body of about the capture's size: its clearance holds
        motion = keep_clearance(motion, captured)
    motion = bend_toes(motion)  # tips out of the floor, planted feet where they stand
    rigs = mapping.rigs[0] if mapping.rigs[0] == mapping.rigs[1] else " to ".join(mapping.rigs)
    notes.append(f"retargeted onto the skeleton of character {character!r} ({rigs} rig, legs x{mapping.scale:.3f})")
    return motion, notes


def read_clips(paths: Sequence[str | os.PathLike], options: ImportOptions,
               progress: Progress | None = None, *, skeleton: Skeleton | None = None,
               notify: Notify | None = None) -> list[tuple[PreparedClip, Path]]:
    """Read, :func:`conform` and validate BVH files as clips: ``(prepared clip, its file)`` per path, in order.

    ``skeleton`` is the character's skeleton when it already has clips;
    ``None``: the first file's becomes it. A file that cannot be read,
    conformed or validated raises :class:`ClipValidationError` naming it and
    saying nothing was imported (the caller stores nothing).
    """
    files = [Path(p) for p in paths]
    if not files:
        raise ClipValidationError("no files to import")
    if options.names is not None and len(options.names) != len(files):
        raise ClipValidationError(f"{len(options.names)} names for {len(files)} files")
    clip_names = list(options.names) if options.names is not None else [p.stem for p in files]
    out = []
    for k, (path, name) in enumerate(zip(files, clip_names)):
        if progress:
            progress(k, len(files), str(path))
        try:
            motion = read_bvh(path, scale=options.scale, up=options.up, drop_first=options.drop_first)
        except BVHError as exc:
            raise ClipValidationError(f"{exc} (nothing was imported)") from None
        except ValueError as exc:
            raise ClipValidationError(f"{path}: {exc} (nothing was imported)") from None
        if motion.n_frames * motion.skeleton.n_joints > MAX_CLIP_SAMPLES:
            raise ClipValidationError(
                f"{path}: {motion.n_frames:,} frames of {motion.skeleton.n_joints} joints is too long for one clip "
                f"(at most {MAX_CLIP_SAMPLES:,} joint-frames, e.g. {MAX_CLIP_SAMPLES // 31:,} frames of a 31-joint "
                "CMU skeleton: 2 min 47 s at 120 fps); cut the take into shorter files (nothing was imported)")
        held = 0
        if options.drop_first:  # the T-pose dropped: the exporter's blend out of it is held still too
            motion, held = held_blend(motion)
        try:
            motion, notes = conform(motion, skeleton, str(path), options.character,
                                    dict(options.joint_map) if options.joint_map else None)
        except ClipValidationError as exc:
            raise ClipValidationError(f"{exc} (nothing was imported)") from None
        if held:
            notes.insert(0, f"first {held} frames (the exporter's blend out of the dropped T-pose, joints at "
                            f"{BLEND_START:g}+ m/s) hold frame {held}'s pose")
        skeleton = motion.skeleton
        if notify:
            for note in notes:
                notify(str(path), note)
        rec = ClipRecord(name=name, motion=motion, verbs=options.verbs, objects=options.objects,
                         character=options.character, core=options.core, body_part=options.part,
                         cyclic=options.cyclic, source=str(path.resolve()),
                         start_posture=options.start_posture, end_posture=options.end_posture,
                         style=options.style)
        try:
            out.append((prepare_record(rec, where=str(path)), path))
        except ClipValidationError as exc:
            raise ClipValidationError(f"{exc} (nothing was imported)") from None
    if progress:
        progress(len(files), len(files), "")
    return out

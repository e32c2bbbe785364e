"""Importing BVH files as clips: the options, and reading and validating the files (nothing stored here).

>>> opts = ImportOptions(verbs=("走る",), character="cmu", drop_first=True)
>>> db.import_bvh(["02_03_run.bvh"], opts)   # reads with read_clips, stores all or nothing

Every file becomes one clip; :func:`read_clips` is the one path a file takes
from disk to a validated :class:`~motiondb.records.PreparedClip` (read, then
validate); a step applied to imported motion belongs there.
"""
from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from text2anim.core.bvh import BVHError, read_bvh

from .errors import ClipValidationError
from .records import PreparedClip, prepare_record
from .types import ClipRecord

#: ``progress(done, total, path)``: called before each file and once at the end (``path`` ``""``).
Progress = Callable[[int, int, str], None]


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
        drop_first: drop frame 0 (the T-pose of CMU/cgspeed files).
        replace: overwrite clips of the same names instead of refusing.
        start_posture, end_posture: every clip's postures (:data:`motiondb.types.POSTURES`);
            ``None`` classifies each file's first/last frame.
    """

    verbs: tuple[str, ...]
    objects: tuple[str, ...] = ()
    character: str = "default"
    core: tuple[float, float] | None = None
    part: str | None = None
    cyclic: bool = False
    names: tuple[str, ...] | None = None
    scale: float | str = "auto"
    up: str = "y"
    drop_first: bool = False
    replace: bool = False
    start_posture: str | None = None
    end_posture: str | None = None

    def __post_init__(self) -> None:
        # lists (from argparse, callers) become tuples, so the options stay immutable and hashable
        for name in ("verbs", "objects", "names"):
            value = getattr(self, name)
            if value is not None and not isinstance(value, tuple):
                object.__setattr__(self, name, (value,) if isinstance(value, str) else tuple(value))


def read_clips(paths: Sequence[str | os.PathLike], options: ImportOptions,
               progress: Progress | None = None) -> list[tuple[PreparedClip, Path]]:
    """Read and validate BVH files as clips: ``(prepared clip, its file)`` per path, in order.

    A file that cannot be read or validated raises :class:`ClipValidationError`
    naming it and saying nothing was imported (the caller stores nothing).
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
        rec = ClipRecord(name=name, motion=motion, verbs=options.verbs, objects=options.objects,
                         character=options.character, core=options.core, body_part=options.part,
                         cyclic=options.cyclic, source=str(path.resolve()),
                         start_posture=options.start_posture, end_posture=options.end_posture)
        try:
            out.append((prepare_record(rec, where=str(path)), path))
        except ClipValidationError as exc:
            raise ClipValidationError(f"{exc} (nothing was imported)") from None
    if progress:
        progress(len(files), len(files), "")
    return out

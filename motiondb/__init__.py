"""The motion database: clips of motion with verbs, objects, characters and foot contacts.

Public API (imported lazily, so ``import motiondb.types`` stays light)::

    MotionDB.open(url=None, *, seed=True) -> MotionDB
    db.search(verb, object=None, character=None, body_part=None, prefer_character=None, limit=None)
        -> list[ClipInfo]                         # ranked, no frame data read
    db.load(clip_or_name) -> synthesis.Motion
    db.record(name) -> ClipRecord
    db.add(records, *, replace=False) -> list[ClipInfo]           # all or nothing
    db.import_bvh(paths, ImportOptions(verbs, objects=..., character=..., ...), progress=None)
        -> list[ClipInfo]                                            # all or nothing
    db.remove(name_or_names); db.clips(character=None); db.info(name); db.verbs(); db.characters()

Errors are :class:`DBError` subclasses, all user facing.

Modules: ``store`` (the MotionDB facade), ``types`` (records in and out, postures),
``records`` (validating a record), ``postures`` (classifying a frame's posture),
``bvh_import`` (BVH files to clips), ``schema``/``migrate`` (tables, versions,
migrations), ``seed`` (the built-in library), ``reads``/``writes``/``search``
(queries), ``blobs`` (frames and skeletons as bytes/JSON), ``location``/``connect``
(URLs and drivers), ``readings`` (kana readings), ``errors``.
"""
from __future__ import annotations

from text2anim.core.lazy import lazy_attribute

from .types import ClipRecord

_LAZY = {
    "MotionDB": "store", "ClipInfo": "types", "VerbInfo": "types", "ImportOptions": "bvh_import",
    "classify_posture": "postures",
    "DBError": "errors", "UnknownVerbError": "errors", "UnknownClipError": "errors",
    "UnknownCharacterError": "errors", "ClipValidationError": "errors", "ClipExistsError": "errors",
    "SchemaVersionError": "errors",
    "resolve_url": "location", "default_path": "location",
}

__all__ = ["ClipRecord", *_LAZY]


def __getattr__(name: str):
    return lazy_attribute(__name__, _LAZY, name)

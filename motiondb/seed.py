"""Seeding: filling a new database with the built-in library (or given records), refreshing it when it changes."""
from __future__ import annotations

import hashlib
import os
import warnings
from collections.abc import Callable, Iterable
from contextlib import suppress
from dataclasses import dataclass
from pathlib import Path

from sqlalchemy import Connection, select

from .errors import ClipValidationError, DBError, SeedWarning
from .location import cache_home
from .reads import SkeletonCache
from .migrate import set_version
from . import schema as tb
from .types import ClipDescription, ClipRecord

#: ``source`` of the built-in library's clips (``builtin`` or ``builtin:<file>``).
BUILTIN_SOURCE = "builtin"


@dataclass(frozen=True)
class SeedSource:
    """What a new database is filled with: ``records()``, stored as ``tag``."""

    tag: str  # stored in schema_version.builtin_library
    records: Callable[[], Iterable[ClipRecord]]
    builtin: bool  # the built-in library (refreshed when its tag changes)
    #: the records' foot contacts by clip name where known (the built-in library ships them)
    contacts: Callable[[], dict[str, list[tuple[str, int, int]]]] | None = None
    #: the records' measured descriptions (no actions) by clip name where known (shipped likewise)
    descriptions: Callable[[], dict[str, ClipDescription]] | None = None


def seeding_needed(library: str | None, source: SeedSource | None) -> bool:
    """Whether a database whose ``builtin_library`` is ``library`` should be (re)seeded from ``source``.

    ``""`` means created without seeding (never seeded later); ``None`` means
    not seeded yet (the library was unavailable); another value is the tag of
    what was seeded: the built-in library is refreshed when its tag changes.
    """
    if source is None or library == "":
        return False
    if library is None:
        return True
    return source.builtin and library != source.tag


def _files(root: Path) -> list[Path]:
    """The code and data files under ``root`` (compiled ``.pyc`` files left out), sorted."""
    return sorted(p for p in root.rglob("*") if p.is_file() and p.suffix != ".pyc" and "__pycache__" not in p.parts)


def files_tag(root: Path, files: list[Path] | None = None) -> str:
    """A hash of the code and data files under ``root`` (:func:`_files`, or ``files``), by relative path."""
    h = hashlib.sha256()
    for path in _files(root) if files is None else files:
        h.update(path.relative_to(root).as_posix().encode("utf-8") + b"\0")
        h.update(path.read_bytes() + b"\0")
    return "sha256:" + h.hexdigest()[:32]


def library_tag(root: Path) -> str:
    """:func:`files_tag` of the built-in library's folder ``root``, kept in the user's cache folder
    (:func:`location.cache_home`, one small file per library folder) with the files' names, sizes and
    modification times it was taken for: opening a database reads the library's ~3.5 MB again only when
    one of its files changed (the hash was ~5 ms of every command). A cache that cannot be read or
    written is taken again or left as it was, never an error."""
    files = _files(root)
    stats = [(p.relative_to(root).as_posix(), p.stat()) for p in files]
    stamp = _digest(repr([(name, st.st_size, st.st_mtime_ns) for name, st in stats]))
    kept = cache_home() / "text2anim" / f"library-{_digest(str(root))[:16]}.tag"
    try:
        saved, tag = kept.read_text(encoding="utf-8").split()
        if saved == stamp:
            return tag
    except (OSError, ValueError):
        pass
    tag = files_tag(root, files)
    part = kept.with_name(f".{kept.name}.{os.getpid()}.part")
    try:
        kept.parent.mkdir(parents=True, exist_ok=True)
        part.write_text(f"{stamp} {tag}\n", encoding="utf-8")
        os.replace(part, kept)
    except OSError:
        with suppress(OSError):
            part.unlink(missing_ok=True)
    return tag


def _digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:32]


_LIBRARY = "text2anim.motiondb.library"


def _builtin_records() -> Iterable[ClipRecord]:
    import importlib

    return importlib.import_module(_LIBRARY).builtin_clips()


def _builtin_contacts() -> dict[str, list[tuple[str, int, int]]]:
    import importlib

    return importlib.import_module(_LIBRARY + ".keyframed").seeded_contacts()


def _builtin_descriptions() -> dict[str, ClipDescription]:
    import importlib

    return importlib.import_module(_LIBRARY + ".keyframed").seeded_descriptions()


def seed_source(seed) -> SeedSource | None:
    """What to seed a new database with; ``None`` for nothing (or the built-in library is absent).

    The built-in library is tagged by :func:`files_tag` of its folder (:func:`library_tag`), found without
    importing it: opening a database that is up to date never loads the library's
    generator (scipy.interpolate, IK) nor builds a clip.
    """
    if seed is False or seed is None:
        return None
    if callable(seed) and seed is not True:
        return SeedSource(getattr(seed, "__name__", "custom")[:64], seed, builtin=False)
    import importlib.util

    spec = importlib.util.find_spec(_LIBRARY)
    if spec is None or not spec.submodule_search_locations:
        return None  # the built-in library is not there (yet)
    return SeedSource(library_tag(Path(next(iter(spec.submodule_search_locations)))), _builtin_records, builtin=True,
                      contacts=_builtin_contacts, descriptions=_builtin_descriptions)


def fill(s: Connection, source: SeedSource, library: str | None, url: str, skeletons: SkeletonCache) -> None:
    """Store ``source``'s clips in database ``url`` (session ``s``, under the write lock).

    ``library`` is the tag seeded before (``None`` for none): the old built-in
    clips go first. Clips whose names are taken are kept as they are (a
    :class:`SeedWarning` lists them); the tag is recorded in ``schema_version``.
    """
    from .records import prepare_record
    from .writes import delete_clips, store_clips

    try:
        known = source.contacts() if source.contacts is not None else {}
        measured = source.descriptions() if source.descriptions is not None else {}
        prepared = [prepare_record(r, contacts=known.get(r.name), measured=measured.get(r.name))
                    for r in source.records()]
    except ClipValidationError as exc:
        what = "the built-in motion library" if source.builtin else "the seed records"
        raise DBError(f"cannot fill {url} with {what}: {exc}") from None
    if library is not None:  # a newer built-in library: replace the old built-in clips
        old = [n for n, src in s.execute(select(tb.clips.c.name, tb.clips.c.source))
               if src == BUILTIN_SOURCE or src.startswith(BUILTIN_SOURCE + ":")]
        delete_clips(s, old)
    before = {p.name for p in prepared}
    stored = store_clips(s, prepared, skeletons, conflicts="skip")
    if len(stored) < len(before):
        kept = set(s.scalars(select(tb.clips.c.name).where(tb.clips.c.id.in_(stored)))) if stored else set()
        skipped = sorted(before - kept)
        warnings.warn(SeedWarning(
            f"{len(skipped)} built-in clip(s) not stored because clips of those names or a character "
            f"'default' of another skeleton are already in {url}: {', '.join(skipped[:8])}"
            f"{'…' if len(skipped) > 8 else ''}"), stacklevel=4)
    set_version(s, builtin_library=source.tag)

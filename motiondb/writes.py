"""Writing clips: inserting prepared clips (skeletons, characters, verbs, objects shared) and deleting them.

Both run inside the caller's write transaction (see ``MotionDB._session``), so
a batch is all or nothing.
"""
from __future__ import annotations

import json

from sqlalchemy import Connection, CursorResult, delete, exists, insert, select

from text2anim.core.skeleton import Skeleton

from . import schema as tb
from .schema import utcnow
from .blobs import ENCODING
from .errors import ClipExistsError, ClipValidationError
from .ranks import fill as fill_ranks
from .reads import SkeletonCache, chunks
from .readings import reading
from .records import PreparedClip


def store_clips(s: Connection, prepared: list[PreparedClip], cache: SkeletonCache, *, conflicts: str,
                where: dict[str, str] | None = None) -> list[int]:
    """Insert prepared clips in session ``s``; their ids, in order (skipped clips left out).

    ``conflicts`` says what an existing name does: ``error`` raises
    :class:`ClipExistsError`, ``replace`` deletes the old clip, ``skip`` keeps it
    (and skips clips whose skeleton does not fit their character); ``cache``
    holds the skeletons already read; ``where``
    names the file of a clip in messages.
    """
    where = where or {}
    seen: set[str] = set()
    for p in prepared:
        if p.name in seen:
            raise ClipValidationError(f"two clips named {p.name!r} in one batch; nothing was stored")
        seen.add(p.name)
    existing: set[str] = set()
    for chunk in chunks([p.name for p in prepared]):
        existing.update(s.scalars(select(tb.clips.c.name).where(tb.clips.c.name.in_(chunk))))
    if existing:
        if conflicts == "error":
            shown = sorted(existing)
            listed = ", ".join(repr(n) for n in shown[:5]) + ("…" if len(shown) > 5 else "")
            many = len(shown) > 1
            raise ClipExistsError(
                f"{'clips' if many else 'clip'} {listed} {'are' if many else 'is'} already in the database "
                f"(remove {'them' if many else 'it'} first, or replace); nothing was stored")
        if conflicts == "replace":
            delete_clips(s, sorted(existing))
        else:
            prepared = [p for p in prepared if p.name not in existing]

    kept, clip_skeleton, clip_character = _place(s, prepared, cache, conflicts, where)
    if not kept:
        return []
    verb_ids = _names(s, tb.verbs, "lemma", [v for p in kept for v in p.verbs])
    object_ids = _names(s, tb.objects, "name", [o for p in kept for o in p.objects])
    created = utcnow()
    s.execute(insert(tb.clips), [
        dict(name=p.name, character_id=clip_character[p.name], skeleton_id=clip_skeleton[p.name], fps=p.fps,
             frames=p.frames, duration=p.duration, core_begin=p.core[0], core_end=p.core[1],
             body_part=p.body_part, cyclic=p.cyclic, source=p.source, created=created,
             start_posture=p.start_posture, end_posture=p.end_posture,
             description=json.dumps(p.description.to_dict(), sort_keys=True), style=p.style) for p in kept])
    ids: dict[str, int] = {}
    for chunk in chunks([p.name for p in kept]):
        ids.update((n, i) for i, n in s.execute(select(tb.clips.c.id, tb.clips.c.name)
                                                .where(tb.clips.c.name.in_(chunk))))
    s.execute(insert(tb.clip_frames), [dict(clip_id=ids[p.name], encoding=ENCODING, data=p.blob) for p in kept])
    s.execute(insert(tb.clip_verbs), [dict(clip_id=ids[p.name], verb_id=verb_ids[v], position=k, is_primary=k == 0)
                                      for p in kept for k, v in enumerate(p.verbs)])
    links = [dict(clip_id=ids[p.name], object_id=object_ids[o], position=k)
             for p in kept for k, o in enumerate(p.objects)]
    if links:
        s.execute(insert(tb.clip_objects), links)
    contacts = [dict(clip_id=ids[p.name], side=side, start_frame=a, stop_frame=b)
                for p in kept for side, a, b in p.contacts]
    if contacts:
        s.execute(insert(tb.contacts), contacts)
    stored = [ids[p.name] for p in kept]
    fill_ranks(s, stored)
    return stored


def _place(s: Connection, prepared: list[PreparedClip], cache: SkeletonCache, conflicts: str,
           where: dict[str, str]) -> tuple[list[PreparedClip], dict[str, int], dict[str, int]]:
    """The clips to store, with their skeleton and character ids (new skeletons and characters inserted).

    A clip whose joint hierarchy is not its character's (the skeleton of the character's first
    clip) raises :class:`ClipValidationError`, or is left out when ``conflicts`` is ``skip``.
    """
    sk, ch = tb.skeletons.c, tb.characters.c
    characters: dict[str, tuple[int, int] | None] = {}  # name -> (id, skeleton id)
    char_skel: dict[str, Skeleton] = {}
    skeletons: dict[str, int] = {}  # fingerprint -> id
    keep: list[PreparedClip] = []
    clip_skeleton: dict[str, int] = {}  # clip name -> skeleton id
    clip_character: dict[str, int] = {}  # clip name -> character id
    for p in prepared:
        if p.character not in characters:
            row = s.execute(select(ch.id, ch.skeleton_id).where(ch.name == p.character)).first()
            characters[p.character] = None if row is None else (row.id, row.skeleton_id)
        known = characters[p.character]
        if known is not None:
            if p.character not in char_skel:
                char_skel[p.character] = cache.get(s, known[1])
            ref = char_skel[p.character]
            if not ref.same_hierarchy(p.skeleton):
                if conflicts == "skip":
                    continue
                label = where.get(p.name, f"clip {p.name!r}")
                raise ClipValidationError(
                    f"{label}: its skeleton ({p.skeleton.n_joints} joints) has not the joint hierarchy of "
                    f"character {p.character!r} ({ref.n_joints} joints); import it under another character "
                    "(--character NAME); nothing was stored")
        # the skeleton, stored once per fingerprint
        sid = skeletons.get(p.fingerprint) or s.scalar(select(sk.id).where(sk.fingerprint == p.fingerprint))
        if sid is None:
            sid = _new_id(s.execute(insert(tb.skeletons).values(
                fingerprint=p.fingerprint, n_joints=p.skeleton.n_joints, definition=p.skeleton_def)))
        skeletons[p.fingerprint] = sid
        if known is None:
            cid = _new_id(s.execute(insert(tb.characters).values(name=p.character, skeleton_id=sid)))
            characters[p.character] = known = (cid, sid)
            char_skel[p.character] = p.skeleton
        keep.append(p)
        clip_skeleton[p.name], clip_character[p.name] = sid, known[0]
    return keep, clip_skeleton, clip_character


def _new_id(result: CursorResult) -> int:
    """The primary key of the row an INSERT added."""
    key = result.inserted_primary_key
    assert key is not None
    return int(key[0])


def _names(s: Connection, table, column: str, names: list[str]) -> dict[str, int]:
    """Ids of the verbs or objects ``names`` (rows of ``table`` keyed by ``column``), the missing ones
    inserted with their readings in order of first use."""
    key = table.c[column]
    wanted = list(dict.fromkeys(names))
    ids: dict[str, int] = {}
    for chunk in chunks(wanted):
        ids.update((n, i) for i, n in s.execute(select(table.c.id, key).where(key.in_(chunk))))
    missing = [n for n in wanted if n not in ids]
    if missing:
        s.execute(insert(table), [{column: n, "reading": reading(n)} for n in missing])
        for chunk in chunks(missing):
            ids.update((n, i) for i, n in s.execute(select(table.c.id, key).where(key.in_(chunk))))
    return ids


def delete_clips(s: Connection, names: list[str]) -> None:
    """Delete the named clips with their frames, links and contacts, and whatever no clip uses any more."""
    ids = list(s.scalars(select(tb.clips.c.id).where(tb.clips.c.name.in_(names))))
    for chunk in chunks(ids):
        for table in (tb.search_ranks, tb.clip_frames, tb.contacts, tb.clip_verbs, tb.clip_objects):
            s.execute(delete(table).where(table.c.clip_id.in_(chunk)))
        s.execute(delete(tb.clips).where(tb.clips.c.id.in_(chunk)))
    cl, ch, sk = tb.clips.c, tb.characters.c, tb.skeletons.c
    s.execute(delete(tb.verbs).where(~exists().where(tb.clip_verbs.c.verb_id == tb.verbs.c.id)))
    s.execute(delete(tb.objects).where(~exists().where(tb.clip_objects.c.object_id == tb.objects.c.id)))
    s.execute(delete(tb.characters).where(~exists().where(cl.character_id == ch.id)))
    s.execute(delete(tb.skeletons).where(~exists().where(cl.skeleton_id == sk.id),
                                         ~exists().where(ch.skeleton_id == sk.id)))

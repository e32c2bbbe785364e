"""Writing clips: inserting prepared clips (skeletons, characters, verbs, objects shared) and deleting them.

Both run inside the caller's write transaction (see ``MotionDB._session``), so
a batch is all or nothing.
"""
from __future__ import annotations

from sqlalchemy import delete, exists, select
from sqlalchemy.orm import Session

from text2anim.core.skeleton import Skeleton

from .blobs import ENCODING
from .errors import ClipExistsError, ClipValidationError
from .reads import SkeletonCache, chunks
from .readings import reading
from .records import PreparedClip
from .schema import (
    Character,
    Clip,
    ClipFrames,
    ClipObject,
    ClipVerb,
    Contact,
    ObjectRow,
    SkeletonRow,
    Verb,
    utcnow,
)


def store_clips(s: Session, prepared: list[PreparedClip], cache: SkeletonCache, *, conflicts: str,
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
        existing.update(s.scalars(select(Clip.name).where(Clip.name.in_(chunk))))
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

    characters: dict[str, Character] = {}
    char_skel: dict[str, Skeleton] = {}
    skeletons: dict[str, SkeletonRow] = {}
    verbs: dict[str, Verb] = {}
    objects: dict[str, ObjectRow] = {}
    keep = []
    for p in prepared:
        # the character's joint hierarchy (its skeleton: the first clip's) must match
        ch = characters.get(p.character) or s.scalar(select(Character).where(Character.name == p.character))
        if ch is not None:
            if p.character not in char_skel:
                char_skel[p.character] = cache.get(s, ch.skeleton_id)
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
        srow = skeletons.get(p.fingerprint) or s.scalar(
            select(SkeletonRow).where(SkeletonRow.fingerprint == p.fingerprint))
        if srow is None:
            srow = SkeletonRow(fingerprint=p.fingerprint, n_joints=p.skeleton.n_joints, definition=p.skeleton_def)
            s.add(srow)
            s.flush()
        skeletons[p.fingerprint] = srow
        if ch is None:
            ch = Character(name=p.character, skeleton_id=srow.id)
            s.add(ch)
            s.flush()
            char_skel[p.character] = p.skeleton
        characters[p.character] = ch
        clip = Clip(name=p.name, character_id=ch.id, skeleton_id=srow.id, fps=p.fps, frames=p.frames,
                    duration=p.duration, core_begin=p.core[0], core_end=p.core[1], body_part=p.body_part,
                    cyclic=p.cyclic, source=p.source, created=utcnow(), start_posture=p.start_posture,
                    end_posture=p.end_posture)
        for k, lemma in enumerate(p.verbs):
            v = verbs.get(lemma) or s.scalar(select(Verb).where(Verb.lemma == lemma))
            if v is None:
                v = Verb(lemma=lemma, reading=reading(lemma))
                s.add(v)
            verbs[lemma] = v
            clip.verb_links.append(ClipVerb(verb=v, position=k, is_primary=(k == 0)))
        for k, name in enumerate(p.objects):
            o = objects.get(name) or s.scalar(select(ObjectRow).where(ObjectRow.name == name))
            if o is None:
                o = ObjectRow(name=name, reading=reading(name))
                s.add(o)
            objects[name] = o
            clip.object_links.append(ClipObject(object=o, position=k))
        clip.contacts = [Contact(side=side, start_frame=a, stop_frame=b) for side, a, b in p.contacts]
        clip.frame_data = ClipFrames(encoding=ENCODING, data=p.blob)
        s.add(clip)
        keep.append(clip)
    s.flush()
    return [c.id for c in keep]


def delete_clips(s: Session, names: list[str]) -> None:
    """Delete the named clips with their frames, links and contacts, and whatever no clip uses any more."""
    ids = list(s.scalars(select(Clip.id).where(Clip.name.in_(names))))
    for chunk in chunks(ids):
        for table in (ClipFrames, Contact, ClipVerb, ClipObject):
            s.execute(delete(table).where(table.clip_id.in_(chunk)))
        s.execute(delete(Clip).where(Clip.id.in_(chunk)))
    s.execute(delete(Verb).where(~exists().where(ClipVerb.verb_id == Verb.id)))
    s.execute(delete(ObjectRow).where(~exists().where(ClipObject.object_id == ObjectRow.id)))
    s.execute(delete(Character).where(~exists().where(Clip.character_id == Character.id)))
    s.execute(delete(SkeletonRow).where(~exists().where(Clip.skeleton_id == SkeletonRow.id),
                                        ~exists().where(Character.skeleton_id == SkeletonRow.id)))
    s.expire_all()

"""Reading clip metadata (never frame data) and skeletons, in plain column queries."""
from __future__ import annotations

from collections.abc import Iterator
from datetime import timezone
from typing import Any, TypeVar

from sqlalchemy import BindParameter, bindparam, select
from sqlalchemy.orm import Session

from text2anim.core.skeleton import Skeleton

from .blobs import skeleton_from_json
from .errors import DBError
from .schema import Character, Clip, ClipObject, ClipVerb, Contact, ObjectRow, SkeletonRow, Verb
from .types import ClipInfo

#: Clip ids per ``IN (...)`` query.
CHUNK = 500

_T = TypeVar("_T")


def chunks(items: list[_T], n: int = CHUNK) -> Iterator[list[_T]]:
    """``items`` in lists of at most ``n`` (bounded ``IN (...)`` lists)."""
    for i in range(0, len(items), n):
        yield items[i:i + n]


class SkeletonCache:
    """Skeletons by ``skeletons.id``, each decoded once per open database (rows never change)."""

    def __init__(self) -> None:
        self._by_id: dict[int, Skeleton] = {}

    def get(self, s: Session, skeleton_id: int) -> Skeleton:
        """The skeleton of row ``skeleton_id``, read in session ``s`` the first time."""
        skel = self._by_id.get(skeleton_id)
        if skel is None:
            definition = s.scalar(select(SkeletonRow.definition).where(SkeletonRow.id == skeleton_id))
            if definition is None:
                raise DBError(f"skeleton {skeleton_id} is missing from the database")
            skel = skeleton_from_json(definition)
            self._by_id[skeleton_id] = skel
        return skel


_IDS: BindParameter[list[int]] = bindparam("ids", expanding=True)
_INFO_CLIPS = (
    select(Clip.id, Clip.name, Character.name.label("character"), Clip.fps, Clip.frames, Clip.duration,
           Clip.core_begin, Clip.core_end, Clip.body_part, Clip.cyclic, Clip.source, Clip.created,
           Clip.start_posture, Clip.end_posture, SkeletonRow.n_joints)
    .join(Character, Character.id == Clip.character_id)
    .join(SkeletonRow, SkeletonRow.id == Clip.skeleton_id)
    .where(Clip.id.in_(_IDS))
)
_INFO_VERBS = (select(ClipVerb.clip_id, Verb.lemma).join(Verb, Verb.id == ClipVerb.verb_id)
               .where(ClipVerb.clip_id.in_(_IDS)).order_by(ClipVerb.clip_id, ClipVerb.position))
_INFO_OBJECTS = (select(ClipObject.clip_id, ObjectRow.name).join(ObjectRow, ObjectRow.id == ClipObject.object_id)
                 .where(ClipObject.clip_id.in_(_IDS)).order_by(ClipObject.clip_id, ClipObject.position))
_INFO_CONTACTS = (select(Contact.clip_id, Contact.side, Contact.start_frame, Contact.stop_frame)
                  .where(Contact.clip_id.in_(_IDS)).order_by(Contact.clip_id, Contact.start_frame))


def clip_infos(s: Session, ids: list[int]) -> list[ClipInfo]:
    """ClipInfo for clip ids, in that order (metadata, verbs, objects, contacts; never frame data).

    Plain column queries (four per 500 clips), not ORM objects: this is the
    hot path of every search.
    """
    if not ids:
        return []
    rows: dict[int, Any] = {}
    verbs: dict[int, list[str]] = {}
    objects: dict[int, list[str]] = {}
    contacts: dict[int, dict[str, list[tuple[int, int]]]] = {}
    for chunk in chunks(ids):
        p = {"ids": chunk}
        for r in s.execute(_INFO_CLIPS, p):
            rows[r.id] = r
        for cid, lemma in s.execute(_INFO_VERBS, p):
            verbs.setdefault(cid, []).append(lemma)
        for cid, name in s.execute(_INFO_OBJECTS, p):
            objects.setdefault(cid, []).append(name)
        for cid, side, a, b in s.execute(_INFO_CONTACTS, p):
            contacts.setdefault(cid, {"left": [], "right": []})[side].append((a, b))
    out = []
    for i in ids:
        r = rows[i]
        created = r.created if r.created.tzinfo else r.created.replace(tzinfo=timezone.utc)
        sides = contacts.get(i, {"left": [], "right": []})
        out.append(ClipInfo(
            name=r.name, character=r.character, verbs=tuple(verbs.get(i, ())),
            objects=tuple(objects.get(i, ())), fps=r.fps, frames=r.frames, duration=r.duration,
            core=(r.core_begin, r.core_end), body_part=r.body_part, cyclic=bool(r.cyclic), source=r.source,
            created=created, joints=int(r.n_joints),
            left_contacts=tuple(sides["left"]), right_contacts=tuple(sides["right"]),
            start_posture=r.start_posture, end_posture=r.end_posture,
        ))
    return out

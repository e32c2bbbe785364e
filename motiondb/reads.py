"""Reading clip metadata (never frame data) and skeletons, in plain column queries."""
from __future__ import annotations

import json
from collections.abc import Iterator
from datetime import timezone
from functools import lru_cache
from typing import TYPE_CHECKING, Any, TypeVar

from sqlalchemy import BindParameter, Connection, bindparam, select

from .errors import DBError
from . import schema as tb
from .types import ClipDescription, ClipInfo

if TYPE_CHECKING:  # only named: metadata reads (`text2anim plan`) load no numpy
    from text2anim.core.skeleton import Skeleton

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

    def get(self, s: Connection, skeleton_id: int) -> Skeleton:
        """The skeleton of row ``skeleton_id``, read in session ``s`` the first time."""
        skel = self._by_id.get(skeleton_id)
        if skel is None:
            definition = s.scalar(select(tb.skeletons.c.definition).where(tb.skeletons.c.id == skeleton_id))
            if definition is None:
                raise DBError(f"skeleton {skeleton_id} is missing from the database")
            from .blobs import skeleton_from_json  # numpy: only when frames are read

            skel = skeleton_from_json(definition)
            self._by_id[skeleton_id] = skel
        return skel


_IDS: BindParameter[list[int]] = bindparam("ids", expanding=True)
_CL, _CH, _SK, _VB, _CV = tb.clips.c, tb.characters.c, tb.skeletons.c, tb.verbs.c, tb.clip_verbs.c
_OB, _CO, _CT = tb.objects.c, tb.clip_objects.c, tb.contacts.c
_INFO_CLIPS = (
    select(_CL.id, _CL.name, _CH.name.label("character"), _CL.fps, _CL.frames, _CL.duration,
           _CL.core_begin, _CL.core_end, _CL.body_part, _CL.cyclic, _CL.source, _CL.created,
           _CL.start_posture, _CL.end_posture, _CL.description, _CL.style, _SK.n_joints)
    .join(tb.characters, _CH.id == _CL.character_id)
    .join(tb.skeletons, _SK.id == _CL.skeleton_id)
    .where(_CL.id.in_(_IDS))
)
_INFO_VERBS = (select(_CV.clip_id, _VB.lemma).join(tb.verbs, _VB.id == _CV.verb_id)
               .where(_CV.clip_id.in_(_IDS)).order_by(_CV.clip_id, _CV.position))
_INFO_OBJECTS = (select(_CO.clip_id, _OB.name).join(tb.objects, _OB.id == _CO.object_id)
                 .where(_CO.clip_id.in_(_IDS)).order_by(_CO.clip_id, _CO.position))
_INFO_CONTACTS = (select(_CT.clip_id, _CT.side, _CT.start_frame, _CT.stop_frame)
                  .where(_CT.clip_id.in_(_IDS)).order_by(_CT.clip_id, _CT.start_frame))


@lru_cache(maxsize=4096)
def description(stored: str | None) -> ClipDescription:
    """A clip's stored ``description`` JSON as a :class:`ClipDescription` (cached: searches read it per hit)."""
    try:
        d = json.loads(stored or "{}")
    except ValueError:
        d = {}
    return ClipDescription.from_dict(d if isinstance(d, dict) else {})


def clip_infos(s: Connection, ids: list[int]) -> list[ClipInfo]:
    """ClipInfo for clip ids, in that order (metadata, verbs, objects, contacts; never frame data).

    Plain column queries, four per 500 clips.
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
            start_posture=r.start_posture, end_posture=r.end_posture, description=description(r.description),
            style=r.style,
        ))
    return out

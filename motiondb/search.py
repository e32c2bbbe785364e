"""Finding clips by verb: which clips match and in what order.

Matching. A clip matches a verb query ``v`` when one of its verbs (primary or
synonym) has the lemma ``v`` or the same katakana reading as ``v``
(:func:`motiondb.readings.reading`). So ``とぶ`` finds the clips declaring
``跳ぶ`` or ``飛ぶ``, and a clip declaring ``("ジャンプする", "跳ぶ", "飛ぶ")`` is
found by each of the three. Objects match the same way (name or reading).

Filters. ``character`` keeps that character's clips only. ``body_part`` keeps
clips declared for that part, for its mirror side (``left_arm`` ↔
``right_arm``, ``left_leg`` ↔ ``right_leg``; the caller mirrors such a clip:
``ClipInfo.body_part`` differs from the request) and whole-body clips; clips
declared for any other part are left out.

Ranking (each key breaks the ties of the one before):

1. character: clips of ``prefer_character`` (the previous clip's character) first;
2. body part (when asked): declared for the part < its mirror side < whole body;
3. start posture (when asked): clips whose ``start_posture`` is
   ``prefer_start_posture`` (the posture the previous clip ends in) first, the
   others after (in the order of the keys below);
4. object: when an object is asked, clips declaring it < clips declaring no
   object < clips declaring other objects; when none is asked, clips declaring
   no object come first;
5. verb: the query is the clip's primary verb < one of its synonyms < the
   primary verb only by reading (another spelling) < a synonym only by reading;
6. the clip's name (so the order is total and deterministic).

Hence "verb+object over verb over synonym": 蹴る + ボール puts a kick clip that
declares ボール before a plain kick, and a clip whose primary verb is 蹴る before
one that only lists 蹴る as a synonym. And 立ち上がる after a clip that ends
crouched (``prefer_start_posture="crouched"``) puts the clip that rises from a
crouch before the one that rises from a chair, whatever their verbs and
objects: a clip that cannot start where the character is would need another
clip in between (see :mod:`text2anim.postures`). The posture key changed
nothing for searches that do not ask for it. The ordering is done by the database
(``ORDER BY`` on these keys, ``LIMIT`` when asked), never by reading frames.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from functools import lru_cache

from sqlalchemy import Integer, and_, bindparam, case, exists, func, or_, select
from sqlalchemy.orm import Session

from .readings import normalize, reading
from .schema import Character, Clip, ClipObject, ClipVerb, ObjectRow, Verb

#: The mirror side of each sided body part.
MIRROR_PART = {"left_arm": "right_arm", "right_arm": "left_arm", "left_leg": "right_leg", "right_leg": "left_leg"}


@dataclass(frozen=True)
class VerbMatch:
    """Verb rows a query matched: ``exact`` by lemma, ``by_reading`` by reading only."""

    exact: tuple[int, ...]
    by_reading: tuple[int, ...]

    @property
    def all(self) -> tuple[int, ...]:
        return self.exact + self.by_reading


_MATCH_VERBS = (select(Verb.id, Verb.lemma)
                .where(or_(Verb.lemma == bindparam("lemma"), Verb.reading == bindparam("reading")))
                .order_by(Verb.id))
_MATCH_OBJECTS = (select(ObjectRow.id)
                  .where(or_(ObjectRow.name == bindparam("name"), ObjectRow.reading == bindparam("reading")))
                  .order_by(ObjectRow.id))
_CHARACTER_ID = select(Character.id).where(Character.name == bindparam("name"))


def match_verbs(session: Session, verb: str) -> VerbMatch:
    """The verbs whose lemma or reading equals ``verb``'s."""
    lemma = normalize(verb)
    rows = session.execute(_MATCH_VERBS, {"lemma": lemma, "reading": reading(lemma)}).all()
    exact = tuple(i for i, lem in rows if lem == lemma)
    return VerbMatch(exact, tuple(i for i, lem in rows if lem != lemma))


def match_objects(session: Session, obj: str) -> tuple[int, ...]:
    name = normalize(obj)
    return tuple(session.scalars(_MATCH_OBJECTS, {"name": name, "reading": reading(name)}))


@lru_cache(maxsize=256)
def _ranked_statement(has_exact: bool, objects: str, prefer: bool, body_part: str | None, character: bool,
                      limit: bool, collate_c: bool, posture: bool = False):
    """The ranking query for one combination of options (built once; values are bound parameters).

    ``objects``: ``"none"`` (no object asked), ``"asked"`` (clips declaring one
    of ``:objects``), ``"unknown"`` (an object no clip declares).
    """
    if has_exact:
        exact = ClipVerb.verb_id.in_(bindparam("exact", expanding=True))
        verb_tier = case((and_(exact, ClipVerb.is_primary), 0), (exact, 1), (ClipVerb.is_primary, 2), else_=3)
    else:
        verb_tier = case((ClipVerb.is_primary, 2), else_=3)
    per_clip = (
        select(ClipVerb.clip_id.label("clip_id"), func.min(verb_tier).label("verb_tier"))
        .where(ClipVerb.verb_id.in_(bindparam("verbs", expanding=True)))
        .group_by(ClipVerb.clip_id)
        .subquery()
    )
    any_object = exists().where(ClipObject.clip_id == Clip.id)
    if objects == "none":
        object_tier = case((any_object, 1), else_=0)
    elif objects == "asked":
        asked = exists().where(ClipObject.clip_id == Clip.id,
                               ClipObject.object_id.in_(bindparam("objects", expanding=True)))
        object_tier = case((asked, 0), (any_object, 2), else_=1)
    else:  # an object nobody declares: clips without objects first
        object_tier = case((any_object, 2), else_=1)
    order = []
    if prefer:
        order.append(case((Clip.character_id == bindparam("prefer"), 0), else_=1))
    stmt = select(Clip.id).join(per_clip, per_clip.c.clip_id == Clip.id)
    if body_part is not None:
        mirror = MIRROR_PART.get(body_part)
        parts = [body_part] + ([mirror] if mirror else [])
        stmt = stmt.where(or_(Clip.body_part.in_(parts), Clip.body_part.is_(None)))
        whens = [(Clip.body_part == body_part, 0)] + ([(Clip.body_part == mirror, 1)] if mirror else [])
        order.append(case(*whens, else_=2))
    if posture:
        order.append(case((Clip.start_posture == bindparam("posture"), 0), else_=1))
    if character:
        stmt = stmt.where(Clip.character_id == bindparam("character"))
    name = Clip.name.collate("C") if collate_c else Clip.name
    # (a constant is never an ORDER BY term: PostgreSQL would read it as a column position)
    stmt = stmt.order_by(*order, object_tier, per_clip.c.verb_tier, name)
    if limit:
        stmt = stmt.limit(bindparam("limit", type_=Integer))
    return stmt


def ranked_clip_ids(session: Session, verbs: VerbMatch, *, object_ids: tuple[int, ...] | None = None,
                    character_id: int | None = None, body_part: str | None = None,
                    prefer_character_id: int | None = None, prefer_start_posture: str | None = None,
                    limit: int | None = None) -> list[int]:
    """Ids of the matching clips, best first (see the module docstring)."""
    objects = "none" if object_ids is None else ("asked" if object_ids else "unknown")
    stmt = _ranked_statement(bool(verbs.exact), objects, prefer_character_id is not None, body_part,
                             character_id is not None, limit is not None,
                             session.get_bind().dialect.name == "postgresql", prefer_start_posture is not None)
    params: dict[str, Any] = {"verbs": list(verbs.all)}
    if verbs.exact:
        params["exact"] = list(verbs.exact)
    if object_ids:  # objects == "asked"
        params["objects"] = list(object_ids)
    if prefer_character_id is not None:
        params["prefer"] = prefer_character_id
    if character_id is not None:
        params["character"] = character_id
    if prefer_start_posture is not None:
        params["posture"] = prefer_start_posture
    if limit is not None:
        params["limit"] = int(limit)
    return list(session.scalars(stmt, params))


def binary_order(session: Session, column):
    """``column`` for ORDER BY in code-point order on every backend (PostgreSQL sorts by locale otherwise)."""
    return column.collate("C") if session.get_bind().dialect.name == "postgresql" else column


def character_id(session: Session, name: str) -> int | None:
    return session.scalar(_CHARACTER_ID, {"name": name})

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
4. spelling: clips declaring the query itself (as primary verb or synonym) before clips
   matched only by its reading (a homophone: 取る finds 撮る's clip by トル, 指す finds 刺す's
   by サス; another word, whatever objects either declares);
5. object: when an object is asked, clips declaring it < clips declaring no
   object < clips declaring other objects; when none is asked, clips declaring
   no object come first;
6. verb: the query is the clip's primary verb < one of its synonyms < the
   primary verb only by reading (another spelling) < a synonym only by reading;
7. the clip's name (so the order is total and deterministic).

Hence "verb+object over verb over synonym": 蹴る + ボール puts a kick clip that
declares ボール before a plain kick, and a clip whose primary verb is 蹴る before
one that only lists 蹴る as a synonym. And 立ち上がる after a clip that ends
crouched (``prefer_start_posture="crouched"``) puts the clip that rises from a
crouch before the one that rises from a chair, whatever their verbs and
objects: a clip that cannot start where the character is would need another
clip in between (see :mod:`scheduler.postures`). The posture key changed
nothing for searches that do not ask for it. The ordering is done by the database
(``ORDER BY`` on these keys, ``LIMIT`` when asked), never by reading frames, and a
search is one SQL statement (:func:`find`): the names are matched, the hits ranked and
their verbs, objects and contacts gathered in the same query.
"""
from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from datetime import datetime, timezone
from functools import lru_cache
from operator import itemgetter
from typing import Any

from sqlalchemy import (BindParameter, Connection, Integer, String, and_, bindparam, case, func, or_, select,
                        type_coerce)

from .errors import UnknownVerbError
from .readings import nearest, normalize, reading
from .ranks import candidates
from . import schema as tb
from .reads import description
from .types import ClipInfo

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


_MATCH_VERBS = (select(tb.verbs.c.id, tb.verbs.c.lemma)
                .where(or_(tb.verbs.c.lemma == bindparam("lemma"), tb.verbs.c.reading == bindparam("reading")))
                .order_by(tb.verbs.c.id))
_CHARACTER_ID = select(tb.characters.c.id).where(tb.characters.c.name == bindparam("name"))


def match_verbs(session: Connection, verb: str) -> VerbMatch:
    """The verbs whose lemma or reading equals ``verb``'s."""
    lemma = normalize(verb)
    rows = session.execute(_MATCH_VERBS, {"lemma": lemma, "reading": reading(lemma)}).all()
    exact = tuple(i for i, lem in rows if lem == lemma)
    return VerbMatch(exact, tuple(i for i, lem in rows if lem != lemma))


def binary_order(session: Connection, column):
    """``column`` for ORDER BY in code-point order on every backend (PostgreSQL sorts by locale otherwise)."""
    return column.collate("C") if session.dialect.name == "postgresql" else column


def character_id(session: Connection, name: str) -> int | None:
    return session.scalar(_CHARACTER_ID, {"name": name})


# ------------------------------------------------------------- one query per search
def _aggregate(postgres: bool, *columns):
    """A JSON array of ``[columns...]`` rows (``json_agg`` on PostgreSQL, ``json_group_array`` elsewhere)."""
    if postgres:
        return func.json_agg(func.json_build_array(*columns))
    return func.json_group_array(func.json_array(*columns))


_CL, _CH, _SK, _VB, _CV = tb.clips, tb.characters, tb.skeletons, tb.verbs, tb.clip_verbs
_OB, _CO, _CT = tb.objects, tb.clip_objects, tb.contacts


@lru_cache(maxsize=256)
def _search_statement(body_part: str | None, character: bool, limit: bool, postgres: bool,
                      asked: tuple[bool, bool, bool] = (False, False, False)):
    """Matching, ranking and every :class:`ClipInfo` field of the hits in one SELECT (see the module docstring).

    The verb, object and character names are bound parameters matched inside the
    query (no id look-ups first); the ranked ids (``LIMIT`` applied) are an inner
    query, and the verbs, objects and contacts of those hits only are aggregated
    as JSON arrays by the outer one. The object, preferred character and start posture
    are always bound (``NULL`` when not asked: their tiers are then the same for every
    clip), so a process compiles few variants. With a ``limit``, only the clips
    :func:`motiondb.ranks.candidates` picks are ranked (``asked``: whether the object,
    the preferred character and the start posture were asked), so the work does not grow
    with the number of clips of the verb.
    """
    lemma: BindParameter[str] = bindparam("lemma")
    exact = _VB.c.lemma == lemma
    verb_tier = case((and_(exact, _CV.c.is_primary), 0), (exact, 1), (_CV.c.is_primary, 2), else_=3)
    per_clip: Any = (
        select(_CV.c.clip_id.label("clip_id"), func.min(verb_tier).label("verb_tier"),
               func.min(case((exact, 0), else_=1)).label("spelling_tier"))
        .join(_VB, _VB.c.id == _CV.c.verb_id)
        .where(or_(exact, _VB.c.reading == bindparam("reading")))
        .group_by(_CV.c.clip_id)
    )
    if limit:
        obj, prefer, posture = asked
        per_clip = per_clip.where(_CV.c.clip_id.in_(candidates(
            body_part=body_part, mirror=MIRROR_PART.get(body_part) if body_part else None, character=character,
            prefer=prefer, posture=posture, obj=obj)))
    per_clip = per_clip.subquery()
    # clips declaring the object (0) < clips declaring none (1) < clips declaring others (2)
    matched = or_(_OB.c.name == bindparam("object"), _OB.c.reading == bindparam("object_reading"))
    object_tier = func.coalesce(
        select(func.min(case((matched, 0), else_=2))).select_from(_CO)
        .join(_OB, _OB.c.id == _CO.c.object_id)
        .where(_CO.c.clip_id == _CL.c.id).scalar_subquery(), 1)
    keys = [per_clip.c.spelling_tier.label("spelling_tier"), object_tier.label("object_tier"),
            per_clip.c.verb_tier.label("verb_tier")]
    stmt = (select(_CL.c.id.label("id"), _CL.c.name.label("name")).join(per_clip, per_clip.c.clip_id == _CL.c.id)
            .join(_CH, _CH.c.id == _CL.c.character_id))
    keys.insert(0, case((_CH.c.name == bindparam("prefer"), 0), else_=1).label("character_tier"))
    if body_part is not None:
        mirror = MIRROR_PART.get(body_part)
        parts = [body_part] + ([mirror] if mirror else [])
        stmt = stmt.where(or_(_CL.c.body_part.in_(parts), _CL.c.body_part.is_(None)))
        whens = [(_CL.c.body_part == body_part, 0)] + ([(_CL.c.body_part == mirror, 1)] if mirror else [])
        keys.insert(len(keys) - 3, case(*whens, else_=2).label("part_tier"))
    keys.insert(len(keys) - 3, case((_CL.c.start_posture == bindparam("posture"), 0), else_=1).label("posture_tier"))
    if character:
        stmt = stmt.where(_CH.c.name == bindparam("character"))
    tiers = stmt.add_columns(*keys).subquery()  # each key computed once per matching clip
    order = [tiers.c[k.name] for k in keys] + [tiers.c.name.collate("C") if postgres else tiers.c.name]
    ranked = select(tiers.c.id, func.row_number().over(order_by=order).label("rank")).order_by(*order)
    if limit:
        ranked = ranked.limit(bindparam("limit", type_=Integer))
    hits = ranked.subquery()
    verbs = (select(_aggregate(postgres, _CV.c.position, _VB.c.lemma)).join(_VB, _VB.c.id == _CV.c.verb_id)
             .where(_CV.c.clip_id == _CL.c.id).scalar_subquery())
    objs = (select(_aggregate(postgres, _CO.c.position, _OB.c.name))
            .join(_OB, _OB.c.id == _CO.c.object_id)
            .where(_CO.c.clip_id == _CL.c.id).scalar_subquery())
    contacts = (select(_aggregate(postgres, _CT.c.side, _CT.c.start_frame, _CT.c.stop_frame))
                .where(_CT.c.clip_id == _CL.c.id).scalar_subquery())
    # the three lists in one JSON value: one decoding per hit (json() keeps SQLite's arrays nested)
    lists = (func.json_build_array(verbs, objs, contacts) if postgres
             else func.json_array(func.json(verbs), func.json(objs), func.json(contacts)))
    # SQLite keeps times as ISO text and flags as 0/1: read as they are (no per-row type processing),
    # turned into ClipInfo's datetime and bool once per hit by _info
    created = _CL.c.created if postgres else type_coerce(_CL.c.created, String)
    cyclic = _CL.c.cyclic if postgres else type_coerce(_CL.c.cyclic, Integer)
    return (select(_CL.c.name, _CH.c.name.label("character"), _CL.c.fps, _CL.c.frames, _CL.c.duration,
                   _CL.c.core_begin, _CL.c.core_end, _CL.c.body_part, cyclic.label("cyclic"), _CL.c.source,
                   created.label("created"), _CL.c.start_posture, _CL.c.end_posture, _CL.c.description, _CL.c.style,
                   _SK.c.n_joints,
                   lists.label("lists"))
            .select_from(hits)
            .join(_CL, _CL.c.id == hits.c.id)
            .join(_CH, _CH.c.id == _CL.c.character_id)
            .join(_SK, _SK.c.id == _CL.c.skeleton_id)
            .order_by(hits.c.rank))


def _lists(value) -> list[list]:
    """The ``[verbs, objects, contacts]`` JSON of a hit as lists (PostgreSQL's driver decodes it, SQLite gives
    text; an aggregate of no rows is NULL on PostgreSQL)."""
    lists = json.loads(value) if isinstance(value, str) else value
    return [x or [] for x in lists]


_BY_POSITION = itemgetter(0)
_CONTACT_ORDER = itemgetter(1, 2, 0)  # start, stop, side


def _info(r) -> ClipInfo:
    """A result row of :func:`_search_statement` as a :class:`ClipInfo`."""
    (name, character, fps, frames, duration, core_begin, core_end, body_part, cyclic, source, created,
     start_posture, end_posture, desc, style, n_joints, lists) = r  # unpacked: a Row's attributes cost ~1 us each
    verbs, objects, contacts = _lists(lists)
    verbs.sort(key=_BY_POSITION)
    objects.sort(key=_BY_POSITION)
    contacts.sort(key=_CONTACT_ORDER)
    if isinstance(created, str):  # SQLite: SQLAlchemy's storage format, "YYYY-MM-DD HH:MM:SS.ffffff"
        created = datetime.fromisoformat(created)
    return ClipInfo(
        name=name, character=character, verbs=tuple([v for _, v in verbs]),
        objects=tuple([o for _, o in objects]), fps=fps, frames=frames, duration=duration,
        core=(core_begin, core_end), body_part=body_part, cyclic=bool(cyclic), source=source,
        created=created if created.tzinfo else created.replace(tzinfo=timezone.utc), joints=int(n_joints),
        left_contacts=tuple([(int(a), int(b)) for side, a, b in contacts if side == "left"]),
        right_contacts=tuple([(int(a), int(b)) for side, a, b in contacts if side != "left"]),
        start_posture=start_posture, end_posture=end_posture, description=description(desc), style=style,
    )


def find(session: Connection, verb: str, *, object: str | None = None, character: str | None = None,
         body_part: str | None = None, prefer_character: str | None = None,
         prefer_start_posture: str | None = None, limit: int | None = None) -> list[ClipInfo]:
    """The matching clips' :class:`ClipInfo`, best first, in one SQL statement (names as the user wrote them)."""
    lemma = normalize(verb)
    obj = normalize(object) if object is not None else ""
    stmt = _search_statement(body_part, character is not None, limit is not None,
                             session.dialect.name == "postgresql",
                             (bool(obj), bool(prefer_character), prefer_start_posture is not None))
    params: dict[str, Any] = {"lemma": lemma, "reading": reading(lemma), "object": obj or None,
                              "object_reading": reading(obj) if obj else None,
                              "prefer": normalize(prefer_character) if prefer_character else None,
                              "posture": prefer_start_posture}
    if character is not None:
        params["character"] = normalize(character)
    if limit is not None:
        params["limit"] = int(limit)
    return [_info(r) for r in session.execute(stmt, params)]


def prefer(hits: Sequence[ClipInfo], *, body_part: str | None = None, character: str | None = None,
           start_posture: str | None = None) -> list[ClipInfo]:
    """``hits`` as :func:`find` ranks them for ``character`` and ``start_posture``, from hits it found
    for the same verb, object, character filter and ``body_part`` without those two preferences.

    Without the preferences their tiers (1 and 3 in the module docstring) are equal for every clip,
    so ``hits`` are in the order of the other keys; a stable sort on (character, body part, posture)
    puts them first, as the query's ``ORDER BY`` does.
    """
    if character is None and start_posture is None:
        return list(hits)
    preferred = normalize(character) if character else None
    mirror = MIRROR_PART.get(body_part) if body_part else None

    def tiers(c: ClipInfo) -> tuple[int, int, int]:
        part = 0 if body_part is None or c.body_part == body_part else 1 if mirror and c.body_part == mirror else 2
        return (c.character != preferred, part, c.start_posture != start_posture)
    return sorted(hits, key=tiers)


def unknown_verb_error(s: Connection, verb: str) -> UnknownVerbError:
    """The error for a verb no clip has, naming the nearest known verbs by reading."""
    verbs = tb.verbs.c
    rows = s.execute(select(verbs.lemma, verbs.reading)
                     .order_by(binary_order(s, verbs.reading), binary_order(s, verbs.lemma))).all()
    cands = {lemma: r for lemma, r in rows}
    return UnknownVerbError(verb, lambda: [(lemma, cands[lemma]) for lemma in nearest(verb, cands, n=5)],
                            n_verbs=len(cands))


def near_clip_names(s: Connection, name: str) -> list[str]:
    """Up to five clip names close to ``name`` (for an unknown clip's message)."""
    import difflib

    names = list(s.scalars(select(tb.clips.c.name).order_by(binary_order(s, tb.clips.c.name))))
    return difflib.get_close_matches(normalize(name), names, n=5, cutoff=0.5)


def character_names(s: Connection) -> list[str]:
    """Every character's name, sorted."""
    names = tb.characters.c.name
    return list(s.scalars(select(names).order_by(binary_order(s, names))))

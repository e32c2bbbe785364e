"""The ranking table ``search_ranks``: filling it, and the few clips a limited search needs to rank.

A search ranks a verb's clips by tiers (:mod:`motiondb.search`): some depend on the query
(the preferred character, the start posture, the body part, the object asked), the others do
not (the spelling, whether the clip declares objects, primary verb or synonym, the name).
Within one verb's rows, the latter are the order ``(has_objects, secondary, name)`` that the
indexes of :data:`schema.search_ranks` keep. A query tier is a yes/no question (a body part:
which of its two or three answers). Rows that say yes to every question of a set ``S`` and come
before a clip ``r`` in the stored order come before it in the ranking too, whenever ``r`` says
yes to ``S`` (they tie or win on every query tier and then follow the stored order). So a clip
among the best ``k`` is among the first ``k`` of the segment "yes to its own answers" in stored
order, and the best ``k`` lie within the union, over every combination of answers, of each
segment's first ``k`` rows: at most ``k x 2^q`` rows (``q`` <= 3 questions, x 3 for a body part)
read in index order, whatever the number of clips. Clips matched by reading only (another
spelling of the verb) are few and are all taken.

Rows are written by :func:`fill` whenever clips are stored (:func:`motiondb.writes.store_clips`,
and for every clip when a database of schema version 2 is migrated) and deleted with their clip.
"""
from __future__ import annotations

from collections.abc import Sequence
from itertools import product

from sqlalchemy import (ColumnElement, CompoundSelect, Connection, Integer, Select, and_, bindparam, case,
                        exists, insert, literal, select, union_all)

from . import schema as tb
from .reads import chunks

#: One answer to a ranking question: the condition its rows meet (``None``: any row).
Answer = ColumnElement[bool] | None

_R, _CV, _CL, _CO = tb.search_ranks.c, tb.clip_verbs.c, tb.clips.c, tb.clip_objects.c
_COLUMNS = ["verb_id", "clip_id", "object_id", "secondary", "has_objects", "character_id", "start_posture",
            "body_part", "name"]


def _rows(object_id) -> Select:
    """``search_ranks`` rows of every ``clip_verbs`` row, with ``object_id`` (0 or the declared object's)."""
    declared = tb.clip_objects.alias("declared")
    has_objects = case((exists().where(declared.c.clip_id == _CL.id), 1), else_=0)
    return select(_CV.verb_id, _CV.clip_id, object_id, case((_CV.is_primary, 0), else_=1), has_objects,
                  _CL.character_id, _CL.start_posture, _CL.body_part, _CL.name).join(tb.clips, _CL.id == _CV.clip_id)


def fill(s: Connection, clip_ids: Sequence[int] | None = None) -> None:
    """Write the ranking rows of clips ``clip_ids`` (every clip when ``None``) from their stored rows."""
    own = _rows(literal(0, Integer))
    declared = _rows(_CO.object_id).join(tb.clip_objects, _CO.clip_id == _CV.clip_id)
    if clip_ids is None:
        s.execute(insert(tb.search_ranks).from_select(_COLUMNS, own))
        s.execute(insert(tb.search_ranks).from_select(_COLUMNS, declared))
        return
    for chunk in chunks(list(clip_ids)):
        s.execute(insert(tb.search_ranks).from_select(_COLUMNS, own.where(_CV.clip_id.in_(chunk))))
        s.execute(insert(tb.search_ranks).from_select(_COLUMNS, declared.where(_CV.clip_id.in_(chunk))))


def candidates(*, body_part: str | None, mirror: str | None, character: bool, prefer: bool, posture: bool,
               obj: bool) -> CompoundSelect:
    """The ids of the clips that can be among a search's best ``:limit`` (see the module docstring).

    Bound parameters as :func:`motiondb.search.find` binds them (``lemma``, ``reading``,
    ``object``, ``object_reading``, ``character``, ``prefer``, ``posture``, ``limit``); the flags say
    which of them the query asks, so a segment exists only for a question asked.
    """
    vb, ch, ob = tb.verbs.c, tb.characters.c, tb.objects.c
    exact = select(vb.id).where(vb.lemma == bindparam("lemma")).scalar_subquery()
    base: list[ColumnElement[bool]] = []
    if character:
        base.append(_R.character_id == select(ch.id).where(ch.name == bindparam("character")).scalar_subquery())
    parts: list[Answer] = []  # a body part's tier: exact < mirror side < whole body
    if body_part is not None:
        allowed = [body_part] + ([mirror] if mirror else [])
        base.append((_R.body_part.in_(allowed)) | _R.body_part.is_(None))
        parts += [_R.body_part == p for p in allowed] + [_R.body_part.is_(None)]
    own = _R.object_id == 0
    objects: list[Answer] = [own]
    if obj:
        matched = select(ob.id).where((ob.name == bindparam("object")) | (ob.reading == bindparam("object_reading")))
        objects.append(_R.object_id.in_(matched))
    questions: list[list[Answer]] = [objects, parts or [None]]
    if prefer:
        questions.append([None, _R.character_id == select(ch.id).where(ch.name == bindparam("prefer"))
                          .scalar_subquery()])
    if posture:
        questions.append([None, _R.start_posture == bindparam("posture")])
    order = [_R.has_objects, _R.secondary, _R.name]
    segments = []
    for answers in product(*questions):
        where = [_R.verb_id == exact, *base, *(a for a in answers if a is not None)]
        seg = select(_R.clip_id).where(and_(*where)).order_by(*order).limit(bindparam("limit", type_=Integer))
        segments.append(select(seg.subquery().c.clip_id))
    others = select(vb.id).where(vb.reading == bindparam("reading"), vb.lemma != bindparam("lemma"))
    segments.append(select(_R.clip_id).where(_R.verb_id.in_(others), own, *base))
    return union_all(*segments)

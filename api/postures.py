"""Posture continuity: clips chosen so that each starts where the previous one ended.

Every clip declares the posture of its first and last frame
(:data:`motiondb.types.POSTURES`: ``standing``, ``seated``, ``crouched``,
``kneeling``, ``lying``). Along one actor's sequence of whole-body motions a
clip should start in the posture the previous clip ends in: しゃがんで、立ち上がる
rises from the crouch (``crouch_down`` + ``stand_from_crouch``), not from a
chair that is not there; 転んで、起き上がる gets up from the floor (``fall`` +
``get_up``).

- :func:`choose` picks one clip per motion from the ranked candidates
  (``db.search`` order) with the fewest posture mismatches along the
  sequence, a dynamic programme over the sequence; ties keep the database's
  ranking, earlier motions first.
- :func:`bridges` gives the clips to insert where no candidate can match
  (座って、歩く: ``stand_up`` between ``sit_down`` and ``walk``), found in the
  database by the verbs of :data:`BRIDGE_VERBS`.
- :func:`matching` finds a clip that keeps a posture (a seated idle for a
  wait after 座る), for fillers.
- :func:`arrange` applies both to a planned time table: it returns the
  analysis with the bridging motions added (each linked to its neighbours)
  and the clip of every motion, for a second planning pass
  (:meth:`Arrangement.finder` wraps the pipeline's clip finder).

Nothing here reads frame data: postures are clip metadata
(:class:`motiondb.ClipInfo` ``start_posture``/``end_posture``).
"""
from __future__ import annotations

import itertools
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any, overload

from text2anim.motiondb import ClipInfo, UnknownVerbError
from text2anim.motiondb.types import POSTURES, Posture

from .clip_timing import timing

#: Verbs whose clips take the actor *into* each posture, tried in this order to build bridges.
#: Only clips that change posture (start elsewhere, end there), whole-body and not looping, are used.
BRIDGE_VERBS: dict[Posture, tuple[str, ...]] = {
    "standing": ("立ち上がる", "起き上がる", "立つ"),
    "seated": ("座る", "腰掛ける"),
    "crouched": ("しゃがみ込む", "しゃがむ"),
    "kneeling": ("ひざまずく", "膝をつく"),
    "lying": ("横になる", "寝転ぶ", "寝る"),
}
#: At most this many clips are inserted between two motions (seated -> crouched takes two:
#: stand up, crouch down).
MAX_BRIDGE = 2


# ------------------------------------------------------------------- choose
def _mismatch(prev_end: str | None, start: str) -> int:
    return 0 if prev_end is None or prev_end == start else 1


@overload
def choose(candidates_by_motion: Mapping[Any, Sequence[ClipInfo]], *,
           initial: str | None = None) -> dict[Any, ClipInfo | None]: ...


@overload
def choose(candidates_by_motion: Sequence[Sequence[ClipInfo]], *,
           initial: str | None = None) -> list[ClipInfo | None]: ...


def choose(candidates_by_motion: Sequence[Sequence[ClipInfo]] | Mapping[Any, Sequence[ClipInfo]], *,
           initial: str | None = None) -> list[ClipInfo | None] | dict[Any, ClipInfo | None]:
    """One clip per motion of a sequence, so that postures meet where the candidates allow it.

    Args:
        candidates_by_motion: for each motion of one actor's sequence, in
            playing order, its candidate clips best first (``db.search``'s
            ranking); a list of lists, or a mapping (motion id -> list) in
            playing order.
        initial: the posture the actor is in before the first motion;
            ``None`` (default) lets the first clip start in any posture.

    Returns:
        The chosen clip per motion, in the same shape (a list, or a dict with
        the same keys); ``None`` for a motion without candidates, which the
        posture chain passes through (the next clip is matched to the one before).

    The choice minimises, in this order: the number of joins where a clip
    starts in another posture than the previous clip ends in (and than
    ``initial`` for the first), then the candidates' ranks, the first motion's
    rank first (so with no mismatch to avoid, every motion gets its best
    candidate). A dynamic programme over the sequence: O(n k²) for n motions
    of k candidates.
    """
    keys = list(candidates_by_motion) if isinstance(candidates_by_motion, Mapping) else None
    lists = [list(candidates_by_motion[k]) for k in keys] if keys is not None else \
        [list(c) for c in candidates_by_motion]
    if initial is not None and initial not in POSTURES:
        raise ValueError(f"unknown posture {initial!r}; known: {', '.join(POSTURES)}")
    present = [i for i, c in enumerate(lists) if c]
    picks: list[ClipInfo | None] = [None] * len(lists)
    if present:
        # best[k] = (mismatches, ranks so far) of the best path ending in candidate k of the current
        # motion; tuples compare as the docstring says (fewer mismatches, then earlier ranks)
        first = lists[present[0]]
        best: list[tuple[int, tuple[int, ...]]] = [(_mismatch(initial, c.start_posture), (k,))
                                                   for k, c in enumerate(first)]
        prev = first
        for i in present[1:]:
            cur = lists[i]
            best = [min((m + _mismatch(prev[j].end_posture, c.start_posture), ranks + (k,))
                        for j, (m, ranks) in enumerate(best))
                    for k, c in enumerate(cur)]
            prev = cur
        _, path = min(best)
        for i, k in zip(present, path):
            picks[i] = lists[i][k]
    if keys is not None:
        return dict(zip(keys, picks))
    return picks


def mismatches(clips: Sequence[ClipInfo | None], *, initial: str | None = None) -> list[int]:
    """Indices ``i`` where ``clips[i]`` starts in another posture than the clip before it ends in
    (``None`` entries are passed through; ``initial`` is the posture before the first)."""
    out = []
    before = initial
    for i, c in enumerate(clips):
        if c is None:
            continue
        if before is not None and c.start_posture != before:
            out.append(i)
        before = c.end_posture
    return out


# ------------------------------------------------------------------ bridges
def _changers(db, character: str | None) -> list[ClipInfo]:
    """Every posture-changing clip found by :data:`BRIDGE_VERBS`, in preference order."""
    out: list[ClipInfo] = []
    seen: set[str] = set()
    for target, verbs in BRIDGE_VERBS.items():
        for verb in verbs:
            try:
                hits = db.search(verb, prefer_character=character)
            except UnknownVerbError:
                continue
            for c in hits:
                if (c.name not in seen and c.body_part is None and not c.cyclic
                        and c.end_posture == target and c.start_posture != target):
                    seen.add(c.name)
                    out.append(c)
    return out


def bridges(prev_end_posture: Posture, next_start_posture: Posture, db, *, character: str | None = None,
            max_clips: int = MAX_BRIDGE) -> list[ClipInfo]:
    """The clips to play between a clip ending in ``prev_end_posture`` and one starting in ``next_start_posture``.

    The clips come from ``db`` (a :class:`motiondb.MotionDB`): those found by
    the verbs of :data:`BRIDGE_VERBS` that change posture (whole-body, not
    looping, ``start_posture != end_posture``), ``character``'s first. The
    shortest chain (at most ``max_clips``) from one posture to the other wins;
    among equally short ones, the verbs' order in :data:`BRIDGE_VERBS` and then
    the database's ranking. With the built-in library: seated -> standing
    ``[stand_up]``, crouched -> standing ``[stand_from_crouch]``, lying ->
    standing ``[get_up]``, standing -> seated ``[sit_down]``, standing ->
    crouched ``[crouch_down]``, seated -> crouched ``[stand_up, crouch_down]``.

    Returns ``[]`` when the postures are the same, and when the database has
    no chain between them (standing -> lying: no clip lies down on purpose);
    the caller then joins the clips as before.
    """
    for p in (prev_end_posture, next_start_posture):
        if p not in POSTURES:
            raise ValueError(f"unknown posture {p!r}; known: {', '.join(POSTURES)}")
    if prev_end_posture == next_start_posture:
        return []
    edges = _changers(db, character)
    for n in range(1, max_clips + 1):
        # chains of n clips, in the order of the edges (itertools.product is lexicographic)
        for path in itertools.product(edges, repeat=n):
            if path[0].start_posture != prev_end_posture or path[-1].end_posture != next_start_posture:
                continue
            if all(a.end_posture == b.start_posture for a, b in zip(path, path[1:])):
                return list(path)
    return []


def matching(db, verb: str, posture: Posture, *, character: str | None = None) -> ClipInfo | None:
    """The best clip of ``verb`` that starts and ends in ``posture``, or ``None`` (also for an unknown verb).

    For fillers that must not change the posture: the idle clip (待つ) after a
    clip that ends seated is a seated idle if the database has one, else
    nothing (the actor holds its last pose).
    """
    if posture not in POSTURES:
        raise ValueError(f"unknown posture {posture!r}; known: {', '.join(POSTURES)}")
    try:
        hits = db.search(verb, prefer_character=character, prefer_start_posture=posture)
    except UnknownVerbError:
        return None
    return next((c for c in hits if c.start_posture == posture and c.end_posture == posture), None)


# ------------------------------------------------------------------ arrange
@dataclass(frozen=True)
class Arrangement:
    """What :func:`arrange` decided.

    Attributes:
        analysis: the analysis with the bridging motions added (new ids,
            linked into the constraints between their neighbours).
        clips: motion id -> chosen clip, for every whole-body motion of the
            sequences and every bridge.
        bridges: ids of the added motions, in order.
        changed: anything differs from the first planning pass (another clip
            somewhere, or a bridge); when not, the first table stands.
    """

    analysis: Any
    clips: dict[int, ClipInfo] = field(default_factory=dict)
    bridges: tuple[int, ...] = ()
    changed: bool = False

    def finder(self, fallback: Callable) -> Callable:
        """A clip finder for :func:`scheduler.plan` returning :attr:`clips`, else asking ``fallback``.

        ``fallback`` is the pipeline's finder (``text2anim.pipeline.ClipFinder``):
        the chosen clips are recorded in its ``chosen`` dict as its own are.
        """
        clips = self.clips

        def find(spec, prefer):
            info = clips.get(spec.id)
            if info is None:
                return fallback(spec, prefer)
            chosen = getattr(fallback, "chosen", None)
            if chosen is not None:
                chosen[spec.id] = info
            return timing(info)

        return find


def _sequences(table) -> dict[Any, list]:
    """Per actor, the whole-body elements (everything but compositions) in playing order."""
    out: dict[Any, list] = {}
    for e in sorted(table.elements, key=lambda e: (e.start, e.id)):
        if e.method != "composition":
            out.setdefault(e.actor, []).append(e)
    return out


def arrange(analysis, table, chosen: Mapping[int, ClipInfo], search: Callable, db) -> Arrangement:
    """Choose clips with matching postures along each actor's sequence and add bridges where none match.

    Args:
        analysis: the :class:`nlp.types.Analysis` that was planned.
        table: its first time table (:func:`scheduler.plan` with the pipeline's finder).
        chosen: motion id -> the clip the first pass took (``ClipFinder.chosen``).
        search: ``search(spec, prefer_character) -> [ClipInfo, ...]`` ranked
            candidates of a motion (``ClipFinder.search``).
        db: the :class:`motiondb.MotionDB`, for :func:`bridges`.

    Each actor's sequence is its table elements other than compositions, in
    playing order. A motion's candidates are those of its search that are
    whole-body or partial and looping or not as its first-pass clip (so the
    time table keeps its shape). Where the chosen clips still do not meet,
    the :func:`bridges` clips become new motions between the two (verb: the
    clip's primary verb; an empty span where the second motion starts in the
    text). The constraint that led to the second now leads to the first
    bridge (its delay stays before the bridge: the actor waits in the posture
    it is in, then changes it; from another actor's motion, the change starts
    where the second motion would have), and the bridges and the second motion
    follow each other; a second motion linked to nothing follows the bridges
    hung on the first. So a second :func:`scheduler.plan` with
    :meth:`Arrangement.finder` times them like any motion.
    """
    from text2anim.nlp.types import Constraint, MotionSpec

    specs = {m.id: m for m in analysis.motions}
    picked: dict[int, ClipInfo] = {}
    for actor, seq in _sequences(table).items():
        cands = {}
        prefer = None
        for e in seq:
            first = chosen.get(e.id)
            spec = specs.get(e.id)
            if first is None or spec is None:
                continue
            try:
                hits = search(spec, prefer)
            except UnknownVerbError:
                hits = []
            same = [c for c in hits if (c.body_part is None) == (first.body_part is None) and c.cyclic == first.cyclic
                    and c.name != first.name]
            cands[e.id] = [first] + same  # the first pass's pick (a variant, text2anim.variants) ranks first
            prefer = first.character
        picked.update({k: v for k, v in choose(cands).items() if v is not None})

    changed = any(picked[k].name != chosen[k].name for k in picked)
    motions = list(analysis.motions)
    constraints = list(analysis.constraints)
    next_id = max((m.id for m in motions), default=0) + 1
    added: list[int] = []
    for actor, seq in _sequences(table).items():
        ids = [e.id for e in seq if e.id in picked]
        for a, b in zip(ids, ids[1:]):
            ca, cb = picked[a], picked[b]
            if ca.end_posture == cb.start_posture:
                continue
            incoming = next((k for k, c in enumerate(constraints) if c.second == b), None)
            link = constraints[incoming] if incoming is not None else None
            if link is not None and link.method == "composition":
                continue  # b is laid onto a (a base chosen by the clips): no room for a bridge
            plan = bridges(ca.end_posture, cb.start_posture, db, character=ca.character)
            if not plan:
                continue
            spec_b = specs[b]
            new_ids = list(range(next_id, next_id + len(plan)))
            next_id += len(plan)
            for nid, clip in zip(new_ids, plan):
                picked[nid] = clip
                motions.insert(next(i for i, m in enumerate(motions) if m.id == b),
                               MotionSpec(nid, spec_b.actor, clip.verb, span=(spec_b.span[0], spec_b.span[0])))
            chain = [a] + new_ids + [b]
            if incoming is not None and link is not None:
                # the link that led to b leads to the first bridge (a delay is spent in the old posture;
                # a link from another actor's motion starts the change of posture where b would have
                # started); the bridges and b follow each other, b as the link said when it came from a
                same = link.first == a
                new = [replace(link, second=chain[1])]
                new += [Constraint(x, y, link.relation, link.overlap, None, link.method, link.cue) if same
                        else Constraint(x, y, "serial", False, None, "connection", "posture")
                        for x, y in zip(chain[1:-1], chain[2:])]
                constraints[incoming:incoming + 1] = new
            else:
                # b follows a by sentence order alone: the bridges hang on a, b comes after them
                constraints += [Constraint(x, y, "serial", False, None, "connection", "posture")
                                for x, y in zip(chain[:-2], chain[1:-1])]
            added += new_ids
            changed = True
    new_analysis = replace(analysis, motions=tuple(motions), constraints=tuple(constraints)) if added else analysis
    return Arrangement(new_analysis, picked, tuple(added), changed)


__all__ = ["Arrangement", "BRIDGE_VERBS", "MAX_BRIDGE", "arrange", "bridges", "choose", "matching", "mismatches"]

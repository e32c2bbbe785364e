"""Posture continuity applied to a planned time table: other clips, and bridging motions added.

:func:`arrange` reads the first time table, chooses clips whose postures meet
along each actor's sequence (:func:`postures.choose`) and, where none can, adds
the :func:`postures.bridges` clips as motions of their own to the analysis (and
:func:`facing.turn_away`'s turn where an actor leaves the person it faced),
linked between their neighbours, for a second planning pass
(:meth:`Arrangement.finder` gives that pass the clips chosen here).
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Generic

from text2anim.nlp.lexicon import RISING_VERBS, SEATS
from text2anim.nlp.types import Analysis, Constraint, MotionSpec

from .clips import C, ClipSource
from .fillers import IDLE_VERB
from .picker import Picker
from .plan import ClipFinder
from .facing import came_to, turn_away
from .postures import bridges, choose, matching
from .seated import seated_motions
from .types import ClipTiming, Element, TimeTable


@dataclass(frozen=True)
class Arrangement(Generic[C]):
    """What :func:`arrange` decided.

    Attributes:
        analysis: the analysis with the bridging motions added (new ids,
            linked into the constraints between their neighbours).
        clips: motion id -> chosen clip, for every whole-body motion of the
            sequences and every bridge.
        bridges: ids of the added motions that change posture, in order.
        changed: anything differs from the first planning pass (another clip
            somewhere, a bridge, a seated idle); when not, the first table stands.
        seated: ids of the added seated or kneeling idles a standing clip is composed onto
            (:mod:`seated`), in order.
    """

    analysis: Analysis
    clips: dict[int, C] = field(default_factory=dict)
    bridges: tuple[int, ...] = ()
    changed: bool = False
    seated: tuple[int, ...] = ()

    def finder(self, picker: Picker[C]) -> ClipFinder:
        """A clip finder for :func:`plan.plan` returning :attr:`clips`, else asking ``picker``;
        the clips of :attr:`clips` are recorded in ``picker.chosen`` as its own are."""
        clips = self.clips

        def find(spec: MotionSpec, prefer: str | None) -> ClipTiming:
            info = clips.get(spec.id)
            return picker(spec, prefer) if info is None else picker.take(spec, info)

        return find


def _sequences(table: TimeTable) -> dict[str | None, list[Element]]:
    """Per actor, the whole-body elements (everything but compositions) in playing order."""
    out: dict[str | None, list[Element]] = {}
    for e in sorted(table.elements, key=lambda e: (e.start, e.id)):
        if e.method != "composition":
            out.setdefault(e.actor, []).append(e)
    return out


def _from_a_seat(opening: MotionSpec) -> bool:
    """Does an actor's first motion rise from a seat: one named (椅子から立った: ``lexicon.SEATS``), or none, by a
    verb of rising (生徒たちは立ってお辞儀をした: ``lexicon.RISING_VERBS``; 起き上がる rises from lying)?"""
    return ((opening.target_role == "source" and opening.target in SEATS)
            or (opening.verb in RISING_VERBS and opening.target is None))


def _choose(analysis: Analysis, table: TimeTable, chosen: Mapping[int, C], source: ClipSource[C]) -> dict[int, C]:
    """Motion id -> a clip per whole-body motion, the postures meeting where the candidates allow.

    A motion's candidates are those of its search that are whole-body or partial
    and looping or not as its first-pass clip (so the time table keeps its shape),
    the first pass's pick (a variant, :mod:`variants`) first. An actor whose first motion rises from a seat
    (:func:`_from_a_seat`) starts seated: it rises from the chair, not from a crouch.
    """
    specs = {m.id: m for m in analysis.motions}
    picked: dict[int, C] = {}
    for seq in _sequences(table).values():
        cands = {}
        prefer = None
        for e in seq:
            first = chosen.get(e.id)
            spec = specs.get(e.id)
            if first is None or spec is None:
                continue
            same = [c for c in source.candidates(spec, prefer)
                    if (c.body_part is None) == (first.body_part is None) and c.cyclic == first.cyclic
                    and c.name != first.name]
            cands[e.id] = [first] + same
            prefer = first.character
        opening = specs.get(seq[0].id) if seq else None
        initial = "seated" if opening is not None and _from_a_seat(opening) else None
        picked.update({k: v for k, v in choose(cands, initial=initial).items() if v is not None})
    return picked


def _relink(constraints: list[Constraint], incoming: int | None, chain: list[int], cue: str = "posture") -> None:
    """Link the motions of ``chain`` (a, the bridges, b) in ``constraints``, in place.

    The link that led to b leads to the first bridge (a delay is spent in the old
    posture; a link from another actor's motion starts the change of posture where b
    would have started); the bridges and b follow each other, b as the link said when
    it came from a. Without a link (b follows a by sentence order alone) the bridges
    hang on a and b comes after them. ``cue``: the new links' (``posture``, or ``facing`` for a turn away).
    """
    bridge = lambda x, y: Constraint(x, y, "serial", False, None, "connection", cue)  # noqa: E731
    if incoming is None:
        constraints += [bridge(x, y) for x, y in zip(chain[:-2], chain[1:-1])]
        return
    link = constraints[incoming]
    same = link.first == chain[0]
    new = [replace(link, second=chain[1])]
    new += [Constraint(x, y, link.relation, link.overlap, None, link.method, link.cue) if same else bridge(x, y)
            for x, y in zip(chain[1:-1], chain[2:])]
    constraints[incoming:incoming + 1] = new


def _seat(motions: list[MotionSpec], constraints: list[Constraint], b: int, nid: int) -> None:
    """Play motion ``b`` seated (or kneeling), in place: that posture's idle ``nid`` takes its place in the
    sequence (the link that led to b leads to it; b's opening delay is its) and b is composed onto it."""
    k = next(i for i, m in enumerate(motions) if m.id == b)
    spec_b = motions[k]
    motions[k] = replace(spec_b, delay=None)
    motions.insert(k, MotionSpec(nid, spec_b.actor, IDLE_VERB, span=(spec_b.span[0], spec_b.span[0]),
                                 delay=spec_b.delay))
    incoming = next((i for i, c in enumerate(constraints) if c.second == b), None)
    if incoming is not None:
        constraints[incoming] = replace(constraints[incoming], second=nid)
    constraints.append(Constraint(nid, b, "parallel", None, None, "composition", "posture"))


def arrange(analysis: Analysis, table: TimeTable, chosen: Mapping[int, C], source: ClipSource[C]) -> Arrangement[C]:
    """Choose clips with matching postures along each actor's sequence, keep the seat, add bridges where none match.

    Args:
        analysis: the :class:`nlp.types.Analysis` that was planned.
        table: its first time table (:func:`plan.plan` with a :class:`picker.Picker`).
        chosen: motion id -> the clip the first pass took (``Picker.chosen``).
        source: the database, for each motion's ranked candidates and for :func:`postures.bridges`.

    Each actor's sequence is its table elements other than compositions, in
    playing order. The motions :func:`seated.seated_motions` says are played
    seated or kneeling are composed onto that posture's idle, which takes their place
    (verb :data:`fillers.IDLE_VERB`; none in the database: they are left standing).
    Where the chosen clips still do not meet, the bridges become
    new motions between the two (verb: the clip's primary verb; an empty span
    where the second motion starts in the text), linked as :func:`_relink` says.
    So a second :func:`plan.plan` with :meth:`Arrangement.finder` times them like
    any motion.
    """
    specs = {m.id: m for m in analysis.motions}
    picked = _choose(analysis, table, chosen, source)
    changed = any(picked[k].name != chosen[k].name for k in picked)
    motions = list(analysis.motions)
    constraints = list(analysis.constraints)
    composing = frozenset(i for c in constraints if c.method == "composition" for i in (c.first, c.second))
    next_id = max((m.id for m in motions), default=0) + 1
    added: list[int] = []
    idles: list[int] = []
    for seq in _sequences(table).values():
        ids = [e.id for e in seq if e.id in picked]
        kept = dict(seated_motions(ids, picked, composing).composed)  # id -> the posture it plays in
        for b in [i for i in ids if i in kept]:
            idle = matching(source, IDLE_VERB, kept[b], character=picked[b].character)
            if idle is None:
                del kept[b]
                continue
            picked[next_id] = idle
            _seat(motions, constraints, b, next_id)
            idles.append(next_id)
            next_id += 1
        for a, b in zip(ids, ids[1:]):
            ca, cb = picked[a], picked[b]
            end = kept.get(a, ca.end_posture)
            same = end == kept.get(b, cb.start_posture)
            turn = turn_away(specs.get(a), specs[b], cb, source, character=ca.character,
                             met=came_to(analysis.motions, specs[b])) if same else []
            if same and not turn:
                continue
            incoming = next((k for k, c in enumerate(constraints) if c.second == b), None)
            if incoming is not None and constraints[incoming].method == "composition":
                continue  # b is laid onto a (a base chosen by the clips): no room for a bridge
            plan = turn or bridges(end, cb.start_posture, source, character=ca.character)
            if not plan:
                continue
            spec_b = specs[b]
            new_ids = list(range(next_id, next_id + len(plan)))
            next_id += len(plan)
            for nid, clip in zip(new_ids, plan):
                picked[nid] = clip
                motions.insert(next(i for i, m in enumerate(motions) if m.id == b),
                               MotionSpec(nid, spec_b.actor, clip.verb, span=(spec_b.span[0], spec_b.span[0])))
            _relink(constraints, incoming, [a] + new_ids + [b], "facing" if turn else "posture")
            added += new_ids
    changed = changed or bool(added or idles)
    new_analysis = replace(analysis, motions=tuple(motions), constraints=tuple(constraints)) \
        if added or idles else analysis
    return Arrangement(new_analysis, picked, tuple(added), changed, tuple(idles))


__all__ = ["Arrangement", "arrange"]

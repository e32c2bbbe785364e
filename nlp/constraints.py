"""Temporal constraints between motions (docs/language.md §3).

1. Each motion with a head gives a constraint from its clause ending
   (``endings.ENDINGS``): first = the motion, second = its head; for 前に the
   order is reversed (the head is performed first).
2. The constraints must form a tree: every motion but the first of a track is
   the ``second`` of exactly one constraint.  A head can collect two links
   (走って、右手を振りながら歩く: 走る -> 歩く and 振る -> 歩く); a parallel link
   is symmetric in time, so it is turned round (歩く -> 振る, composition).
3. Consecutive clause groups (sentences) are joined by a connection from the
   motion that ends the earlier one to the root of the next one.
4. Time cues (そして, 同時に, しばらくして, N秒後に, すぐに) then rewrite the
   link into the motion they modify; a delay before the motion that opens a
   track (3秒後に歩く) becomes that motion's own start delay.  When that motion is the head of a
   ながら / たまま clause, the link into the whole group is rewritten.
"""
from __future__ import annotations

from dataclasses import dataclass

from .bunsetsu import Phrase
from .endings import ENDINGS
from .lexicon import TOGETHER_WORDS
from .motions import TimeCue
from .types import Constraint


@dataclass(slots=True)
class _Edge:
    first: int  # phrase indices
    second: int
    relation: str
    overlap: bool | None
    delay: float | None
    method: str
    cue: str
    reversed: bool = False
    flipped: bool = False


def build_constraints(phrases: list[Phrase], cues: list[TimeCue]) -> list[Constraint]:
    """The constraints among the motions of ``phrases`` (ids already given)."""
    groups = _motion_groups(phrases)
    edges: list[_Edge] = []
    for group in groups:
        group_edges = [_dependency_edge(ph) for ph in group if ph.predicate.head is not None]
        _make_tree(group_edges, group)
        edges.extend(group_edges)
    for prev, cur in zip(groups, groups[1:]):
        edges.append(_joins_in(phrases, prev, cur) or _sentence_edge(prev, cur, edges))
    for cue in cues:
        _apply_cue(cue, edges, phrases)
    ids = {ph.index: ph.predicate.id for group in groups for ph in group}
    out = [
        Constraint(ids[e.first], ids[e.second], e.relation, e.overlap,
                   e.delay, e.method, e.cue)
        for e in edges
    ]
    return _tree_order(out)


def _tree_order(constraints: list[Constraint]) -> list[Constraint]:
    """Depth-first from the first motion of the tree, children by id: the
    order in which a reader (and the scheduler) meets the links."""
    children: dict[int, list[Constraint]] = {}
    for c in sorted(constraints, key=lambda c: (c.first, c.second)):
        children.setdefault(c.first, []).append(c)
    seconds = {c.second for c in constraints}
    roots = sorted({c.first for c in constraints} - seconds)
    out: list[Constraint] = []
    todo = [c for r in reversed(roots) for c in reversed(children.get(r, []))]
    while todo:
        c = todo.pop()
        out.append(c)
        todo.extend(reversed(children.get(c.second, [])))
    return out


def _motion_groups(phrases: list[Phrase]) -> list[list[Phrase]]:
    groups: list[list[Phrase]] = []
    last_group = None
    for ph in phrases:
        if not (ph.pred and ph.pred.motion):
            continue
        if ph.group != last_group:
            groups.append([])
            last_group = ph.group
        groups[-1].append(ph)
    return groups


def _dependency_edge(ph: Phrase) -> _Edge:
    e = ENDINGS[ph.predicate.ending]
    head = ph.predicate.head
    assert head is not None  # only phrases with a head have an edge
    a, b = ph.index, head
    if e.reversed:
        a, b = b, a
    return _Edge(a, b, e.relation, e.overlap, None, e.method, ph.predicate.cue or ph.predicate.ending,
                 reversed=e.reversed)


def _make_tree(edges: list[_Edge], group: list[Phrase]) -> None:
    """Leave exactly one incoming edge per motion but one (module docstring).

    At a clash the 前に edge is kept (座る前に手を振る: 振る -> 座る) and a serial
    link from the 前に clause's own dependent moves to the motion performed
    first (走って、座る前に手を振る: 走る -> 振る -> 座る); a parallel edge is
    turned round; anything else is dropped and the orphan re-attached.
    """
    while True:
        incoming: dict[int, list[_Edge]] = {}
        for e in edges:
            incoming.setdefault(e.second, []).append(e)
        clash = next((ins for ins in incoming.values() if len(ins) > 1), None)
        if clash is None:
            break
        keep = min(clash, key=lambda e: (not e.reversed, e.relation == "parallel",
                                         not e.flipped, e.first))
        for e in clash:
            if e is not keep:
                _resolve(e, keep, edges, incoming)
    _attach_orphans(edges, group)


def _resolve(e: _Edge, keep: _Edge, edges: list[_Edge], incoming: dict) -> None:
    if e.relation == "parallel" and not e.flipped and not _ancestor(edges, e.second, e.first, e):
        e.first, e.second, e.flipped = e.second, e.first, True
    elif (keep.reversed and e.relation == "serial" and keep.first not in incoming
          and not _ancestor(edges, e.first, keep.first, e)):
        e.second = keep.first
    else:
        edges.remove(e)


def _attach_orphans(edges: list[_Edge], group: list[Phrase]) -> None:
    """Safety net: join any second root to the nearest earlier motion outside
    its subtree, so the group stays one tree."""
    order = [ph.index for ph in group]
    roots = [n for n in order if n not in {e.second for e in edges}]
    for root in roots[1:]:
        below = _subtree(edges, root)
        before = [n for n in reversed(order[:order.index(root)]) if n not in below]
        after = [n for n in order if n not in below]
        parent = (before or after)[0]
        edges.append(_Edge(parent, root, "serial", False, None, "connection", "order"))


def _subtree(edges: list[_Edge], node: int) -> set[int]:
    seen, todo = set(), [node]
    while todo:
        n = todo.pop()
        if n not in seen:
            seen.add(n)
            todo.extend(e.second for e in edges if e.first == n)
    return seen


def _ancestor(edges: list[_Edge], node: int, candidate: int, skip: _Edge) -> bool:
    """Is ``candidate`` reachable from ``node`` going up incoming edges?"""
    seen, todo = set(), [node]
    while todo:
        n = todo.pop()
        if n == candidate:
            return True
        if n in seen:
            continue
        seen.add(n)
        todo.extend(e.first for e in edges if e.second == n and e is not skip)
    return False


def _sentence_edge(prev: list[Phrase], cur: list[Phrase], edges: list[_Edge]) -> _Edge:
    """。: from the motion that ends ``prev`` to the root of ``cur``."""
    src = prev[-1].index
    seen = set()
    while src not in seen:  # 座る前に手を振る。: 座る is performed last
        seen.add(src)
        nxt = next((e.second for e in edges if e.first == src and e.reversed), None)
        if nxt is None:
            break
        src = nxt
    has_incoming = {e.second for e in edges}
    root = next((ph.index for ph in cur if ph.index not in has_incoming), cur[0].index)
    cue = prev[-1].predicate.cue or "。"
    return _Edge(src, root, "serial", False, None, "connection", cue)


def _joins_in(phrases: list[Phrase], prev: list[Phrase], cur: list[Phrase]) -> _Edge | None:
    """花子は踊り始めた。太郎も一緒に踊った: someone else doing the same motion 一緒に, right after it was
    told, does it with them (a parallel link from that motion), not after it has ended."""
    first, last = cur[0], prev[-1]
    together = [ph for ph in phrases if ph.key in TOGETHER_WORDS and ph.head == first.index]
    if not together or first.predicate.verb != last.predicate.verb or first.predicate.actor == last.predicate.actor:
        return None
    return _Edge(last.index, first.index, "parallel", None, None, "composition", f"。+{together[0].key}")


def _apply_cue(cue: TimeCue, edges: list[_Edge], phrases: list[Phrase]) -> None:
    target = cue.target
    for _ in range(len(edges) + 1):
        edge = next((e for e in edges if e.second == target), None)
        if edge is None:
            # the motion that opens its track (3秒後に太郎が歩く): no link to adjust,
            # the delay holds back its start
            if cue.delay:
                phrases[target].predicate.delay = cue.delay
            return
        dependent_of_target = phrases[edge.first].predicate.head == target
        if edge.relation == "parallel" and dependent_of_target and edge.first != target:
            target = edge.first  # 手を振りながら歩く: adjust the link into the group
            continue
        edge.relation, edge.overlap, edge.method = cue.relation, cue.overlap, cue.method
        edge.delay = cue.delay
        edge.cue = f"{edge.cue}+{cue.cue}"
        return

"""Relations between actors from the rows' targets: who should stand where relative to whom, and when.

Each row whose target is another actor of the scene gives one :class:`~scene.types.Relation`: its kind
from the target's role and side (docs/language.md §8), its distance from the verb (a natural distance for
that act between two people of the built-in body's size, hips to hips, scaled to the actor's size), its
time from the row's played times:

=========================== ========== ================================= ==========================
role (side)                 kind       distance                          time
=========================== ========== ================================= ==========================
goal (front, none)          ``face``   the next act's for the same       when the body has come to
                                                                          rest after the row's end
                                       person, else :data:`APPROACH`
goal (behind)               ``behind`` :data:`BEHIND`                     the row's end
goal (beside, near, ...)    ``beside`` :data:`BESIDE`                     the row's end
source                      ``away``   :data:`APPROACH`                   the row's start
addressee, patient,         ``face``   :data:`DISTANCES` by verb, else   the row's middle (its
recipient                              :data:`BY_ROLE`                    middle half for facing)
partner                     ``face`` for :data:`FACE_TO_FACE` verbs and  the row's middle
                            the side ``front`` (向かい合って), else
                            ``beside`` (:data:`BESIDE`, together)
=========================== ========== ================================= ==========================
"""
from __future__ import annotations

from collections.abc import Sequence

from text2anim.scheduler.types import Element

from .types import Relation

#: m, hips to hips: where an approach ends when nothing closer follows ("about 1 m to talk or hand over").
APPROACH = 1.0
BEHIND = 0.8
BESIDE = 0.8
#: m, hips to hips, by verb (lemma): the distance a person keeps for that act (a hug closes in, a wave is
#: from afar).
DISTANCES = {
    "握手する": 0.75, "ハイタッチする": 0.8, "抱き合う": 0.4, "抱き締める": 0.4, "抱く": 0.4, "抱き付く": 0.4,
    "抱きつく": 0.4, "渡す": 0.95, "手渡す": 0.95, "差し出す": 0.95, "受け取る": 0.95, "貰う": 0.95,
    "話す": 1.1, "話し掛ける": 1.2, "会話する": 1.1, "話し合う": 1.1, "お辞儀する": 1.6, "挨拶する": 1.6,
    "会釈する": 1.6, "謝る": 1.4, "うなずく": 1.4, "頷く": 1.4, "振る": 3.0, "指さす": 2.5, "指差す": 2.5,
    "投げる": 4.0, "放る": 4.0, "蹴る": 4.0, "押す": 0.6, "叩く": 0.6, "殴る": 0.7, "触る": 0.6, "撫でる": 0.6,
    "見る": 2.0, "見つめる": 1.5, "踊る": 1.2, "喧嘩する": 0.8, "戦う": 1.2, "繋ぐ": 0.5, "捕まえる": 0.6,
}
BY_ROLE = {"addressee": 1.6, "patient": 0.6, "recipient": 1.2, "partner": 1.0}
#: Partners who face each other for these; any other verb done with a partner is done side by side.
FACE_TO_FACE = frozenset(
    """握手する ハイタッチする 抱き合う 話す 会話する 話し合う お辞儀する 挨拶する 喧嘩する 戦う キスする 見つめ合う
    乾杯する 向かい合う 組み合う 渡す 受け取る 振り合う 手を振り合う 話する おしゃべりする 顔を見合わせる 見合わせる""".split()
)
#: Verbs of taking someone by the hand: when that person then goes along beside the actor (手を引いて走った), the
#: hand is taken at their side, not face to face.
LEADING_HAND = frozenset("繋ぐ つなぐ 手を繋ぐ".split())
#: The hand (or hands) each verb of two people's hands meeting makes its contact with: the scene puts the
#: two so those hands meet at the instant of contact.
HANDS = {"握手する": "right_hand", "ハイタッチする": "right_hand", "渡す": "right_hand", "手渡す": "right_hand",
         "差し出す": "right_hand", "受け取る": "both_hands", "貰う": "both_hands"}
#: The built-in body's standing hips height (m): distances are for a person of that size.
HIPS_HEIGHT = 0.93


def relations(rows: Sequence[Element], present: set[str | None], scale: dict[str | None, float],
              sends: dict[int, tuple[float, float]] | None = None,
              reaches: dict[int, float] | None = None, arrivals: dict[int, float] | None = None) -> list[Relation]:
    """The relations of ``rows`` (played times) between actors in ``present``, in time order;
    ``scale`` is each actor's size against the built-in body (its hips height over :data:`HIPS_HEIGHT`);
    ``sends`` the instant (s) a row sends a thing off (a throw's release, a kick's strike) and where the
    chest faces then: the recipient stands that way, whatever the hips do in the wind-up; ``reaches`` the
    instant (s) a row's hand reaches out to another's (:data:`HANDS`): the two are placed then, hand to hand;
    ``arrivals`` when an approach's body has come to rest (s; its row's end by default)."""
    sends, reaches, arrivals = sends or {}, reaches or {}, arrivals or {}
    out: list[Relation] = []
    for i, r in enumerate(rows):
        if r.target is None or r.target == r.actor or r.target not in present or (
                r.method == "composition" and _is_base_of(rows, r)) or _answers(rows[:i], r):
            continue
        kind, dist, time = _shape(r, rows[i + 1:])
        if kind == "away" and any(o.actor == r.actor and o.other == r.target for o in out):
            continue  # 花子に手を振って、立ち去る: she stands where the wave put her, and he walks away from there
        quarter = 0.25 * (r.end - r.start)
        span = None if r.target_role in ("goal", "source") else (r.start + quarter, r.end - quarter)
        facing, hands = None, None
        if r.id in sends:
            (time, facing), span = sends[r.id], None
        if r.id in reaches:
            other = _meeting(rows, r)
            if other is not None:
                time, hands = reaches[r.id], (HANDS[r.verb], HANDS[other.verb])
        start = r.start if r.target_role == "goal" else None
        if r.id in arrivals:
            time = arrivals[r.id]
        out.append(Relation(r.id, r.actor, r.target, kind, dist * scale.get(r.actor, 1.0), time, r.verb,
                            r.target_role or "", span, facing, start, hands))
    out.extend(_seat_mates(rows, present, scale))
    return sorted(out, key=lambda rel: (rel.time, rel.element))


#: m, hips to hips: two people sitting on one bench.
SEAT_MATES = 0.6


def _seat_mates(rows: Sequence[Element], present: set[str | None], scale) -> list[Relation]:
    """Two people sitting on one thing at once (太郎と花子はベンチに座った) sit side by side on it."""
    out = []
    seats = [r for r in rows if r.target_role == "support" and r.actor in present and r.target not in present]
    for i, r in enumerate(seats):
        first = next((q for q in seats[:i] if q.target == r.target and q.actor != r.actor
                      and q.start < r.end and r.start < q.end), None)
        if first is not None and first.actor is not None:
            out.append(Relation(r.id, r.actor, first.actor, "beside", SEAT_MATES * scale.get(r.actor, 1.0), r.end,
                                r.verb, "partner"))
    return out


def _meeting(rows: Sequence[Element], r: Element) -> Element | None:
    """The target's row whose hand meets ``r``'s (its handshake, its taking of what ``r`` hands over)."""
    return next((e for e in rows if e.actor == r.target and e.verb in HANDS and e.start < r.end and r.start < e.end),
                None)


def _answers(earlier: Sequence[Element], r: Element) -> bool:
    """A partner's own row of the motion another row already relates them by (花子's copy of 太郎は花子と踊る)."""
    return r.target_role == "partner" and any(
        e.actor == r.target and e.target == r.actor and e.verb == r.verb and e.target_role == "partner"
        for e in earlier)


def _is_base_of(rows: Sequence[Element], r: Element) -> bool:
    """A composition whose target its base row already states (歩きながら手を振る to one person)."""
    base = next((b for b in rows if b.id == r.prev), None)
    return base is not None and base.target == r.target


def _shape(r: Element, later: Sequence[Element]) -> tuple[str, float, float]:
    role, mid = r.target_role, 0.5 * (r.start + r.end)
    if role == "goal":
        if r.target_side == "behind":
            return "behind", BEHIND, r.end
        if r.target_side in ("beside", "near", "left", "right", "on", "around", "under"):
            return "beside", BESIDE, r.end
        nxt = next((x for x in later if x.actor == r.actor and x.method != "composition"), None)
        close = DISTANCES.get(nxt.verb) if nxt is not None and nxt.target == r.target else None
        return "face", min(APPROACH, close) if close else APPROACH, r.end
    if role == "source" and r.verb not in HANDS:  # 離れる: where it starts; 受け取る from someone: face them
        return "away", APPROACH, r.start
    if role == "partner" and r.verb not in FACE_TO_FACE and r.target_side != "front":  # 向かい合って: face
        return "beside", BESIDE, mid
    if r.verb in LEADING_HAND and any(x.actor == r.target and x.target == r.actor and x.target_side == "beside"
                                      for x in later):  # 太郎の手を引いて走った: by his side, to run on together
        return "beside", BESIDE, mid
    return "face", DISTANCES.get(r.verb, BY_ROLE.get(role or "", APPROACH)), mid

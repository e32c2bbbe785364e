"""Clause endings: how a predicate's clause ends and what that means.

The table is docs/language.md §3 (Table 2 of the seed paper, extended).  ``level``
ranks how much a clause can contain, after Minami's hierarchy of Japanese
subordinate clauses: a ながら / たまま clause (level 1) cannot contain a て
clause (level 2), so 走って、右手を振りながら歩く links 走って past 振りながら to
歩く.  A predicate's head is the next motion whose level is at least its own.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class Ending:
    kind: str
    relation: str  # serial | parallel
    overlap: bool | None
    method: str  # connection | transition | composition
    level: int
    reversed: bool = False  # 前に: the head is performed first
    hold: bool = False  # たまま: held at its end pose
    closes_subject: bool = False  # a が-subject inside this clause ends here


_SERIAL_OVERLAP = ("serial", True, "transition")
_SERIAL = ("serial", False, "connection")
_PARALLEL = ("parallel", None, "composition")

ENDINGS = {
    e.kind: e
    for e in (
        Ending("te", *_SERIAL_OVERLAP, 2),  # 走って、
        Ending("renyou", *_SERIAL_OVERLAP, 2),  # 走り、
        Ending("nagara", *_PARALLEL, 1),  # 振りながら / 振りつつ
        Ending("mama", *_PARALLEL, 1, hold=True),  # 上げたまま
        Ending("tekara", *_SERIAL, 2, closes_subject=True),  # 歩いてから
        Ending("ato", *_SERIAL, 2, closes_subject=True),  # 歩いた後で / たあと
        Ending("cond", *_SERIAL, 2, closes_subject=True),  # 終わったら / ば / と
        Ending("tari", *_SERIAL, 2),  # 走ったり
        Ending("douji", *_PARALLEL, 2, closes_subject=True),  # (の)と同時に
        Ending("mae", *_SERIAL, 2, reversed=True, closes_subject=True),  # 座る前に
        Ending("aida", *_PARALLEL, 2, closes_subject=True),  # 間に / うちに
        Ending("toki", *_PARALLEL, 2, closes_subject=True),  # 歩く時
        Ending("toki_past", *_SERIAL, 2, closes_subject=True),  # 座った時
        Ending("totan", *_SERIAL_OVERLAP, 2, closes_subject=True),  # 座った途端
        Ending("other", *_SERIAL, 2, closes_subject=True),  # ので, が, けど
        Ending("final", *_SERIAL, 3),  # 。 ！ ？ newline, 終止形 + 、
    )
}

#: Endings whose predicate is not an action of the actor.
NOT_MOTION = {
    "relative": "relative clause (modifies a noun)",
    "nominal": "nominalised by の (a complement, not an action)",
    "quote": "quoted speech",
    "negated": "negated",
    "embedded": "inside a noun-modifying clause",
    "light": "bare する without an action noun",
    "state": "state or formal verb",
    "manner": "manner て-form (says how the next motion is done)",
    "potential": "potential form (an ability, not an action: 泳げる)",
    "desire": "a wish (走りたい: wanting to, not doing it)",
    "prohibition": "a prohibition (走るな: not to do it)",
    "non-agent": "its subject is not a person (雨が降る, 音楽が流れる)",
    "direction": "says which way the next motion goes (花子に向かって走る)",
    "facing": "says that the actors face each other (向かい合って)",
    "greeting": "a set greeting (いらっしゃいませ, おかえりなさい: said to someone, not done)",
    "prop": "says what the next motion is done with (杖をついて歩く: the cane in hand)",
    "companion": "says who goes along on the next motion (犬を連れて散歩する: the dog walks too)",
    "passive": "done to its subject by someone else (花子に言われた, 先生に呼ばれた)",
    "landing": "the landing of the jump just before it (ジャンプして、着地した: one jump, which lands)",
    "unseen": "done with the face alone (目を覚ます), which is not animated: said in the notes",
}

"""Coordinated actors (太郎と花子が…): every one of them performs the motions."""
from __future__ import annotations

from text2anim import nlp


def _rows(text):
    a = nlp.analyze(text)
    return ([(m.id, m.actor, m.verb, m.span) for m in a.motions],
            [(c.first, c.second, c.relation, c.method) for c in a.constraints])


def test_two_actors_walk_together():
    motions, links = _rows("太郎と花子が歩く。")
    assert motions == [(1, "太郎", "歩く", (6, 8)), (2, "花子", "歩く", (6, 8))]
    assert links == [(1, 2, "parallel", "composition")]


def test_each_actor_keeps_the_chain():
    motions, links = _rows("太郎と花子は走って、座る。")
    assert [(m[1], m[2]) for m in motions] == [("太郎", "走る"), ("太郎", "座る"), ("花子", "走る"), ("花子", "座る")]
    assert (1, 2, "serial", "transition") in links and (3, 4, "serial", "transition") in links
    assert (1, 3, "parallel", "composition") in links
    # Every motion but the first of each track is the second of exactly one constraint.
    seconds = [b for _, b, _, _ in links]
    assert sorted(seconds) == [2, 3, 4]


def test_three_actors_and_a_companion_phrase():
    motions, _ = _rows("太郎と次郎と花子がジャンプする。")
    assert [m[1] for m in motions] == ["太郎", "次郎", "花子"]
    motions, _ = _rows("太郎は歩く。花子が走る。")
    assert [m[1] for m in motions] == ["太郎", "花子"]

"""What a warm process keeps of the joins it laid and finished (the plans and renderings,
synthesis.optimal.join.KEPT_JOINS; the hips' paths, synthesis.join.hipspath.KEPT_PATHS; the joins the post-pass
finished, synthesis.join.joinpass.KEPT_FINISHED): a text animated again, or with a sentence added after it, takes
them from what it kept, and gives the same bytes and report as a process that kept nothing."""
from __future__ import annotations

import json

from text2anim import animate
from text2anim.output.bvh_write import format_bvh
from text2anim.synthesis.join import hipspath, joinpass
from text2anim.synthesis.optimal import adaptation
from text2anim.synthesis.optimal import join as optimal_join

TEXT = "花子は歩いて、止まる。そして振り向いて、手を振る。"


def _output(db: str, blend: str) -> tuple[str, str]:
    anim = animate(TEXT, db=db, blend=blend)
    return format_bvh(anim.motions["花子"]), json.dumps(anim.report, ensure_ascii=False, sort_keys=True)


def test_a_text_animated_again_reuses_its_joins_and_gives_the_same_bytes(library_db):
    for blend in ("optimal", "constraint"):
        hipspath.KEPT_PATHS.clear()
        joinpass.KEPT_FINISHED.clear()
        solved = _output(library_db, blend)
        paths, finished = len(hipspath.KEPT_PATHS), len(joinpass.KEPT_FINISHED)
        assert paths >= 1 and finished >= 3  # its joins were searched, and at least one bent the hips
        again = _output(library_db, blend)
        assert (len(hipspath.KEPT_PATHS), len(joinpass.KEPT_FINISHED)) == (paths, finished)  # each join met again
        assert again == solved


def _forget() -> None:
    for kept in (hipspath.KEPT_PATHS, joinpass.KEPT_FINISHED, optimal_join.KEPT_JOINS, adaptation.KEPT_ADAPTED):
        kept.clear()


def _animated(text: str, db: str) -> tuple[str, dict]:
    anim = animate(text, db=db)
    return "".join(format_bvh(m) for m in anim.motions.values()), anim.report


def test_a_sentence_added_lays_only_its_own_joins_and_gives_a_fresh_process_s_bytes(library_db, monkeypatch):
    story = "太郎は走る。3秒後に歩く。"  # the scheduler inserts a stop and a wait: elements numbered after the text's
    added = story + "そして手を振る。"
    _forget()
    fresh = _animated(added, library_db)
    _forget()
    before = _animated(story, library_db)[1]
    laid = len(optimal_join.KEPT_JOINS)
    assert laid == len(before["joins"])
    rendered = []
    real = optimal_join.carry_out
    monkeypatch.setattr(optimal_join, "carry_out", lambda *a: rendered.append(a) or real(*a))
    again = _animated(added, library_db)
    assert again == fresh
    ids = [(j["first"], j["second"]) for j in again[1]["joins"]]
    assert ids[:laid] != [(j["first"], j["second"]) for j in before["joins"]]  # the same joins, renumbered
    assert len(rendered) == len(ids) - laid  # only the added sentence's join was laid anew


def test_a_join_laid_with_other_options_is_not_taken_for_it(library_db):
    _forget()
    locked = _animated(TEXT, library_db)
    free = animate(TEXT, db=library_db, lock_feet=False)
    _forget()
    assert format_bvh(free.motions["花子"]) == format_bvh(animate(TEXT, db=library_db, lock_feet=False).motions["花子"])
    assert format_bvh(free.motions["花子"]) != locked[0]

"""What a warm process keeps of the joins it finished (the hips' paths, synthesis.join.hipspath.KEPT_PATHS; the
joins the post-pass finished, synthesis.join.joinpass.KEPT_FINISHED): a text animated again takes them from
what it kept, and gives the same bytes and report as when they were solved and finished."""
from __future__ import annotations

import json

from text2anim import animate
from text2anim.output.bvh_write import format_bvh
from text2anim.synthesis.join import hipspath, joinpass

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

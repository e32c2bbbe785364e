"""The hips' paths a warm process keeps (synthesis.join.hipspath.KEPT_PATHS): a sentence animated again takes its
joins' paths from what it kept, and gives the same bytes as when they were solved."""
from __future__ import annotations

from text2anim import animate
from text2anim.output.bvh_write import format_bvh
from text2anim.synthesis.join import hipspath

TEXT = "太郎は走って、ボールを蹴る。そして喜ぶ。"


def test_a_sentence_animated_again_reuses_its_paths_and_gives_the_same_bytes(library_db):
    hipspath.KEPT_PATHS.clear()
    solved = format_bvh(animate(TEXT, db=library_db).motions["太郎"])
    regions = len(hipspath.KEPT_PATHS)
    assert regions >= 2  # the seed sentence's two joins both bend the hips
    again = format_bvh(animate(TEXT, db=library_db).motions["太郎"])
    assert len(hipspath.KEPT_PATHS) == regions  # no new programme: each join met its kept path
    assert again == solved

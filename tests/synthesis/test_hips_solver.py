"""The hips' path of least acceleration solves its programmes through highspy's compiled class, and through
scipy's wrapper of the same solver where a highspy release moved that private class: the same figures."""
from __future__ import annotations

import pytest

import text2anim
from text2anim.core.metrics import quality
from text2anim.synthesis.join import hipspath

TEXT = "太郎は走って、ボールを蹴る。そして喜ぶ。"


def test_the_solver_path_without_highspys_private_class_gives_the_same_animation(library_db, monkeypatch):
    assert hipspath._Highs is not None  # the installed highspy has it: the fast path is the one used
    fast = quality(text2anim.animate(TEXT, db=library_db).motions["太郎"])
    monkeypatch.setattr(hipspath, "_Highs", None)
    slow = quality(text2anim.animate(TEXT, db=library_db).motions["太郎"])
    for name in ("root_pop", "jerk_p99", "skating_gmd", "floating_cm", "floor_penetration_cm"):
        assert getattr(slow, name) == pytest.approx(getattr(fast, name), rel=0.02, abs=1e-3), name

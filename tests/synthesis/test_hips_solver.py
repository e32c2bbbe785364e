"""The hips' path of least acceleration solves its programmes through PIQP's interior point method (its AVX2 build,
so that the goldens' bytes hold across x86 machines), and through scipy's HiGHS where piqp is missing: the same
figures."""
from __future__ import annotations

import pytest

import text2anim
from text2anim.core.metrics import quality
from text2anim.synthesis.join import hipspath

TEXT = "太郎は走って、ボールを蹴る。そして喜ぶ。"


def test_the_solver_path_without_piqp_gives_the_same_animation(library_db, monkeypatch):
    assert hipspath._piqp() is not None  # the installed piqp: the fast path is the one used
    fast = text2anim.animate(TEXT, db=library_db)
    monkeypatch.setattr(hipspath, "_piqp", lambda: None)
    slow = text2anim.animate(TEXT, db=library_db)
    bent = [j["metrics"]["post"]["hips_bent_cm"] for j in fast.report["joins"]]
    assert max(bent) > 1.0  # the seed sentence's joins do bend the hips: both solvers' paths are in the figures
    q_fast, q_slow = quality(fast.motions["太郎"]), quality(slow.motions["太郎"])
    for name in ("root_pop", "jerk_p99", "skating_gmd", "floating_cm", "floor_penetration_cm"):
        assert getattr(q_slow, name) == pytest.approx(getattr(q_fast, name), rel=0.02, abs=1e-3), name


def test_piqp_runs_its_avx2_build_where_the_cpu_has_avx2():
    import piqp

    module = hipspath._piqp()
    if piqp.instruction_set.avx2:
        assert module.__name__ == "piqp.piqp_python_avx2"
    else:
        assert module is piqp

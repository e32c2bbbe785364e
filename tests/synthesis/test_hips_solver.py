"""The hips' path of least acceleration solves its programmes through PIQP's interior point method (its AVX2 build,
so that the goldens' bytes hold across x86 machines), and through scipy's HiGHS where piqp is missing: the same
figures."""
from __future__ import annotations

import pytest

import text2anim
from text2anim.core.kept import Kept
from text2anim.core.metrics import quality
from text2anim.synthesis.join import hipspath, joinpass

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


def test_piqp_solves_every_programme_of_a_long_text_to_highs_optimum(library_db, monkeypatch):
    """Issue 41's 32-motion text (93 regions, 186 programmes): PIQP (its multistage factorisation, in frame order)
    answers every programme itself — its test for infeasibility once called a least-peak programme of this text
    infeasible, and HiGHS's fallback cost that region ~95 ms — at HiGHS's optimum (the optima's paths may differ
    where they tie: HiGHS's is a vertex)."""
    minimum, highs = hipspath._minimum, hipspath._minimum_scipy
    values = []

    def no_fallback(*args):
        raise AssertionError("PIQP found no optimum")

    def compared(cost, rows, lower, upper, col_lower, col_upper, stage):
        x = minimum(cost, rows, lower, upper, col_lower, col_upper, stage)
        values.append((float(cost @ x), float(cost @ highs(cost, rows, lower, upper, col_lower, col_upper))))
        return x

    monkeypatch.setattr(hipspath, "_minimum_scipy", no_fallback)
    monkeypatch.setattr(hipspath, "_minimum", compared)
    monkeypatch.setattr(hipspath, "KEPT_PATHS", Kept(256))  # every region solved here, none kept from before
    monkeypatch.setattr(joinpass, "KEPT_FINISHED", Kept(joinpass.KEPT_FINISHED.size))
    text2anim.animate("走る。" + "3秒後に歩く。" * 31, db=library_db)
    assert len(values) >= 150
    for piqp_value, highs_value in values:
        assert piqp_value == pytest.approx(highs_value, rel=1e-6, abs=1e-6)

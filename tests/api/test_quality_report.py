"""Issue 11's figures in the animation report and in ``text2anim compare``, on the built-in library."""
from __future__ import annotations

import json

import pytest

import text2anim
from cli_run import text2anim as run
from text2anim.core.metrics import CRITERIA, quality

EXAMPLE = "太郎は走って、ボールを蹴る。そして喜ぶ。"
FIGURES = {"fps", "frames", "skating_ratio", "root_pop", "jerk_p99", "floor_penetration_cm", "frozen_fraction",
           "floating_cm", "skating_gmd"}


@pytest.fixture(scope="module")
def anim(library_db):
    return text2anim.animate(EXAMPLE, db=library_db)


def test_every_join_is_measured_around_its_blend_next_to_its_source_clips(anim):
    report = json.loads(json.dumps(anim.report, ensure_ascii=False))
    clip_of = {e["id"]: e["clip"] for e in report["time_table"]}
    assert len(report["joins"]) == 2
    for j in report["joins"]:
        q = j["quality"]
        begin = min(iv["begin"] for iv in j["intervals"])
        end = max(iv["end"] for iv in j["intervals"])
        assert q["window_s"][0] <= begin and q["window_s"][1] >= end  # the window holds the whole blend
        assert q["fps"] == 30.0 and set(q["join"]) == FIGURES
        assert q["sources"]["first"]["clip"] == clip_of[j["first"]]
        assert q["sources"]["second"]["clip"] == clip_of[j["second"]]
        assert set(q["sources"]["first"]) == FIGURES | {"clip"} and set(q["meets"]) == set(CRITERIA)
    # the report's figures are those of text2anim.core.metrics on the output (window) and on the clips
    (motion,) = anim.motions.values()
    for j in report["joins"]:
        q = quality(motion, window=tuple(j["quality"]["window_s"]))
        assert j["quality"]["join"]["root_pop"] == pytest.approx(q.root_pop, abs=0.01)
        # the report gives the ratio to 2 decimals (nonzero since the library is capture, issue 12)
        assert j["quality"]["join"]["skating_ratio"] == pytest.approx(q.skating_ratio, abs=5e-3)
    assert report["actors"]["太郎"]["quality"]["root_pop"] == pytest.approx(quality(motion).root_pop, abs=0.01)


def test_compare_prints_the_30_fps_figures_per_method(library_db):
    proc = run("compare", "歩いて、走る。", "--methods", "optimal,crossfade", "--json", "--db", library_db)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    for m in ("optimal", "crossfade"):
        row = doc["methods"][m]
        assert {"root_pop", "jerk_p99", "floor_penetration_cm", "frozen_fraction", "join_root_pop", "joins_ok"} <= set(row)
        # a part of the whole can pop no more than the whole (the join's figure is rounded to 0.01 m/s²)
        assert row["join_root_pop"] <= row["root_pop"] + 0.005 and row["joins_ok"].endswith("/1")

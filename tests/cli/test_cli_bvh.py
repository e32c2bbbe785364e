"""The first commands: info, metrics, convert, as a user runs them."""
from __future__ import annotations

import json

import numpy as np
import pytest

from cli_run import assert_clean_error, text2anim
from shared_data import cmu
from text2anim.core import read_bvh


def test_info_summarises_a_walk():
    proc = text2anim("info", cmu("02_01_walk"), "--drop-first")
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    assert "343 at 120.000 fps" in out and "31 joints" in out
    assert "left foot: 3 contacts" in out and "right foot: 3 contacts" in out


def test_metrics_json():
    proc = text2anim("metrics", cmu("16_15_walk"), "--drop-first", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["quality"]["fps"] == 30.0 and data["quality"]["skating_ratio"] <= 0.02  # GMD ratio at 30 fps
    assert 2.0 < data["quality"]["root_pop"] < 7.0 and data["quality"]["frozen_fraction"] == 0.0
    assert set(data["foot_skate"]) == {"left", "right"}
    assert data["jerk"]["max"] > data["jerk"]["rms"] > 0


def test_convert_without_options_keeps_world_positions(tmp_path):
    out = tmp_path / "walk.bvh"
    proc = text2anim("convert", cmu("02_01_walk"), "-o", out)
    assert proc.returncode == 0, proc.stderr
    np.testing.assert_allclose(read_bvh(out).positions, read_bvh(cmu("02_01_walk")).positions, atol=1e-6)


def test_convert_resamples_and_drops_the_t_pose(tmp_path):
    out = tmp_path / "walk30.bvh"
    proc = text2anim("convert", cmu("02_01_walk"), "-o", out, "--fps", "30", "--drop-first")
    assert proc.returncode == 0, proc.stderr
    m = read_bvh(out)
    assert m.fps == pytest.approx(30) and m.n_frames == 86


@pytest.mark.parametrize("args, fragment", [
    (("info", "no/such/file.bvh"), "no such file"),
    (("metrics", "--json", "{bad}"), "bad.bvh:4: expected a number"),
    (("convert", "{walk}", "-o", "/nonexistent-dir/out.bvh"), "does not exist"),
    (("convert", "{walk}", "-o", "{tmp}"), "is a directory"),
    (("info", "{walk}", "--scale", "-1"), "positive"),
])
def test_bad_input_gives_one_clear_message(tmp_path, args, fragment):
    bad = tmp_path / "bad.bvh"
    bad.write_text("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 zero\n}\n")
    args = [a.format(bad=bad, walk=cmu("02_01_walk"), tmp=tmp_path) for a in args]
    proc = text2anim(*args)
    assert_clean_error(proc, fragment)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.bvh"]

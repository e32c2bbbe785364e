"""A run into a walk leaves the walk on the floor (capture of other subjects, imported as a user would).

CMU 09_01 (run) and 05_01 (walk) from ``../shared/mocap/cmu_repro``: the foot lock at the join could not
hold the right foot on the floor, and settling the walk where that foot hung lifted the whole walk 47 cm;
then, the walk on the floor, the lock still held the foot where the run had planted it while the hips
went on, and the foot hung behind on a straight leg, 50 cm up, for 1.7 s.
"""
from __future__ import annotations

import json

import numpy as np
import pytest

from cli_run import text2anim
from shared_data import SHARED
from text2anim.core import read_bvh
from text2anim.core.contacts import detect_contacts
from text2anim.core.floor import FOOT_CLEARANCE, lowest_foot_heights
from text2anim.core.metrics import BUILTIN_LIMITS, quality

REPRO = SHARED / "mocap" / "cmu_repro"
pytestmark = pytest.mark.skipif(not (REPRO / "05_01_walk.bvh").exists(),
                                reason=f"shared capture not found at {REPRO} (README.md: Real capture for the tests)")


def test_a_run_into_a_walk_keeps_the_walk_on_the_floor(tmp_path):
    db = f"sqlite:///{tmp_path / 'usr.sqlite'}"
    for take, verb in (("09_01_run", "疾走する"), ("05_01_walk", "散歩する")):
        done = text2anim("db", "import", REPRO / f"{take}.bvh", "--verb", verb, "--cyclic", "--drop-first",
                         "--character", "usr", "--db", db)
        assert done.returncode == 0, done.stderr
    out, report = tmp_path / "scene.bvh", tmp_path / "scene.json"
    done = text2anim("疾走して、散歩する。", "--db", db, "-o", out, "--report", report)
    assert done.returncode == 0, done.stderr
    joins = json.loads(report.read_text())["joins"]
    for join in joins:  # no join moved the next clip up or down by more than two captures' floors differ
        assert abs((join["metrics"].get("settled_cm") or [0, 0, 0])[1]) <= 5.0, join["metrics"]
    motion = read_bvh(out)
    low = lowest_foot_heights(motion)  # (T, 2) each foot's lowest joint, m
    contacts = detect_contacts(motion)
    walk = np.arange(motion.n_frames) / motion.fps > 0.6 * motion.n_frames / motion.fps  # the walk's last 40 %
    planted = np.concatenate([low[walk & contacts.left, 0], low[walk & contacts.right, 1]])
    assert len(planted) > 20  # the walk steps
    assert np.median(planted) == pytest.approx(FOOT_CLEARANCE, abs=0.02)  # planted feet on the floor (47 cm up before)
    assert low[walk].min(axis=1).max() < 0.15  # always a foot near the floor while walking
    assert quality(motion).floating_cm <= BUILTIN_LIMITS["floating_cm"]  # no foot stands on air (44 cm before)
    # no foot held up in the air: a run's kick-back peaks for a tenth of a second, the held foot stayed 50 cm
    # up for 1.7 s
    up = low.max(axis=1) > 0.25
    longest = max((len(r) for r in np.split(up, np.flatnonzero(np.diff(up)) + 1) if r[0]), default=0)
    assert longest / motion.fps < 0.4

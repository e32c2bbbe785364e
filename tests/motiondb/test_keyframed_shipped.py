"""The shipped keyframed clips (``keyframed.npz``): what a fresh build of ``clips/*.json`` gives, and what
a new database is seeded with."""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from text2anim.motiondb import MotionDB
from text2anim.motiondb.library import build_all, capture, keyframed

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "library"))  # the build scripts (not installed)
import build_keyframed  # noqa: E402

REBUILD = "python tools/library/build_keyframed.py"


def test_the_shipped_file_was_built_from_the_current_json_and_generator():
    stored = keyframed.shipped()[0]
    assert stored == keyframed.sources_hash(), f"clips/*.json or the generator changed: run {REBUILD}"


def test_the_shipped_file_holds_exactly_what_a_fresh_build_gives():
    fresh = build_keyframed.arrays()  # generated from the JSON now (build_all is cached for the session)
    with np.load(keyframed.ARRAYS) as data:
        assert list(data.files) == list(fresh), f"other clips than a build gives: run {REBUILD}"
        for name, array in fresh.items():
            assert data[name].dtype == array.dtype and np.array_equal(data[name], array), f"{name}: run {REBUILD}"


def test_every_seeded_keyframed_clip_is_the_generated_one_within_float32():
    gone = capture.replaced()
    generated = [b.record for b in build_all(30.0) if b.record.name not in gone]
    shipped = keyframed.keyframed_records()
    assert [r.name for r in shipped] == [r.name for r in generated]
    for s, g in zip(shipped, generated):
        for field in ("verbs", "objects", "core", "body_part", "cyclic", "source", "start_posture", "end_posture"):
            assert getattr(s, field) == getattr(g, field), (s.name, field)
        assert s.motion.n_frames == g.motion.n_frames and s.motion.fps == g.motion.fps
        np.testing.assert_allclose(s.motion.root_positions, g.motion.root_positions, rtol=0, atol=1e-6)
        np.testing.assert_allclose(s.motion.rotations, g.motion.rotations, rtol=0, atol=2e-7)
        np.testing.assert_allclose(np.linalg.norm(s.motion.rotations, axis=-1), 1.0, atol=1e-12)


def test_a_new_database_holds_every_generated_keyframed_clip(db_url):
    gone = capture.replaced()
    generated = {b.record.name: b.record for b in build_all(30.0) if b.record.name not in gone}
    with MotionDB.open(db_url) as db:
        stored = {c.name: c for c in db.clips()}
        assert set(generated) <= set(stored)
        for name, g in generated.items():
            info = stored[name]
            assert info.source == g.source and info.cyclic == g.cyclic and info.body_part == g.body_part
            assert info.verbs[:len(g.verbs)] == g.verbs  # then the near-synonyms of near.json
            assert info.core == pytest.approx(g.core, abs=1e-12)
            m = db.load(name)
            assert m.n_frames == g.motion.n_frames
            np.testing.assert_allclose(m.root_positions, g.motion.root_positions, rtol=0, atol=1e-6)
            np.testing.assert_allclose(m.rotations, g.motion.rotations, rtol=0, atol=2e-7)


def test_the_shipped_contacts_are_what_storing_each_builtin_clip_computes():
    from text2anim.core.contacts import detect_contacts
    from text2anim.motiondb.library import builtin_clips

    shipped = keyframed.seeded_contacts()
    records = builtin_clips()
    assert sorted(shipped) == sorted(r.name for r in records), f"run {REBUILD} (after capture.npz changed?)"
    for r in records:
        fc = detect_contacts(r.motion)
        assert shipped[r.name] == [(side, a, b) for side in ("left", "right") for a, b in fc.intervals(side)], \
            f"{r.name}: run {REBUILD}"

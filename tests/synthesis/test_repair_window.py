"""A join's renderings are of the track from its blend on (:func:`synthesis.optimal.repair.carry_out`):
the track it lays keeps every frame before the join as it was, and its pose — joined from the track's and the
kept rendering's — is the kinematics of its own frames, bit for bit (the next join reads it); and the contacts
every join reads of the track, found from the new frames alone (synthesis.join.laying.extended), are the whole
track's."""
from __future__ import annotations

import numpy as np

import text2anim
from text2anim.core import fk
from text2anim.core.contacts import detect_contacts
from text2anim.core.motion import Motion, concatenate
from text2anim.synthesis.optimal import join as optimal_join


def test_every_join_of_a_long_text_keeps_the_track_before_it_and_a_true_pose(monkeypatch):
    joins = []
    real = optimal_join.carry_out

    def recorded(tr, plan, *args):
        out = real(tr, plan, *args)
        joins.append((tr, out))
        return out

    monkeypatch.setattr(optimal_join, "carry_out", recorded)
    optimal_join.KEPT_JOINS.clear()  # every join rendered here, none taken from an earlier test's
    text2anim.animate("太郎は走る。" + "3秒後に歩く。" * 3)
    assert len(joins) >= 3  # the run into a walk, and walk into walk: joins late on a track
    assert max(tr.n_frames for tr, _ in joins) > 400
    for tr, (_, c0, rendered, locks, window) in joins:
        fresh_c = detect_contacts(Motion(tr.skeleton, tr.fps, tr.root_positions, tr.rotations, tr.translations))
        for side in ("left", "right"):
            assert np.array_equal(detect_contacts(tr).of(side), fresh_c.of(side))
        out = concatenate([tr[:c0], rendered])  # the track as laid
        w0 = window[0]
        assert all(lk.begin >= w0 for lk in locks)
        for a, b in ((out.rotations, tr.rotations), (out.root_positions, tr.root_positions)):
            assert np.array_equal(a[:w0], b[:w0])
        fresh = fk.forward(out.skeleton, out.rotations, out.local_translations())
        assert np.array_equal(out.positions, fresh.positions)
        assert np.array_equal(out.pose.rotations, fresh.rotations)

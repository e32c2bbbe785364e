"""Inertialization and the join retiming: the offsets carry velocity over and vanish; the warp keeps its ends."""
from __future__ import annotations

import numpy as np

from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton
from text2anim.synthesis.join.inertialize import inertialize_at, inertialize_before, quintic, spring
from text2anim.synthesis.join.joinpass import warp_frames


def test_quintic_starts_with_the_offset_and_its_velocity_and_ends_at_rest():
    x0, v0, t1 = np.array([0.3, -0.2]), np.array([-1.0, 2.0]), 0.4
    t = np.linspace(0.0, 0.5, 501)
    x = quintic(x0, v0, t, t1)
    dt = t[1] - t[0]
    np.testing.assert_allclose(x[0], x0)
    np.testing.assert_allclose((x[1] - x[0]) / dt, v0, atol=0.02)
    np.testing.assert_allclose(x[t >= t1], 0.0, atol=1e-12)  # zero, and stays zero, from t1 on
    v = np.gradient(x, dt, axis=0)
    assert np.abs(v[(t > t1 - 0.01) & (t < t1)]).max() < 1e-3  # arrives at rest


def test_spring_keeps_the_velocity_and_decays_by_half_life():
    x = spring(np.array(1.0), np.array(0.0), np.array([0.0, 1.0, 10.0]), halflife=1.0)
    assert x[0] == 1.0 and 0.0 < x[2] < 1e-3 < x[1] < 1.0
    y = spring(np.array(0.0), np.array(2.0), np.array([0.0, 1e-4]), halflife=0.2)
    assert abs((y[1] - y[0]) / 1e-4 - 2.0) < 0.01


def _line(velocities: np.ndarray, fps: float = 30.0) -> Motion:
    """A one-joint motion whose root moves along X with the given per-frame velocities (m/s)."""
    sk = Skeleton(("Hips",), np.array([-1]), np.zeros((1, 3)))
    x = np.concatenate([[0.0], np.cumsum(velocities[:-1]) / fps])
    rots = np.tile([0.0, 0.0, 0.0, 1.0], (len(x), 1, 1))
    return Motion(sk, fps, np.stack([x, np.zeros_like(x), np.zeros_like(x)], 1), rots)


def test_a_velocity_jump_is_carried_over_and_decays():
    m = _line(np.r_[np.full(30, 3.0), np.zeros(30)])  # runs at 3 m/s, then stands: a halt in one frame
    out = inertialize_at(m, 30, 0.5)
    v = np.diff(out.root_positions[:, 0]) * 30
    assert abs(v[29] - 3.0) < 0.2 and abs(v[30] - 3.0) < 1.0  # the speed goes on through the seam (not 3 -> 0)
    assert np.abs(out.root_positions[45:] - m.root_positions[45:]).max() < 1e-9  # and is gone after 0.5 s
    np.testing.assert_array_equal(out.root_positions[:30], m.root_positions[:30])  # the past is untouched


def test_backwards_the_frames_before_the_seam_take_the_jump():
    m = _line(np.r_[np.full(30, 3.0), np.zeros(30)])
    out = inertialize_before(m, 30, 0.5)
    np.testing.assert_array_equal(out.root_positions[30:], m.root_positions[30:])
    v = np.diff(out.root_positions[:, 0]) * 30
    assert abs(v[28]) < 1.0  # arrives at the standing frame slowed down (not at 3 m/s)


def test_the_warp_plays_every_frame_in_order_with_rate_one_at_both_ends():
    for n, n_new, seam in [(20, 36, 14), (30, 45, 3), (12, 12, None)]:
        w = warp_frames(n, n_new, seam)
        assert len(w) == max(n, n_new) and w[0] == 0.0 and w[-1] < n
        rate = np.diff(w)
        assert (rate > 0).all()
        assert abs(rate[0] - 1.0) < 0.02 and abs(rate[-1] - 1.0) < 0.05

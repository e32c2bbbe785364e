"""The blend weight's Hermite cubic, written out so a command need not import scipy.interpolate, is
scipy's ``CubicHermiteSpline`` bit for bit (the animation must not change by a bit)."""
from __future__ import annotations

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from text2anim.synthesis.optimal.weights import MAX_SLOPE, hermite, hermite_weights, monotone_slopes


def test_the_hermite_weight_is_scipys_cubic_hermite_spline_bit_for_bit():
    rng = np.random.default_rng(7)
    slopes = [(0.0, 0.0), (MAX_SLOPE, 0.0), (0.0, MAX_SLOPE), (1.0, 1.0)] + [tuple(rng.uniform(0, 3, 2)) for _ in range(500)]
    for m0, m1 in slopes:
        for n in (1, 2, 7, 30, 121):
            u = np.arange(n + 1) / n
            want = CubicHermiteSpline([0.0, 1.0], [0.0, 1.0], [m0, m1])(u)
            assert np.array_equal(hermite(u, m0, m1), want), (m0, m1, n)
    u = rng.uniform(-0.5, 1.5, 1000)  # clipped to [0, 1] first
    assert np.array_equal(hermite(u, 0.7, 1.9), CubicHermiteSpline([0.0, 1.0], [0.0, 1.0], [0.7, 1.9])(np.clip(u, 0, 1)))


def test_hermite_weights_rise_from_0_to_1():
    w = hermite_weights(30, *monotone_slopes(2.0, 0.5))
    assert w[0] == 0.0 and w[-1] == 1.0 and np.all(np.diff(w) >= 0)

"""The easing curves every ramp of the project uses (core.easing): ends, slopes, symmetry, the area."""
from __future__ import annotations

import numpy as np

from text2anim.core.easing import smootherstep, smootherstep_area, smoothstep


def test_both_curves_rise_from_0_to_1_flat_at_the_ends_and_are_clipped_outside():
    u = np.linspace(-0.5, 1.5, 2001)
    for curve in (smoothstep, smootherstep):
        w = curve(u)
        assert w.shape == u.shape
        assert np.all(w[u <= 0] == 0.0) and np.all(w[u >= 1] == 1.0)
        assert np.all(np.diff(w) >= 0)  # monotone
        inside = (u > 0) & (u < 1)
        assert np.allclose(w[inside] + curve(1.0 - u[inside]), 1.0)  # symmetric about (1/2, 1/2)
        h = 1e-4
        assert abs(curve(h) / h) < 1e-3 and abs((1.0 - curve(1.0 - h)) / h) < 1e-3  # slope 0 at both ends


def test_smootherstep_has_no_curvature_at_the_ends_where_smoothstep_has():
    h = 1e-3
    second = lambda f, x: (f(x + h) - 2 * f(x) + f(x - h)) / h ** 2  # noqa: E731
    assert abs(second(smootherstep, h)) < 0.1
    assert abs(second(smoothstep, h) - 6.0) < 0.1  # 6 - 12u at u = 0


def test_the_area_is_the_integral_of_smootherstep():
    u = np.linspace(0.0, 1.0, 4001)
    numeric = np.concatenate([[0.0], np.cumsum((smootherstep(u[1:]) + smootherstep(u[:-1])) / 2 * np.diff(u))])
    assert np.allclose(smootherstep_area(u), numeric, atol=1e-7)
    assert smootherstep_area(np.array(1.0)) == 0.5

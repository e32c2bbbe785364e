"""Easing curves: a ratio ``u`` in ``[0, 1]`` to a weight rising from 0 to 1 with zero slope at both ends.

- :func:`smoothstep`: ``3u² - 2u³``, zero slope at both ends (C1): ramps of a correction in and out
  (foot pins, lifts, clearance humps, blends of a loop's seam);
- :func:`smootherstep`: ``6u⁵ - 15u⁴ + 10u³``, zero slope and curvature at both ends (C2): blend
  weights whose acceleration must not jump;
- :func:`smootherstep_area`: the integral of :func:`smootherstep` from 0 (a playback rate easing by it).

Each takes a scalar or an array of any shape and returns the same shape; ``u`` outside ``[0, 1]`` is
clipped (the curve is flat there) by :func:`smoothstep` and :func:`smootherstep`.
"""
from __future__ import annotations

from typing import Any

import numpy as np


def smoothstep(u: Any) -> Any:
    """``3u² - 2u³`` of ``u`` clipped to ``[0, 1]``: 0 at 0, 1 at 1, slope 0 at both (C1); shape of ``u``."""
    u = np.clip(u, 0.0, 1.0)
    return u * u * (3 - 2 * u)


def smootherstep(u: Any) -> np.ndarray:
    """``6u⁵ - 15u⁴ + 10u³`` of ``u`` clipped to ``[0, 1]``: 0 at 0, 1 at 1, slope and curvature 0 at
    both (C2); float64, shape of ``u``."""
    u = np.clip(np.asarray(u, dtype=np.float64), 0.0, 1.0)
    return u * u * u * (u * (6.0 * u - 15.0) + 10.0)


def smootherstep_area(u: np.ndarray) -> np.ndarray:
    """``∫₀ᵘ smootherstep(x) dx = u⁶ - 3u⁵ + 2.5u⁴`` for ``u`` in ``[0, 1]`` (1/2 at ``u = 1``); shape of ``u``."""
    return u ** 6 - 3.0 * u ** 5 + 2.5 * u ** 4

"""Weight: the hips' vertical excursion about their reference height, larger (a springy or a heavy step) or
smaller (a tired shuffle).

The reference of a looping clip is the hips' mean height; of any other clip, the height sliding from its
first frame's to its last (a jump's flight is its excursion: an energetic jump goes higher; a sit-down's
end stays where the seat is). The style's ``bounce`` factor at intensity 1, raised to the intensity.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.motion import Motion


def bounce(motion: Motion, factor: float, cyclic: bool) -> Motion:
    """``motion`` with its hips' vertical excursion scaled by ``factor``."""
    if factor == 1.0 or motion.n_frames < 2:
        return motion
    root = np.array(motion.root_positions)
    y = root[:, 1]
    ref = np.full_like(y, y.mean()) if cyclic else np.linspace(y[0], y[-1], len(y))
    root[:, 1] = ref + factor * (y - ref)
    return motion.replace(root_positions=root)

"""Frame counts at a frame rate, from clip metadata alone (no numpy: `text2anim plan` loads none)."""
from __future__ import annotations

import math


def resampled_frames(n_frames: int, fps: float, new_fps: float) -> int:
    """How many frames :meth:`Motion.resample` makes of ``n_frames`` at ``fps`` at ``new_fps``.

    The new frames sample ``0, 1/new_fps, ...`` up to the last original frame, at
    ``(n_frames - 1) / fps`` seconds; so a clip's played length is known from its
    metadata, without its frames.
    """
    new_fps = float(new_fps)
    if new_fps == fps or n_frames < 2:
        return n_frames
    last = (n_frames - 1) / fps
    return math.floor(last * new_fps + 1e-9) + 1

"""Where a joined motion plays its source clips as they are: the hips' path of every element as placed.

A join changes some frames and plays the rest of its two clips verbatim, only turned and moved
(:class:`~synthesis.join.placed.Placed`: the prepared clip moved by its ``rigid``). The figures of the
frames a method plays verbatim are its sources', not its own: a kick's 9 m/s² inside the kick's core
is the same in every method's output. :func:`placed_paths` keeps, per whole-body element, the hips'
horizontal path as placed on the output's frames, so a reading can tell the accelerations a method
introduced from the ones it played (:func:`text2anim.quality.introduced_root_pop`).
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .join.placed import Placed


def placed_paths(placed: Sequence[Placed], n_frames: int) -> np.ndarray:
    """``(K, n_frames, 2)`` m: the hips' horizontal position (x, z) of each of the ``K`` placed elements (or
    repetitions) at every track frame where it is played (its own frames ``[lead, stop)``), NaN elsewhere."""
    out = np.full((len(placed), n_frames, 2), np.nan)
    for k, p in enumerate(placed):
        a = max(0, p.offset + p.lead)
        b = min(n_frames, p.offset + min(p.stop, p.motion.n_frames))
        if b > a:
            out[k, a:b] = p.motion.root_positions[a - p.offset:b - p.offset][:, [0, 2]]
    return out


def fitted(paths: np.ndarray, n_frames: int) -> np.ndarray:
    """``paths`` ``(K, T, 2)`` cut or extended (NaN: not played) to ``n_frames`` frames: a motion made longer
    after it was laid (another actor's join given more time) plays no placed element on the frames added."""
    if paths.shape[1] >= n_frames:
        return paths[:, :n_frames]
    pad = np.full((paths.shape[0], n_frames - paths.shape[1], 2), np.nan)
    return np.concatenate([paths, pad], axis=1)

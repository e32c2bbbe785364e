"""A long track edited window after window (the join post-pass, one join after another): its frames are kept as
pieces end to end, so that an edit of a window copies that window, not the track.

:meth:`Spliced.window` puts the frames ``[a, b)`` together (slices of the pieces: their poses, when known, are
sliced and joined with them), :meth:`Spliced.put` puts an edited window (of any length) in their place, and
:meth:`Spliced.motion` joins the pieces once at the end. Alongside, each frame's lowest foot heights
(:func:`core.contacts.lowest_heights`, ``(T, feet)``) are kept spliced the same way: the floor levels of the
whole track (:func:`core.contacts.floor_levels`) for the contacts of a window, without the whole track's kinematics.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.contacts import floor_levels, lowest_heights
from text2anim.core.motion import Motion, concatenate


class Spliced:
    """A motion as pieces end to end (see the module docstring)."""

    def __init__(self, motion: Motion):
        self._pieces = [motion]
        self._heights = lowest_heights(motion)

    @property
    def n_frames(self) -> int:
        return len(self._heights)

    def floor(self) -> np.ndarray:
        """``(feet,)`` m: the whole track's floor levels (:func:`core.contacts.floor_levels`)."""
        return floor_levels(self._heights)

    def lowest_outside(self, a: int, b: int) -> float:
        """m: the lowest foot joint of the track outside its frames ``[a, b)`` (``inf`` where there are none):
        with a window's own, the whole track's (GMD's floor, :func:`core.metrics.gmd_floor`)."""
        rest = np.concatenate([self._heights[:a], self._heights[b:]])
        return float(rest.min()) if rest.size else float("inf")

    def window(self, a: int, b: int) -> Motion:
        """Frames ``[a, b)`` of the track (``0 <= a < b <= n_frames``)."""
        parts, start = [], 0
        for p in self._pieces:
            end = start + p.n_frames
            if end > a and start < b:
                parts.append(p[max(a, start) - start:min(b, end) - start])
            start = end
        return parts[0] if len(parts) == 1 else concatenate(parts)

    def put(self, a: int, b: int, edited: Motion) -> None:
        """Frames ``[a, b)`` of the track replaced by ``edited`` (later frames follow it)."""
        pieces, start = [], 0
        for p in self._pieces:
            end = start + p.n_frames
            if end <= a or start >= b:  # untouched (a piece starting at ``a`` is not: the edit goes before it)
                pieces.append(p)
                start = end
                continue
            if start < a:
                pieces.append(p[:a - start])
            if start <= a < end:
                pieces.append(edited)
            if end > b:
                pieces.append(p[max(b, start) - start:])
            start = end
        self._pieces = [p for p in pieces if p.n_frames]
        self._heights = np.concatenate([self._heights[:a], lowest_heights(edited), self._heights[b:]])

    def motion(self) -> Motion:
        """The whole track, its pieces joined."""
        return self._pieces[0] if len(self._pieces) == 1 else concatenate(self._pieces)

"""Where actors stand at time 0 when the text gives them no place of their own.

Several tracks are independent; :func:`spread_actors` spaces actors that share
one origin (:func:`default_origins`), so characters do not start inside each other.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from .tracks import Track

ACTOR_SPACING = 1.5  # m between actors placed by default


def default_origins(n: int, spacing: float = ACTOR_SPACING) -> list[tuple[float, float]]:
    """``n`` ground positions (x, z) in a row along X, ``spacing`` metres apart, centred on the origin.

    Every actor faces +Z (heading 0) from there, side by side.
    """
    return [((i - (n - 1) / 2.0) * spacing, 0.0) for i in range(n)]


def spread_actors(tracks: Sequence[Track], spacing: float = ACTOR_SPACING) -> tuple[Track, ...]:
    """The tracks with default origins when several actors would otherwise start on the same spot.

    Tracks keep their own ``origin`` unless two or more share one; then all
    of them are put on :func:`default_origins` (order as given).
    """
    tracks = tuple(tracks)
    if len(tracks) < 2:
        return tracks
    spots = {(round(t.origin[0], 3), round(t.origin[1], 3)) for t in tracks}
    if len(spots) == len(tracks):
        return tracks
    return tuple(replace(t, origin=o) for t, o in zip(tracks, default_origins(len(tracks), spacing)))


"""The synthesis result as the scene placed it: the rows at their played times, and the result moved.

The scene stage (:func:`scene.place`) reads the time table's rows at the times synthesis played them and
moves each actor rigidly; here a :class:`~synthesis.result.Result` is moved the same way, its motions,
its placed paths and each element's placement, so the report and the quality figures read the moved scene.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from text2anim.core.ground import Rigid
from text2anim.scheduler.types import Element, TimeTable
from text2anim.synthesis.result import Placement, Result


def played_rows(table: TimeTable, result: Result) -> list[Element]:
    """The rows of ``table`` with the start and end synthesis played them at (as scheduled where it did
    not report them); rows it did not execute are left out."""
    out = []
    for e in table.elements:
        played = result.elements.get(e.id)
        if played is not None and not played.executed:
            continue
        start = played.start if played is not None and played.start is not None else e.start
        end = played.end if played is not None and played.end is not None else e.end
        out.append(replace(e, start=start, end=end))
    return out


def moved_result(result: Result, motions: dict, rigids: dict[str | None, Rigid]) -> Result:
    """``result`` with the scene's ``motions`` (each actor's moved by its rigid, a walk steered on its way)
    and its placed paths and element placements moved by the rigids; ``result`` itself when no actor moves."""
    moving = {a: r for a, r in rigids.items() if (r.yaw, r.offset) != (0.0, (0.0, 0.0)) and a in result.motions}
    if not moving and all(motions[a] is m for a, m in result.motions.items()):
        return result
    motions = {a: motions[a] for a in result.motions}
    paths = {a: (_moved_path(p, moving[a]) if a in moving else p) for a, p in result.placed_paths.items()}
    elements = {k: (_moved_element(v, moving[v.actor]) if v.actor in moving else v) for k, v in result.elements.items()}
    return replace(result, motions=motions, placed_paths=paths, elements=elements)


def _moved_path(path, rigid: Rigid):
    """Placed paths ``(K, T, 2)`` (x, z; NaN where not played) moved by ``rigid``."""
    p = np.asarray(path, dtype=float)
    pts = np.stack([p[..., 0], np.zeros(p.shape[:-1]), p[..., 1]], axis=-1)
    moved = rigid.apply_points(pts)
    return np.stack([moved[..., 0], moved[..., 2]], axis=-1)


def _moved_element(e, rigid: Rigid):
    if e.placement is None:
        return e
    r = Rigid(e.placement.yaw, (e.placement.x, e.placement.z)).then(rigid)
    return replace(e, placement=Placement(r.yaw, r.offset[0], r.offset[1]))

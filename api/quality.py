"""The literature's quality figures of a synthesised animation, per actor and per join (issue 11).

Everything here is measured after resampling to 30 fps
(:data:`core.metrics.COMPARE_FPS`), so a join compares with its source clips
at one rate:

- per actor, the whole motion's :class:`~core.metrics.Quality`;
- per join, the same figures on a window around it (its blend intervals
  widened by :data:`JOIN_MARGIN` on each side, where a velocity jump at a
  blend's edge shows), next to the figures of the two source clips (each
  whole clip) and whether the window meets each criterion of
  :func:`core.metrics.against_sources` (skating ≤ the sources' larger + 0.01,
  root pop and jerk p99 ≤ 1.2 × the sources' larger, floor penetration ≤ 1 cm,
  frozen frames ≤ 5 %, a foot floating ≤ the sources' larger + 2 cm);
- per join, what a body could not do on the frames the method made (``transition``,
  :func:`transition_figures`): the centre of mass outside the feet (:mod:`core.balance`), the hips
  gliding at a steady speed (:mod:`core.glide`) and the body held up in the air (:mod:`core.hang`), each
  with whether it is within what capture does;
- per actor, the root pop the method *introduced* (:func:`introduced_root_pop`): over the frames whose
  hips acceleration is not that of a source clip as placed (turned and moved, played verbatim, or moved
  by a constant offset), the worst jolt of the frames the method made itself.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from text2anim.core.metrics import (COMPARE_FPS, ROOT_POP_WINDOW, Quality, Series, against_sources, at_rate, quality,
                                    series, summarise, window_frames)

JOIN_MARGIN = 0.5  # s added before and after a join's blend intervals


def transition_figures(motion30, made: np.ndarray, per_frame: tuple[np.ndarray, np.ndarray, np.ndarray]) -> dict:
    """Balance (cm, :func:`core.balance.balance_cm`), the longest glide (s, :func:`core.glide.glide_s`) and the
    longest hang in the air (s, :func:`core.hang.hang_s`) of a motion at 30 fps over the bool mask ``made``
    ``(T,)`` of the frames a method made (a join's window, not played as recorded), each with whether it is
    within capture's limit. ``per_frame``: the motion's :func:`transition_frames` (taken once per actor, for
    all its joins)."""
    from text2anim.core import balance, glide, hang

    runs_cm, gliding, hanging = per_frame
    b = float(np.where(made, runs_cm, 0.0).max()) if len(made) else 0.0
    g = glide.longest_s(gliding & made, motion30.fps)
    h = float(np.where(made, hanging, 0.0).max()) if len(made) else 0.0
    return {"balance_cm": round(b, 2), "glide_s": round(g, 3), "hang_s": round(h, 3),
            "meets": {"balance": b <= balance.LIMIT_CM, "glide": g <= glide.LIMIT_S, "hang": h <= hang.LIMIT_S}}


def transition_frames(motion30) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per frame of a motion at 30 fps: the balance runs (:func:`core.balance.balance_runs_cm`), whether the
    hips glide (:func:`core.glide.gliding`) and how long its airborne run hangs (:func:`core.hang.hang_times`),
    ``(T,)`` each."""
    from text2anim.core import balance, glide, hang

    return balance.balance_runs_cm(motion30), glide.gliding(motion30), hang.hang_times(motion30)


def rounded(q: Quality) -> dict:
    """A :class:`Quality` as JSON-ready numbers, rounded so reports are stable and readable."""
    d = q.to_dict()
    for k in ("skating_ratio", "frozen_fraction", "skating_gmd"):
        d[k] = round(d[k], 4)
    for k in ("root_pop", "jerk_p99", "floor_penetration_cm", "floating_cm"):
        d[k] = round(d[k], 2)
    return d


def join_window(join, duration: float, margin: float = JOIN_MARGIN) -> tuple[float, float] | None:
    """``(t0, t1)`` seconds around a join's blend intervals (clamped to the motion), or None without any."""
    ivs = [iv for iv in join.intervals if iv.end > iv.begin]
    if not ivs:
        return None
    return max(0.0, min(iv.begin for iv in ivs) - margin), min(duration, max(iv.end for iv in ivs) + margin)


def actor_series(motions: dict, fps: float = COMPARE_FPS) -> dict[Any, Series]:
    """``{actor: Series}``: every actor's per-frame figures at ``fps`` (resampled, FK once), for
    :func:`actor_quality` and :func:`join_quality` both."""
    return {a: series(at_rate(m, fps)) for a, m in motions.items()}


def actor_quality(motions: dict, fps: float = COMPARE_FPS, series_of: dict | None = None) -> dict:
    """``{actor: Quality}`` of every actor's whole motion at ``fps``; ``series_of``: their
    :func:`actor_series`, when already taken."""
    per_actor = actor_series(motions, fps) if series_of is None else series_of
    return {a: summarise(per_actor[a]) for a in motions}


def join_quality(result, tracks: Sequence = (), fps: float = COMPARE_FPS,
                 series_of: dict | None = None) -> list[dict | None]:
    """Per join of ``result`` (same order), the figures of its window and of its source clips at ``fps``.

    Each entry: ``{"fps", "window_s": [t0, t1], "join": {...}, "sources": {"first": {...}, "second": {...}},
    "meets": {criterion: bool}}``; ``sources`` and ``meets`` only when ``tracks`` (the synthesis input)
    are given. None for a join without a blend interval (a motion not executed). ``series_of``: the
    :func:`actor_series` of ``result.motions`` when already taken (else taken here, as needed).
    """
    clips = {e.id: e.clip for t in tracks for e in t.elements}
    by_actor: dict = dict(series_of or {})
    by_clip: dict = {}
    made_by: dict = {}  # per actor: its motion at fps and the frames no placed clip plays as recorded
    out: list[dict | None] = []
    for j in result.joins:
        actor = result.actor_of(j.second)
        motion = result.motions.get(actor)
        window = join_window(j, motion.duration) if motion is not None else None
        if window is None:
            out.append(None)
            continue
        if actor not in by_actor:
            by_actor[actor] = series(at_rate(motion, fps))
        s = by_actor[actor]
        a, b = window_frames(s.fps, window)
        here = summarise(s, a, b)
        entry = {"fps": fps, "window_s": [round(window[0], 3), round(window[1], 3)], "join": rounded(here)}
        if actor not in made_by:
            m30 = at_rate(motion, fps)
            made_by[actor] = (m30, made_frames(result, actor, m30.n_frames, fps), transition_frames(m30))
        m30, made, per_frame = made_by[actor]
        entry["transition"] = transition_figures(m30, _within(made, a, b), per_frame)
        src = {}
        for key, eid in (("first", j.first), ("second", j.second)):
            clip = clips.get(eid)
            if clip is not None:
                if clip.name not in by_clip:
                    by_clip[clip.name] = quality(clip.motion, fps)
                src[key] = (clip.name, by_clip[clip.name])
        if src:
            entry["sources"] = {k: {"clip": name, **rounded(q)} for k, (name, q) in src.items()}
            entry["meets"] = against_sources(here, [q for _, q in src.values()])
        out.append(entry)
    return out


def made_frames(result, actor, n: int, fps: float = COMPARE_FPS) -> np.ndarray:
    """``(n,)`` bool at ``fps``: the frames of ``actor``'s motion in ``result`` that no placed clip plays as
    recorded (:func:`played_frames`; all of them where the placed paths are not known)."""
    paths = result.placed_paths.get(actor)
    if paths is None:
        return np.ones(n, dtype=bool)
    return ~played_frames(result.motions[actor], paths, fps)[:n]


def _within(mask: np.ndarray, a: int, b: int) -> np.ndarray:
    """``mask`` ``(T,)`` left True only on frames ``[a, b)`` (a window's frames, :func:`window_frames`)."""
    inside = np.zeros(len(mask), dtype=bool)
    inside[max(0, a):max(0, b)] = True
    return mask & inside


#: m: how far a hips path may stray from a placed element's moved by one constant offset and still be its own
PLAYED_TOL = 1e-3


def played_frames(motion, paths, fps: float = COMPARE_FPS) -> np.ndarray:
    """``(T,)`` bool at ``fps``: frames whose root pop (the hips' horizontal acceleration after the 3-frame
    average) is that of a source clip as placed: on every frame it is taken from (two either side) the
    hips are where one and the same placed element has them, moved by one constant offset (within
    :data:`PLAYED_TOL`). A constant offset changes no acceleration: a clip played verbatim, or moved
    whole (an adaptation's hips held by its feet's offsets), keeps its own figure there.

    ``motion``: a result's motion at its own rate; ``paths``: its ``(K, T0, 2)``
    :attr:`~synthesis.result.Result.placed_paths`, resampled here to ``fps`` as the motion is (linear).
    """
    m = at_rate(motion, fps)
    n = m.n_frames
    half = (ROOT_POP_WINDOW - 1) // 2 + 1  # frames either side the acceleration at a frame is taken from
    if n < 2 * half + 1 or len(paths) == 0:
        return np.zeros(n, dtype=bool)
    t_old = np.arange(paths.shape[1]) / motion.fps
    t_new = np.minimum(np.arange(n) / m.fps, t_old[-1])
    xz = m.root_positions[:, [0, 2]]
    own = np.zeros(n, dtype=bool)
    for path in paths:
        at = np.stack([np.interp(t_new, t_old, path[:, k]) for k in range(2)], axis=1)  # NaN spreads: not played
        off = np.lib.stride_tricks.sliding_window_view(xz - at, 2 * half + 1, axis=0)  # (n - 2 half, 2, 2 half + 1)
        spread = np.linalg.norm(off.max(axis=-1) - off.min(axis=-1), axis=-1)  # NaN where not played
        own[half:n - half] |= spread < PLAYED_TOL  # NaN compares False
    return own


def introduced_root_pop(result, fps: float = COMPARE_FPS, series_of: dict | None = None) -> dict[Any, float | None]:
    """``{actor: m/s²}``: the largest root pop a method introduced: over the frames whose hips acceleration
    is not a source clip's own as placed (:func:`played_frames`), at ``fps``; 0 where it plays its clips
    unchanged throughout; None for an actor whose placed paths are not known.

    The whole output's root pop often lies inside a source clip's core, which every method plays as
    recorded (a kick's own 9 m/s²); this reading is the worst jolt the method's own frames add: its
    blends, its adaptation's lower body, its post-pass, its foot locks, its holds.
    """
    out: dict[Any, float | None] = {}
    for actor, motion in result.motions.items():
        paths = result.placed_paths.get(actor)
        if paths is None:
            out[actor] = None
            continue
        s = (series_of or {}).get(actor) or series(at_rate(motion, fps))
        changed = ~played_frames(motion, paths, fps)
        acc = s.root_acc[changed]
        acc = acc[~np.isnan(acc)]
        out[actor] = round(float(acc.max()), 2) if acc.size else 0.0
    return out


def exported_figures(result, motions: dict, fps: float = COMPARE_FPS) -> dict[Any, tuple[Quality, list[dict]]]:
    """``{actor: (quality, transitions)}`` of ``motions``: ``result``'s animation as exported onto another
    character (retargeted frame for frame, at any size: :meth:`Animation.exported_motions` in metres),
    measured at a person's size (:func:`core.size.at_human_size`): the whole motion's :class:`Quality` at
    ``fps`` and, per join of the actor (in order, those with a blend interval), :func:`transition_figures`
    over its window on the frames the method made (found on ``result``'s own motion: a retarget keeps every
    frame where it is)."""
    from text2anim.core.size import at_human_size

    out: dict[Any, tuple[Quality, list[dict]]] = {}
    for actor, m in motions.items():
        m30 = at_rate(at_human_size(m)[0], fps)
        made = made_frames(result, actor, m30.n_frames, fps)
        per_frame = transition_frames(m30)
        mine = []
        for j in result.joins:
            window = join_window(j, m.duration) if result.actor_of(j.second) == actor else None
            if window is not None:
                mine.append(transition_figures(m30, _within(made, *window_frames(fps, window)), per_frame))
        out[actor] = (quality(m30, fps), mine)
    return out


def missed_criteria(entry: dict) -> list[str]:
    """The criteria a :func:`join_quality` entry misses, each with its figure and its limit:
    ``"jerk p99 3971 m/s³ > 1.2 × the sources' larger 2950 = 3540"`` (none without ``meets``)."""
    from text2anim.core import metrics

    here, meets = entry["join"], entry.get("meets", {})
    worst = {k: max((s[k] for s in entry.get("sources", {}).values()), default=0.0)
             for k in ("skating_ratio", "root_pop", "jerk_p99")}
    factor = metrics.SOURCE_FACTOR
    said = {
        "skating": f"skating ratio {here['skating_ratio']:.3f} > the sources' larger {worst['skating_ratio']:.3f} "
                   f"+ {metrics.SKATING_MARGIN:g}",
        "root_pop": f"root pop {here['root_pop']:.1f} m/s² > {factor:g} × the sources' larger "
                    f"{worst['root_pop']:.1f} = {factor * worst['root_pop']:.1f}",
        "jerk": f"jerk p99 {here['jerk_p99']:.0f} m/s³ > {factor:g} × the sources' larger {worst['jerk_p99']:.0f} "
                f"= {factor * worst['jerk_p99']:.0f}",
        "penetration": f"floor penetration {here['floor_penetration_cm']:.2f} cm > {metrics.MAX_PENETRATION_CM:g} cm",
        "frozen": f"frozen frames {100 * here['frozen_fraction']:.1f} % > {100 * metrics.MAX_FROZEN:g} %",
    }
    return [said[k] for k, ok in meets.items() if not ok]

"""The scene after synthesis: the actors moved where their relations want them, and the things placed.

:func:`place` is the pipeline's ``scene`` stage: it reads the rows of the time table at their played times
and each actor's synthesised motion, and returns the :class:`~scene.types.Scene`.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from text2anim.core.motion import Motion
from text2anim.nlp.lexicon import LAP_SECONDS, LOCOMOTION_VERBS
from text2anim.scheduler.types import Element

from .circling import centre, circle
from .fit import arrival, fit
from .relations import HANDS, HIPS_HEIGHT, relations
from .things import kicks, reach_instant, send_instant, things
from .types import Met, Scene, Spot, Staging

#: A relation that misses its heading by more than :data:`HEADING_SLACK` degrees, or one that places a body
#: (a goal, a partner, a patient, a recipient) and misses its distance by more than this (m, at a person's
#: size), is said in the scene's ``unplaced`` (it could not be met). An addressee's distance is only a
#: preference: a wave or a bow to someone already close is still for them.
DISTANCE_SLACK = 0.5
HEADING_SLACK = 30.0
PLACING_ROLES = frozenset(("goal", "partner", "patient", "recipient", "source"))


def place(staging: Staging, rows: Sequence[Element], motions: dict[str | None, Motion], fps: float) -> Scene:
    """The placed scene of ``rows`` (time-table rows at their played times) and ``motions`` (each actor's
    motion as synthesised from its spot of ``staging``)."""
    scale = {a: size_of(m) for a, m in motions.items()}
    motions, radii = _rounds(rows, motions, fps)
    sends = {r.id: t for r in rows if r.actor in motions
             and (t := send_instant(r, motions[r.actor], fps)) is not None}
    reaches = {r.id: reach_instant(r, motions[r.actor], HANDS[r.verb], fps) for r in rows
               if r.actor in motions and r.verb in HANDS}
    arrivals = {r.id: arrival(motions[r.actor], r.end) for r in rows
                if r.actor in motions and r.target_role == "goal"}
    rels = [replace(rel, distance=radii[rel.element]) if rel.element in radii else rel
            for rel in relations(rows, set(motions), scale, sends, reaches, arrivals)]
    steered, rigids, met = fit(motions, rels, kicks(rows, motions, fps))
    moved = {a: rigids[a].apply(m) for a, m in steered.items()}
    spots = tuple(_moved_spot(s, rigids) for s in staging.spots if s.actor in rigids)
    made, said = things(rows, moved, scale, fps)
    said = [*(_missed(m, scale) for m in met if _misses(m, scale)), *_unknown_targets(rows, motions, made), *said]
    return Scene(moved, rigids, spots, made, tuple(met), tuple(said), fps)


def _rounds(rows: Sequence[Element], motions: dict[str | None, Motion], fps: float
            ) -> tuple[dict[str | None, Motion], dict[int, float]]:
    """Each walk round something (a goal ``around``: 木の周りを三周歩く) steered into its laps (one each
    :data:`~nlp.lexicon.LAP_SECONDS` it plays, at least one: :func:`circling.circle`), and the radius (m) of each one's loops by its row's id: how far from the walker
    the person it goes round stands."""
    out, radii = dict(motions), {}
    for r in rows:
        if r.target_side == "around" and r.target_role == "goal" and r.actor in out and r.verb in LOCOMOTION_VERBS:
            m = out[r.actor]
            f0 = int(np.clip(round(r.start * fps), 0, m.n_frames - 1))
            f1 = int(np.clip(round(r.end * fps), f0 + 1, m.n_frames))
            out[r.actor] = circle(m, f0, f1, max(1, round((r.end - r.start) / LAP_SECONDS)))
            radii[r.id] = centre(out[r.actor], f0, f1)[1]
    return out, radii


def size_of(motion: Motion) -> float:
    """The actor's size against the built-in body: the hips' standing height (the 90th percentile: an actor
    who crouches or sits is no smaller) over :data:`HIPS_HEIGHT`."""
    return float(np.clip(np.percentile(motion.root_positions[:, 1], 90) / HIPS_HEIGHT, 0.05, 50.0))


def _moved_spot(spot: Spot, rigids) -> Spot:
    r = rigids[spot.actor]
    p = r.apply_points(np.array([spot.origin[0], 0.0, spot.origin[1]]))
    return Spot(spot.actor, (float(p[0]), float(p[2])), float(spot.heading + r.yaw))


def _misses(m: Met, scale) -> bool:
    size = scale.get(m.relation.actor, 1.0)
    far = abs(m.distance - m.relation.distance) > DISTANCE_SLACK * size and m.relation.role in PLACING_ROLES
    return far or m.heading_error_deg > HEADING_SLACK


def _missed(m: Met, scale) -> str:
    r = m.relation
    who = r.actor or "the default character"
    return (f"{who} {r.verb} ({r.role} {r.other}) at {r.time:.2f} s: {m.distance:.2f} m from {r.other} "
            f"(wanted {r.distance:.2f} m), facing {m.heading_error_deg:.0f}° off: both were already placed")


def _unknown_targets(rows: Sequence[Element], motions, made) -> list[str]:
    names = {t.name for t in made}
    out = []
    for r in rows:
        if r.target and r.target not in motions and r.target not in names and r.target_role not in (
                "support", "destination", "goal", "at", "source"):
            out.append(f"{r.target}: the text names this person, but they are not in the scene")
            names.add(r.target)
    return out

"""The synthesis tracks of a planned text: each row's clip loaded from the database.

The scheduler says which clip each row plays, mirrored or not, and unrolls a
repeated row into one row per repetition (:func:`scheduler.repeats.played_rows`);
here the clips are read, resampled to the output rate and mirrored, and each
track gets the captured idle its held poses play.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING

from text2anim.motiondb import ClipInfo, MotionDB, UnknownVerbError
from text2anim.scheduler.repeats import played_rows

if TYPE_CHECKING:  # synthesis loads when a motion is made: text2anim.plan never imports it
    from text2anim.core.motion import Motion
    from text2anim.scene import Staging
    from text2anim.synthesis import tracks as splan

    from .planning import Planned

#: The verb of the clips a held pose plays (a cyclic one: the built-in ``wait``, captured).
IDLE_VERB = "待つ"
#: Suffix of a mirrored clip's name on a track (a co-actor's or a repetition's variant).
MIRRORED = "~mirrored"


class ClipLoader:
    """Clips loaded from ``db`` once each, resampled to ``fps`` (and mirrored where asked)."""

    def __init__(self, db: MotionDB, fps: float):
        self.db, self.fps = db, fps
        self.cache: dict[tuple[str, bool], splan.Clip] = {}

    def get(self, info: ClipInfo, mirrored: bool = False) -> splan.Clip:
        key = (info.name, mirrored)
        if key not in self.cache:
            if mirrored:
                from text2anim.core.mirror import mirror

                plain = self.get(info)
                self.cache[key] = replace(plain, name=info.name + MIRRORED, motion=mirror(plain.motion))
            else:
                from text2anim.synthesis.tracks import Clip

                motion = self.db.load(info)
                if motion.fps != self.fps:
                    motion = motion.resample(self.fps)
                self.cache[key] = Clip(info.name, motion, tuple(info.core), info.cyclic, info.body_part)
        return self.cache[key]

    def idle(self, character: str, posture: str | None) -> Callable[[], Motion | None]:
        """The captured idle a track of ``character`` holds its poses with (the best cyclic clip of
        :data:`IDLE_VERB` for that character in ``posture``; none for a posture without one, such as
        lying), looked up when first asked."""
        def fetch() -> Motion | None:
            try:
                hits = self.db.search(IDLE_VERB, character=character, prefer_start_posture=posture, limit=1)
            except UnknownVerbError:
                return None
            fits = hits and hits[0].cyclic and hits[0].start_posture == posture
            return self.get(hits[0]).motion if fits else None

        return fetch


def build_tracks(planned: Planned, db: MotionDB, fps: float, staging: Staging | None = None) -> list[splan.Track]:
    """The synthesis tracks of a time table: its played rows with their clips loaded from ``db`` at ``fps``,
    each actor at its spot of ``staging`` (default: :func:`scene.stage` of ``planned``).

    Every row of the table plays, the fillers of the waits included (:mod:`scheduler.fillers`),
    a repeated one as one element per repetition (:mod:`scheduler.repeats`).
    """
    from text2anim.scene import stage
    from text2anim.synthesis.tracks import Element, Track

    staging = staging if staging is not None else stage(planned)

    clips = ClipLoader(db, fps)
    tracks = []
    for actor in played_rows(planned):
        elements = []
        for played in actor.rows:
            r = played.row
            elements.append(Element(r.id, clips.get(played.clip, played.mirrored), r.start, r.end, r.method, r.prev,
                                    r.speed, r.repeat, r.hold, r.body_part))
        last = actor.last
        idle = clips.idle(last.character, last.end_posture) if last is not None else None
        spot = staging.spot(actor.actor)
        tracks.append(Track(actor.actor, tuple(elements), spot.origin, spot.heading, idle=idle))
    return tracks


def contact_instants(planned: Planned, db: MotionDB, fps: float) -> Callable:
    """``instant(row) -> seconds``: when a row's clip makes contact with another person, on the animation's
    clock (:mod:`scene.timing`): the hand's reach (both hands for a hug, a taking or a catch) within the
    clip's core (:func:`core.contact_instant.contact_instant`); for a throw, its release and the thing's
    flight; the clip read as the row plays it."""
    from text2anim.core.contact_instant import contact_instant
    from text2anim.scene.things import THROW
    from text2anim.scene.timing import FLIGHT_S

    clips = ClipLoader(db, fps)

    def instant(row) -> float | None:
        info = planned.clips.get(row.id)
        if info is None:
            return None
        m = clips.get(info, row.id in planned.mirrored).motion
        side = "left" if row.id in planned.mirrored else "right"
        if row.verb in THROW:
            return row.start + contact_instant(m, f"{side}_hand", "release", info.core) / m.fps / row.speed + FLIGHT_S
        effector = "both_hands" if row.verb in BOTH_HANDS else f"{side}_hand"
        return row.start + contact_instant(m, effector, "reach", info.core) / m.fps / row.speed

    return instant


#: Contact verbs done with both hands (the instant is when both reach furthest).
BOTH_HANDS = frozenset("受け取る 貰う 抱き合う 抱き締める 取る キャッチする 受け止める 捕まえる".split())


__all__ = ["BOTH_HANDS", "IDLE_VERB", "MIRRORED", "ClipLoader", "build_tracks", "contact_instants"]

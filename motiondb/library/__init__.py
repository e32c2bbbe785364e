"""The built-in motion library: real motion capture where it exists, keyframes elsewhere.

``builtin_clips(fps)`` gives every clip as a :class:`motiondb.types.ClipRecord`
on :func:`canonical_skeleton` (see :mod:`.skeleton`): the clips cut from CMU
motion capture (:mod:`.capture`: the cut list ``capture.toml`` and the arrays
``capture.npz`` that ``tools/library/build_capture.py`` makes from it), and the keyframed clips for
actions no capture covers (bow, clap, cheer, ...). A keyframed clip that a
captured one ``replaces`` is not in the library. ``source`` says which is
which: ``builtin:capture:CMU <trial> <seconds>`` or ``builtin:keyframed:<file>``.

The keyframed clips are data:
``clips/*.json`` hold key poses, timing, root travel, foot plants, the core
interval and the verbs (format in :mod:`.keyframes`); ``clips/_poses.json``
the shared named poses (``stand``, ...). Generation is deterministic
(the same bytes on every run) and cached per frame rate; a database is seeded
from its result at 30 fps shipped as ``keyframed.npz`` (:mod:`.keyframed`,
rebuilt by ``python tools/library/build_keyframed.py``), so the
first run generates nothing. Generating (:func:`build_all`) goes:

1. the keyed curves are sampled with scipy splines (:mod:`.keyframes`);
2. the feet are planted exactly by leg IK (:mod:`.plant`);
3. hands are put on their ``reach`` targets by arm IK (:mod:`.reach`);
4. cyclic clips are generated with one extra cycle on each side and cut,
   so the last frame flows into the first;
5. the clip is lifted by the shoe sole (:data:`.skeleton.SHOE_SOLE`, 1.8 cm):
   keyed heights are from the bare sole, the floor is where a shod foot
   stands. Knees and hands keyed onto the floor (kneeling, lying) then rest
   with their joint centres 1.8 cm higher too, 5-7 cm up: a knee's or wrist's
   own thickness. Swinging feet keep the clearance every output keeps
   (:func:`core.clearance.clear_swings`), and no joint or end site (a toe
   tip, a fingertip) goes under the floor (:func:`core.clearance.clear_floor`).

A clip declared for the right side (``body_part="right_arm"``) serves a
left-side request through :func:`core.mirror.mirror`.

Postures: a clip's data says how it starts and ends (``starts``/``ends``:
``stand`` by default, ``sit``, ``crouch``, ``kneel``, ``floor``, ``hold``); the record
carries them as :data:`motiondb.types.POSTURES` words (:data:`POSTURE_OF`), so
the pipeline can chain clips whose postures meet (``sit_down`` then
``stand_up``, ``crouch_down`` then ``stand_from_crouch``, ``kneel`` then ``stand_from_kneel``, ``fall`` then
``get_up``).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING

import numpy as np

from text2anim.motiondb.types import ClipRecord, Posture
from text2anim.core.motion import Motion

from . import capture, keyframed
from .keyframes import CLIPS_DIR, POSTURE_OF, ClipData, ClipDataError, PlantSpec, load_json_dir, parse_clip
from .near import with_near_synonyms
from .actions import with_actions
from .skeleton import ANKLE_HEIGHT, SHOE_SOLE, TOE_HEIGHT, canonical_skeleton

if TYPE_CHECKING:  # the generator (scipy.interpolate, IK) is imported by build_clip only: seeding reads keyframed.npz
    from .plant import FramePlant, PlantReport

__all__ = ["BuiltClip", "ClipDataError", "POSTURE_OF", "builtin_clips", "build_all",
           "canonical_skeleton"]

SOURCE = "builtin:keyframed"

#: Sole points (heel, ball) in the ankle's frame: what touches the ground.
SOLE = np.array([
    [0.0, -ANKLE_HEIGHT, -0.05],
    [0.0, -ANKLE_HEIGHT, 0.13],
])


@dataclass(frozen=True)
class BuiltClip:
    """A generated clip and how its foot planting went (for tests and previews)."""

    record: ClipRecord
    report: PlantReport | None
    data: ClipData

    @property
    def starts(self) -> str:
        """The posture the clip starts in: ``stand`` (the relaxed standing pose), ``sit``, ``hold``, ..."""
        return self.data.raw.get("starts", "stand")

    @property
    def ends(self) -> str:
        """The posture the clip ends in (``stand`` unless the data says ``sit``, ``crouch``, ``kneel``, ``floor``,
        ``hold``)."""
        return self.data.raw.get("ends", "stand")

    @property
    def start_posture(self) -> Posture:
        """:attr:`starts` as a :data:`motiondb.types.POSTURES` word (``standing``, ``seated``, ...)."""
        return POSTURE_OF[self.starts]

    @property
    def end_posture(self) -> Posture:
        """:attr:`ends` as a :data:`motiondb.types.POSTURES` word."""
        return POSTURE_OF[self.ends]


def _posture(raw: dict, key: str, name: str) -> Posture:
    word = raw.get(key, "stand")
    if word not in POSTURE_OF:
        raise ClipDataError(f"{name}: {key} must be one of {', '.join(POSTURE_OF)}, not {word!r}")
    return POSTURE_OF[word]


def _frame_plants(clip: ClipData, t_first: float, h: float, t_last: float) -> list[FramePlant]:
    from .plant import FramePlant

    n = int(round((t_last - t_first) / h)) + 1
    always = [FramePlant(p.side, 0, n - 1, int(round(-t_first / h))) for p in clip.plants if np.isinf(p.start)]
    plants = [p for p in clip.plants if not np.isinf(p.start)]
    if clip.cyclic:
        reps: list[PlantSpec] = []
        for k in range(-2, clip.cycles + 3):
            reps.extend(p.shifted(k * clip.period) for p in plants)
        plants = [p for p in reps if p.stop >= t_first - 1e-9 and p.start <= t_last + 1e-9]
    out = []
    for p in plants:
        start = int(np.ceil((p.start - t_first) / h - 1e-6))
        stop = int(np.floor((p.stop - t_first) / h + 1e-6))
        anchor = int(round((p.anchor - t_first) / h))
        heel = None if p.heel_off is None else int(round((p.heel_off - t_first) / h))
        flat = None if p.flat is None else int(round((p.flat - t_first) / h))
        out.append(FramePlant(p.side, start, stop, anchor, heel, p.toe_off, flat, p.strike, p.keep, p.pitch))
    return always + out


def build_clip(clip: ClipData, poses: dict, fps: float) -> tuple[Motion, PlantReport | None]:
    """Generate one clip's motion at ``fps`` (cyclic clips: an exact whole number of frames per cycle)."""
    from text2anim.core.clearance import clear_floor, clear_swings
    from text2anim.core.floor import shifted

    from .keyframe_curves import curves_to_motion, sample_curves
    from .plant import plant_feet
    from .reach import apply_reach

    skel = canonical_skeleton()
    if clip.cyclic:
        per = max(2, int(round(clip.period * fps)))
        h = clip.period / per
        n = per * clip.cycles
        margin = per
        times = (np.arange(n + 2 * margin) - margin) * h
    else:
        h = 1.0 / fps
        n = int(np.floor(clip.duration * fps + 1e-6)) + 1
        margin = 0
        times = np.arange(n) * h
    curves = sample_curves(clip, poses, skel, times)
    motion = curves_to_motion(curves, skel, fps)
    report = None
    if clip.plants:
        plants = _frame_plants(clip, float(times[0]), h, float(times[-1]))
        motion, report = plant_feet(motion, plants, toe_height=TOE_HEIGHT, sole=SOLE,
                                    report_frames=slice(margin, margin + n))
    motion = apply_reach(motion, clip.raw.get("reach", {}), times, clip.name)
    if margin:
        motion = motion.frames(margin, margin + n)
    return clear_floor(clear_swings(shifted(motion, SHOE_SOLE))), report


@lru_cache(maxsize=8)
def build_all(fps: float = 30.0) -> tuple[BuiltClip, ...]:
    """Every built-in clip at ``fps`` with its plant report (cached; the motions are read-only)."""
    poses, raws = load_json_dir(CLIPS_DIR)
    out = []
    names = set()
    for raw in raws:
        clip = parse_clip(raw)
        if clip.name in names:
            raise ClipDataError(f"two built-in clips are named {clip.name!r}")
        names.add(clip.name)
        motion, report = build_clip(clip, poses, float(fps))
        core = clip.core
        if clip.cyclic and raw.get("core") in (None, "all"):
            core = (0.0, motion.duration)  # a whole number of frames per cycle: the exact loop length
        record = ClipRecord(
            name=clip.name, motion=motion, verbs=clip.verbs, objects=clip.objects,
            character="default", core=core, body_part=clip.body_part, cyclic=clip.cyclic,
            source=f"{SOURCE}:{raw.get('_file', clip.name)}",
            start_posture=_posture(raw, "starts", clip.name), end_posture=_posture(raw, "ends", clip.name),
        )
        out.append(BuiltClip(record, report, clip))
    return tuple(out)


def builtin_clips(fps: float = 30.0) -> list[ClipRecord]:
    """The built-in library as :class:`ClipRecord` s on :func:`canonical_skeleton` (deterministic, cached):
    the keyframed clips no capture replaces, then the captured ones, with the near-synonyms of
    ``near.json`` (:mod:`motiondb.library.near`) added to their verbs and their actions from
    ``actions.json`` (:mod:`motiondb.library.actions`).

    At the shipped rate (:data:`.keyframed.FPS`, 30 fps, what a database is seeded with) the
    keyframed clips are read from ``keyframed.npz`` (:mod:`.keyframed`); at another rate they
    are generated (:func:`build_all`: a cyclic clip keeps a whole number of frames per cycle)."""
    if float(fps) == keyframed.FPS:
        keyed = list(keyframed.keyframed_records())
    else:
        gone = capture.replaced()
        keyed = [b.record for b in build_all(float(fps)) if b.record.name not in gone]
    return with_actions(with_near_synonyms(keyed + list(capture.capture_records(float(fps)))))

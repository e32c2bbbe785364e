"""A clip's keyframe data (JSON): the format, loading and validation (:func:`parse_clip`); the curves are
sampled into a :class:`core.motion.Motion` by :mod:`~text2anim.motiondb.library.keyframe_curves`.

The data format (one clip object per file in ``clips/``, or a family file
``{"clips": [...]}``; files whose name starts with ``_`` hold shared data):

``name``, ``verbs`` (primary lemma first, as a morphological analyser gives
it; spelling variants as further synonyms), ``objects``, ``body_part``,
``cyclic``, ``core`` (``[begin, end]`` seconds; cyclic clips: the whole
clip), ``starts``/``ends`` (the posture at either end: ``stand`` by default,
else ``sit`` (on a 0.45 m seat), ``crouch`` (squatting on flat feet, the
``crouch`` pose), ``kneel`` (on the right knee, the left foot forward, the
``kneel`` pose), ``floor`` (lying face down, as ``fall`` ends), ``hold``
(standing, an object in the hands); stored as the database's postures, see
:data:`POSTURE_OF`), ``about`` (a note for readers);

timing: ``duration`` seconds (one-shot clips), or for cyclic clips
``period`` (seconds of one cycle), ``cycles`` (>= 2) and ``travel``
(``[dx, dy, dz]`` root displacement per cycle);

``keys``: a list of key poses ``{"t": seconds, "pose": NAME, "set": {JOINT:
[x, y, z]}, "root": {"x": .., "y": .., "z": ..}}``. Angles are degrees of
the joint's local rotation ``R = Rz(z) Ry(y) Rx(x)`` (the BVH ZYX channel
order) from the T-pose rest. ``"pose"`` keys every joint (and the root
height) of a named pose from ``_poses.json``; ``"set"`` keys the joints it
lists (over the named pose if both are given). A joint name
``"both:Arm"`` keys ``LeftArm`` with ``[x, y, z]`` and ``RightArm`` with
the mirror image ``[x, -y, -z]``, so a symmetric pose is written once.
Every channel is interpolated over *its own* keys (an animator's curves:
a joint not mentioned in a key keeps moving smoothly through it), held
before its first and after its last key; joints never keyed keep the
``base`` pose (default ``stand``). Root ``x``/``z`` are absolute metres; a
one-shot clip starts at the origin (they are 0 at its first key unless keyed
there); in a cyclic clip they are positions in the first cycle, the travel
being added per cycle.

Conventions of the canonical skeleton worth knowing when writing angles:
hip flexion (thigh forward) is ``-x``; knee flexion ``+x``; ankle
plantarflexion (toes down) ``+x``; spine/neck/head bending forward ``+x``,
turning left ``+y``; left arm: down ``-z`` (``-80`` hangs), forward ``-y``;
left elbow flexion ``-y`` (write arms with ``both:`` or mirror by hand).

Interpolation (scipy): one-shot clips use ``PchipInterpolator``'s slopes
(shape preserving: holds stay still, keys are not overshot) in a
``CubicHermiteSpline`` whose first and last slopes are zero (each channel
eases out of its first key and settles into its last; ``"interp":
"spline"`` asks for a clamped ``CubicSpline``), cyclic clips a periodic
``CubicSpline`` so the loop is C2. Euler angles are interpolated, then
converted with ``Rotation.from_euler``.

Extras: ``drag`` (``{JOINT: seconds}``: the joint follows its curve that
much later, for overlap/follow-through; forearms and hands drag a little by
default), ``sway`` (scale of the deterministic idle layer: weight shift,
breathing, small head and arm drift; 1 for one-shot whole-body clips by
default, 0 for cyclic ones, whose sway frequencies are rounded to whole
cycles per period), ``flight`` (``[[takeoff, landing], ...]``: root follows
a ballistic parabola between those keys), ``reach`` (hand targets, see
:mod:`motiondb.library.reach`) and ``plants``:

``plants``: ``"both"`` (both feet planted all along, where they stand at the
first frame) or ``{"left": [PLANT, ...], "right": [...]}`` with ``PLANT``
either ``[t0, t1]`` or ``{"t": [t0, t1], "anchor": seconds|"start"|"mid"|
"end", "strike": deg, "flat": s, "heel_off": s, "toe_off": deg, "pitch": deg,
"keep": bool}``: the foot is on the ground from ``t0`` to ``t1`` where the keyed
foot is at ``anchor`` (default: start; cyclic clips: middle), landing on the
heel with the toes ``strike`` degrees up (negative: on the ball) until
``flat``, rolling onto the ball from ``heel_off`` to ``toe_off`` degrees at
``t1`` (a ``heel_off`` before ``t0``: it lands with the heel already rising);
``pitch`` holds it on the ball, the heel that many degrees up, over the plant
where ``strike`` and ``heel_off`` say nothing (the rear foot of a kneel, toes
tucked under); ``keep`` holds the foot as keyed instead of flat. Cyclic plants may reach
outside ``[0, period)``: they repeat every period. See
:mod:`motiondb.library.plant` for how they are made exact.
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Generic, TypeVar

import numpy as np

from text2anim.core.bodyparts import BodyPart
from text2anim.core.skeleton import Skeleton
from text2anim.motiondb.types import Posture

CLIPS_DIR = Path(__file__).with_name("clips")

#: The data's ``starts``/``ends`` words (keyframe clips and the capture cut list) -> the database's
#: posture (``hold``: standing with an object in the hands; ``kneel``: on one knee; ``floor``: lying face
#: down, as ``fall`` ends).
POSTURE_OF: dict[str, Posture] = {"stand": "standing", "hold": "standing", "sit": "seated", "crouch": "crouched",
                                  "kneel": "kneeling", "floor": "lying"}


class ClipDataError(ValueError):
    """Keyframe data that cannot be turned into a clip (names the clip and the problem)."""


Unit = TypeVar("Unit", int, float)


@dataclass(frozen=True)
class Plant(Generic[Unit]):
    """A foot plant: the ball of ``side``'s foot is on the ground from ``start`` to ``stop``, in seconds as
    the keyframe data gives it (:data:`PlantSpec`) or in frames, inclusive, as the generator plants it
    (:data:`FramePlant`, :mod:`~text2anim.motiondb.library.plant`).

    ``anchor``: the time whose forward-kinematics foot fixes where (and facing
    where) the foot is planted. ``strike``: the foot lands on its heel with the
    toes that many degrees up and is flat at ``flat``. ``heel_off``: from then
    on the heel rises (toe pivot) to ``toe_off`` degrees at ``stop``. ``pitch``: elsewhere on the plant the
    heel is held that many degrees up (on the ball of the foot). ``keep``: hold the foot as the keys
    have it at ``anchor`` instead of flat on the ground (a foot resting on its toes).
    """

    side: str
    start: Unit
    stop: Unit
    anchor: Unit
    heel_off: Unit | None = None
    toe_off: float = 0.0
    flat: Unit | None = None
    strike: float = 0.0
    keep: bool = False
    pitch: float = 0.0

    def shifted(self, dt: Unit) -> "Plant[Unit]":
        """The same plant ``dt`` later."""
        return Plant(self.side, self.start + dt, self.stop + dt, self.anchor + dt,
                     None if self.heel_off is None else self.heel_off + dt, self.toe_off,
                     None if self.flat is None else self.flat + dt, self.strike, self.keep, self.pitch)


#: A plant in seconds (the keyframe data's) and in frames (the generator's).
PlantSpec = Plant[float]
FramePlant = Plant[int]


@dataclass
class ClipData:
    """A parsed clip file."""

    raw: dict
    name: str
    verbs: tuple[str, ...]
    objects: tuple[str, ...] = ()
    body_part: BodyPart | None = None
    cyclic: bool = False
    core: tuple[float, float] | None = None
    duration: float = 0.0
    period: float = 0.0
    cycles: int = 1
    travel: np.ndarray = field(default_factory=lambda: np.zeros(3))
    plants: list[PlantSpec] = field(default_factory=list)


# ----------------------------------------------------------------- loading
def load_json_dir(directory: Path = CLIPS_DIR) -> tuple[dict, list[dict]]:
    """``(poses, clip objects)`` from every ``*.json`` in ``directory`` (sorted by file name)."""
    poses: dict = {}
    clips: list[dict] = []
    for path in sorted(directory.glob("*.json")):
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
        if path.name.startswith("_"):
            poses.update(data.get("poses", {}))
            continue
        items = data["clips"] if "clips" in data else [data]
        for item in items:
            item.setdefault("_file", path.name)
            clips.append(item)
    return poses, clips


def expand_joints(values: dict, skeleton: Skeleton, where: str) -> dict[int, np.ndarray]:
    """``{JOINT or "both:Suffix": [x, y, z]}`` -> ``{joint index: angles}`` (mirrored for ``both:``)."""
    out: dict[int, np.ndarray] = {}
    for key, ang in values.items():
        a = np.asarray(ang, dtype=np.float64)
        if a.shape != (3,):
            raise ClipDataError(f"{where}: {key} needs [x, y, z] degrees, got {ang!r}")
        pairs: tuple[tuple[str, np.ndarray], ...]
        if key.startswith("both:"):
            suffix = key[5:]
            pairs = (("Left" + suffix, a), ("Right" + suffix, a * np.array([1.0, -1.0, -1.0])))
        else:
            pairs = ((key, a),)
        for name, v in pairs:
            try:
                out[skeleton.index(name)] = v
            except KeyError:
                raise ClipDataError(f"{where}: unknown joint {name!r}") from None
    return out


def resolve_pose(name: str, poses: dict, skeleton: Skeleton, where: str, _seen=()) -> tuple[dict, dict]:
    """A named pose as ``({joint index: angles}, {"y": root height, ...})``, following ``base`` chains."""
    if name not in poses:
        raise ClipDataError(f"{where}: unknown pose {name!r}")
    if name in _seen:
        raise ClipDataError(f"{where}: pose {name!r} is based on itself")
    p = poses[name]
    joints: dict[int, np.ndarray] = {}
    root: dict[str, float] = {}
    if "base" in p:
        joints, root = resolve_pose(p["base"], poses, skeleton, where, _seen + (name,))
        joints, root = dict(joints), dict(root)
    joints.update(expand_joints(p.get("joints", {}), skeleton, f"{where} (pose {name})"))
    root.update(p.get("root", {}))
    return joints, root


def _plant_list(raw, clip: ClipData) -> list[PlantSpec]:
    if raw is None:
        return []
    if raw == "both":  # both feet planted for the whole clip
        return [PlantSpec(side, -np.inf, np.inf, 0.0) for side in ("left", "right")]
    out = []
    for side in ("left", "right"):
        for item in raw.get(side, []):
            flat, strike, keep, pitch = None, 0.0, False, 0.0
            if isinstance(item, dict):
                keep = bool(item.get("keep", False))
                t0, t1 = item["t"]
                anchor = item.get("anchor")
                heel_off = item.get("heel_off")
                toe_off = float(item.get("toe_off", 0.0))
                flat = item.get("flat")
                strike = float(item.get("strike", 0.0))
                pitch = float(item.get("pitch", 0.0))
            else:
                t0, t1 = item
                anchor, heel_off, toe_off = None, None, 0.0
            if anchor in (None, "start"):
                anchor = (t0 + t1) / 2 if clip.cyclic and anchor is None else t0
            elif anchor == "mid":
                anchor = (t0 + t1) / 2
            elif anchor == "end":
                anchor = t1
            if not t0 < t1:
                raise ClipDataError(f"{clip.name}: plant {side} {item!r} is empty")
            out.append(PlantSpec(side, float(t0), float(t1), float(anchor),
                                 None if heel_off is None else float(heel_off), toe_off,
                                 None if flat is None else float(flat), strike, keep, pitch))
    return out


def parse_clip(raw: dict) -> ClipData:
    name = raw.get("name") or raw.get("_file", "?")
    try:
        clip = ClipData(raw=raw, name=name, verbs=tuple(raw["verbs"]))
    except KeyError:
        raise ClipDataError(f"{name}: no verbs") from None
    clip.objects = tuple(raw.get("objects", ()))
    clip.body_part = raw.get("body_part")
    clip.cyclic = bool(raw.get("cyclic", False))
    if clip.cyclic:
        clip.period = float(raw["period"])
        clip.cycles = int(raw.get("cycles", 2))
        clip.travel = np.asarray(raw.get("travel", [0.0, 0.0, 0.0]), dtype=np.float64)
        clip.duration = clip.period * clip.cycles
        if clip.cycles < 2:
            raise ClipDataError(f"{name}: a cyclic clip needs at least two cycles")
    else:
        keys = raw.get("keys", [])
        clip.duration = float(raw.get("duration", max((k["t"] for k in keys), default=0.0)))
    core = raw.get("core")
    clip.core = (0.0, clip.duration) if core in (None, "all") else (float(core[0]), float(core[1]))
    clip.plants = _plant_list(raw.get("plants"), clip)
    return clip

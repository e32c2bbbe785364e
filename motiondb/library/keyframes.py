"""Turn a clip's keyframe data (JSON) into a :class:`core.motion.Motion`.

The data format (one clip object per file in ``clips/``, or a family file
``{"clips": [...]}``; files whose name starts with ``_`` hold shared data):

``name``, ``verbs`` (primary lemma first, as a morphological analyser gives
it; spelling variants as further synonyms), ``objects``, ``body_part``,
``cyclic``, ``core`` (``[begin, end]`` seconds; cyclic clips: the whole
clip), ``starts``/``ends`` (the posture at either end: ``stand`` by default,
else ``sit`` (on a 0.45 m seat), ``crouch`` (squatting on flat feet, the
``crouch`` pose), ``floor`` (lying face down, as ``fall`` ends), ``hold``
(standing, an object in the hands); stored as the database's postures, see
:data:`motiondb.library.POSTURE_OF`), ``about`` (a note for readers);

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
"end", "strike": deg, "flat": s, "heel_off": s, "toe_off": deg, "keep":
bool}``: the foot is on the ground from ``t0`` to ``t1`` where the keyed foot
is at ``anchor`` (default: start; cyclic clips: middle), landing on the heel
with the toes ``strike`` degrees up (negative: on the ball) until ``flat``,
rolling onto the ball from ``heel_off`` to ``toe_off`` degrees at ``t1``;
``keep`` holds the foot as keyed instead of flat. Cyclic plants may reach
outside ``[0, period)``: they repeat every period. See
:mod:`motiondb.library.plant` for how they are made exact.
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.interpolate import CubicHermiteSpline, CubicSpline, PchipInterpolator
from scipy.spatial.transform import Rotation

from text2anim.core.bodyparts import BodyPart
from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton

CLIPS_DIR = Path(__file__).with_name("clips")
GRAVITY = 9.81

#: Default follow-through (seconds of lag) of the joints' curves.
DEFAULT_DRAG = {"LeftForeArm": 0.03, "RightForeArm": 0.03, "LeftHand": 0.06, "RightHand": 0.06}

#: The idle layer: (joint or "root.x"/"root.z", channel, amplitude, frequency Hz).
#: Amplitudes in degrees (metres for the root). Every term is a sine starting at
#: zero, so each clip starts exactly on its first key pose.
SWAY_TERMS = (
    ("root", 0, 0.006, 0.21), ("root", 0, 0.003, 0.53), ("root", 2, 0.003, 0.31),
    ("Spine", 2, 0.5, 0.21), ("Spine", 0, 0.4, 0.29),
    ("Spine1", 0, 0.7, 0.24),  # breathing
    ("LeftShoulder", 2, 0.6, 0.24), ("RightShoulder", 2, -0.6, 0.24),
    ("Neck1", 1, 1.2, 0.17), ("Head", 0, 0.8, 0.37), ("Head", 2, 0.6, 0.23),
    ("LeftArm", 2, 1.2, 0.33), ("RightArm", 2, -1.0, 0.27),
    ("LeftArm", 1, 1.0, 0.19), ("RightArm", 1, -1.2, 0.23),
    ("LeftForeArm", 1, -1.5, 0.41), ("RightForeArm", 1, 1.5, 0.37),
)


class ClipDataError(ValueError):
    """Keyframe data that cannot be turned into a clip (names the clip and the problem)."""


@dataclass(frozen=True)
class PlantSpec:
    """A foot plant in seconds: the ball of ``side``'s foot is on the ground from ``t0`` to ``t1``.

    ``anchor``: the time whose forward-kinematics foot fixes where (and facing
    where) the foot is planted. ``strike``: the foot lands on its heel with the
    toes that many degrees up and is flat at ``flat``. ``heel_off``: from then
    on the heel rises (toe pivot) to ``toe_off`` degrees at ``t1``. ``keep``: hold the foot as the keys
    have it at ``anchor`` instead of flat on the ground (a foot resting on its toes).
    """

    side: str
    t0: float
    t1: float
    anchor: float
    heel_off: float | None = None
    toe_off: float = 0.0
    flat: float | None = None
    strike: float = 0.0
    keep: bool = False

    def shifted(self, dt: float) -> "PlantSpec":
        return PlantSpec(self.side, self.t0 + dt, self.t1 + dt, self.anchor + dt,
                         None if self.heel_off is None else self.heel_off + dt, self.toe_off,
                         None if self.flat is None else self.flat + dt, self.strike, self.keep)


@dataclass
class Curves:
    """Sampled keyframe curves: ``root`` ``(T, 3)`` metres, ``euler`` ``(T, J, 3)`` degrees (x, y, z)."""

    times: np.ndarray
    root: np.ndarray
    euler: np.ndarray


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
            flat, strike, keep = None, 0.0, False
            if isinstance(item, dict):
                keep = bool(item.get("keep", False))
                t0, t1 = item["t"]
                anchor = item.get("anchor")
                heel_off = item.get("heel_off")
                toe_off = float(item.get("toe_off", 0.0))
                flat = item.get("flat")
                strike = float(item.get("strike", 0.0))
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
                                 None if flat is None else float(flat), strike, keep))
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


# ---------------------------------------------------------- interpolation
def interpolator(t: np.ndarray, v: np.ndarray, kind: str, period: float | None):
    """A callable ``f(times) -> values`` through the keys ``(t, v)`` (``v`` is ``(K, ...)``)."""
    if len(t) == 1:
        return lambda x: np.broadcast_to(v[0], (len(x),) + v.shape[1:]).copy()
    if period is not None:
        tt = np.concatenate([t, [t[0] + period]])
        vv = np.concatenate([v, v[:1]])
        spline = CubicSpline(tt, vv, axis=0, bc_type="periodic")
        return lambda x: spline(t[0] + np.mod(np.asarray(x) - t[0], period))
    if kind == "spline":
        f = CubicSpline(t, v, axis=0, bc_type="clamped")
    elif kind == "linear":
        return lambda x: np.stack([np.interp(np.clip(x, t[0], t[-1]), t, v[:, k]) for k in range(v.shape[1])], axis=-1)
    else:
        # PCHIP slopes (shape preserving), but at rest on the first and last key: a one-shot clip
        # eases out of its first pose and settles into its last.
        slopes = PchipInterpolator(t, v, axis=0).derivative()(t)
        slopes[0] = 0.0
        slopes[-1] = 0.0
        f = CubicHermiteSpline(t, v, slopes, axis=0)
    return lambda x: f(np.clip(x, t[0], t[-1]))


def _flight_keys(root_keys: list[tuple[float, dict]], flights, where: str) -> list[tuple[float, dict]]:
    """Add dense root keys along a ballistic parabola between each takeoff and landing key."""
    by_t = {t: r for t, r in root_keys}
    extra = []
    for t_off, t_land in flights:
        if t_off not in by_t or t_land not in by_t:
            raise ClipDataError(f"{where}: flight {t_off}-{t_land} needs root keys at both ends")
        a, b = by_t[t_off], by_t[t_land]
        for axis in ("x", "y", "z"):
            if (axis in a) != (axis in b):
                raise ClipDataError(f"{where}: flight ends key root {axis} differently")
        dur = t_land - t_off
        n = max(2, int(np.ceil(dur * 60)))
        for k in range(1, n):
            tau = dur * k / n
            r = {}
            for axis in ("x", "z"):
                if axis in a:
                    r[axis] = a[axis] + (b[axis] - a[axis]) * tau / dur
            if "y" in a:
                v0 = (b["y"] - a["y"] + GRAVITY * dur ** 2 / 2) / dur
                r["y"] = a["y"] + v0 * tau - GRAVITY * tau ** 2 / 2
            extra.append((t_off + tau, r))
    merged = sorted(root_keys + extra, key=lambda kv: kv[0])
    return merged


def sample_curves(clip: ClipData, poses: dict, skeleton: Skeleton, times: np.ndarray) -> Curves:
    """Evaluate the clip's root and joint-angle curves at ``times`` (seconds)."""
    raw = clip.raw
    where = clip.name
    J = skeleton.n_joints
    base_name = raw.get("base", "stand")
    base_joints, base_root = resolve_pose(base_name, poses, skeleton, where)
    joint_keys: dict[int, list[tuple[float, np.ndarray]]] = {}
    root_keys: list[tuple[float, dict]] = []
    last_t = -np.inf
    for key in raw.get("keys", []):
        t = float(key["t"])
        if t <= last_t:
            raise ClipDataError(f"{where}: key times must increase ({t} after {last_t})")
        last_t = t
        vals: dict[int, np.ndarray] = {}
        key_root: dict = {}
        if "pose" in key:
            pj, pr = resolve_pose(key["pose"], poses, skeleton, f"{where} t={t}")
            vals.update(pj)
            key_root.update({k: v for k, v in pr.items() if k == "y"})
        vals.update(expand_joints(key.get("set", {}), skeleton, f"{where} t={t}"))
        r = key.get("root")
        if isinstance(r, (list, tuple)):
            r = dict(zip("xyz", r))
        key_root.update(r or {})
        for j, v in vals.items():
            joint_keys.setdefault(j, []).append((t, v))
        if key_root:
            root_keys.append((t, {k: float(v) for k, v in key_root.items()}))
    if not clip.cyclic and root_keys is not None and raw.get("keys"):
        # One-shot clips start at the origin: root x/z are 0 at the first key unless keyed there.
        t_first = float(raw["keys"][0]["t"])
        first = next((r for t, r in root_keys if t == t_first), None)
        if first is None:
            first = {}
            root_keys.insert(0, (t_first, first))
        for horizontal in ("x", "z"):
            if any(horizontal in r for _, r in root_keys):
                first.setdefault(horizontal, 0.0)
    root_keys = _flight_keys(root_keys, raw.get("flight", []), where)

    period = clip.period if clip.cyclic else None
    kind = raw.get("interp", "pchip")
    drag = dict(DEFAULT_DRAG)
    drag.update(raw.get("drag", {}))
    drag_idx = {skeleton.index(n): float(s) for n, s in drag.items()}

    T = len(times)
    euler = np.empty((T, J, 3))
    for j in range(J):
        keys = joint_keys.get(j)
        if not keys:
            euler[:, j] = base_joints.get(j, np.zeros(3))
            continue
        kt = np.array([k[0] for k in keys])
        kv = np.stack([k[1] for k in keys])
        f = interpolator(kt, kv, kind, period)
        euler[:, j] = f(times - drag_idx.get(j, 0.0))

    root = np.empty((T, 3))
    travel = clip.travel if clip.cyclic else np.zeros(3)
    defaults = (0.0, float(base_root.get("y", 0.94)), 0.0)
    for axis, coord in enumerate("xyz"):
        keys = [(t, r[coord]) for t, r in root_keys if coord in r]
        line = travel[axis] * times / clip.period if clip.cyclic else np.zeros(T)
        if not keys:
            root[:, axis] = defaults[axis] + line
            continue
        kt = np.array([k[0] for k in keys])
        kv = np.array([k[1] for k in keys])
        if clip.cyclic:
            kv = kv - travel[axis] * kt / clip.period
        root[:, axis] = interpolator(kt, kv[:, None], kind, period)(times)[:, 0] + line

    sway = float(raw.get("sway", 0.0 if clip.cyclic else 1.0))
    if sway:
        for joint, ch, amp, freq in SWAY_TERMS:
            if clip.cyclic:  # whole cycles per period, so the loop stays exact
                freq = max(1, round(freq * clip.period)) / clip.period
            wave = sway * amp * np.sin(2 * np.pi * freq * times)
            if joint == "root":
                root[:, ch] += wave
            else:
                euler[:, skeleton.index(joint), ch] += wave
    return Curves(np.asarray(times, dtype=np.float64), root, euler)


def curves_to_motion(curves: Curves, skeleton: Skeleton, fps: float) -> Motion:
    """Euler curves (degrees, ZYX order) to quaternions, as a :class:`Motion`."""
    T, J, _ = curves.euler.shape
    e = curves.euler.reshape(-1, 3)[:, ::-1]  # (z, y, x) for the intrinsic "ZYX" sequence
    q = Rotation.from_euler("ZYX", e, degrees=True).as_quat().reshape(T, J, 4)
    return Motion(skeleton, fps, curves.root, q)

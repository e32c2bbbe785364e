"""Sampling a parsed keyframed clip (:mod:`~text2anim.motiondb.library.keyframes`): every channel
interpolated over its own keys, flights, drag and the idle layer (:func:`sample_curves`), then turned
into a :class:`~text2anim.core.motion.Motion` (:func:`curves_to_motion`). Seconds in, frames out."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicHermiteSpline, CubicSpline, PchipInterpolator
from scipy.spatial.transform import Rotation

from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton

from .keyframes import ClipData, ClipDataError, expand_joints, resolve_pose

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


#: The captured standing idle whose hips' drift (weight shifting from foot to foot, breathing in the
#: knees) keyframed gestures standing on both feet play over, instead of the root terms of
#: :data:`SWAY_TERMS`: a living body (the synthetic drift moved the hips 0.7 cm in a nod; capture 2-3 cm).
IDLE_CLIP = "wait"


def idle_drift(times: np.ndarray) -> np.ndarray:
    """``(T, 3)`` metres: the captured idle's hips position at ``times`` (seconds) less where it starts, its
    net travel taken out; played forward and back (ping-pong) for clips longer than the idle."""
    from .capture import captured_clip

    idle = captured_clip(IDLE_CLIP)
    root = idle.root_positions - idle.root_positions.mean(axis=0)
    n = len(root)
    root = root - np.linspace(0.0, 1.0, n)[:, None] * (root[-1] - root[0])  # no net travel: a loop of drift
    frames = np.asarray(times) * idle.fps
    period = 2 * (n - 1)
    k = np.mod(frames, period)
    k = np.where(k > n - 1, period - k, k)  # forward, then back
    out = np.stack([np.interp(k, np.arange(n), root[:, a]) for a in range(3)], axis=1)
    return out - out[0]


@dataclass
class Curves:
    """Sampled keyframe curves: ``root`` ``(T, 3)`` metres, ``euler`` ``(T, J, 3)`` degrees (x, y, z)."""

    times: np.ndarray
    root: np.ndarray
    euler: np.ndarray


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
        # a gesture standing on both feet drifts as the captured idle's hips do (a loop keeps its own drift,
        # a clip that steps or travels its keyed path)
        captured = not clip.cyclic and raw.get("plants") == "both"
        if captured:
            root += sway * idle_drift(times)
        for joint, ch, amp, freq in SWAY_TERMS:
            if clip.cyclic:  # whole cycles per period, so the loop stays exact
                freq = max(1, round(freq * clip.period)) / clip.period
            wave = sway * amp * np.sin(2 * np.pi * freq * times)
            if joint == "root":
                if not captured:
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

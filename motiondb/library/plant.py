"""Exact foot plants for keyframed clips, by two-bone leg IK.

Keyframed legs only roughly agree with the root's travel: a stance foot
drifts. Given when each foot is planted (:class:`FramePlant`, frames), this
module makes the plants exact and keeps the swings smooth:

- **Where.** A plant's position and heading are those of the keyed foot
  at its ``anchor`` frame (ball of the foot = toe joint, yaw of the foot).
- **Vertical lock** (``start``..``stop``): the foot is on the ground with
  the plant's yaw. It may land on the heel, toes ``strike`` degrees up, and
  roll flat by ``flat``; it is flat until ``heel_off``, then rolls onto the
  ball (heel rising to ``toe_off`` degrees at ``stop``) while the toes stay
  flat on the ground. The height comes from the sole: its lowest point
  (heel or ball) touches the ground.
- **Horizontal lock**: the ball does not move horizontally over the vertical
  lock *and* over any neighbouring frame the contact detector
  (:func:`core.contacts.detect_contacts`) would call a contact (low and
  slow), and the frames either side of those (its speed is a central
  difference): so the detector's contact intervals are exactly frames where
  the foot stands still (the foot first lifts, then swings). The locks grow
  by iteration until the detector agrees.
- **Between plants** the foot follows its keyed path plus a correction (lock
  minus keyed) blended by a smoothstep from one lock's value to the next's.
  Near lift-off and touchdown the ball is kept at least
  :data:`SWING_CLEARANCE` above its planted height (a smooth hump), so a
  step clears the ground instead of shuffling.
  Horizontally, the keyed swing (from the end of one vertical lock to the
  start of the next) is replayed over the real gap, eased in and out by a
  time-warp (its speed ramps from zero at a lock over :data:`RAMP_FRAMES`
  frames, so the swing keeps its keyed shape but leaves and lands without a
  horizontal velocity jump). Vertically the ramp is shorter
  (:data:`V_RAMP_FRAMES`): feet push off and touch down briskly.
  Foot orientation corrections are slerped the same way. The heel and ball
  are kept above the ground.
- **Reach**: where a locked foot would need more than :data:`MAX_REACH` of
  the leg's length (a knee snapping straight, or a plant out of reach), the
  root is lowered just enough, by a smooth envelope (a maximum filter then a
  Gaussian of the same support, so it is never less than needed).
  Swing targets beyond that are pulled in smoothly towards
  :data:`SOFT_REACH` (soft IK), so a knee never snaps straight.
- **IK**: :func:`core.ik.leg_ik` puts the ankle where the ball target
  and foot orientation require, the knee bending towards a pole in front of
  the keyed knee; then the ankle (and toe) world rotations are set.

:func:`plant_feet` returns the planted motion and a :class:`PlantReport`
(largest lock error, frames added to locks), which the tests check.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter1d, maximum_filter1d
from scipy.spatial.transform import Rotation

from text2anim.core.bodyparts import body_map
from text2anim.core.contacts import detect_contacts, runs
from text2anim.core.ik import leg_ik
from text2anim.core.motion import Motion

SIDES = ("left", "right")
#: Frames over which the toes ease from flat-on-the-ground back to their keyed bend.
TOE_BLEND_FRAMES = 5
#: Largest hip-to-ankle distance of a locked foot, as a fraction of the leg's length.
MAX_REACH = 0.993
#: Any farther ankle target is pulled in smoothly towards this fraction (soft IK: the knee
#: straightens gradually instead of snapping).
SOFT_REACH = 0.9995
#: Smoothing (frames) of the root drop that keeps locked feet within reach.
DROP_SIGMA = 3.0
#: Gaussian smoothing (frames) of swing paths away from the locks.
SWING_SMOOTH = 1.2
#: Frames over which a correction fades out after a clip's last lock (in before its first).
EDGE_FADE_FRAMES = 12.0
#: Frames over which a swing's speed ramps up from (down to) zero at a lock.
RAMP_FRAMES = 2.5
#: The same for the vertical: shorter, a foot pushes off and touches down briskly.
V_RAMP_FRAMES = 1.5
#: A stepping foot's ball rises at least this high above its planted height near lift-off and
#: touchdown (over RISE frames, held HOLD frames, released over RELEASE frames), so it clears the
#: contact detector's "low" band instead of shuffling.
SWING_CLEARANCE = 0.06
CLEAR_RISE, CLEAR_HOLD, CLEAR_RELEASE = 2.5, 2.0, 3.0


@dataclass(frozen=True)
class FramePlant:
    """A plant in frames (``start``/``stop`` inclusive); see the module docstring."""

    side: str
    start: int
    stop: int
    anchor: int
    heel_off: int | None = None
    toe_off: float = 0.0
    flat: int | None = None
    strike: float = 0.0
    keep: bool = False


@dataclass(frozen=True)
class PlantReport:
    """``max_error``: metres, largest distance of a locked ball from its lock (3-D on vertical
    locks, horizontal on the rest); ``extended``: frames the horizontal locks grew by;
    ``iterations``: passes until the detector agreed; ``stray_contacts``: detector contact
    frames left outside any lock (should be 0)."""

    max_error: float
    extended: int
    iterations: int
    stray_contacts: int


def _smoothstep(u):
    u = np.clip(u, 0.0, 1.0)
    return u * u * (3 - 2 * u)


def _warp_curve(r_in: float, r_out: float, n: int = 257) -> tuple[np.ndarray, np.ndarray]:
    """``(x, w)``: a monotone map of ``[0, 1]`` onto itself whose slope ramps from 0 over ``r_in``
    at the start and back to 0 over ``r_out`` at the end (no ramp when 0)."""
    x = np.linspace(0.0, 1.0, n)
    v = np.ones(n)
    if r_in > 0:
        v *= _smoothstep(x / r_in)
    if r_out > 0:
        v *= _smoothstep((1.0 - x) / r_out)
    w = np.concatenate([[0.0], np.cumsum((v[1:] + v[:-1]) / 2)])
    return x, w / w[-1]


class _Gaps:
    """Per frame of the gaps between locked runs: the warped (fractional) frame of the keyed
    path to follow, the blend weight ``u`` (0 at the previous lock, 1 at the next) and the
    neighbouring lock frames (``-1`` where the clip edge is)."""

    def __init__(self, locked: np.ndarray, ramp: float = RAMP_FRAMES, source: np.ndarray | None = None):
        """``source``: a mask whose gaps contain ``locked``'s gaps; each gap then replays the keyed
        path over the enclosing ``source`` gap (the keyed swing, compressed into the real one)."""
        T = len(locked)
        frames = np.arange(T, dtype=float)
        self.tau = frames.copy()
        self.u = np.zeros(T)
        self.prev = np.where(locked, np.arange(T), -1)
        self.next = np.where(locked, np.arange(T), -1)
        self.src_prev = self.prev.copy()  # the keyed frame the path starts from at ``prev``
        self.src_next = self.next.copy()
        for a, b in runs(~locked):
            a, b = int(a), int(b)
            e = a - 1 if a > 0 else None
            s = b if b < T else None
            lo = float(e) if e is not None else 0.0
            hi = float(s) if s is not None else float(T - 1)
            span = max(hi - lo, 1e-9)
            r = min(0.35, ramp / span) if ramp > 0 else 0.0
            x, w = _warp_curve(r if e is not None else 0.0, r if s is not None else 0.0)
            uu = (frames[a:b] - lo) / span
            src_lo, src_hi = lo, hi
            if source is not None:
                left = np.flatnonzero(source[:a])
                right = np.flatnonzero(source[b:])
                src_lo = float(left[-1]) if (e is not None and len(left)) else lo
                src_hi = float(b + right[0]) if (s is not None and len(right)) else hi
            self.tau[a:b] = src_lo + (src_hi - src_lo) * np.interp(uu, x, w)
            if e is not None and s is not None:
                self.u[a:b] = uu
            elif s is None:  # after the last lock: the correction fades out
                self.u[a:b] = np.clip((frames[a:b] - lo) / EDGE_FADE_FRAMES, 0.0, 1.0)
            else:  # before the first lock: it fades in
                self.u[a:b] = 1.0 - np.clip((hi - frames[a:b]) / EDGE_FADE_FRAMES, 0.0, 1.0)
            self.prev[a:b] = -1 if e is None else e
            self.next[a:b] = -1 if s is None else s
            self.src_prev[a:b] = -1 if e is None else int(round(src_lo))
            self.src_next[a:b] = -1 if s is None else int(round(src_hi))
        self.locked = locked

    def path(self, values: np.ndarray) -> np.ndarray:
        """``values`` ``(T, k)`` sampled at the warped frames (linear between frames)."""
        T = len(values)
        i0 = np.clip(np.floor(self.tau).astype(int), 0, T - 1)
        i1 = np.clip(i0 + 1, 0, T - 1)
        f = (self.tau - i0)[:, None]
        return values[i0] * (1 - f) + values[i1] * f

    def rotations(self, rots: Rotation) -> Rotation:
        T = len(rots)
        i0 = np.clip(np.floor(self.tau).astype(int), 0, T - 1)
        i1 = np.clip(i0 + 1, 0, T - 1)
        f = self.tau - i0
        r0 = rots[i0]
        return r0 * Rotation.from_rotvec((r0.inv() * rots[i1]).as_rotvec() * f[:, None])

    def ends(self):
        """Per frame: (previous lock frame, its source frame, next lock frame, its source frame, weight,
        whether there is a previous lock, whether there is a next one); at a clip edge the missing
        side repeats the other (its correction is then faded to zero, see :meth:`blend`)."""
        pv = np.where(self.prev >= 0, self.prev, self.next)
        sp = np.where(self.prev >= 0, self.src_prev, self.src_next)
        nx = np.where(self.next >= 0, self.next, self.prev)
        sn = np.where(self.next >= 0, self.src_next, self.src_prev)
        return pv, sp, nx, sn, _smoothstep(self.u), self.prev >= 0, self.next >= 0

    def blend(self, lock: np.ndarray, keyed: np.ndarray) -> np.ndarray:
        """The correction ``lock - keyed`` ``(T, k)``: exact on locked frames, smoothstep-blended across
        gaps between its values at the gap's ends (taken against the keyed frames the path replays);
        before the first and after the last lock it fades to zero (the keys alone)."""
        if not self.locked.any():
            return np.zeros_like(keyed)
        pv, sp, nx, sn, w, has_p, has_n = self.ends()
        c0 = np.where(has_p[:, None], lock[pv] - keyed[sp], 0.0)
        c1 = np.where(has_n[:, None], lock[nx] - keyed[sn], 0.0)
        mixed = c0 * (1 - w[:, None]) + c1 * w[:, None]
        return np.where(self.locked[:, None], lock - keyed, mixed)

    def blend_rotations(self, lock: Rotation, keyed: Rotation) -> Rotation:
        """Rotation corrections ``lock * keyed^-1``, slerped across gaps like :meth:`blend`."""
        T = len(keyed)
        if not self.locked.any():
            return Rotation.identity(T)
        pv, sp, nx, sn, w, has_p, has_n = self.ends()
        ident = np.tile([0.0, 0.0, 0.0, 1.0], (T, 1))
        r0 = Rotation.from_quat(np.where(has_p[:, None], (lock[pv] * keyed[sp].inv()).as_quat(), ident))
        r1 = Rotation.from_quat(np.where(has_n[:, None], (lock[nx] * keyed[sn].inv()).as_quat(), ident))
        mixed = r0 * Rotation.from_rotvec((r0.inv() * r1).as_rotvec() * w[:, None])
        exact = (lock * keyed.inv()).as_quat()
        return Rotation.from_quat(np.where(self.locked[:, None], exact, mixed.as_quat()))


def _clearance(locked: np.ndarray) -> np.ndarray:
    """``(T,)`` in [0, 1]: a smooth hump next to each lock (0 on locks) on the frames between them."""
    T = len(locked)
    out = np.zeros(T)
    frames = np.arange(T, dtype=float)

    def hump(k):
        up = _smoothstep(k / CLEAR_RISE)
        down = 1.0 - _smoothstep((k - CLEAR_RISE - CLEAR_HOLD) / CLEAR_RELEASE)
        return up * down

    for a, b in runs(~locked):
        a, b = int(a), int(b)
        seg = frames[a:b]
        h = np.zeros(b - a)
        if a > 0:
            h = np.maximum(h, hump(seg - (a - 1)))
        if b < T:
            h = np.maximum(h, hump(b - seg))
        out[a:b] = h
    return out


def _yaw(rot: Rotation) -> np.ndarray:
    fwd = rot.apply([0.0, 0.0, 1.0])
    return np.arctan2(fwd[..., 0], fwd[..., 2])


class _Foot:
    """Lock state and keyed data of one foot."""

    def __init__(self, motion: Motion, side: str, plants: list[FramePlant], toe_height: float, ground: float):
        bm = body_map(motion.skeleton)
        skel = motion.skeleton
        self.side = side
        self.ankle, self.toe = bm.feet[side]
        self.knee = int(skel.parents[self.ankle])
        self.hip = int(skel.parents[self.knee])
        self.toe_local = skel.offsets[self.toe].copy()
        T = motion.n_frames
        pose = motion.pose
        self.F = pose.positions[:, self.toe].copy()
        self.RF = Rotation.from_matrix(pose.rotations[:, self.ankle])
        self.knee_pos = pose.positions[:, self.knee].copy()
        self.thigh_fwd = np.einsum("tij,j->ti", pose.rotations[:, self.hip], [0.0, 0.0, 1.0])
        self.ground = ground
        self.toe_y = ground + toe_height
        self.owner = np.full(T, -1)
        self.vlock = np.zeros(T, dtype=bool)
        self.pitch = np.zeros(T)
        anchors: list[np.ndarray] = []  # (x, z) of each plant's anchor, metres
        yaws: list[float] = []
        self.keep_y = np.full(T, np.nan)
        self.keep_rot = np.tile([0.0, 0.0, 0.0, 1.0], (T, 1))
        for k, p in enumerate(sorted(plants, key=lambda p: p.start)):
            s, e = max(0, p.start), min(T - 1, p.stop)
            if s > e:
                continue
            if (self.owner[s:e + 1] >= 0).any():
                raise ValueError(f"overlapping {side} plants around frame {s}")
            a = int(np.clip(p.anchor, 0, T - 1))
            idx = len(anchors)
            anchors.append(self.F[a, [0, 2]].copy())
            yaws.append(float(_yaw(self.RF[a])))
            self.owner[s:e + 1] = idx
            self.vlock[s:e + 1] = True
            if p.keep:
                self.keep_y[s:e + 1] = self.F[a, 1]
                self.keep_rot[s:e + 1] = self.RF[a].as_quat()
            if p.heel_off is not None and p.toe_off:
                fr = np.arange(max(s, p.heel_off), e + 1)
                u = (fr - p.heel_off) / max(1, p.stop - p.heel_off)
                self.pitch[fr] = p.toe_off * _smoothstep(u)
            if p.flat is not None and p.strike:
                fr = np.arange(s, min(e, p.flat) + 1)
                u = (fr - p.start) / max(1, p.flat - p.start)
                self.pitch[fr] = -p.strike * (1 - _smoothstep(u))
        self.P = np.array(anchors).reshape(-1, 2)  # (plants, 2)
        self.yaw = np.array(yaws)  # (plants,) radians
        self.last_target: np.ndarray | None = None  # the ball targets of the last solve, (T, 3)

    def targets(self, sole: np.ndarray):
        """Ball targets ``(T, 3)``, foot world rotations and toe world rotations (used on vertical locks)."""
        T = len(self.F)
        h = self.owner >= 0
        v = self.vlock
        gv = _Gaps(v, ramp=V_RAMP_FRAMES)
        gh = _Gaps(h, source=v)
        lock_xz = self.P[np.maximum(self.owner, 0)] if len(self.P) else np.zeros((T, 2))
        xz = gh.path(self.F[:, [0, 2]]) + gh.blend(lock_xz, self.F[:, [0, 2]])

        owner_v = np.where(v, self.owner, 0)
        yaw = self.yaw[owner_v] if len(self.yaw) else np.zeros(T)
        flat = Rotation.from_euler("YX", np.stack([yaw, np.radians(self.pitch)], axis=1))
        # On vertical locks the sole's lowest point touches the ground.
        ball_y = np.full((T, 3), [0.0, self.toe_y, 0.0])
        lock_y = self.toe_y + self.ground - _sole_heights(ball_y, flat, sole, self.toe_local).min(axis=1)
        keep = ~np.isnan(self.keep_y)
        if keep.any():
            lock_y[keep] = self.keep_y[keep]
            q = flat.as_quat()
            q[keep] = self.keep_rot[keep]
            flat = Rotation.from_quat(q)
        y = gv.path(self.F[:, [1]]) + gv.blend(lock_y[:, None], self.F[:, [1]])
        y[:, 0] = np.maximum(y[:, 0], self.toe_y + SWING_CLEARANCE * _clearance(v))
        target = np.stack([xz[:, 0], y[:, 0], xz[:, 1]], axis=1)
        # Soften the swing's frame-scale corners (never the locks, nor the clearance): a Gaussian of
        # SWING_SMOOTH frames on the horizontal path, faded in away from the locks.
        smooth = gaussian_filter1d(target[:, [0, 2]], SWING_SMOOTH, axis=0, mode="nearest")
        w_h = _smoothstep(_distance_to(h, T) / (2 * SWING_SMOOTH))[:, None]
        target[:, [0, 2]] += w_h * (smooth - target[:, [0, 2]])

        RFw = gv.rotations(self.RF)
        delta = gv.blend_rotations(flat, self.RF)
        Q = delta * RFw
        q = Q.as_quat()
        q[v] = flat.as_quat()[v]
        Q = Rotation.from_quat(q)
        # Keep heel and ball above the ground off the vertical locks.
        low = _sole_heights(target, Q, sole, self.toe_local).min(axis=1)
        target[:, 1] += np.where(v, 0.0, np.maximum(0.0, self.ground - low))
        # Toes: flat on the ground while the heel is up; following the foot while it is toes-up.
        toes = Rotation.from_euler("YX", np.stack([yaw, np.radians(np.minimum(self.pitch, 0.0))], axis=1))
        self.keep_mask = keep
        return target, Q, toes


def _sole_heights(toe_target: np.ndarray, Q: Rotation, sole: np.ndarray, toe_local: np.ndarray) -> np.ndarray:
    """Heights ``(T, S)`` of the sole points (ankle frame) for a ball at ``toe_target`` and foot rotation ``Q``."""
    T = len(toe_target)
    rel = sole - toe_local  # sole points relative to the toe joint, in the ankle frame
    pts = np.stack([Q.apply(np.tile(r, (T, 1))) for r in rel], axis=1)
    return toe_target[:, None, 1] + pts[:, :, 1]


def _set_world(motion: Motion, joints_rots: list[tuple[int, Rotation]]) -> Motion:
    """Set several joints' world rotations ``(T)`` from one forward-kinematics pass.

    The joints must not be ancestors of one another.
    """
    pose = motion.pose
    rots = motion.rotations.copy()
    for j, world in joints_rots:
        parent = Rotation.from_matrix(pose.rotations[:, motion.skeleton.parents[j]])
        rots[:, j] = (parent.inv() * world).as_quat()
    return motion.replace(rotations=rots)


def _leg_length(motion: Motion, foot: "_Foot") -> float:
    skel = motion.skeleton
    return float(np.linalg.norm(skel.offsets[foot.knee]) + np.linalg.norm(skel.offsets[foot.ankle]))


def _soft_reach(target: np.ndarray, hip: np.ndarray, length: float, a: float, b: float) -> np.ndarray:
    """Ankle targets pulled towards ``hip`` beyond ``a * length`` so they never pass ``b * length``
    (identity below ``a``, then an exponential approach; C1)."""
    v = target - hip
    d = np.linalg.norm(v, axis=1)
    lo, hi = a * length, b * length
    over = d > lo
    if not over.any():
        return target
    soft = np.where(over, lo + (hi - lo) * (1 - np.exp(-(d - lo) / (hi - lo))), d)
    return hip + v * (soft / np.maximum(d, 1e-12))[:, None]


def _root_drop(motion: Motion, feet: dict, ankle_targets: dict, max_reach: float) -> np.ndarray:
    """Smooth root drop ``(T,)`` (metres, >= 0) keeping locked ankles within ``max_reach`` of their legs."""
    pos = motion.positions
    T = motion.n_frames
    need = np.zeros(T)
    for side, target in ankle_targets.items():
        foot = feet[side]
        r = max_reach * _leg_length(motion, foot)
        v = target - pos[:, foot.hip]
        vy = v[:, 1]
        n2 = np.sum(v * v, axis=1)
        disc = vy ** 2 - n2 + r ** 2
        drop = np.where(disc >= 0, -vy - np.sqrt(np.maximum(disc, 0.0)), -vy)
        drop = np.where(n2 > r ** 2, np.maximum(drop, 0.0), 0.0)
        locked = foot.owner >= 0
        need = np.maximum(need, np.where(locked, drop, 0.0))
    if not need.any():
        return need
    half = int(np.ceil(2 * DROP_SIGMA))
    env = maximum_filter1d(need, size=2 * half + 1, mode="nearest")
    return gaussian_filter1d(env, DROP_SIGMA, mode="nearest", truncate=2.0)


def plant_feet(motion: Motion, plants: list[FramePlant], *, toe_height: float, sole: np.ndarray,
               ground: float = 0.0, max_iterations: int = 12,
               max_reach: float = MAX_REACH, report_frames: slice = slice(None)) -> tuple[Motion, PlantReport]:
    """Make ``plants`` exact on ``motion`` (see the module docstring).

    ``sole``: ``(S, 3)`` points of the sole in the ankle's frame (heel, ball) kept above
    ``ground``; ``toe_height``: toe joint above the ground when the ball is down;
    ``report_frames``: the frames the report is about (a cyclic clip's kept cycles).
    """
    T = motion.n_frames
    feet = {s: _Foot(motion, s, [p for p in plants if p.side == s], toe_height, ground) for s in SIDES}
    keyed = motion
    extended = 0
    iterations = 0
    result = motion
    drop = np.zeros(T)
    for iterations in range(1, max_iterations + 1):
        solved = {}
        ankle_targets = {}
        for side, foot in feet.items():
            if not (foot.owner >= 0).any():
                continue
            target, Q, toe_flat = foot.targets(sole)
            ankle_targets[side] = target - Q.apply(np.tile(foot.toe_local, (T, 1)))
            solved[side] = (target, Q, toe_flat)
            foot.last_target = target
        if not solved:
            break
        drop = _root_drop(keyed, feet, ankle_targets, max_reach)
        root = keyed.root_positions.copy()
        root[:, 1] -= drop
        result = keyed.replace(root_positions=root)
        hips = result.positions
        for side in solved:
            foot = feet[side]
            pole = foot.knee_pos + 0.5 * foot.thigh_fwd - drop[:, None] * np.array([0.0, 1.0, 0.0])
            target = _soft_reach(ankle_targets[side], hips[:, foot.hip], _leg_length(result, foot),
                                 max_reach, SOFT_REACH)
            result = leg_ik(result, side, target, pole=pole)
        result = _set_world(result, [(feet[s].ankle, solved[s][1]) for s in solved])
        # Toes: flat on the ground on vertical locks, easing back to their keyed bend after.
        pose = result.pose
        rots = result.rotations.copy()
        for side in solved:
            foot = feet[side]
            v = foot.vlock & ~foot.keep_mask
            if not v.any():
                continue
            ankle_world = Rotation.from_matrix(pose.rotations[:, foot.ankle])
            flat_local = (ankle_world.inv() * solved[side][2]).as_quat()
            keyed_local = keyed.rotations[:, foot.toe]
            w = _smoothstep(_distance_to(v, T) / TOE_BLEND_FRAMES)
            near = _nearest_index(v, T)
            r0 = Rotation.from_quat(flat_local[near])
            r1 = Rotation.from_quat(keyed_local)
            q = (r0 * Rotation.from_rotvec((r0.inv() * r1).as_rotvec() * w[:, None])).as_quat()
            rots[:, foot.toe] = q
        result = result.replace(rotations=rots)

        contacts = detect_contacts(result)
        changed = False
        for side, foot in feet.items():
            if not (foot.owner >= 0).any():
                continue
            # Every contact frame and both its neighbours (the detector's speed is a central
            # difference) must stand still: grow the adjacent lock over any that do not.
            c = contacts.of(side)
            need = c.copy()
            need[1:] |= c[:-1]
            need[:-1] |= c[1:]
            stray = need & (foot.owner < 0)
            for a, b in runs(stray):
                a, b = int(a), int(b)
                if a > 0 and foot.owner[a - 1] >= 0:
                    foot.owner[a:b] = foot.owner[a - 1]
                elif b < T and foot.owner[b] >= 0:
                    foot.owner[a:b] = foot.owner[b]
                else:
                    continue
                extended += b - a
                changed = True
        if not changed:
            break

    # Report (on the frames asked for; the detector sees the part the caller keeps).
    region = np.zeros(T, dtype=bool)
    region[report_frames] = True
    pos = result.positions
    contacts = detect_contacts(result[report_frames])
    err = 0.0
    stray_total = 0
    for side, foot in feet.items():
        c = contacts.of(side)
        if not (foot.owner >= 0).any():
            stray_total += int(c.sum())
            continue
        ball = pos[:, foot.toe]
        h = (foot.owner >= 0) & region
        v = foot.vlock & region
        horiz = np.linalg.norm(ball[h][:, [0, 2]] - foot.P[foot.owner[h]], axis=1)
        assert foot.last_target is not None  # every planted foot was solved
        vert = np.abs(ball[v, 1] - foot.last_target[v, 1])
        err = max(err, float(horiz.max(initial=0.0)), float(vert.max(initial=0.0)))
        stray_total += int((c & ~(foot.owner >= 0)[report_frames]).sum())
    return result, PlantReport(err, extended, iterations, stray_total)


def _distance_to(mask: np.ndarray, T: int) -> np.ndarray:
    """Frames from each frame to the nearest true frame of ``mask`` (large if none)."""
    idx = np.flatnonzero(mask)
    if len(idx) == 0:
        return np.full(T, 1e9)
    frames = np.arange(T)
    pos = np.searchsorted(idx, frames)
    left = idx[np.clip(pos - 1, 0, len(idx) - 1)]
    right = idx[np.clip(pos, 0, len(idx) - 1)]
    return np.minimum(np.abs(frames - left), np.abs(frames - right)).astype(float)


def _nearest_index(mask: np.ndarray, T: int) -> np.ndarray:
    """For each frame, the nearest frame where ``mask`` is true ``(T,)`` (0 if none)."""
    idx = np.flatnonzero(mask)
    if len(idx) == 0:
        return np.zeros(T, dtype=int)
    frames = np.arange(T)
    pos = np.searchsorted(idx, frames)
    left = idx[np.clip(pos - 1, 0, len(idx) - 1)]
    right = idx[np.clip(pos, 0, len(idx) - 1)]
    return np.where(np.abs(frames - left) <= np.abs(frames - right), left, right)

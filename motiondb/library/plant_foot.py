"""One foot of :func:`~text2anim.motiondb.library.plant.plant_feet`: its plants (:class:`FramePlant`), lock
state and keyed data, and the ball targets and foot rotations that make the plants exact (:class:`Foot`)."""
from __future__ import annotations


import numpy as np
from scipy.ndimage import gaussian_filter1d
from scipy.spatial.transform import Rotation

from text2anim.core.bodyparts import body_map
from text2anim.core.motion import Motion

from text2anim.core.easing import smoothstep

from .keyframes import FramePlant
from .plant_gaps import Gaps, clearance, distance_to, swing_heights

#: Gaussian smoothing (frames) of swing paths away from the locks.
SWING_SMOOTH = 1.2
#: Frames over which a swing's vertical speed ramps up from (down to) zero at a lock: shorter than the
#: horizontal :data:`~text2anim.motiondb.library.plant_gaps.RAMP_FRAMES`, a foot pushes off and touches down briskly.
V_RAMP_FRAMES = 1.5
#: A stepping foot's ball rises this high above its planted height (less on a short swing, see
#: :func:`~text2anim.motiondb.library.plant_gaps.swing_heights`), so it clears the contact detector's
#: "low" band instead of shuffling, and GMD's 5 cm above the motion's lowest foot point for more than the
#: top of its arc (at 6 cm, three turns on the spot read 0.263 by GMD's skating, over the capture's 0.26;
#: at 7.5 cm, 0.238).
SWING_CLEARANCE = 0.075
#: A swing's ball leaves and reaches its locks at least this fast (m/s, horizontally, on the gap's first and
#: last frame, when its step is long enough). The contact detector's speed is a central difference
#: (limit 0.4 m/s): at 0.75 m/s the first swing frame, whose difference spans two moving frames, is not
#: taken for standing, so the lock does not grow into the swing and crowd the step into the frames
#: left (a skip's 37 cm hop into three frames), while the lock's own last frame (its difference spans
#: one moving frame: 0.375 m/s) stays a contact, as a walk's double support needs.
MIN_STEP_SPEED = 0.75


def _yaw(rot: Rotation) -> np.ndarray:
    fwd = rot.apply([0.0, 0.0, 1.0])
    return np.arctan2(fwd[..., 0], fwd[..., 2])


class Foot:
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
        self.fps = motion.fps
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
            self.pitch[s:e + 1] = p.pitch
            if p.heel_off is not None and p.toe_off:
                fr = np.arange(max(s, p.heel_off), e + 1)
                u = (fr - p.heel_off) / max(1, p.stop - p.heel_off)
                self.pitch[fr] = p.toe_off * smoothstep(u)
            if p.flat is not None and p.strike:
                fr = np.arange(s, min(e, p.flat) + 1)
                u = (fr - p.start) / max(1, p.flat - p.start)
                self.pitch[fr] = -p.strike * (1 - smoothstep(u))
        self.P = np.array(anchors).reshape(-1, 2)  # (plants, 2)
        self.yaw = np.array(yaws)  # (plants,) radians
        self.last_target: np.ndarray | None = None  # the ball targets of the last solve, (T, 3)

    def targets(self, sole: np.ndarray):
        """Ball targets ``(T, 3)``, foot world rotations and toe world rotations (used on vertical locks)."""
        T = len(self.F)
        h = self.owner >= 0
        v = self.vlock
        gv = Gaps(v, ramp=V_RAMP_FRAMES)
        gh = Gaps(h, source=v)
        gh.retime(self.F[:, [0, 2]], MIN_STEP_SPEED / self.fps, self.fps)
        lock_xz = self.P[np.maximum(self.owner, 0)] if len(self.P) else np.zeros((T, 2))
        xz = gh.path(self.F[:, [0, 2]]) + gh.blend(lock_xz, self.F[:, [0, 2]])

        owner_v = np.where(v, self.owner, 0)
        yaw = self.yaw[owner_v] if len(self.yaw) else np.zeros(T)
        flat = Rotation.from_euler("YX", np.stack([yaw, np.radians(self.pitch)], axis=1))
        # On vertical locks the sole's lowest point touches the ground.
        ball_y = np.full((T, 3), [0.0, self.toe_y, 0.0])
        lock_y = self.toe_y + self.ground - sole_heights(ball_y, flat, sole, self.toe_local).min(axis=1)
        keep = ~np.isnan(self.keep_y)
        if keep.any():
            lock_y[keep] = self.keep_y[keep]
            q = flat.as_quat()
            q[keep] = self.keep_rot[keep]
            flat = Rotation.from_quat(q)
        y = gv.path(self.F[:, [1]]) + gv.blend(lock_y[:, None], self.F[:, [1]])
        y[:, 0] = np.maximum(y[:, 0], self.toe_y + SWING_CLEARANCE * clearance(v))  # all but short swings
        between = swing_heights(v, lock_y, self.F[:, 1], self.fps, SWING_CLEARANCE)
        y[:, 0] = np.where(np.isnan(between), y[:, 0], between)
        target = np.stack([xz[:, 0], y[:, 0], xz[:, 1]], axis=1)
        # Soften the swing's frame-scale corners (never the locks, nor the clearance): a Gaussian of
        # SWING_SMOOTH frames on the horizontal path, faded in away from the locks.
        smooth = gaussian_filter1d(target[:, [0, 2]], SWING_SMOOTH, axis=0, mode="nearest")
        w_h = smoothstep(distance_to(h, T) / (2 * SWING_SMOOTH))[:, None]
        target[:, [0, 2]] += w_h * (smooth - target[:, [0, 2]])

        RFw = gv.rotations(self.RF)
        delta = gv.blend_rotations(flat, self.RF)
        Q = delta * RFw
        q = Q.as_quat()
        q[v] = flat.as_quat()[v]
        Q = Rotation.from_quat(q)
        # Keep heel and ball above the ground off the vertical locks.
        low = sole_heights(target, Q, sole, self.toe_local).min(axis=1)
        target[:, 1] += np.where(v, 0.0, np.maximum(0.0, self.ground - low))
        # Toes: flat on the ground while the heel is up; following the foot while it is toes-up.
        toes = Rotation.from_euler("YX", np.stack([yaw, np.radians(np.minimum(self.pitch, 0.0))], axis=1))
        self.keep_mask = keep
        return target, Q, toes


def sole_heights(toe_target: np.ndarray, Q: Rotation, sole: np.ndarray, toe_local: np.ndarray) -> np.ndarray:
    """Heights ``(T, S)`` of the sole points (ankle frame) for a ball at ``toe_target`` and foot rotation ``Q``."""
    T = len(toe_target)
    rel = sole - toe_local  # sole points relative to the toe joint, in the ankle frame
    pts = np.stack([Q.apply(np.tile(r, (T, 1))) for r in rel], axis=1)
    return toe_target[:, None, 1] + pts[:, :, 1]

"""Between a foot's locks (:mod:`~text2anim.motiondb.library.plant`): the keyed path replayed over each gap,
time-warped to leave and land without a velocity jump, the corrections blended across it, and the
clearance hump next to each lock. Frames throughout."""
from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from text2anim.core.contacts import runs
from text2anim.core.easing import smoothstep

#: Frames over which a correction fades out after a clip's last lock (in before its first).
EDGE_FADE_FRAMES = 12.0
#: Frames over which a swing's speed ramps up from (down to) zero at a lock.
RAMP_FRAMES = 2.5
#: The clearance hump next to a lock: rises over RISE frames, held HOLD frames, released over RELEASE
#: frames (its height is :data:`~text2anim.motiondb.library.plant_foot.SWING_CLEARANCE`).
CLEAR_RISE, CLEAR_HOLD, CLEAR_RELEASE = 2.5, 2.0, 3.0


def _warp_curve(r_in: float, r_out: float, n: int = 257) -> tuple[np.ndarray, np.ndarray]:
    """``(x, w)``: a monotone map of ``[0, 1]`` onto itself whose slope ramps from 0 over ``r_in``
    at the start and back to 0 over ``r_out`` at the end (no ramp when 0)."""
    x = np.linspace(0.0, 1.0, n)
    v = np.ones(n)
    if r_in > 0:
        v *= smoothstep(x / r_in)
    if r_out > 0:
        v *= smoothstep((1.0 - x) / r_out)
    w = np.concatenate([[0.0], np.cumsum((v[1:] + v[:-1]) / 2)])
    return x, w / w[-1]


class Gaps:
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
        return pv, sp, nx, sn, smoothstep(self.u), self.prev >= 0, self.next >= 0

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


def clearance(locked: np.ndarray) -> np.ndarray:
    """``(T,)`` in [0, 1]: a smooth hump next to each lock (0 on locks) on the frames between them."""
    T = len(locked)
    out = np.zeros(T)
    frames = np.arange(T, dtype=float)

    def hump(k):
        up = smoothstep(k / CLEAR_RISE)
        down = 1.0 - smoothstep((k - CLEAR_RISE - CLEAR_HOLD) / CLEAR_RELEASE)
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


def distance_to(mask: np.ndarray, T: int) -> np.ndarray:
    """Frames from each frame to the nearest true frame of ``mask`` (large if none)."""
    idx = np.flatnonzero(mask)
    if len(idx) == 0:
        return np.full(T, 1e9)
    frames = np.arange(T)
    pos = np.searchsorted(idx, frames)
    left = idx[np.clip(pos - 1, 0, len(idx) - 1)]
    right = idx[np.clip(pos, 0, len(idx) - 1)]
    return np.minimum(np.abs(frames - left), np.abs(frames - right)).astype(float)


def nearest_index(mask: np.ndarray, T: int) -> np.ndarray:
    """For each frame, the nearest frame where ``mask`` is true ``(T,)`` (0 if none)."""
    idx = np.flatnonzero(mask)
    if len(idx) == 0:
        return np.zeros(T, dtype=int)
    frames = np.arange(T)
    pos = np.searchsorted(idx, frames)
    left = idx[np.clip(pos - 1, 0, len(idx) - 1)]
    right = idx[np.clip(pos, 0, len(idx) - 1)]
    return np.where(np.abs(frames - left) <= np.abs(frames - right), left, right)

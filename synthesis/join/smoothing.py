"""The join post-pass's candidates (:mod:`synthesis.join.joinpass`, steps 2-3): a join's region at one stretch,
low-passed at one width, its feet re-planted by leg IK and its figures measured.

What every width of a stretch shares is computed once (:class:`Stretch`), when a width's rotations are first
asked: the region's frames retimed (:class:`Deferred`: the pops need only the hips' path), the feet's contact weights
and targets (from the reference motion's kinematics over the region only), and the kinematics of the 3 frames
either side of the region, which no width changes. A width (:class:`Smoothed`) is measured as far as the
search asks, each step dearer than the last:

1. the hips' path low-passed: the root pop, exact (re-planting the feet moves no hips);
2. the rotations low-passed and their kinematics run once: a lower bound of the joint jerk p99
   (:func:`jerk_floor`): the jerk of every joint the leg IK cannot move (all but the knees, ankles and toes)
   is already final, and the p99 of all joints is at least the order statistic of those that still holds if
   every leg value were lower;
3. the feet re-planted (two leg IK solves, :func:`plant_all`, several widths at once) and the jerk measured:
   only for a width the bounds leave a chance of being chosen (:func:`synthesis.join.joinpass.finish_region`).

The figures are bit for bit ``core.metrics.quality(motion[lo - 3:hi + 3], None)`` of the whole candidate
(jerk p99 m/s³, root pop m/s²; ``tests/synthesis/test_smoothing.py``), and the candidate's motion bit for
bit the low-passed motion with its feet re-planted over the region.
"""
from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter1d, maximum_filter1d

from text2anim.core import rotkernels as rk
from text2anim.core.bodyparts import body_map
from text2anim.core.metrics import JERK_PERCENTILE, jerk_p99, joint_jerk, peak_hips_acceleration
from text2anim.core.motion import Motion, concatenate, unroll_quaternions

from .blend import ease, lerp, slerp
from .legsolve import LegGoal, solve_legs

AROUND = 3  # frames either side of a region its figures include (the jerk's differences reach that far)


@functools.lru_cache(maxsize=256)
def _fade(n: int, pad: int) -> np.ndarray:
    """``(n,)``: 0 → 1 over the first ``pad`` frames, 1, 1 → 0 over the last ``pad`` (quintic, C2); read-only, made
    once per size (every width of every stretch asks for it twice)."""
    e = np.ones(n)
    if pad > 0:
        up = ease(np.linspace(0.0, 1.0, pad + 1)[:-1], "smooth")
        e[:pad] = up
        e[n - pad:] = up[::-1]
    e.setflags(write=False)
    return e


def smooths(lo: int, hi: int, sigma: float, pad: int, root_pad: int) -> bool:
    """Whether :func:`low_pass` changes anything: a positive width and room for both fades."""
    return sigma > 0 and hi - lo >= 2 * max(pad, root_pad) + 1


def _filtered(x: np.ndarray, lo: int, hi: int, sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """Rows ``[lo, hi)`` of ``x`` ``(T, ...)`` and of ``x`` Gaussian-filtered over frames (``sigma``), reading
    up to 4 sigma beyond; quaternions ``(T, J, 4)`` are unrolled first and the filtered ones renormalised."""
    # the filter reads the motion up to 4 sigma beyond the region (only the region is written): near its
    # edges it then averages the frames that really follow, not the edge frame held still ("nearest"),
    # which bent a moving hips' path towards a standstill right where the fade hands back to the clip
    ext = int(np.ceil(4.0 * sigma))
    a, b = max(0, lo - ext), min(len(x), hi + ext)
    if x.ndim == 3:
        q = unroll_quaternions(x[a:b])
        qs = gaussian_filter1d(q, sigma, axis=0, mode="nearest")[lo - a:hi - a]
        qs /= np.linalg.norm(qs, axis=-1, keepdims=True)
        return q[lo - a:hi - a], qs
    return x[lo:hi], gaussian_filter1d(x[a:b], sigma, axis=0, mode="nearest")[lo - a:hi - a]


def low_pass_path(root: np.ndarray, lo: int, hi: int, sigma: float, root_pad: int) -> np.ndarray:
    """Root positions ``(hi - lo, 3)`` of :func:`low_pass` over ``[lo, hi)`` (when :func:`smooths`) of a motion
    whose root positions are ``root`` ``(T, 3)``: the hips' path alone is enough (:class:`Deferred`)."""
    own, smooth = _filtered(root, lo, hi, sigma)
    return lerp(own, smooth, _fade(hi - lo, root_pad))


def low_pass_rotations(motion: Motion, lo: int, hi: int, sigma: float, pad: int) -> np.ndarray:
    """Local rotations ``(hi - lo, J, 4)`` of :func:`low_pass` over ``[lo, hi)`` (when :func:`smooths`)."""
    return low_pass_rotations_of(motion, lo, hi, [(sigma, pad)])


def low_pass_rotations_of(motion: Motion, lo: int, hi: int, widths: list[tuple[float, int]]) -> np.ndarray:
    """:func:`low_pass_rotations` of several widths ``(sigma, pad)``, end to end ``(k (hi - lo), J, 4)``: each
    filtered alone, all blended in one slerp (per row: the same bits as one by one, without its fixed cost
    again, ~0.2 ms)."""
    parts = [_filtered(motion.rotations, lo, hi, sigma) for sigma, _pad in widths]
    fade = np.concatenate([_fade(hi - lo, pad) for _sigma, pad in widths])
    own, smooth = (parts[0][k] if len(parts) == 1 else np.concatenate([p[k] for p in parts]) for k in (0, 1))
    return slerp(own, smooth, fade[:, None])


def low_pass(motion: Motion, lo: int, hi: int, sigma: float, pad: int, root_pad: int | None = None) -> Motion:
    """``motion`` with local rotations and root position Gaussian-filtered (``sigma`` frames) over
    ``[lo, hi)``, faded in and out over ``pad`` frames at each end (the root over ``root_pad``, default ``pad``)."""
    root_pad = pad if root_pad is None else root_pad
    if not smooths(lo, hi, sigma, pad, root_pad):
        return motion
    rots = motion.rotations.copy()
    rots[lo:hi] = low_pass_rotations(motion, lo, hi, sigma, pad)
    root = motion.root_positions.copy()
    root[lo:hi] = low_pass_path(motion.root_positions, lo, hi, sigma, root_pad)
    return motion.replace(root_positions=root, rotations=rots)


def _soft(mask: np.ndarray, fps: float) -> np.ndarray:
    """A contact mask as a weight: 1 on contact frames, falling smoothly to 0 over about 0.1 s around them."""
    w = np.clip(2.0 * gaussian_filter1d(mask.astype(np.float64), 0.05 * fps, mode="nearest"), 0.0, 1.0)
    w[mask] = 1.0
    return w


def jerk_floor(jerk: np.ndarray, fixed: np.ndarray) -> float:
    """A lower bound of :func:`jerk_p99` of ``jerk`` ``(n, J)`` once the joints not in ``fixed`` change: the
    fixed joints' order statistic that stays at or below the p99 whatever the others become (0 if none does)."""
    total, known = jerk.size, jerk[:, fixed]
    if total == 0 or known.size == 0 or not np.isfinite(jerk).all():
        return 0.0
    # the p99 interpolates from the value of rank floor(0.99 (N - 1)); one rank lower absorbs the rounding of
    # that index, and at most N - M of the values below it can be the joints that move
    k = int(np.floor(JERK_PERCENTILE / 100.0 * (total - 1))) - 1 - (total - known.size)
    if k < 0:
        return 0.0
    return float(np.partition(known.ravel(), k)[k]) * (1.0 - 1e-12)


@dataclass(frozen=True)
class Deferred:
    """A stretch's base and reference motions (:class:`Stretch`), made when a width's rotations are first asked:
    ``root`` ``(T, 3)`` m, the base's root positions (all its widths' hips' paths, and so their pops, need),
    ``fps``, and ``make``: ``() -> (base, ref)``. Nearly half of a long text's stretches have every width pruned
    by its hips' path alone (:mod:`synthesis.join.pruning`): their frames are never retimed."""

    root: np.ndarray
    fps: float
    make: Callable[[], tuple[Motion, Motion]]


class Stretch:
    """What every smoothing width of one stretch of a join's region shares.

    ``base``: the region retimed (seams carried over), ``ref``: the engine's output retimed alike (the feet
    to keep), both given or :class:`Deferred` (``ref`` then ``None``); ``[lo, hi)``: the frames smoothed,
    ``planted``: per side ``(T,)`` bool over ``base``'s frames, ``widths``: ``(sigma, pad, root_pad)`` (frames)
    of :func:`low_pass` per width, made when first asked (``stretch[i]``). What the widths' rotations share
    (:attr:`feet`, :attr:`fixed`, the kinematics around the region) is made when first asked.
    """

    def __init__(self, base: Motion | Deferred, ref: Motion | None, lo: int, hi: int, planted: dict,
                 widths: list[tuple[float, int, int]] | None = None):
        if isinstance(base, Deferred):
            self.root, self.fps, self._make = base.root, base.fps, base.make
            self._motions: tuple[Motion, Motion] | None = None
        else:
            assert ref is not None
            self.root, self.fps, self._motions = base.root_positions, base.fps, (base, ref)
        self.lo, self.hi, self._planted = lo, hi, planted
        self.widths = list(widths or [])
        self._made: dict[int, Smoothed] = {}
        self.a, self.b = max(0, lo - AROUND), min(len(self.root), hi + AROUND)

    @property
    def base(self) -> Motion:
        """The region retimed, seams carried over (made when first asked)."""
        if self._motions is None:
            self._motions = self._make()
        return self._motions[0]

    @functools.cached_property
    def _shared(self) -> tuple[Motion, list[tuple[str, int, np.ndarray, np.ndarray, np.ndarray]], np.ndarray,
                               np.ndarray, np.ndarray]:
        """``(region, feet, fixed, before, after)`` (:attr:`region`, :attr:`feet`, :attr:`fixed`, and the world
        positions of the measured frames before and after the region)."""
        base = self.base
        assert self._motions is not None
        ref, lo, hi = self._motions[1], self.lo, self.hi
        skel = base.skeleton
        feet = []
        # the region's frames as they are (a width that smooths nothing): where they are the reference's frames
        # (those the seams left alone), their kinematics is the reference's
        region = base[lo:hi]
        if hi - lo >= 2:
            want = None
            for side, (ankle, _toe) in body_map(skel).feet.items():
                c = _soft(maximum_filter1d(self._planted[side], 3), self.fps)[lo:hi]  # held a frame either side too
                if not c.any():
                    continue
                if want is None:  # kinematics is per frame: the region's only
                    own = ref[lo:hi]
                    want = own.pose
                    region.share_pose(own, np.arange(hi - lo))
                r_want = rk.as_quat(rk.from_matrix(want.rotations[:, ankle]))  # Rotation's bits
                feet.append((side, ankle, c, want.positions[:, ankle], r_want))
        moved = np.zeros(skel.n_joints, dtype=bool)  # the knees, ankles and toes the leg IK moves
        for _side, ankle, *_ in feet:
            hip = int(skel.parents[skel.parents[ankle]])
            moved[skel.subtree(hip)[1:]] = True
        # the measured frames either side of the region, their kinematics in one call (FK is per frame)
        around = np.r_[self.a:lo, hi:self.b]
        pos = Motion(skel, self.fps, base.root_positions[around], base.rotations[around],
                     None if base.translations is None else base.translations[around]).positions
        return region, feet, np.flatnonzero(~moved), pos[:lo - self.a], pos[lo - self.a:]

    @property
    def region(self) -> Motion:
        """The base's frames ``[lo, hi)``."""
        return self._shared[0]

    @property
    def feet(self) -> list[tuple[str, int, np.ndarray, np.ndarray, np.ndarray]]:
        """Per side to keep: ``(side, ankle, weights (n,), ankle targets (n, 3), ankle world rotations (n, 4))``."""
        return self._shared[1]

    @property
    def fixed(self) -> np.ndarray:
        """The joints the leg IK leaves alone (all but the kept feet's knees, ankles and toes)."""
        return self._shared[2]

    def __getitem__(self, i: int) -> Smoothed:
        """The ``i``-th of ``widths`` (:meth:`smoothed`), made once."""
        if i not in self._made:
            self._made[i] = self.smoothed(*self.widths[i])
        return self._made[i]

    def release(self) -> None:
        """Forget the widths made: each refers back to this stretch, a cycle that only the cyclic collector
        frees, late (a long track's post-pass held a dozen copies of the track so)."""
        self._made.clear()

    def smoothed(self, sigma: float, pad: int, root_pad: int) -> Smoothed:
        """The region low-passed (:func:`low_pass`): its pop at once, the rest when asked."""
        return Smoothed(self, sigma, pad, root_pad)

    def positions(self, sub: Motion) -> np.ndarray:
        """World positions ``(n, J, 3)`` of the measured frames, the region's from ``sub``."""
        _, _, _, before, after = self._shared
        return np.concatenate([before, sub.positions, after])


class Smoothed:
    """One width of a :class:`Stretch`, measured as far as asked: ``pop`` (exact) at once, from the hips'
    path alone; ``jk_floor`` once the rotations are low-passed and their kinematics run; ``jk`` after
    :meth:`plant` (with ``jk_floor`` when no foot is kept)."""

    def __init__(self, stretch: Stretch, sigma: float, pad: int, root_pad: int):
        self.stretch, self.sigma, self.pad = stretch, sigma, pad
        st = stretch
        self.smooths = smooths(st.lo, st.hi, sigma, pad, root_pad)
        root = st.root[st.a:st.b]
        if self.smooths:
            root = root.copy()
            root[st.lo - st.a:st.hi - st.a] = low_pass_path(st.root, st.lo, st.hi, sigma, root_pad)
        self.root = root  # (b - a, 3) over the measured frames
        self.pop = peak_hips_acceleration(root, st.fps)
        self.jk: float | None = None
        self._floor: float | None = None
        self._sub: Motion | None = None

    @property
    def sub(self) -> Motion:
        """The region's frames ``[lo, hi)``: low-passed, their feet re-planted after :meth:`plant`."""
        if self._sub is None:
            st = self.stretch
            sub = st.region
            if self.smooths:
                rots = low_pass_rotations(st.base, st.lo, st.hi, self.sigma, self.pad)
                sub = Motion(sub.skeleton, sub.fps, self.root[st.lo - st.a:st.hi - st.a], rots, sub.translations)
            self._sub = sub
        return self._sub

    @property
    def measured(self) -> bool:
        """Whether :attr:`jk_floor` is known (the rotations low-passed and their kinematics run)."""
        return self._floor is not None

    @property
    def jk_floor(self) -> float:
        """A lower bound of the jerk p99 (m/s³) before the feet are re-planted (:func:`jerk_floor`)."""
        if self._floor is None:
            self.measure()
        assert self._floor is not None
        return self._floor

    def measure(self) -> None:
        """Low-pass the rotations, run their kinematics, and take :attr:`jk_floor` (and ``jk`` when no foot
        is kept: then the jerk is final)."""
        st = self.stretch
        jerk = joint_jerk(st.positions(self.sub), st.fps)
        if st.feet:
            self._floor = jerk_floor(jerk, st.fixed)
        else:
            self.jk = self._floor = jerk_p99(jerk)

    def plant(self) -> tuple[float, float]:
        """Re-plant the feet (:func:`plant_all` of this width alone, unless done) and measure:
        ``(jerk p99, root pop)``."""
        if self.jk is None:
            plant_all([self])
        assert self.jk is not None
        return self.jk, self.pop

    def motion(self) -> Motion:
        """The whole candidate motion (after :meth:`plant`): the base with the region's frames replaced."""
        st, base = self.stretch, self.stretch.base
        if not self.smooths and not st.feet:
            return base
        root, rots = base.root_positions.copy(), base.rotations.copy()
        root[st.lo:st.hi] = self.sub.root_positions
        rots[st.lo:st.hi] = self.sub.rotations
        return Motion(base.skeleton, base.fps, root, rots, base.translations)


def low_pass_all(widths: list[Smoothed]) -> None:
    """Make the low-passed frames (:attr:`Smoothed.sub`) of the widths of one :class:`Stretch` not made yet, their
    rotations in one slerp (:func:`low_pass_rotations_of`) and their kinematics in one call (per frame: the same
    bits as one by one): for widths about to be measured and re-planted together (:func:`plant_all`)."""
    todo = [w for w in widths if w._sub is None and w.smooths]
    if len(todo) < 2:
        return
    st = todo[0].stretch
    region, n = st.region, st.hi - st.lo
    rots = low_pass_rotations_of(st.base, st.lo, st.hi, [(w.sigma, w.pad) for w in todo])
    trans = None if region.translations is None else np.concatenate([region.translations] * len(todo))
    subs = Motion(region.skeleton, region.fps, np.concatenate([w.root[st.lo - st.a:st.hi - st.a] for w in todo]),
                  rots, trans)
    _ = subs.pose
    for i, w in enumerate(todo):
        w._sub = subs[i * n:(i + 1) * n]


def plant_all(widths: list[Smoothed]) -> None:
    """Re-plant the feet of some widths of one :class:`Stretch` and measure their jerk p99, in one leg IK
    solve per side over all their frames (kinematics and IK are per frame: each width's arithmetic is what
    it would be alone). Each kept foot's leg is solved (:func:`synthesis.join.legsolve.solve_legs`, both legs in
    one solve: what ``set_world_rotation(solve_leg(...))`` gives, leg after leg) onto its target blended in
    by the contact weight, the ankle's world rotation slerped alike."""
    todo = [w for w in widths if w.jk is None]
    if not todo:
        return
    st, k = todo[0].stretch, len(todo)
    if not st.feet:  # nothing to re-plant: the jerk is measured as it is
        for w in todo:
            w.measure()
        return
    n = st.hi - st.lo
    sub = todo[0].sub if k == 1 else concatenate([w.sub for w in todo])
    # both legs' goals from the kinematics before either is solved (one leg's IK moves none of the other's
    # joints), as rows of one conversion, one slerp and one IK solve
    now = sub.pose
    ankles = [foot[1] for foot in st.feet]
    cs = np.concatenate([np.tile(foot[2], k) for foot in st.feet])
    goal = lerp(np.concatenate([now.positions[:, a] for a in ankles]),
                np.concatenate([np.tile(foot[3], (k, 1)) for foot in st.feet]), cs)
    world = now.quaternions(ankles)  # (rows, feet, 4): both ankles' world rotations in one conversion (per row)
    turn = slerp(np.concatenate([world[:, i] for i in range(len(ankles))]),
                 np.concatenate([np.tile(foot[4], (k, 1)) for foot in st.feet]), cs)
    rows = k * n
    sub = solve_legs(sub, [LegGoal(foot[0], 0, rows, goal[i * rows:(i + 1) * rows], turn[i * rows:(i + 1) * rows])
                           for i, foot in enumerate(st.feet)])
    _ = sub.pose  # the legs' kinematics once for all the widths (their slices share it)
    for i, w in enumerate(todo):
        w._sub = sub[i * n:(i + 1) * n]
        w.jk = jerk_p99(joint_jerk(st.positions(w.sub), st.fps))

"""A clip of skeletal motion: immutable frames, their pose and derived data computed once.

Shapes: ``T`` frames, ``J`` joints. Root positions ``(T, 3)`` in metres,
local joint rotations ``(T, J, 4)`` as scipy quaternions ``(x, y, z, w)``.

A motion's arrays are read-only (the arrays handed to it are made read-only too): an edit makes a new
motion (:meth:`Motion.replace`, :meth:`Motion.frames`, :func:`concatenate`), so what its
:class:`~core.posecache.PoseCache` holds never goes stale.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from . import quat
from .fk import Pose
from .posecache import PoseCache
from .skeleton import Skeleton
from .timebase import resampled_frames

# scipy.spatial.transform is imported where it is used: loading it costs ~0.1 s of CPU, and
# commands that never touch a rotation (text2anim plan) import this module for its types.


def _frozen(a, shape: tuple[int, ...]) -> np.ndarray:
    """``a`` as float64 of ``shape``, read-only: the array handed over (or its float64 copy) is frozen, so
    neither the motion nor its maker can edit the frames in place."""
    arr = np.asarray(a, dtype=np.float64)
    arr.setflags(write=False)
    return arr.reshape(shape)


def unroll_quaternions(q: np.ndarray) -> np.ndarray:
    """Flip signs along axis 0 so consecutive quaternions lie in one hemisphere.

    ``q`` is ``(T, ..., 4)``; the result represents the same rotations but
    differences and blends between neighbouring frames take the short way.
    """
    if len(q) < 2:
        return q.copy()
    dots = np.sum(q[1:] * q[:-1], axis=-1)
    flips = np.concatenate([np.ones((1,) + dots.shape[1:]), np.where(dots < 0, -1.0, 1.0)])
    return q * np.cumprod(flips, axis=0)[..., None]


@dataclass(frozen=True, eq=False)
class Motion:
    """Skeletal motion sampled at a fixed frame rate.

    Attributes:
        skeleton: the joint hierarchy.
        fps: frames per second.
        root_positions: ``(T, 3)`` world position of the root joint, metres.
        rotations: ``(T, J, 4)`` local joint rotations, quaternions (x, y, z, w).
        translations: ``(T, J, 3)`` local translations for skeletons whose
            non-root joints carry position channels (rare BVH files); ``None``
            means every non-root joint sits at its rest offset.
    """

    skeleton: Skeleton
    fps: float
    root_positions: np.ndarray
    rotations: np.ndarray
    translations: np.ndarray | None = None
    _cache: PoseCache = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        J = self.skeleton.n_joints
        rp = _frozen(self.root_positions, (-1, 3))
        rot = _frozen(self.rotations, (-1, J, 4))
        if len(rp) != len(rot):
            raise ValueError(f"{len(rp)} root positions for {len(rot)} frames of rotations")
        if not self.fps > 0:
            raise ValueError(f"fps must be positive, got {self.fps}")
        object.__setattr__(self, "root_positions", rp)
        object.__setattr__(self, "rotations", rot)
        object.__setattr__(self, "fps", float(self.fps))
        if self.translations is not None:
            object.__setattr__(self, "translations", _frozen(self.translations, (len(rot), J, 3)))
        object.__setattr__(self, "_cache", PoseCache())

    def __reduce__(self):
        """Pickled as its fields (read-only again, and a new cache, when unpickled)."""
        return Motion, (self.skeleton, self.fps, self.root_positions, self.rotations, self.translations)

    # ------------------------------------------------------------------ size
    @property
    def n_frames(self) -> int:
        return len(self.rotations)

    def __len__(self) -> int:
        return self.n_frames

    @property
    def duration(self) -> float:
        """Seconds covered: frame count times frame time."""
        return self.n_frames / self.fps

    @property
    def times(self) -> np.ndarray:
        """Time of each frame in seconds, ``(T,)``."""
        return np.arange(self.n_frames) / self.fps

    # -------------------------------------------------------------- kinematics
    def local_translations(self) -> np.ndarray:
        """Translation of every joint from its parent, ``(T, J, 3)``; the root's is its world position."""
        if self.translations is not None:
            tr = self.translations.copy()
        else:
            tr = np.broadcast_to(self.skeleton.offsets, (self.n_frames,) + self.skeleton.offsets.shape).copy()
        tr[:, 0] = self.root_positions
        return tr

    @property
    def cache(self) -> PoseCache:
        """This motion's :class:`~core.posecache.PoseCache`: its pose and derived quantities, each computed once."""
        return self._cache

    @property
    def pose(self) -> Pose:
        """Forward kinematics (:func:`core.fk.forward`), computed once per motion; a motion made from another
        whose pose is known computes only what differs (:class:`~core.posecache.PoseCache`)."""
        return self._cache.pose(self)

    def share_pose(self, other: "Motion", rows: np.ndarray) -> "Motion":
        """Let this motion's :attr:`pose` take ``other``'s where the frames are the same: ``rows`` ``(T,)`` says
        which frame of ``other`` each frame may be (``-1``: none); where the two frames are bit for bit equal
        and ``other``'s pose is known, that frame's pose is ``other``'s, and the kinematics, when asked, runs
        for the other frames only. An edit that kept most of a long motion (a join's region) then costs the
        region's kinematics. Returns this motion."""
        self._cache.share(self, other, rows)
        return self

    @property
    def positions(self) -> np.ndarray:
        """World joint positions ``(T, J, 3)``, metres."""
        return self.pose.positions

    def end_site_positions(self) -> np.ndarray:
        """World positions of the BVH end sites ``(T, E, 3)``, in ``skeleton.end_sites`` order."""
        if not self.skeleton.end_sites:
            return np.zeros((self.n_frames, 0, 3))
        joints = np.array([j for j, _ in self.skeleton.end_sites])
        offs = np.stack([o for _, o in self.skeleton.end_sites])
        pose = self.pose
        return pose.positions[:, joints] + np.einsum("teij,ej->tei", pose.rotations[:, joints], offs)

    # ---------------------------------------------------------------- editing
    def replace(self, **changes) -> "Motion":
        """A new motion with some fields changed. When only the local rotations change, and only those
        of some joints (an IK solve of a limb), the new motion's :attr:`pose`, when asked, redoes the
        kinematics of the subtrees holding them, from this motion's pose; when only the root positions
        change, it keeps this pose's world rotations (bit for bit the full computation: :mod:`core.fk`)."""
        out = replace(self, **changes)
        if changes.keys() == {"rotations"} and out.rotations.shape == self.rotations.shape:
            object.__setattr__(out, "_cache", self._cache.of_rotations(self, out.rotations))
        elif changes.keys() == {"root_positions"} and out.root_positions.shape == self.root_positions.shape:
            object.__setattr__(out, "_cache", self._cache.of_root_moved(self, out.root_positions))
        return out

    def with_rotations(self, lo: int, rotations: np.ndarray) -> "Motion":
        """A new motion whose local rotations of the frames ``[lo, lo + n)`` are ``rotations`` ``(n, J, 4)``,
        the rest this one's: what :meth:`replace` with the whole array so edited gives, bit for bit, but only
        those frames are compared with this motion's and, when its pose is asked, have their kinematics
        redone (an edit of a join's window on a long track costs the window's work, plus one copy)."""
        rots = self.rotations.copy()
        hi = lo + len(rotations)
        rots[lo:hi] = rotations
        out = replace(self, rotations=rots)
        object.__setattr__(out, "_cache", self._cache.of_window(self, out.rotations, lo, hi))
        return out

    def frames(self, start: int, stop: int | None = None) -> "Motion":
        """Frames ``start`` .. ``stop - 1`` (Python slice semantics); views of this motion's arrays."""
        sl = slice(start, stop)
        out = Motion(self.skeleton, self.fps, self.root_positions[sl], self.rotations[sl],
                     None if self.translations is None else self.translations[sl])
        object.__setattr__(out, "_cache", self._cache.of_frames(sl))  # FK is per frame: the slice of the pose
        return out

    def __getitem__(self, sl: slice) -> "Motion":
        if not isinstance(sl, slice) or sl.step not in (None, 1):
            raise TypeError("a Motion is sliced by a contiguous frame range, e.g. motion[10:50]")
        return self.frames(sl.start or 0, sl.stop)

    def between(self, t0: float, t1: float) -> "Motion":
        """The frames whose times lie in ``[t0, t1)`` seconds."""
        return self.frames(int(np.ceil(t0 * self.fps - 1e-9)), int(np.ceil(t1 * self.fps - 1e-9)))

    def resample(self, fps: float) -> "Motion":
        """The same motion at another frame rate: slerp for rotations, linear for positions.

        The new frames sample times ``0, 1/fps, ...`` up to the last original frame.
        """
        fps = float(fps)
        if fps == self.fps or self.n_frames < 2:
            return self.replace(fps=fps)
        t_old = self.times
        n_new = resampled_frames(self.n_frames, self.fps, fps)
        t_new = np.minimum(np.arange(n_new) / fps, t_old[-1])
        root = np.stack([np.interp(t_new, t_old, self.root_positions[:, k]) for k in range(3)], axis=1)
        # slerp between the two frames around each new time, every joint at once
        i = np.clip(np.searchsorted(t_old, t_new, side="right") - 1, 0, self.n_frames - 2)
        frac = (t_new - t_old[i]) / (t_old[i + 1] - t_old[i])
        rots = quat.slerp(self.rotations[i], self.rotations[i + 1], frac[:, None])  # (n_new, J, 4)
        trans = None
        if self.translations is not None:
            flat = self.translations.reshape(self.n_frames, -1)
            trans = np.stack([np.interp(t_new, t_old, flat[:, k]) for k in range(flat.shape[1])], axis=1)
        return Motion(self.skeleton, fps, root, rots, trans)

    def then(self, *others: "Motion") -> "Motion":
        """Frames of ``self`` followed by those of ``others`` (same skeleton and fps, no alignment)."""
        return concatenate([self, *others])


def concatenate(motions: list[Motion]) -> Motion:
    """Append motions end to end without any blending or alignment."""
    if not motions:
        raise ValueError("nothing to concatenate")
    first = motions[0]
    for m in motions[1:]:
        if not m.skeleton.same_hierarchy(first.skeleton):
            raise ValueError("cannot concatenate motions of different skeletons")
        if m.fps != first.fps:
            raise ValueError(f"cannot concatenate {first.fps} fps with {m.fps} fps; resample first")
    trans = None
    if any(m.translations is not None for m in motions):
        trans = np.concatenate([m.local_translations() for m in motions])
    out = Motion(first.skeleton, first.fps,
                 np.concatenate([m.root_positions for m in motions]),
                 np.concatenate([m.rotations for m in motions]), trans)
    # FK is per frame: when the parts' bones are the first's, the whole's pose is the parts' poses end to
    # end; known now when every part's is, else when asked (only the parts not yet solved are: a track
    # held or eased to a new length redoes the kinematics of its new frames only)
    if all(m.skeleton is first.skeleton or np.array_equal(m.skeleton.offsets, first.skeleton.offsets)
           for m in motions[1:]):
        object.__setattr__(out, "_cache", PoseCache.of_parts(motions))
    return out

"""A clip of skeletal motion and its forward kinematics.

Shapes: ``T`` frames, ``J`` joints. Root positions ``(T, 3)`` in metres,
local joint rotations ``(T, J, 4)`` as scipy quaternions ``(x, y, z, w)``.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from . import quat
from .skeleton import Skeleton
from .timebase import resampled_frames

# scipy.spatial.transform is imported where it is used: loading it costs ~0.1 s of CPU, and
# commands that never touch a rotation (text2anim plan) import this module for its types.


def quat_to_matrix(q: np.ndarray) -> np.ndarray:
    """Quaternions ``(..., 4)`` to rotation matrices ``(..., 3, 3)`` (``Rotation.as_matrix``'s bits)."""
    from . import rotkernels

    flat = q.reshape(-1, 4)
    if len(flat) == 0:
        return np.zeros(q.shape[:-1] + (3, 3))
    return rotkernels.as_matrix(rotkernels.from_quat(flat)).reshape(q.shape[:-1] + (3, 3))


def matrix_to_quat(m: np.ndarray) -> np.ndarray:
    """Rotation matrices ``(..., 3, 3)`` to quaternions ``(..., 4)`` (``Rotation.from_matrix``'s bits)."""
    from . import rotkernels

    flat = m.reshape(-1, 3, 3)
    if len(flat) == 0:
        return np.zeros(m.shape[:-2] + (4,))
    return rotkernels.as_quat(rotkernels.from_matrix(flat)).reshape(m.shape[:-2] + (4,))


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


@dataclass(frozen=True)
class Pose:
    """World-space result of forward kinematics.

    positions: ``(T, J, 3)`` metres; rotations: ``(T, J, 3, 3)`` world rotation matrices.
    """

    positions: np.ndarray
    rotations: np.ndarray

    def quaternions(self, joints=None) -> np.ndarray:
        """World rotations as ``(T, J, 4)`` quaternions; of ``joints`` only (an index or a list) when given,
        ``(T, 4)`` or ``(T, n, 4)``, converting those joints' matrices only."""
        return matrix_to_quat(self.rotations if joints is None else self.rotations[:, joints])


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

    def __post_init__(self):
        J = self.skeleton.n_joints
        rp = np.asarray(self.root_positions, dtype=np.float64).reshape(-1, 3)
        rot = np.asarray(self.rotations, dtype=np.float64).reshape(-1, J, 4)
        if len(rp) != len(rot):
            raise ValueError(f"{len(rp)} root positions for {len(rot)} frames of rotations")
        if not self.fps > 0:
            raise ValueError(f"fps must be positive, got {self.fps}")
        object.__setattr__(self, "root_positions", rp)
        object.__setattr__(self, "rotations", rot)
        object.__setattr__(self, "fps", float(self.fps))
        if self.translations is not None:
            tr = np.asarray(self.translations, dtype=np.float64).reshape(len(rot), J, 3)
            object.__setattr__(self, "translations", tr)

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

    @cached_property
    def pose(self) -> Pose:
        """Forward kinematics, vectorised over frames and over the joints of each tree depth.

        Computed once per motion; :meth:`frames` of a motion whose pose is known slices it
        (each frame's kinematics depends on that frame alone).
        """
        source = self.__dict__.pop("_pose_source", None)  # not kept once used: it holds another pose
        if source is not None:
            return self._pose_below(*source)
        parts = self.__dict__.pop("_pose_parts", None)  # a concatenation (see :func:`concatenate`)
        if parts is not None:
            return _joined_pose(parts)
        moved = self.__dict__.pop("_pose_moved", None)  # the root moved (see :meth:`replace`)
        if moved is not None:
            return self._pose_root_moved(moved)
        same = self.__dict__.get("_pose_of")
        if same is not None:
            return same.pose
        rows = self.__dict__.pop("_pose_rows", None)  # frames another motion's pose has (see share_pose)
        if rows is not None:
            return self._pose_with(*rows)
        # joint-major (J, T, ...) with the joints in order of depth (Skeleton.depth_order): a depth's joints are one
        # block, read and written in place; only their parents are gathered
        order, inverse, _ = self.skeleton.depth_order()
        world_r, world_p = self._down(quat_to_matrix(self.rotations[:, order]).transpose(1, 0, 2, 3).copy())
        # back to (T, J, ...) in skeleton order, C-contiguous: reductions over these arrays sum in the same order
        world_r = np.ascontiguousarray(world_r.transpose(1, 0, 2, 3)[:, inverse])
        world_r.setflags(write=False)
        return Pose(world_p, world_r)

    def _down(self, local_r: np.ndarray | None, world_r: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Forward kinematics down the tree depth by depth, joint-major in depth order
        (:meth:`Skeleton.depth_order`: a depth's joints are one block, read and written in place; only their
        parents are gathered): from the local rotation matrices ``local_r`` ``(J, T, 3, 3)``, the world
        rotations ``(J, T, 3, 3)`` (in that layout) and the world positions ``(T, J, 3)`` m (skeleton order,
        read-only); given the world rotations ``world_r`` instead, the positions only."""
        order, inverse, levels = self.skeleton.depth_order()
        local_t = self.local_translations()[:, order].transpose(1, 0, 2).copy()
        solve_r = world_r is None
        if world_r is None:
            assert local_r is not None
            world_r = np.empty_like(local_r)
            world_r[0] = local_r[0]
        world_p = np.empty_like(local_t)
        world_p[0] = local_t[0]
        for a, b, parents in levels:
            parent_r = world_r[parents]
            if solve_r:
                np.matmul(parent_r, local_r[a:b], out=world_r[a:b])  # type: ignore[index]
            np.add(world_p[parents], np.einsum("ntij,ntj->nti", parent_r, local_t[a:b]), out=world_p[a:b])
        world_p = np.ascontiguousarray(world_p.transpose(1, 0, 2)[:, inverse])
        world_p.setflags(write=False)
        return world_r, world_p

    def _pose_below(self, known: Pose, tops: tuple[int, ...]) -> Pose:
        """:attr:`pose` from ``known``, the pose of a motion that differs from this one only in the local
        rotations of the joints ``tops`` and their descendants (no top below another): their forward
        kinematics is redone, the other joints' world transforms are kept. Each joint's arithmetic is
        :attr:`pose`'s, so the result is bit for bit the full computation."""
        rotations, positions = known.rotations.copy(), known.positions.copy()
        for top in tops:
            self._subtree_pose(known, top, rotations, positions)
        rotations.setflags(write=False)
        positions.setflags(write=False)
        return Pose(positions, rotations)

    def _subtree_pose(self, known: Pose, top: int, rotations: np.ndarray, positions: np.ndarray) -> None:
        """Write the world transforms of ``top``'s subtree into ``rotations`` ``(T, J, 3, 3)`` and
        ``positions`` ``(T, J, 3)``, from ``known``'s transform of its parent (see :meth:`_pose_below`)."""
        sub = self.skeleton.subtree(top)  # (n,) joints, parents first
        local_r = quat_to_matrix(self.rotations[:, sub]).transpose(1, 0, 2, 3).copy()
        # the subtree's rows of local_translations() (the root, whose row is its position, is not in it)
        own_t = self.translations[:, sub] if self.translations is not None else \
            np.broadcast_to(self.skeleton.offsets[sub], (self.n_frames, len(sub), 3))
        local_t = own_t.transpose(1, 0, 2).copy()
        world_r = np.empty_like(local_r)
        world_p = np.empty_like(local_t)
        outside = self.skeleton.parents[top]  # the one parent outside the subtree
        top_r = np.ascontiguousarray(known.rotations[:, outside])[None]
        top_p = np.ascontiguousarray(known.positions[:, outside])[None]
        world_r[:1] = top_r @ local_r[:1]
        world_p[:1] = top_p + np.einsum("ntij,ntj->nti", top_r, local_t[:1])
        for j, p in self.skeleton.subtree_levels(top):  # slices where a depth's joints are a block (a limb)
            parent_r = world_r[p]
            if isinstance(j, slice):
                np.matmul(parent_r, local_r[j], out=world_r[j])
                np.add(world_p[p], np.einsum("ntij,ntj->nti", parent_r, local_t[j]), out=world_p[j])
            else:
                world_r[j] = parent_r @ local_r[j]
                world_p[j] = world_p[p] + np.einsum("ntij,ntj->nti", parent_r, local_t[j])
        rotations[:, sub] = world_r.transpose(1, 0, 2, 3)
        positions[:, sub] = world_p.transpose(1, 0, 2)

    def share_pose(self, other: "Motion", rows: np.ndarray) -> "Motion":
        """Let this motion's :attr:`pose` take ``other``'s where the frames are the same: ``rows`` ``(T,)`` says
        which frame of ``other`` each frame may be (``-1``: none); where the two frames' root position and
        local rotations (and translations) are bit for bit equal and ``other``'s pose is known, that frame's
        pose is ``other``'s, and the kinematics, when asked, runs for the other frames only (FK is per frame:
        the same bits). An edit that kept most of a long motion (a join's region) then costs the region's
        kinematics. Returns this motion."""
        known = other._known_pose()
        rows = np.asarray(rows, dtype=np.int64)
        if known is None or len(rows) != self.n_frames or any(
                k in self.__dict__ for k in ("pose", "_pose_source", "_pose_parts", "_pose_moved", "_pose_of")) or not (
                other.skeleton is self.skeleton or np.array_equal(other.skeleton.offsets, self.skeleton.offsets)):
            return self
        rows = np.where((rows >= 0) & (rows < other.n_frames), rows, -1)
        have = np.flatnonzero(rows >= 0)
        src = rows[have]
        same = (self.root_positions[have].view(np.int64) == other.root_positions[src].view(np.int64)).all(axis=1)
        same &= (self.rotations[have].view(np.int64) == other.rotations[src].view(np.int64)).all(axis=(1, 2))
        if self.translations is not None or other.translations is not None:
            same &= (self.local_translations()[have].view(np.int64)
                     == other.local_translations()[src].view(np.int64)).all(axis=(1, 2))
        rows[have[~same]] = -1
        if (rows >= 0).any():
            self.__dict__["_pose_rows"] = (known, rows)
        return self

    def _pose_with(self, known: Pose, rows: np.ndarray) -> Pose:
        """:attr:`pose` with the frames ``rows >= 0`` taken from ``known`` (:meth:`share_pose`)."""
        new = rows < 0
        positions = np.empty((self.n_frames, self.skeleton.n_joints, 3))
        rotations = np.empty((self.n_frames, self.skeleton.n_joints, 3, 3))
        positions[~new] = known.positions[rows[~new]]
        rotations[~new] = known.rotations[rows[~new]]
        if new.any():
            part = Motion(self.skeleton, self.fps, self.root_positions[new], self.rotations[new],
                          None if self.translations is None else self.translations[new]).pose
            positions[new] = part.positions
            rotations[new] = part.rotations
        positions.setflags(write=False)
        rotations.setflags(write=False)
        return Pose(positions, rotations)

    def copy_sharing_pose(self) -> "Motion":
        """The same frames in arrays of their own; its :attr:`pose` is this motion's, computed once for both
        (a motion is not edited in place: edits make new motions)."""
        out = Motion(self.skeleton, self.fps, self.root_positions.copy(), self.rotations.copy(),
                     None if self.translations is None else self.translations.copy())
        out.__dict__["_pose_of"] = self
        return out

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
        kinematics of the subtrees holding them, from this motion's pose (bit for bit the
        full computation: :meth:`_pose_below`); when only the root positions change, it keeps this
        pose's world rotations (:meth:`_pose_root_moved`)."""
        out = replace(self, **changes)
        if changes.keys() == {"rotations"} and out.rotations.shape == self.rotations.shape:
            self._carry_pose(out)
        elif changes.keys() == {"root_positions"} and out.root_positions.shape == self.root_positions.shape:
            known = self._known_pose()  # the hips moved: the world rotations stay, positions are redone
            if known is not None:
                out.__dict__["_pose_moved"] = known
        return out

    def _pose_root_moved(self, known: Pose) -> Pose:
        """:attr:`pose` from ``known``, the pose of a motion that differs from this one only in its root
        positions: the world rotations are ``known``'s, the positions are summed down the tree again from
        the same rotated bone offsets (:attr:`pose`'s arithmetic and layout, so the same bits)."""
        order = self.skeleton.depth_order()[0]
        _, world_p = self._down(None, np.ascontiguousarray(known.rotations[:, order].transpose(1, 0, 2, 3)))
        return Pose(world_p, known.rotations)

    def _carry_pose(self, out: "Motion") -> None:
        """Tell ``out`` (this motion with other local rotations) how to get its pose from this one's."""
        known = self._known_pose()
        source = self.__dict__.get("_pose_source")
        if known is None and source is None:
            return
        differs = (out.rotations.view(np.int64) != self.rotations.view(np.int64)).any(axis=(0, 2))
        changed = np.flatnonzero(differs)
        if len(changed) == 0:
            if known is not None:
                out.__dict__["pose"] = known
            else:
                out.__dict__["_pose_source"] = source
            return
        tops = {int(j) for j in changed}
        if known is None:  # edits on edits: redo the subtrees holding them all, when asked
            assert source is not None
            tops |= set(source[1])
            known = source[0]
        parents = self.skeleton.parents
        minimal = []
        for j in sorted(tops):  # the edited joints no other edited joint is an ancestor of
            a = int(parents[j])
            while a >= 0 and a not in tops:
                a = int(parents[a])
            if a < 0:
                minimal.append(j)
        if 0 not in minimal:
            out.__dict__["_pose_source"] = (known, tuple(minimal))

    def frames(self, start: int, stop: int | None = None) -> "Motion":
        """Frames ``start`` .. ``stop - 1`` (Python slice semantics)."""
        sl = slice(start, stop)
        out = Motion(self.skeleton, self.fps, self.root_positions[sl], self.rotations[sl],
                     None if self.translations is None else self.translations[sl])
        known = self._known_pose()
        source = self.__dict__.get("_pose_source")
        # FK is per frame: the slice of the known pose is the pose of the slice
        if known is not None:
            out.__dict__["pose"] = Pose(known.positions[sl], known.rotations[sl])
        elif source is not None:  # a limb edit not yet solved: solve it on the slice only, when asked
            out.__dict__["_pose_source"] = (Pose(source[0].positions[sl], source[0].rotations[sl]), source[1])
        elif "_pose_rows" in self.__dict__:  # frames shared with another motion's pose: the slice's are
            known_rows, rows = self.__dict__["_pose_rows"]
            out.__dict__["_pose_rows"] = (known_rows, rows[sl])
        return out

    def _known_pose(self) -> Pose | None:
        """:attr:`pose` if it is computed (here or on the motion whose copy this is), else ``None``."""
        known = self.__dict__.get("pose")
        same = self.__dict__.get("_pose_of")
        if known is None and same is not None:
            known = same.__dict__.get("pose")
        return known

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

    def read_only(self) -> "Motion":
        """The same frames in read-only arrays of their own: a motion cached and shared by callers
        (the built-in library's clips), which nobody may edit in place."""
        arrays = [self.root_positions, self.rotations] + ([] if self.translations is None else [self.translations])
        own = [np.array(a) for a in arrays]
        for a in own:
            a.setflags(write=False)
        return Motion(self.skeleton, self.fps, *own)

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
        if all(m._known_pose() is not None for m in motions):
            out.__dict__["pose"] = _joined_pose(motions)
        else:
            out.__dict__["_pose_parts"] = tuple(motions)
    return out


def _joined_pose(parts: Sequence[Motion]) -> Pose:
    """The pose of ``parts`` end to end (same bones), each part's own computed once."""
    positions = np.concatenate([m.pose.positions for m in parts])
    rotations = np.concatenate([m.pose.rotations for m in parts])
    positions.setflags(write=False)
    rotations.setflags(write=False)
    return Pose(positions, rotations)

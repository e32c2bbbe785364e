"""Forward kinematics: the world-space :class:`Pose` of a motion's frames, whole or in part.

Inputs are a skeleton and a motion's arrays: local rotations ``(T, J, 4)`` quaternions ``(x, y, z, w)``
and local translations ``(T, J, 3)`` metres (the root's row its world position). :func:`forward` is
the full computation; the others compute the same bits for less when the pose of a motion that
differs in a known way is at hand (a limb edited, the root moved, frames shared, parts joined): each
joint's arithmetic is :func:`forward`'s, and each frame's kinematics depends on that frame alone.
:class:`core.posecache.PoseCache` decides which applies.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .skeleton import Skeleton


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


@dataclass(frozen=True)
class Pose:
    """World-space result of forward kinematics, read-only arrays.

    positions: ``(T, J, 3)`` metres; rotations: ``(T, J, 3, 3)`` world rotation matrices.
    """

    positions: np.ndarray
    rotations: np.ndarray

    def quaternions(self, joints=None) -> np.ndarray:
        """World rotations as ``(T, J, 4)`` quaternions; of ``joints`` only (an index or a list) when given,
        ``(T, 4)`` or ``(T, n, 4)``, converting those joints' matrices only."""
        return matrix_to_quat(self.rotations if joints is None else self.rotations[:, joints])

    def frames(self, sl: slice) -> "Pose":
        """The pose of the frames ``sl`` (views)."""
        return Pose(self.positions[sl], self.rotations[sl])


def _frozen_pose(positions: np.ndarray, rotations: np.ndarray) -> Pose:
    positions.setflags(write=False)
    rotations.setflags(write=False)
    return Pose(positions, rotations)


def forward(skeleton: Skeleton, rotations: np.ndarray, local_t: np.ndarray) -> Pose:
    """The pose of local ``rotations`` ``(T, J, 4)`` and translations ``local_t`` ``(T, J, 3)``, vectorised
    over frames and over the joints of each tree depth."""
    # joint-major (J, T, ...) with the joints in order of depth (Skeleton.depth_order): a depth's joints are one
    # block, read and written in place; only their parents are gathered
    order, inverse, _ = skeleton.depth_order()
    world_r, world_p = _descend(skeleton, local_t, quat_to_matrix(rotations[:, order]).transpose(1, 0, 2, 3).copy())
    # back to (T, J, ...) in skeleton order, C-contiguous: reductions over these arrays sum in the same order
    world_r = np.ascontiguousarray(world_r.transpose(1, 0, 2, 3)[:, inverse])
    world_r.setflags(write=False)
    return Pose(world_p, world_r)


def _descend(skeleton: Skeleton, local_t: np.ndarray, local_r: np.ndarray | None,
             world_r: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Forward kinematics down the tree depth by depth, joint-major in depth order
    (:meth:`Skeleton.depth_order`: a depth's joints are one block, read and written in place; only their
    parents are gathered): from the local rotation matrices ``local_r`` ``(J, T, 3, 3)``, the world
    rotations ``(J, T, 3, 3)`` (in that layout) and the world positions ``(T, J, 3)`` m (skeleton order,
    read-only); given the world rotations ``world_r`` instead, the positions only."""
    order, inverse, levels = skeleton.depth_order()
    local_t = local_t[:, order].transpose(1, 0, 2).copy()
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


def root_moved(skeleton: Skeleton, local_t: np.ndarray, known: Pose) -> Pose:
    """The pose of frames that differ from ``known``'s only in the root's position (``local_t``'s row 0):
    ``known``'s world rotations, the positions summed down the tree again from the same rotated offsets."""
    order = skeleton.depth_order()[0]
    _, world_p = _descend(skeleton, local_t, None, np.ascontiguousarray(known.rotations[:, order].transpose(1, 0, 2, 3)))
    return Pose(world_p, known.rotations)


def below(skeleton: Skeleton, rotations: np.ndarray, translations: np.ndarray | None, known: Pose,
          tops: Sequence[int], rows: tuple[int, int] | None = None) -> Pose:
    """The pose of frames that differ from ``known``'s only in the local ``rotations`` ``(T, J, 4)`` of the
    joints ``tops`` and their descendants (no top below another, the root not among them), and only on the
    frames ``rows`` ``[a, b)`` when given: their kinematics is redone, the other joints' (and frames') world
    transforms are kept. ``translations``: the motion's own non-root translations ``(T, J, 3)``, or ``None``
    (the skeleton's offsets)."""
    world_rot, world_pos = known.rotations.copy(), known.positions.copy()
    sl = slice(None) if rows is None else slice(*rows)
    part = known if rows is None else known.frames(sl)
    for top in tops:
        _subtree(skeleton, rotations[sl], None if translations is None else translations[sl], part, top,
                 world_rot[sl], world_pos[sl])
    return _frozen_pose(world_pos, world_rot)


def _subtree(skeleton: Skeleton, rotations: np.ndarray, translations: np.ndarray | None, known: Pose, top: int,
             world_rot: np.ndarray, world_pos: np.ndarray) -> None:
    """Write the world transforms of ``top``'s subtree into ``world_rot`` ``(T, J, 3, 3)`` and ``world_pos``
    ``(T, J, 3)``, from ``known``'s transform of its parent (see :func:`below`)."""
    sub = skeleton.subtree(top)  # (n,) joints, parents first
    local_r = quat_to_matrix(rotations[:, sub]).transpose(1, 0, 2, 3).copy()
    own_t = translations[:, sub] if translations is not None else \
        np.broadcast_to(skeleton.offsets[sub], (len(rotations), len(sub), 3))
    local_t = own_t.transpose(1, 0, 2).copy()
    world_r = np.empty_like(local_r)
    world_p = np.empty_like(local_t)
    outside = skeleton.parents[top]  # the one parent outside the subtree
    top_r = np.ascontiguousarray(known.rotations[:, outside])[None]
    top_p = np.ascontiguousarray(known.positions[:, outside])[None]
    world_r[:1] = top_r @ local_r[:1]
    world_p[:1] = top_p + np.einsum("ntij,ntj->nti", top_r, local_t[:1])
    for j, p in skeleton.subtree_levels(top):  # slices where a depth's joints are a block (a limb)
        parent_r = world_r[p]
        if isinstance(j, slice):
            np.matmul(parent_r, local_r[j], out=world_r[j])
            np.add(world_p[p], np.einsum("ntij,ntj->nti", parent_r, local_t[j]), out=world_p[j])
        else:
            world_r[j] = parent_r @ local_r[j]
            world_p[j] = world_p[p] + np.einsum("ntij,ntj->nti", parent_r, local_t[j])
    world_rot[:, sub] = world_r.transpose(1, 0, 2, 3)
    world_pos[:, sub] = world_p.transpose(1, 0, 2)


def row_runs(at: np.ndarray, src: np.ndarray, most: int = 8) -> list[tuple[int, int, int]] | None:
    """Frames ``at`` ``(n,)`` taking rows ``src`` ``(n,)`` of another array, as runs ``(at, src, length)`` of
    consecutive frames (a window replaced in a long track: two runs, copied or compared as slices, no
    gather); ``None`` when there are more than ``most``."""
    if not len(at):
        return []
    cuts = np.flatnonzero((np.diff(at) != 1) | (np.diff(src) != 1)) + 1
    if len(cuts) >= most:
        return None
    return [(int(at[s]), int(src[s]), int(e - s)) for s, e in zip(np.r_[0, cuts], np.r_[cuts, len(at)])]


def with_rows(skeleton: Skeleton, rotations: np.ndarray, local_t: np.ndarray, known: Pose, rows: np.ndarray) -> Pose:
    """The pose of ``T`` frames whose frames ``rows >= 0`` ``(T,)`` are ``known``'s frames ``rows``; the others'
    kinematics is computed (:func:`forward` of those frames alone)."""
    new = rows < 0
    n, J = len(rows), skeleton.n_joints
    positions, world_r = np.empty((n, J, 3)), np.empty((n, J, 3, 3))
    kept = np.flatnonzero(~new)
    src = rows[kept]
    spans = row_runs(kept, src)
    if spans is None:
        positions[kept] = known.positions[src]
        world_r[kept] = known.rotations[src]
    for i, r, k in spans or ():
        positions[i:i + k] = known.positions[r:r + k]
        world_r[i:i + k] = known.rotations[r:r + k]
    if new.any():
        part = forward(skeleton, rotations[new], local_t[new])
        positions[new] = part.positions
        world_r[new] = part.rotations
    return _frozen_pose(positions, world_r)


def joined(poses: Sequence[Pose]) -> Pose:
    """``poses`` end to end (of motions on the same bones)."""
    return _frozen_pose(np.concatenate([p.positions for p in poses]), np.concatenate([p.rotations for p in poses]))

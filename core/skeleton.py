"""The joint hierarchy of a character.

Conventions, kept throughout the project: metres, seconds, Y up,
right-handed; rotations are scipy quaternions ``(x, y, z, w)``.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .memo import Memo

POSITION_CHANNELS = ("Xposition", "Yposition", "Zposition")
ROTATION_CHANNELS = ("Xrotation", "Yrotation", "Zrotation")


def _frozen(a, dtype) -> np.ndarray:
    arr = np.array(a, dtype=dtype, copy=True)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True, eq=False)
class Skeleton:
    """A joint hierarchy in topological order (every parent before its children).

    Attributes:
        names: joint names, ``(J,)``.
        parents: parent index per joint, ``(J,)``; ``-1`` for the root (joint 0).
        offsets: rest translation of each joint from its parent, ``(J, 3)`` metres.
        end_sites: ``((joint_index, offset (3,)), ...)``: BVH "End Site" leaves.
        channels: BVH channel names per joint, in file order, e.g.
            ``("Xposition", "Yposition", "Zposition", "Zrotation", "Yrotation", "Xrotation")``.
            The rotation channels' order is the intrinsic Euler order of that joint.
    """

    names: tuple[str, ...]
    parents: np.ndarray
    offsets: np.ndarray
    end_sites: tuple[tuple[int, np.ndarray], ...] = ()
    channels: tuple[tuple[str, ...], ...] = field(default=())
    #: what is derived from the hierarchy (depth order, subtrees, ...), computed once: the arrays are read-only
    derived: Memo = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        names = tuple(self.names)
        n = len(names)
        object.__setattr__(self, "names", names)
        object.__setattr__(self, "parents", _frozen(self.parents, np.int64).reshape(n))
        object.__setattr__(self, "offsets", _frozen(self.offsets, np.float64).reshape(n, 3))
        object.__setattr__(
            self, "end_sites", tuple((int(j), _frozen(o, np.float64).reshape(3)) for j, o in self.end_sites)
        )
        channels = tuple(tuple(c) for c in self.channels) if self.channels else self.default_channels(n)
        object.__setattr__(self, "channels", channels)
        if len(channels) != n:
            raise ValueError(f"{len(channels)} channel lists for {n} joints")
        if n and self.parents[0] != -1:
            raise ValueError("joint 0 must be the root")
        if np.any(self.parents[1:] >= np.arange(1, n)) or np.any(self.parents[1:] < 0):
            raise ValueError("joints must be listed parents first, with a single root")
        object.__setattr__(self, "derived", Memo())

    @staticmethod
    def default_channels(n: int) -> tuple[tuple[str, ...], ...]:
        """Root: XYZ position + ZYX rotation; others: ZYX rotation (the CMU layout)."""
        rot = ("Zrotation", "Yrotation", "Xrotation")
        return tuple((POSITION_CHANNELS + rot) if j == 0 else rot for j in range(n))

    @property
    def n_joints(self) -> int:
        return len(self.names)

    def index(self, name: str) -> int:
        try:
            return self.names.index(name)
        except ValueError:
            raise KeyError(f"no joint named {name!r}") from None

    def children(self, j: int) -> list[int]:
        return [int(c) for c in np.flatnonzero(self.parents == j)]

    def subtree(self, j: int) -> np.ndarray:
        """Joint ``j`` and its descendants, ``(n,)`` in topological order (``j`` first); cached, read-only."""
        def make() -> np.ndarray:
            inside = np.zeros(self.n_joints, dtype=bool)
            inside[j] = True
            for k in range(j + 1, self.n_joints):
                inside[k] = inside[self.parents[k]]
            return _frozen(np.flatnonzero(inside), np.int64)
        return self.derived.get(("subtree", j), make)

    def depth_levels(self) -> tuple[tuple[np.ndarray, np.ndarray], ...]:
        """``(joints, their parents)`` per tree depth 1, 2, ... (the root, depth 0, is left out); cached."""
        def make() -> tuple[tuple[np.ndarray, np.ndarray], ...]:
            depth = np.zeros(self.n_joints, dtype=np.int64)
            for j in range(1, self.n_joints):
                depth[j] = depth[self.parents[j]] + 1
            return tuple((np.flatnonzero(depth == d), self.parents[depth == d])
                         for d in range(1, int(depth.max(initial=0)) + 1))
        return self.derived.get("depth_levels", make)

    def depth_order(self) -> tuple[np.ndarray, np.ndarray, tuple[tuple[int, int, np.ndarray], ...]]:
        """The joints in order of tree depth (for forward kinematics, :func:`core.fk.forward`):
        ``order`` ``(J,)`` (root first, each depth's joints in skeleton order), its ``inverse`` (position of
        each joint), and per depth 1, 2, ... the block ``[a, b)`` of its joints in that order with their
        parents' positions ``(b - a,)``; cached."""
        def make() -> tuple[np.ndarray, np.ndarray, tuple[tuple[int, int, np.ndarray], ...]]:
            order = np.concatenate([[0]] + [joints for joints, _ in self.depth_levels()]).astype(np.int64)
            inverse = np.empty_like(order)
            inverse[order] = np.arange(len(order))
            levels, a = [], 1
            for joints, parents in self.depth_levels():
                levels.append((a, a + len(joints), inverse[parents]))
                a += len(joints)
            return order, inverse, tuple(levels)
        return self.derived.get("depth_order", make)

    def subtree_levels(self, top: int) -> tuple[tuple[np.ndarray | slice, np.ndarray | slice], ...]:
        """Per tree depth below ``top``, the positions in :meth:`subtree` ``(top)`` of that depth's joints and
        of their parents, as slices where they are consecutive (a limb's forward kinematics,
        :func:`core.fk.below`); cached per joint."""
        def make() -> tuple[tuple[np.ndarray | slice, np.ndarray | slice], ...]:
            sub = self.subtree(top)
            slot = np.full(self.n_joints, -1)
            slot[sub] = np.arange(len(sub))
            levels = []
            for joints, parents in self.depth_levels():
                inside = slot[joints] > 0
                if inside.any():
                    levels.append((_block(slot[joints[inside]]), _block(slot[parents[inside]])))
            return tuple(levels)
        return self.derived.get(("subtree_levels", top), make)

    def rotation_order(self, j: int) -> str:
        """Intrinsic Euler order of joint ``j`` as scipy spells it (e.g. ``"ZYX"``), as listed."""
        return "".join(c[0] for c in self.channels[j] if c in ROTATION_CHANNELS)

    def has_position_channels(self, j: int) -> bool:
        return any(c in POSITION_CHANNELS for c in self.channels[j])

    def scaled(self, s: float) -> "Skeleton":
        """The same hierarchy with every length multiplied by ``s``."""
        return Skeleton(self.names, self.parents, self.offsets * s,
                        tuple((j, o * s) for j, o in self.end_sites), self.channels)

    def same_hierarchy(self, other: "Skeleton") -> bool:
        return self.names == other.names and np.array_equal(self.parents, other.parents)

    def rest_positions(self) -> np.ndarray:
        """World positions of the joints in the rest pose, root at the origin, ``(J, 3)``."""
        pos = np.zeros((self.n_joints, 3))
        for j in range(1, self.n_joints):
            pos[j] = pos[self.parents[j]] + self.offsets[j]
        return pos

    def height(self) -> float:
        """Vertical extent of the rest pose including end sites (metres if the skeleton is)."""
        pos = self.rest_positions()
        ends = [pos[j] + o for j, o in self.end_sites]
        allp = np.vstack([pos, *ends]) if ends else pos
        return float(np.ptp(allp[:, 1])) if len(allp) else 0.0


def _block(idx: np.ndarray) -> np.ndarray | slice:
    """``idx`` as a slice when it is a run of consecutive indices (a view instead of a gathered copy)."""
    if len(idx) and np.array_equal(idx, np.arange(idx[0], idx[0] + len(idx))):
        return slice(int(idx[0]), int(idx[0]) + len(idx))
    return idx

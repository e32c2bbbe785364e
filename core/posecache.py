"""What is computed from one motion's frames, kept with that motion: its pose and any derived quantity.

A :class:`~core.motion.Motion` owns one :class:`PoseCache` (``motion.cache``). Motions are immutable (their
arrays are read-only), so a value computed once from a motion's frames holds for as long as the motion
lives, and goes with it: the cache is an attribute of the motion, not a table keyed by motions.

- ``cache.pose(motion)``: forward kinematics (:mod:`core.fk`), computed once. A motion made from another
  whose pose is known (a slice, a limb edited, on every frame or on a window of frames, the root moved, parts
  joined, frames shared with it) is given a *recipe* instead: the other's pose and what differs, so that its
  own pose, when asked, costs that difference only (bit for bit the full computation). The recipe is dropped
  once used. Frames shared with another pose stay shared through a later edit (only the edited frames are
  redone), so a long track whose joins are finished one after another never runs the kinematics of all its
  frames again.
- ``cache.get(key, make)``: any other quantity derived from the motion's frames (foot contacts, headings,
  pose features), by a key that names it and its parameters by value (``("headings", 0.3)``).

The keyed part is a :class:`~core.memo.Memo`, as a :class:`~core.skeleton.Skeleton`'s for what it derives.
A copy or an unpickled cache starts empty.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from . import fk
from .fk import Pose
from .memo import Memo
from .skeleton import Skeleton


class Frames(Protocol):
    """What the cache reads of a motion (:class:`core.motion.Motion` is one)."""

    @property
    def skeleton(self) -> Skeleton: ...

    @property
    def root_positions(self) -> np.ndarray: ...

    @property
    def rotations(self) -> np.ndarray: ...

    @property
    def translations(self) -> np.ndarray | None: ...

    @property
    def cache(self) -> "PoseCache": ...

    def local_translations(self) -> np.ndarray: ...

    def frames(self, start: int, stop: int | None = None) -> "Frames": ...


# ------------------------------------------------------------------ recipes
@dataclass(frozen=True)
class _Below:
    """Only the local rotations of ``tops`` and their descendants differ from ``known``'s frames, and only on
    the frames ``rows`` ``[a, b)`` when given (an edit of a window of a long track: its kinematics is the
    window's)."""

    known: Pose
    tops: tuple[int, ...]
    rows: tuple[int, int] | None = None

    def pose(self, m: Frames) -> Pose:
        return fk.below(m.skeleton, m.rotations, m.translations, self.known, self.tops, self.rows)

    def frames(self, sl: slice) -> "PoseCache":
        """A cache for the frames ``sl`` of the motion: the known pose's where the slice misses ``rows``."""
        known = self.known.frames(sl)
        if self.rows is None:
            return PoseCache(recipe=_Below(known, self.tops))
        start, stop, _ = sl.indices(len(self.known.positions))
        a, b = max(self.rows[0], start) - start, min(self.rows[1], stop) - start
        return PoseCache(known) if b <= a else PoseCache(recipe=_Below(known, self.tops, (a, b)))


@dataclass(frozen=True)
class _RootMoved:
    """Only the root's positions differ from ``known``'s frames."""

    known: Pose

    def pose(self, m: Frames) -> Pose:
        return fk.root_moved(m.skeleton, m.local_translations(), self.known)


@dataclass(frozen=True)
class _Rows:
    """Frames ``rows >= 0`` are ``known``'s frames ``rows``."""

    known: Pose
    rows: np.ndarray

    def pose(self, m: Frames) -> Pose:
        return fk.with_rows(m.skeleton, m.rotations, m.local_translations(), self.known, self.rows)

    def redone(self, frames: np.ndarray | slice) -> "PoseCache":
        """A cache for the motion with ``frames`` (a bool mask or a slice) edited: their kinematics computed."""
        rows = self.rows.copy()
        rows[frames] = -1
        return PoseCache(recipe=_Rows(self.known, rows) if (rows >= 0).any() else None)


@dataclass(frozen=True)
class _Parts:
    """The motion is ``parts`` end to end, on the same bones."""

    parts: tuple[Frames, ...]

    def pose(self, m: Frames) -> Pose:
        return fk.joined([p.cache.pose(p) for p in self.parts])

    def frames(self, sl: slice) -> "PoseCache":
        """A cache for the frames ``sl`` of the motion: the parts' frames there, end to end, joined when asked
        (a window of a long track laid in pieces costs the window's, not the track's)."""
        ends = np.cumsum([len(p.rotations) for p in self.parts])
        start, stop, _ = sl.indices(int(ends[-1]) if len(ends) else 0)
        cut = []
        for k in range(int(np.searchsorted(ends, start, side="right")), len(self.parts)):
            at = int(ends[k]) - len(self.parts[k].rotations)
            if at >= stop:
                break
            part, a, b = self.parts[k], max(start, at) - at, min(stop, int(ends[k])) - at
            cut.append(part if a == 0 and b == len(part.rotations) else part.frames(a, b))  # (whole: itself)
        return PoseCache(recipe=_Parts(tuple(cut))) if cut else PoseCache()


Recipe = _Below | _RootMoved | _Rows | _Parts


class PoseCache(Memo):
    """One motion's pose (:meth:`pose`) and derived quantities (:meth:`~core.memo.Memo.get`); see the module docstring."""

    __slots__ = ("_pose", "_recipe")

    def __init__(self, pose: Pose | None = None, recipe: Recipe | None = None) -> None:
        super().__init__()
        self._pose = pose
        self._recipe = recipe

    def pose(self, m: Frames) -> Pose:
        """The pose of ``m`` (the motion owning this cache), computed once."""
        if self._pose is None:
            recipe, self._recipe = self._recipe, None  # not kept once used: it holds another pose
            self._pose = fk.forward(m.skeleton, m.rotations, m.local_translations()) if recipe is None \
                else recipe.pose(m)
        return self._pose

    def known_pose(self) -> Pose | None:
        """The pose if it is computed, else ``None``."""
        return self._pose

    # --------------------------------------------------- caches of motions made from this one
    def of_frames(self, sl: slice) -> "PoseCache":
        """A cache for the frames ``sl`` of this motion: the slice of the pose when it is known (a limb edit
        not yet solved is solved on the slice only; frames shared with another pose, the slice's are)."""
        if self._pose is not None:
            return PoseCache(self._pose.frames(sl))
        if isinstance(self._recipe, _Below):
            return self._recipe.frames(sl)
        if isinstance(self._recipe, _Rows):
            return PoseCache(recipe=_Rows(self._recipe.known, self._recipe.rows[sl]))
        if isinstance(self._recipe, _Parts):
            return self._recipe.frames(sl)
        return PoseCache()

    def of_root_moved(self, m: Frames, root_positions: np.ndarray) -> "PoseCache":
        """A cache for ``m`` (this cache's motion) with the root positions ``root_positions`` ``(T, 3)``
        instead: the world rotations stay (frames shared with another pose and not moved still are)."""
        if self._pose is None and isinstance(self._recipe, _Rows):
            return self._recipe.redone((root_positions.view(np.int64) != m.root_positions.view(np.int64)).any(axis=1))
        if self._pose is not None and np.array_equal(root_positions.view(np.int64), m.root_positions.view(np.int64)):
            return PoseCache(self._pose)  # the same frames (a writable copy of the rows): the same pose
        return PoseCache(recipe=None if self._pose is None else _RootMoved(self._pose))

    def of_rotations(self, m: Frames, rotations: np.ndarray) -> "PoseCache":
        """A cache for ``m`` (this cache's motion) with the local ``rotations`` ``(T, J, 4)`` instead: the
        subtrees holding the joints whose rotations differ are redone from this pose (or from the pose this
        one's recipe starts from: edits on edits), when asked."""
        known, below = self._pose, self._recipe if isinstance(self._recipe, _Below) else None
        if isinstance(self._recipe, _Rows):  # frames shared with another pose: those not edited still are
            return self._recipe.redone((rotations.view(np.int64) != m.rotations.view(np.int64)).any(axis=(1, 2)))
        if known is None and below is None:
            return PoseCache()
        changed = np.flatnonzero((rotations.view(np.int64) != m.rotations.view(np.int64)).any(axis=(0, 2)))
        if len(changed) == 0:
            return PoseCache(known, None if known is not None else below)
        tops = {int(j) for j in changed}
        if known is None:
            assert below is not None
            tops |= set(below.tops)
            known = below.known
        minimal = _highest(m.skeleton.parents, tops)
        return PoseCache(recipe=None if 0 in minimal else _Below(known, tuple(minimal)))

    def of_window(self, m: Frames, rotations: np.ndarray, lo: int, hi: int) -> "PoseCache":
        """A cache for ``m`` (this cache's motion) with the local ``rotations`` ``(T, J, 4)`` instead, which
        differ from ``m``'s on the frames ``[lo, hi)`` only (the caller says so: nothing outside is compared):
        :meth:`of_rotations`' answer, with the kinematics redone over those frames only, when asked."""
        known, below = self._pose, self._recipe if isinstance(self._recipe, _Below) else None
        if isinstance(self._recipe, _Rows):
            return self._recipe.redone(slice(lo, hi))
        if known is None and below is None:
            return PoseCache()
        new, old = rotations[lo:hi], m.rotations[lo:hi]
        changed = np.flatnonzero((new.view(np.int64) != old.view(np.int64)).any(axis=(0, 2)))
        if len(changed) == 0:
            return PoseCache(known, None if known is not None else below)
        tops = {int(j) for j in changed}
        rows: tuple[int, int] | None = (lo, hi)
        if known is None:
            assert below is not None
            tops |= set(below.tops)
            known = below.known
            rows = None if below.rows is None else (min(lo, below.rows[0]), max(hi, below.rows[1]))
        minimal = _highest(m.skeleton.parents, tops)
        return PoseCache(recipe=None if 0 in minimal else _Below(known, tuple(minimal), rows))

    @staticmethod
    def of_parts(parts: Sequence[Frames]) -> "PoseCache":
        """A cache for ``parts`` end to end: their poses joined, now if every part's is known, else when asked
        (only the parts not yet solved are)."""
        # a part itself still parts end to end gives those (a track laid in pieces join after join stays one
        # level of pieces, joined once when asked)
        parts = [q for p in parts for q in (p.cache.unjoined_parts() or (p,))]
        if all(p.cache.known_pose() is not None for p in parts):
            return PoseCache(fk.joined([p.cache.pose(p) for p in parts]))
        return PoseCache(recipe=_Parts(tuple(parts)))

    def unjoined_parts(self) -> tuple[Frames, ...] | None:
        """The parts whose poses end to end are this one, not yet joined (:meth:`of_parts`), else ``None``."""
        return self._recipe.parts if self._pose is None and isinstance(self._recipe, _Parts) else None

    def share(self, m: Frames, other: Frames, rows: np.ndarray) -> None:
        """Let ``m``'s pose (this cache's) take ``other``'s where the frames are the same: ``rows`` ``(T,)``
        says which frame of ``other`` each frame may be (``-1``: none); where the two frames' root position
        and local rotations (and translations) are bit for bit equal and ``other``'s pose is known, the
        frame's pose is ``other``'s."""
        known, through = other.cache.known_pose(), None
        if known is None and isinstance(other.cache._recipe, _Rows):  # other's frames shared with a third pose
            known, through = other.cache._recipe.known, other.cache._recipe.rows
        rows = np.asarray(rows, dtype=np.int64)
        if known is None or len(rows) != len(m.rotations) or self._pose is not None or \
                self._recipe is not None and not isinstance(self._recipe, _Rows):
            return
        if not (other.skeleton is m.skeleton or np.array_equal(other.skeleton.offsets, m.skeleton.offsets)):
            return
        rows = np.where((rows >= 0) & (rows < len(other.rotations)), rows, -1)
        have = np.flatnonzero(rows >= 0)
        src = rows[have]
        same = _same_frames(m, other, have, src)
        if m.translations is not None or other.translations is not None:
            same &= (m.local_translations()[have].view(np.int64)
                     == other.local_translations()[src].view(np.int64)).all(axis=(1, 2))
        rows[have[~same]] = -1
        if through is not None:
            rows = np.where(rows >= 0, through[np.maximum(rows, 0)], -1)
        if (rows >= 0).any():
            self._recipe = _Rows(known, rows)


def _same_frames(m: Frames, other: Frames, have: np.ndarray, src: np.ndarray) -> np.ndarray:
    """``(n,)`` bool: ``m``'s frames ``have`` have bit for bit ``other``'s frames ``src``' root position and
    local rotations (runs of consecutive frames compared as slices)."""
    spans = fk.row_runs(have, src)
    if spans is None:
        same = (m.root_positions[have].view(np.int64) == other.root_positions[src].view(np.int64)).all(axis=1)
        return same & (m.rotations[have].view(np.int64) == other.rotations[src].view(np.int64)).all(axis=(1, 2))
    out = []
    for i, r, k in spans:
        same = (m.root_positions[i:i + k].view(np.int64) == other.root_positions[r:r + k].view(np.int64)).all(axis=1)
        out.append(same & (m.rotations[i:i + k].view(np.int64) == other.rotations[r:r + k].view(np.int64)).all(axis=(1, 2)))
    return np.concatenate(out) if out else np.zeros(0, dtype=bool)


def _highest(parents: np.ndarray, joints: set[int]) -> list[int]:
    """The ``joints`` no other of them is an ancestor of, ascending."""
    out = []
    for j in sorted(joints):
        a = int(parents[j])
        while a >= 0 and a not in joints:
            a = int(parents[a])
        if a < 0:
            out.append(j)
    return out

"""A human skeleton's limbs from its shape, when no name table knows its joints.

Read from the rest pose (metres, Y up; ``H`` the skeleton's height):

1. the **hips** are the first joint from the root with a branch: two chains that reach down (the legs,
   their lowest point more than 0.3 H below it) and one that reaches up (the spine);
2. up the spine, the **upper chest** is the first joint with a chain reaching out to each side (the arms,
   more than 0.2 H sideways) and one going up (the neck); the **head** is the last joint of that chain
   below the top of the skull (its end site or end joint);
3. along a leg (following the child that reaches lowest): the **foot** is the first joint within 0.12 of
   the leg's height of its lowest point, the **lower leg** (knee) the joint nearest halfway down from the
   leg's first joint set off sideways from the hips, the **upper leg** the joint before the knee when a
   whole thigh (0.15 H) lies between them (a helper such as Daz's ``lButtock`` comes before it), else that
   first sideways joint (a thigh split by a twist segment); the **toes** the foot's next joint;
4. along an arm (following the child that reaches furthest out): the **hand** is the first joint with
   several children (the fingers), else the last; the **lower arm** (elbow) the joint nearest 55 % of
   the way from the arm's first joint to the hand, the **upper arm** the joint before it, the
   **shoulder** the arm's first joint when that is not the upper arm;
5. **left** is the side of ``up × forward``, forward being where the toes point from the ankles.

A skeleton without two such legs, two such arms or a head is not read as a human one:
:class:`core.rig_error.RigError` says which is missing.
"""
from __future__ import annotations

import numpy as np

from .rig_error import RigError
from .skeleton import Skeleton


class _Shape:
    """The rest pose's geometry: positions ``(J, 3)``, children, and each subtree's extent, gathered once
    from the leaves up (the skeleton is in topological order), so every question about a subtree costs
    O(1) and reading a skeleton is linear in its joints (a 9,990-joint chain took 28 s walking a subtree
    per joint)."""

    def __init__(self, skel: Skeleton):
        self.skel = skel
        self.pos = skel.rest_positions()
        self.parents = [int(p) for p in skel.parents]
        self.children: list[list[int]] = [[] for _ in self.pos]
        for j, p in enumerate(self.parents):
            if p >= 0:
                self.children[p].append(j)
        points = [[self.pos[j]] for j in range(len(self.pos))]
        for j, offset in skel.end_sites:
            points[j].append(self.pos[j] + np.asarray(offset))
        self.tips = [np.array(p) for p in points]  # each joint's own point and end site
        self.low = self._up(np.array([t.min(axis=0) for t in self.tips]), np.minimum)  # (J, 3) subtree minimum
        self.high = self._up(np.array([t.max(axis=0) for t in self.tips]), np.maximum)  # (J, 3) subtree maximum
        self.total = self._up(np.array([t.sum(axis=0) for t in self.tips]), np.add)  # (J, 3) sum of its points
        self.count = self._up(np.array([float(len(t)) for t in self.tips]), np.add)  # (J,) its points
        roots = [j for j, p in enumerate(self.parents) if p < 0]
        self.height = float(self.high[roots, 1].max() - self.low[roots, 1].min()) or 1.0
        self._reach: dict[bytes, tuple[np.ndarray, np.ndarray]] = {}

    def _up(self, own: np.ndarray, combine) -> np.ndarray:
        """``own`` (one row per joint) combined over each joint's subtree, children into parents."""
        out = own.copy()
        for j in range(len(out) - 1, 0, -1):
            p = self.parents[j]
            if p >= 0:
                out[p] = combine(out[p], out[j])
        return out

    def mean(self, j: int) -> np.ndarray:
        """The mean of ``j``'s subtree's points ``(3,)``."""
        return self.total[j] / self.count[j]

    def reach(self, j: int, centre: np.ndarray, axis: np.ndarray) -> float:
        """How far ``j``'s subtree reaches from ``centre`` along ``axis``: max |(p - centre) · axis|."""
        key = axis.tobytes()
        if key not in self._reach:
            along = [t @ axis for t in self.tips]
            self._reach[key] = (self._up(np.array([a.min() for a in along]), np.minimum),
                                self._up(np.array([a.max() for a in along]), np.maximum))
        lo, hi = self._reach[key]
        c = float(centre @ axis)
        return max(float(hi[j]) - c, c - float(lo[j]))

    def chain(self, j: int, key) -> list[int]:
        """``j`` and, at each joint, the child that scores lowest by ``key(child)``."""
        out = [j]
        while self.children[out[-1]]:
            out.append(min(self.children[out[-1]], key=key))
        return out


def _nearest(shape: _Shape, joints: list[int], point: np.ndarray) -> int:
    return min(joints, key=lambda j: float(np.linalg.norm(shape.pos[j] - point)))


def _leg(shape: _Shape, start: int, hips: int, side_axis: np.ndarray) -> dict[str, int]:
    chain = shape.chain(start, key=lambda c: shape.low[c, 1])
    ys = shape.pos[chain, 1]
    lowest = float(shape.low[start, 1])
    offset = np.abs((shape.pos[chain] - shape.pos[hips]) @ side_axis)
    upper = next((j for j, o in zip(chain, offset) if o > 0.03 * shape.height), chain[0])
    top = float(shape.pos[upper, 1])
    foot = next((j for j, y in zip(chain, ys) if y - lowest < 0.12 * (top - lowest) and j != upper), None)
    if foot is None or chain.index(foot) < chain.index(upper) + 2:
        raise RigError("a leg has no knee and ankle below its hip")
    between = chain[chain.index(upper) + 1:chain.index(foot)]
    mid = (shape.pos[upper] + shape.pos[foot]) / 2
    knee = _nearest(shape, between, mid)
    thigh = chain[chain.index(knee) - 1]  # a helper before the thigh (Daz's lButtock) is not the upper leg,
    if np.linalg.norm(shape.pos[knee] - shape.pos[thigh]) >= 0.15 * shape.height:  # a twist segment is
        upper = thigh
    roles = {"UpperLeg": upper, "LowerLeg": knee, "Foot": foot}
    after = chain.index(foot) + 1
    if after < len(chain):
        roles["Toes"] = chain[after]
    return roles


def _arm(shape: _Shape, start: int, chest: int, side_axis: np.ndarray) -> dict[str, int]:
    chain = shape.chain(start, key=lambda c: -shape.reach(c, shape.pos[chest], side_axis))
    hand = next((j for j in chain if len(shape.children[j]) >= 2), chain[-1])
    upto = chain[:chain.index(hand)]
    if len(upto) < 2:
        raise RigError("an arm has no upper arm and elbow before its hand")
    point = shape.pos[chain[0]] + 0.55 * (shape.pos[hand] - shape.pos[chain[0]])
    elbow = _nearest(shape, upto[1:], point)
    upper = chain[chain.index(elbow) - 1]
    roles = {"UpperArm": upper, "LowerArm": elbow, "Hand": hand}
    if chain[0] != upper:
        roles["Shoulder"] = chain[0]
    return roles


def infer_roles(skel: Skeleton) -> dict[str, int]:
    """``{role: joint index}`` (:data:`core.rigs.ROLES`) of a human skeleton read from its shape (module
    docstring); raises :class:`core.rig_error.RigError` naming what a human skeleton would have and this lacks."""
    shape = _Shape(skel)
    H = shape.height
    hips = 0
    while True:
        y = shape.pos[hips, 1]
        down = [c for c in shape.children[hips] if shape.low[c, 1] < y - 0.3 * H]
        up = [c for c in shape.children[hips] if shape.high[c, 1] > y + 0.3 * H]
        if len(down) == 2 and up:
            break
        if len(shape.children[hips]) != 1:
            raise RigError(f"no hips with two legs below them and a spine above (the first branch, "
                           f"{skel.names[hips]!r}, has {len(down)} chain(s) reaching down)")
        hips = shape.children[hips][0]
    spine_start = max(up, key=lambda c: shape.high[c, 1])
    # forward: where the toes point from the ankles (rest pose), else +Z
    tips = [shape.chain(c, key=lambda k: shape.low[k, 1]) for c in down]
    fwd = sum(shape.mean(t[-1])[[0, 2]] - shape.pos[t[max(0, len(t) - 2)], [0, 2]] for t in tips)
    forward = np.array([fwd[0], 0.0, fwd[1]]) if np.linalg.norm(fwd) > 1e-3 * H else np.array([0.0, 0.0, 1.0])
    forward /= np.linalg.norm(forward)
    left_axis = np.cross([0.0, 1.0, 0.0], forward)

    chest = spine_start
    while True:
        c = shape.pos[chest]
        out = [k for k in shape.children[chest] if shape.reach(k, c, left_axis) > 0.2 * H]
        sides = {np.sign(float((shape.mean(k) - c) @ left_axis)) for k in out}
        if len(out) >= 2 and sides == {-1.0, 1.0}:
            break
        above = [k for k in shape.children[chest] if shape.high[k, 1] > c[1]]
        if not above:
            raise RigError("no arms: no joint up the spine has a chain reaching out to each side")
        chest = max(above, key=lambda k: shape.high[k, 1])
    neck_start = [k for k in shape.children[chest] if k not in out]
    if not neck_start:
        raise RigError("no head: nothing goes up between the arms")
    neck = max(neck_start, key=lambda k: shape.high[k, 1])
    top = shape.high[neck, 1]
    head_chain = shape.chain(neck, key=lambda k: -shape.high[k, 1])
    below_top = [j for j in head_chain if shape.pos[j, 1] < top - 0.05 * H]  # none: a head as tall as a point
    head = below_top[-1] if below_top else neck

    roles: dict[str, int] = {"hips": hips, "spine": spine_start, "head": head}
    if chest != spine_start:  # the arms' branch is the upper chest (VRM's naming), the joint below it the chest
        roles["upperChest"] = chest
        below = shape.parents[chest]
        if below not in (spine_start, hips):
            roles["chest"] = below
    if neck != head:
        roles["neck"] = neck
    for k in down:
        side = "left" if float((shape.mean(k) - shape.pos[hips]) @ left_axis) > 0 else "right"
        roles.update({side + r: j for r, j in _leg(shape, k, hips, left_axis).items()})
    for k in out[:2]:
        side = "left" if float((shape.mean(k) - shape.pos[chest]) @ left_axis) > 0 else "right"
        roles.update({side + r: j for r, j in _arm(shape, k, chest, left_axis).items()})
    missing = [r for r in ("leftUpperLeg", "rightUpperLeg", "leftHand", "rightHand") if r not in roles]
    if missing:
        raise RigError("not a human skeleton: both legs and both arms must reach out to their own side "
                       f"(missing {', '.join(missing)})")
    return roles

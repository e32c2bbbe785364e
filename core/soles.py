"""A character's soles, read from its mesh: the line from heel to ball each foot stands on.

A skeleton says where the ankle and the toe joint are, not where the sole is: Mixamo puts the toe
joint at the ball, 40° below the ankle's forward, where our built-in body's is 23° below it, so a
foot turned to point its bone where ours points stands 17° heel-down (three.js's Michelle). The mesh
knows: :func:`sole_lines` takes the vertices skinned to a foot and its toes (:mod:`core.gltf_mesh`),
in the rest pose, and finds the lowest point of the heel (the back quarter of the foot's length) and of
the ball and toes (the front 40 %); the line between them is what stands on the floor.
:func:`core.retarget.rest_alignment` turns that line onto the level forward of the source foot at rest,
the retarget plants the toe joint at the mesh's own height above that line, and :func:`clear_soles`
keeps the underside out of the floor.

Units: metres, Y up; directions are unit ``(3,)`` vectors in the rest pose's world frame.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .clearance import FLOOR_RAMP_SECONDS, RAMP, envelope, lift
from .gltf_mesh import bind_vertices
from .gltf_rig import GltfRig
from .ik import leg_ik
from .motion import Motion

__all__ = ["Sole", "sole_lines", "clear_soles", "underside_heights", "sole_pitch", "HEEL", "BALL", "MIN_VERTICES",
           "MAX_PITCH", "TOE_SHARE", "UNDERSIDE", "MAX_POINTS"]

#: The back share of a foot's length where its heel is looked for ...
HEEL = 0.25
#: ... and the front share where its ball and toes are.
BALL = 0.4
#: Fewer vertices than this on a foot say nothing about its sole.
MIN_VERTICES = 8
#: A sole line steeper than this (degrees) in the rest pose is no sole a character stands on (a mesh of
#: boxes around the joints, a foot modelled pointed): such a foot keeps its bone's alignment.
MAX_PITCH = 10.0
#: A sole lies under the foot: its toe joint stands no higher above it than this share of the ankle's height
#: (a Mixamo shoe: 0.25; boxes around the joints of a 0.2 m figure, wider than its foot is long: 0.75).
TOE_SHARE = 0.5
#: A vertex this far above the sole line (m), or closer, is on the underside ...
UNDERSIDE = 0.01
#: ... of which at most this many, spread from heel to toe, are kept out of the floor.
MAX_POINTS = 64


@dataclass(frozen=True, eq=False)
class Sole:
    """One foot's sole in the rest pose: ``line`` ``(3,)`` unit, heel to ball; ``toe_height`` (m) how far the
    foot's toe joint (the ankle on a foot without one) stands above that line: the mesh's own
    :data:`core.floor.FOOT_CLEARANCE`; ``ankle``, ``toe`` the joints; ``points`` ``(P, 3)`` the underside:
    vertices within :data:`UNDERSIDE` of the line (at most :data:`MAX_POINTS`), each from the joint
    ``carriers`` ``(P,)`` it moves with (the ankle or the toe joint, whichever weighs more), rest pose."""

    line: np.ndarray
    toe_height: float
    ankle: int
    toe: int
    points: np.ndarray
    carriers: np.ndarray


def sole_lines(rig: GltfRig, feet: dict[str, tuple[int, int]]) -> dict[str, Sole]:
    """``{name: Sole}`` of each foot ``feet[name] = (ankle, toe)`` (skeleton joint indices; the ankle twice
    on a foot without a toe joint) in the rest pose, from the vertices bound to the ankle and the joints
    below it; a foot whose mesh says too little (no skinned vertices, fewer than :data:`MIN_VERTICES`, no
    length) is left out."""
    skel = rig.skeleton
    rest = rig.node_world[list(rig.nodes), :3, 3]  # (J, 3) the joints where the vertices were bound
    up = np.array([0.0, 1.0, 0.0])
    out = {}
    for name, (joint, toe) in feet.items():
        below = [int(j) for j in skel.subtree(joint)]
        bound = bind_vertices(rig.gl, rig.bin, rig.node_world, np.array([rig.nodes[j] for j in below]))
        v = bound.positions
        if len(v) < MIN_VERTICES:
            continue
        ahead = (rest[below[-1]] if len(below) > 1 else v.mean(axis=0)) - rest[joint]
        fwd = ahead - up * (ahead @ up)
        if np.linalg.norm(fwd) < 1e-9:
            continue
        fwd /= np.linalg.norm(fwd)
        u = (v - rest[joint]) @ fwd
        lo, span = float(u.min()), float(np.ptp(u))
        if span < 1e-6:
            continue
        heel = np.flatnonzero(u <= lo + HEEL * span)
        ball = np.flatnonzero(u >= lo + (1 - BALL) * span)
        h, b = heel[np.argmin(v[heel, 1])], ball[np.argmin(v[ball, 1])]
        slope = (v[b, 1] - v[h, 1]) / max(u[b] - u[h], 1e-9)
        if abs(slope) > np.tan(np.radians(MAX_PITCH)):
            continue
        line = fwd + slope * up
        above = rest[toe, 1] - (v[h, 1] + slope * ((rest[toe] - rest[joint]) @ fwd - u[h]))
        if toe != joint and not 0.0 <= above <= TOE_SHARE * (rest[joint, 1] - (v[h, 1] - slope * u[h])):
            continue
        under = np.flatnonzero(v[:, 1] - (v[h, 1] + slope * (u - u[h])) <= UNDERSIDE * np.sqrt(1 + slope ** 2))
        under = under[np.argsort(u[under], kind="stable")]
        under = under[np.unique(np.linspace(0, len(under) - 1, min(len(under), MAX_POINTS)).round().astype(int))]
        toe_node = rig.nodes[toe]
        on_toe = (bound.weights[under] * (bound.nodes[under] == toe_node)).sum(axis=1) > 0.5 if toe != joint \
            else np.zeros(len(under), dtype=bool)
        carriers = np.where(on_toe, toe, joint)
        out[name] = Sole(line / np.linalg.norm(line), float(above / np.sqrt(1 + slope ** 2)), joint, toe,
                         v[under] - rest[carriers], carriers)
    return out


def underside_heights(motion: Motion, sole: Sole) -> np.ndarray:
    """``(T, P)`` heights (m) of the sole's underside points as ``motion`` (on the sole's rig) moves them."""
    rot = motion.pose.rotations[:, sole.carriers, 1]  # (T, P, 3): the rows giving y
    return np.einsum("tpb,pb->tp", rot, sole.points) + motion.positions[:, sole.carriers, 1]


def sole_pitch(motion: Motion, sole: Sole) -> np.ndarray:
    """``(T,)`` degrees the sole line rises from heel to ball as ``motion`` turns the foot (+: heel down)."""
    d = np.einsum("tab,b->ta", motion.pose.rotations[:, sole.ankle], sole.line)
    return np.degrees(np.arctan2(d[:, 1], np.hypot(d[:, 0], d[:, 2])))


def clear_soles(motion: Motion, soles: dict[str, Sole]) -> Motion:
    """``motion`` (on the rig the soles were read from; ``soles`` keyed ``"leftFoot"``/``"rightFoot"``) with
    each foot lifted where its underside (``Sole.points``) would go below ``y = 0``, as
    :func:`core.clearance.clear_floor` lifts a joint or an end site."""
    limbs, deficits = [], []
    for role, sole in soles.items():
        limbs.append((leg_ik, role[:-len("Foot")], sole.ankle))
        deficits.append(np.maximum(0.0, -underside_heights(motion, sole).min(axis=1)))
    n = max(RAMP, int(round(FLOOR_RAMP_SECONDS * motion.fps)))
    return lift(motion, limbs, [envelope(d, n) for d in deficits], 0)

"""Balance: the body's centre of mass over the feet that carry it (docs/timetable.md §3).

**Centre of mass** (:func:`centre_of_mass`): fourteen segments between the joints of the rig's humanoid
roles (:func:`core.rigs.rig_roles`), each with its share of the body's mass and the place of its own
centre along it, from de Leva (1996), *Adjustments to Zatsiorsky-Seluyanov's segment inertia
parameters*, J. Biomech. 29(9):1223-1230, Table 4 (males): head 6.94 % (its centre half a head above
the neck joint), trunk 43.46 % (51.38 % of the way from the neck to the hip joints' midpoint), upper arm
2.71 % (57.72 % from the shoulder), forearm 1.62 % (45.74 % from the elbow), hand 0.61 % (beyond the
wrist by a third of the forearm's direction: the table's 79 % to the knuckles), thigh 14.16 % (40.95 %
from the hip), shank 4.33 % (44.59 % from the knee), foot 1.37 % (halfway from the ankle to the toe
joint). The shares add up to 100 %.

**Support area**: on each frame, the convex hull of the ankle and toe joints (on the ground plane) of
the feet on the floor (the lowest joint within the contact rule's 5 cm of where a planted foot's lowest
joint stands, :data:`core.floor.FOOT_CLEARANCE` above the floor at y = 0; at any speed: a foot pivoting or
sliding still carries weight; the floor, not each foot's lowest reach in the motion, since clips of two
captures plant their feet a few centimetres apart), widened by :data:`FOOT_RADIUS` (half a
foot's width and the heel behind the ankle joint), in leg lengths (:func:`core.size.leg_length`,
0.86 m for a person) so size does not matter.

**The figure** (:func:`balance_cm`): on frames where a foot is down, the centre of mass moves slower than
:data:`SLOW` (a body moving slowly must be balanced statically; walking and running fall forward
between steps by design) and the hips are higher than :data:`SEATED` leg lengths (a seated, kneeling or
lying body rests on more than its feet), how far (cm, at a person's size) the centre of mass's ground
projection is outside the support area, over runs of at least :data:`RUN` s (the least of each run);
the largest over the motion. Calibrated on the shared capture
(``benchmarks/bench_transitions.py``): the limit :data:`LIMIT_CM` is what capture does — over the 68 shared
CMU takes at most 5.4 cm (a dance), except a sit-down onto a chair (14_27: 19 cm, its weight going onto
the seat while the hips are still above :data:`SEATED`), which the limit leaves out.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .contacts import runs
from .floor import ON_FLOOR
from .motion import Motion
from .rigs import rig_roles
from .rig_error import RigError
from .size import HUMAN_LEG, human_scale, leg_length

#: (proximal role, distal role, mass share, centre's place from proximal to distal) — de Leva 1996, Table 4
#: (males). The head, hands and feet have no distal joint of their own in a rig: module docstring.
SEGMENTS = (
    ("upperArm", "lowerArm", 0.0271, 0.5772),
    ("lowerArm", "hand", 0.0162, 0.4574),
    ("upperLeg", "lowerLeg", 0.1416, 0.4095),
    ("lowerLeg", "foot", 0.0433, 0.4459),
)
HEAD, TRUNK, HAND, FOOT = 0.0694, 0.4346, 0.0061, 0.0137
TRUNK_AT = 0.5138  # from the neck to the hip joints' midpoint
#: leg lengths: half a foot's width (~4.5 cm) and the heel behind the ankle joint, for a person's 0.86 m legs
FOOT_RADIUS = 0.055
#: m/s at a person's size: a centre of mass slower than this is held to static balance
SLOW = 0.3
#: s: how long the centre of mass must stay outside the support area to count
RUN = 0.2
#: leg lengths: hips lower than this above the feet's floor are seated, kneeling or lying
SEATED = 0.75
#: cm: the most capture's centre of mass stays outside its support area (bench_transitions.py: 5.4 cm, a dance,
#: CMU 05_02; swordplay 3.7, a deep squat 2.7, everything else under 1.5), rounded up
LIMIT_CM = 6.0


def _side(role: str, side: str) -> str:
    return side + role[0].upper() + role[1:]


def centre_of_mass(motion: Motion, roles: dict[str, int] | None = None) -> np.ndarray:
    """``(T, 3)`` world positions (m) of the body's centre of mass (module docstring). ``roles``: the rig's
    :func:`core.rigs.rig_roles`, when already read. Raises :class:`RigError` for a rig whose humanoid joints
    cannot be placed."""
    roles = rig_roles(motion.skeleton)[1] if roles is None else roles
    pos = motion.positions  # (T, J, 3)
    neck = pos[:, roles.get("neck", roles["head"])]
    head = pos[:, roles["head"]]
    hip_mid = 0.5 * (pos[:, roles["leftUpperLeg"]] + pos[:, roles["rightUpperLeg"]])
    com = HEAD * (head + 0.5 * (head - neck)) + TRUNK * (neck + TRUNK_AT * (hip_mid - neck))
    for side in ("left", "right"):
        for a, b, mass, at in SEGMENTS:
            pa, pb = pos[:, roles[_side(a, side)]], pos[:, roles[_side(b, side)]]
            com += mass * (pa + at * (pb - pa))
        wrist, elbow = pos[:, roles[_side("hand", side)]], pos[:, roles[_side("lowerArm", side)]]
        com += HAND * (wrist + (wrist - elbow) / 3.0)
        ankle = pos[:, roles[_side("foot", side)]]
        toe = pos[:, roles[_side("toes", side)]] if _side("toes", side) in roles else ankle
        com += FOOT * (0.5 * (ankle + toe))
    return com


def _segment_nearest(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``(T, 2)`` the points of segments ``a``-``b`` ``(T, 2)`` nearest the 2-D points ``p`` ``(T, 2)``."""
    ab = b - a
    t = np.clip(np.einsum("ti,ti->t", p - a, ab) / np.maximum(np.einsum("ti,ti->t", ab, ab), 1e-12), 0.0, 1.0)
    return a + t[:, None] * ab


def _inside_triangle(p: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """``(T,)`` whether 2-D points ``p`` lie in triangles ``abc`` (all ``(T, 2)``)."""
    def cross(u, v, w):
        return (v[:, 0] - u[:, 0]) * (w[:, 1] - u[:, 1]) - (v[:, 1] - u[:, 1]) * (w[:, 0] - u[:, 0])
    d1, d2, d3 = cross(a, b, p), cross(b, c, p), cross(c, a, p)
    neg = (d1 < 0) | (d2 < 0) | (d3 < 0)
    pos = (d1 > 0) | (d2 > 0) | (d3 > 0)
    return ~(neg & pos)


def support_gap(point: np.ndarray, corners: np.ndarray, down: np.ndarray) -> np.ndarray:
    """``(T, 2)`` metres from the 2-D ``point`` ``(T, 2)`` to the nearest point of the convex hull of the
    ``corners`` ``(T, K, 2)`` that are ``down`` ``(T, K)`` (0 inside; NaN where none is down). The hull of
    K points holds the point iff one of their triangles does, and outside it the nearest of the segments
    between them is on its boundary (every other segment lies inside it)."""
    T, K = down.shape
    best = np.full(T, np.inf)
    gap = np.zeros((T, 2))
    inside = np.zeros(T, dtype=bool)
    for i in range(K):
        for j in range(i, K):
            ok = down[:, i] & down[:, j]
            near = _segment_nearest(point, corners[:, i], corners[:, j])
            d = np.linalg.norm(near - point, axis=-1)
            better = ok & (d < best)
            best = np.where(better, d, best)
            gap[better] = (near - point)[better]
            for k in range(j + 1, K):
                tri = ok & down[:, k]
                inside |= tri & _inside_triangle(point, corners[:, i], corners[:, j], corners[:, k])
    gap[inside] = 0.0
    gap[~down.any(axis=1)] = np.nan
    return gap


@dataclass(frozen=True)
class Stance:
    """What the balance figure reads of a motion's ``T`` frames, on the ground plane (x, z), metres.

    ``com`` ``(T, 2)``: the centre of mass's projection; ``corners`` ``(T, K, 2)``: the ankle and toe joints of
    both feet, ``down`` ``(T, K)`` those on the floor; ``speed`` ``(T,)``: the centre of mass's (m/s at a
    person's size); ``seated`` ``(T,)``: hips lower than :data:`SEATED`; ``radius``: :data:`FOOT_RADIUS` at the
    body's size."""

    com: np.ndarray
    corners: np.ndarray
    down: np.ndarray
    speed: np.ndarray
    seated: np.ndarray
    radius: float

    def standing(self, slow: float = SLOW) -> np.ndarray:
        """``(T,)``: a foot down, the centre of mass slower than ``slow`` (m/s at a person's size), not seated
        (with the default, the frames the figure judges)."""
        return self.down.any(axis=1) & (self.speed < slow) & ~self.seated


def stance(motion: Motion) -> Stance | None:
    """The :class:`Stance` of ``motion``; None for a rig whose humanoid joints cannot be placed or a
    motion shorter than 2 frames."""
    if motion.n_frames < 2:
        return None
    try:
        _, roles = rig_roles(motion.skeleton)
        com = centre_of_mass(motion, roles)
        leg = leg_length(motion.skeleton)
    except (RigError, ValueError):
        return None
    pos = motion.positions
    corners, down = [], []
    for side in ("left", "right"):
        ankle = roles[_side("foot", side)]
        toe = roles.get(_side("toes", side), ankle)
        corners += [pos[:, ankle, :][:, [0, 2]], pos[:, toe, :][:, [0, 2]]]
        low = np.minimum(pos[:, ankle, 1], pos[:, toe, 1]) < ON_FLOOR / (HUMAN_LEG / leg)
        down += [low, low]
    speed = np.linalg.norm(np.gradient(com[:, [0, 2]], axis=0), axis=-1) * motion.fps * (HUMAN_LEG / leg)
    feet_floor = np.minimum(pos[:, roles["leftFoot"], 1], pos[:, roles["rightFoot"], 1])
    seated = pos[:, roles["hips"], 1] - feet_floor < SEATED * leg
    return Stance(com[:, [0, 2]], np.stack(corners, axis=1), np.stack(down, axis=1), speed, seated, FOOT_RADIUS * leg)


def balance_gaps(motion: Motion) -> np.ndarray:
    """``(T, 2)`` metres at the body's own size, on the ground plane (x, z): how far, and which way, the centre
    of mass's ground projection must move to reach the support area widened by :data:`FOOT_RADIUS` (module
    docstring); 0 inside it; NaN on frames the figure does not judge (no foot down, moving fast, seated).
    All NaN for a rig whose humanoid joints cannot be placed."""
    st = stance(motion)
    if st is None:
        return np.full((motion.n_frames, 2), np.nan)
    gap = support_gap(st.com, st.corners, st.down)
    dist = np.linalg.norm(gap, axis=-1)
    out = gap * (np.maximum(0.0, dist - st.radius) / np.maximum(dist, 1e-12))[:, None]
    out[~st.standing()] = np.nan
    return out


def balance_heights(motion: Motion) -> np.ndarray:
    """``(T,)`` metres at the body's own size: how far the centre of mass's ground projection is outside the
    support area (:func:`balance_gaps`' length); NaN on frames the figure does not judge."""
    return np.linalg.norm(balance_gaps(motion), axis=-1)


def balance_runs(motion: Motion) -> np.ndarray:
    """``(T,)`` metres at the body's own size: on every frame of a run of at least :data:`RUN` s of judged
    frames with the centre of mass outside the support area (:func:`balance_heights`), the least it is
    outside over that run; 0 elsewhere. A body falls towards its next foot for an instant (capture does
    too); it cannot stand outside its feet."""
    h = balance_heights(motion)
    out = np.zeros(motion.n_frames)
    n = max(2, int(round(RUN * motion.fps)))
    for a, b in runs(np.isfinite(h) & (np.nan_to_num(h) > 0.0)):
        if b - a >= n:
            out[a:b] = h[a:b].min()
    return out


def balance_runs_cm(motion: Motion) -> np.ndarray:
    """:func:`balance_runs` in centimetres at a person's size (× 0.86 m / the body's leg length), ``(T,)``."""
    return balance_runs(motion) * 100.0 * human_scale(motion)


def balance_cm(motion: Motion, frames: np.ndarray | None = None) -> float:
    """The most the centre of mass stays outside the support area (cm, at a person's size,
    :func:`balance_runs_cm`) over the motion, or over the bool mask ``frames`` ``(T,)``."""
    h = balance_runs_cm(motion)
    if frames is not None:
        h = np.where(frames, h, 0.0)
    return float(h.max()) if h.size else 0.0

"""Motion composition (動作合成, paper 003 §4.4): a body part of one motion switched to another's.

"歩きながら右手を振る": the right arm of the walk is switched to the right arm
of the wave for the wave's time on the track.

- **Switch times** (§4.4.1, eq. (1)): ``F(ta, tb) = α|P1(ta) - P2(tb)| +
  β|V1(ta) - V2(tb)| + γ·Tf``, ``P``/``V`` the position and velocity of the
  part's end effectors relative to the hips (in the hips' heading frame, so
  two clips facing different ways compare). The start pair minimises the
  first two terms over the base around the scheduled start and the partial
  clip's initial section (before its core); the end pair minimises all three
  over the partial clip's end section (after its core) and the base near it
  in absolute time; ``Tf = |ln(stretch)|``, the stretch being the ratio of the
  base interval to the clip interval it is played over (0 when unstretched).
  The partial clip is time-warped linearly onto the base interval, never
  faster than it was recorded (:data:`MIN_STRETCH`) unless no end pair allows
  it: jerk grows with the cube of a speed-up, and a captured throw played
  1.26 times faster (its release 9.2k m/s³, 15k composed on a run) broke the
  built-in jerk limit; played slower, the end section is cut shorter instead.
- **Blend duration** (§4.4.2, eq. (2)): ``|P_a,i - P_b,j| / V_a,i``, the
  effector distance at the switch over the base effector's speed there,
  clamped to ``[BLEND_MIN, BLEND_MAX]`` (the paper gives no bounds; a still
  base hand would make it infinite).
- **Interpolation** (eqs. (3)–(4)): the part's joint rotations from the base to
  the clip with ``ratio = time / blend_duration`` — by slerp, not by a linear
  blend of angles — at the start, and back at the end. The ratio is eased by
  the ``smooth`` profile of :mod:`synthesis.join.blend` (``PROFILE = "linear"`` is
  eq. (4) as written): measured on the CMU walk + wave it lowers the largest
  jerk of the blends from 2.5k to 1.4k m/s³, the clips' own being 1.4k.
- **Sway transfer** (§4.4.3): for every other joint of the partial clip the
  *base trajectory* is the cubic Hermite curve
  (:class:`scipy.interpolate.CubicHermiteSpline`) through its start and end
  rotation with the start and end angular velocity (in rotation-vector
  coordinates relative to the start); the difference between the real
  trajectory and that curve is the sway, and it is added (as a rotation) to
  the composed motion's same joint. It vanishes, with its rate, at both ends
  by construction. Receivers: torso and head (the paper's figure: 腰や首) —
  not the hips or legs, whose sway would move feet planted by the base, nor
  the other arm, whose motion in a captured clip is usually a gesture of its
  own; a residual above :data:`SWAY_MAX_DEG` is scaled down to it.
- **Which angles** are switched (the paper: the part's joint angles): by
  default the part keeps its orientation *relative to the hips*
  (:func:`hips_relative`) so the hand follows the clip's path around the body
  whatever the base's spine does; ``frame="local"`` copies the local angles.
- **たまま** (``hold``): the base element's end pose is held while the part
  plays (the element is prepared with that hold; nothing special here).

Weights (the paper gives none): ``α = 1`` per metre, ``β = 0.2`` per m/s,
``γ = 0.5``; searches ±:data:`SEARCH` s; a stretch beyond ×/÷
:data:`MAX_STRETCH` is not taken, nor one below 1 where another fits; blends of eq. (2) clamped to ``[0.25, 0.5]`` s.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from text2anim.core.bodyparts import body_map
from text2anim.core.ground import headings, to_heading_frame
from text2anim.core.motion import Motion

from .blend import ease, ratio, sample, slerp

ALPHA, BETA, GAMMA = 1.0, 0.2, 0.5
SEARCH = 0.5  # s
MAX_STRETCH = 1.5  # the partial clip is played at most this much slower
MIN_STRETCH = 1.0  # and never faster than it was recorded (see the module docstring)
BLEND_MIN, BLEND_MAX = 0.25, 0.5  # s
PROFILE = "smooth"  # eq. (4)'s ratio, eased; "linear" is eq. (4) as written
SWAY_RECEIVERS = ("torso", "head")
SWAY_MAX_DEG = 15.0  # a donor's own gesture of another joint is not sway: larger residuals are scaled down
FRAME = "hips"


def effectors(motion: Motion, part: str) -> list[int]:
    """The end effectors of a body part: hands for arms, the head, the chest for the torso, feet for legs."""
    bm = body_map(motion.skeleton)
    table = {
        "right_arm": [bm.hands["right"]], "left_arm": [bm.hands["left"]],
        "both_arms": [bm.hands["left"], bm.hands["right"]], "head": [bm.head], "torso": [bm.chest],
        "upper": [bm.hands["left"], bm.hands["right"], bm.head],
        "right_leg": [bm.feet["right"][0]], "left_leg": [bm.feet["left"][0]],
        "lower": [bm.feet["left"][0], bm.feet["right"][0]],
    }
    if part not in table:
        bm.joints(part)  # raises the error naming the known parts
    return table[part]


def part_joints(motion: Motion, part: str) -> list[int]:
    """Joints whose rotations a composition of ``part`` switches (the root's never: it carries the base's place)."""
    return [j for j in body_map(motion.skeleton).joints(part) if j != 0]


def sway_joints(motion: Motion, part: str) -> list[int]:
    """Joints that receive the sway: torso and head, minus the switched part."""
    bm = body_map(motion.skeleton)
    switched = set(bm.joints(part))
    out = sorted({j for g in SWAY_RECEIVERS for j in bm.joints(g)} - switched)
    return out


def features(motion: Motion, part: str) -> tuple[np.ndarray, np.ndarray]:
    """eq. (1)'s ``P`` and ``V``: effector positions relative to the hips in the hips' heading frame
    ``(T, 3k)`` metres, and their velocities ``(T, 3k)`` m/s."""
    eff = effectors(motion, part)
    pos = motion.positions
    rel = pos[:, eff] - pos[:, :1]
    local = to_heading_frame(rel, headings(motion))
    P = local.reshape(len(pos), -1)
    V = np.gradient(P, axis=0) * motion.fps if len(P) > 1 else np.zeros_like(P)
    return P, V


def _norm3(x: np.ndarray) -> np.ndarray:
    """Sum over effectors of the Euclidean norms of ``(..., 3k)``."""
    return np.linalg.norm(x.reshape(x.shape[:-1] + (-1, 3)), axis=-1).sum(axis=-1)


@dataclass(frozen=True)
class CompositionTiming:
    """Switch times of a composition.

    ``ta0, ta1``: base (track) frames where the switch starts and ends;
    ``tb0, tb1``: the partial clip's frames played there (linearly warped);
    ``blend_in, blend_out``: blend lengths in frames (eq. (2));
    ``cost_start, cost_end``: eq. (1) at the chosen pairs.
    """

    ta0: int
    ta1: int
    tb0: int
    tb1: int
    blend_in: int
    blend_out: int
    cost_start: float
    cost_end: float

    @property
    def stretch(self) -> float:
        return (self.ta1 - self.ta0) / max(self.tb1 - self.tb0, 1)


def _blend_frames(Pa, Pb, Va, fps) -> int:
    """eq. (2): blend_duration = |P_a,i - P_b,j| / V_a,i, clamped, in frames."""
    dist = float(_norm3(Pa - Pb))
    speed = float(_norm3(Va))
    dur = dist / speed if speed > 1e-6 else BLEND_MAX
    return int(round(np.clip(dur, BLEND_MIN, BLEND_MAX) * fps))


def composition_timing(base: Motion, start: int, end: int, donor: Motion, core: tuple[int, int],
                       part: str) -> CompositionTiming:
    """eq. (1) and eq. (2): where the switch of ``part`` starts and ends.

    Args:
        base: the motion the part is laid onto (the track).
        start, end: the scheduled track frames of the partial element (its frame 0 at ``start``).
        donor: the partial element's frames (``end - start`` of them).
        core: the donor's core ``[c0, c1)``.
    """
    fps = base.fps
    W = max(1, int(round(SEARCH * fps)))
    N, M = base.n_frames, donor.n_frames
    Pa, Va = features(base, part)
    Pb, Vb = features(donor, part)
    # start: base near the scheduled start, donor's initial section (before its core)
    ta = np.arange(max(0, start - W // 2), min(N - 1, start + W) + 1)
    tb = np.arange(0, max(1, min(core[0], M - 1) + 1))
    F0 = ALPHA * _norm3(Pa[ta][:, None] - Pb[tb][None]) + BETA * _norm3(Va[ta][:, None] - Vb[tb][None])  # eq. (1), no Tf
    i, j = np.unravel_index(np.argmin(F0), F0.shape)
    ta0, tb0 = int(ta[i]), int(tb[j])
    # end: donor's end section (after its core) and the base near it in absolute time
    tb_e = np.arange(min(max(core[1] - 1, tb0 + 1), M - 1), M)
    lo = ta0 + (tb_e[0] - tb0) - W
    hi = ta0 + (tb_e[-1] - tb0) + W
    ta_e = np.arange(max(ta0 + 2, lo), min(N - 1, hi) + 1)
    if len(ta_e) == 0:
        ta_e = np.array([min(N - 1, max(ta0 + 2, ta0 + tb_e[-1] - tb0))])
    stretch = (ta_e[:, None] - ta0) / np.maximum(tb_e[None, :] - tb0, 1)
    Tf = np.abs(np.log(np.maximum(stretch, 1e-6)))
    F1 = (ALPHA * _norm3(Pa[ta_e][:, None] - Pb[tb_e][None]) + BETA * _norm3(Va[ta_e][:, None] - Vb[tb_e][None])
          + GAMMA * Tf)  # eq. (1)
    within = (stretch >= 1 / MAX_STRETCH) & (stretch <= MAX_STRETCH)
    F1 = F1 + np.where(within & (stretch >= MIN_STRETCH), 0.0, np.where(within, 1e3, 1e6))  # never faster, if it fits
    k, m = np.unravel_index(np.argmin(F1), F1.shape)
    ta1, tb1 = int(ta_e[k]), int(tb_e[m])
    n_in = _blend_frames(Pa[ta0], Pb[tb0], Va[ta0], fps)
    n_out = _blend_frames(Pa[ta1], Pb[tb1], Va[ta1], fps)
    span = ta1 - ta0
    if n_in + n_out > span:  # both blends must fit in the switch
        scale = span / max(n_in + n_out, 1)
        n_in, n_out = int(n_in * scale), int(n_out * scale)
    return CompositionTiming(ta0, ta1, tb0, tb1, max(n_in, 1), max(n_out, 1), float(F0[i, j]), float(F1[k, m]))


def hermite_sway(rotations: np.ndarray, fps: float) -> tuple[np.ndarray, np.ndarray]:
    """§4.4.3: base trajectory and sway of local rotations ``(T, J, 4)``.

    Per joint, ``r(t) = log(R(0)^-1 R(t))`` (rotation vector relative to the
    start); the base trajectory ``h(t)`` is the cubic Hermite curve with
    ``h(0) = r(0)``, ``h(T) = r(T)`` and end slopes ``r'(0)``, ``r'(T)``.
    Returns the base trajectory as rotations ``R(0) exp(h(t))`` ``(T, J, 4)``
    and the sway ``exp(h(t))^-1 exp(r(t))`` ``(T, J, 4)``: a rotation that is
    the identity, with zero rate, at both ends.
    """
    from scipy.interpolate import CubicHermiteSpline  # only a partial clip's sway needs it (~0.08 s to import)

    T, J, _ = rotations.shape
    if T < 3:
        ident = np.zeros((T, J, 4))
        ident[..., 3] = 1.0
        return rotations.copy(), ident
    R = Rotation.from_quat(rotations.reshape(-1, 4))
    R0 = Rotation.from_quat(np.repeat(rotations[:1], T, axis=0).reshape(-1, 4))
    r = (R0.inv() * R).as_rotvec().reshape(T, J, 3)
    t = np.arange(T) / fps
    d0 = (r[1] - r[0]) * fps
    d1 = (r[-1] - r[-2]) * fps
    spline = CubicHermiteSpline([t[0], t[-1]], np.stack([r[0], r[-1]]), np.stack([d0, d1]), axis=0)
    h = spline(t)  # (T, J, 3)
    H = Rotation.from_rotvec(h.reshape(-1, 3))
    base = (R0 * H).as_quat().reshape(T, J, 4)
    sway = (H.inv() * Rotation.from_rotvec(r.reshape(-1, 3))).as_quat().reshape(T, J, 4)
    return base, sway


@dataclass(frozen=True)
class Composed:
    """A composition's result: the new motion and what was decided."""

    motion: Motion
    timing: CompositionTiming
    part: str
    joints: tuple[int, ...]
    sway_joints: tuple[int, ...]
    sway_deg: float  # largest sway angle added, degrees


def hips_relative(base: Motion, donor: Motion, joints: list[int]) -> np.ndarray:
    """Local rotations ``(T, len(joints), 4)`` that give the part ``joints`` of ``base`` the
    orientation relative to the hips that ``donor`` has (both ``T`` frames long).

    Only the part's top joints (whose parent is outside the part) change from
    the donor's local rotations: each is set so its world rotation relative
    to the root equals the donor's, whatever the base's spine does.
    """
    parents = base.skeleton.parents
    inside = set(joints)
    out = donor.rotations[:, joints].copy()
    if 0 in inside:
        return out
    bp, dp = base.pose, donor.pose
    root_b = Rotation.from_matrix(bp.rotations[:, 0])
    root_d = Rotation.from_matrix(dp.rotations[:, 0])
    for k, j in enumerate(joints):
        p = int(parents[j])
        if p in inside:
            continue
        rel = root_d.inv() * Rotation.from_matrix(dp.rotations[:, j])  # the donor's, relative to its hips
        out[:, k] = (Rotation.from_matrix(bp.rotations[:, p]).inv() * root_b * rel).as_quat()
    return out


def compose(base: Motion, start: int, end: int, donor: Motion, core: tuple[int, int], part: str,
            sway: bool = True, timing: CompositionTiming | None = None, frame: str = FRAME) -> Composed:
    """Lay ``part`` of ``donor`` (the partial element, scheduled at track frames ``[start, end)``) onto ``base``.

    ``frame``: ``"hips"`` keeps the part's orientation relative to the hips
    (:func:`hips_relative`: a waved hand follows the clip's path around the
    body even when the base's spine bends or twists differently), ``"local"``
    copies the part's local joint angles as the paper writes it.
    """
    t = timing or composition_timing(base, start, end, donor, core, part)
    joints = part_joints(base, part)
    n = t.ta1 - t.ta0
    src = t.tb0 + np.arange(n) * (t.tb1 - t.tb0) / max(n, 1)  # linear time warp of the donor
    warped = sample(donor, src)
    seg = base[t.ta0:t.ta1]
    rots = seg.rotations.copy()
    receivers: list[int] = []
    sway_deg = 0.0
    if sway:  # §4.4.3, first: the part's hips-relative angles are then taken on the swayed spine
        receivers = sway_joints(base, part)
        _, s = hermite_sway(warped.rotations[:, receivers], base.fps)
        s = _clamp_sway(s)
        rots[:, receivers] = (Rotation.from_quat(rots[:, receivers].reshape(-1, 4))
                              * Rotation.from_quat(s.reshape(-1, 4))).as_quat().reshape(n, len(receivers), 4)
        sway_deg = float(np.degrees(Rotation.from_quat(s.reshape(-1, 4)).magnitude().max())) if s.size else 0.0
    if frame == "hips":
        target = hips_relative(seg.replace(rotations=rots.copy()), warped, joints)  # (rots is edited below)
    elif frame == "local":
        target = warped.rotations[:, joints]
    else:
        raise ValueError(f"unknown composition frame {frame!r}; use 'hips' or 'local'")
    w = np.ones(n)
    w[:t.blend_in] = ease(ratio(t.blend_in), PROFILE)  # eqs. (3)-(4): ratio = time / blend_duration
    w[n - t.blend_out:] = ease(ratio(t.blend_out), PROFILE)[::-1]
    rots[:, joints] = slerp(rots[:, joints], target, w[:, None])  # eq. (3), by slerp
    all_rots = base.rotations.copy()
    all_rots[t.ta0:t.ta1] = rots
    return Composed(base.replace(rotations=all_rots), t, part, tuple(joints), tuple(receivers), sway_deg)


def _clamp_sway(s: np.ndarray) -> np.ndarray:
    """Sway rotations ``(T, J, 4)`` scaled down where they exceed :data:`SWAY_MAX_DEG`."""
    r = Rotation.from_quat(s.reshape(-1, 4)).as_rotvec()
    ang = np.linalg.norm(r, axis=-1)
    lim = np.radians(SWAY_MAX_DEG)
    scale = np.where(ang > lim, lim / np.maximum(ang, 1e-12), 1.0)
    return Rotation.from_rotvec(r * scale[:, None]).as_quat().reshape(s.shape)

"""Pose distance of paper 000 §4.3 (eq. (13)) and the approach speeds of eqs. (14)–(15).

eq. (13): ``D(t0, t1) = Σ_i |p_i(t1) - p_i(t0)| / n`` — the mean distance (metres)
between corresponding joints of two poses, computed as Kovar et al. do
(*Motion graphs*, 2002): before comparing, each pose is moved so that its
hips stand over the origin and face +Z (the root's horizontal position and
heading are aligned; heights are kept). So the distance does not depend on
where a clip is placed on the ground, only on the shape of the body, and a
search can run before the next clip is placed.

``features`` turns frames into those aligned positions once, ``(T, K, 3)``;
``distance_matrix`` compares every frame of one set with every frame of
another at once (numpy broadcasting), ``(Na, Nb)``.

Joint sets: the paper computes ``Q_p`` and ``Q_v`` over the upper or the
lower body, whichever the blend interval is for (:func:`part_joints`): the
lower body is the hips and both legs, the upper body the torso, head and
arms (:mod:`core.bodyparts`).
"""
from __future__ import annotations

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.ground import root_headings
from text2anim.core.motion import Motion


def part_joints(motion: Motion, part: str) -> list[int]:
    """Joint indices of a body part (``lower``, ``upper``, ``whole`` or a :data:`~core.bodyparts.GROUPS` name)."""
    if part == "whole":
        return list(range(motion.skeleton.n_joints))
    return list(body_map(motion.skeleton).joints(part))


def _window(motion: Motion, lo: int, hi: int) -> tuple[int, np.ndarray]:
    """:func:`features` of every joint for a block of frames holding ``[lo, hi)``: its first frame and the
    block, joint-major ``(J, n, 3)``, read-only. Kept in the motion's cache and widened when a request falls
    outside (a join's search asks for many frame ranges near the join of both body parts of the same track
    and clips). Each value depends on its own frame and joint alone."""
    known = motion.cache.known("posedist.window")
    if known is not None:
        a, block = known
        if a <= lo and hi <= a + block.shape[1]:
            return known
        lo, hi = min(lo, a), max(hi, a + block.shape[1])
    pos = motion[lo:hi].positions  # (a slice's kinematics: a long track's pose need not be joined)
    root = pos[:, 0]
    h = root_headings(motion)[lo:hi]
    d = pos - np.stack([root[:, 0], np.zeros(len(pos)), root[:, 2]], axis=1)[:, None, :]
    c, s = np.cos(h), np.sin(h)
    # turn by -h about +Y: the character then faces +Z
    block = np.stack([(c[:, None] * d[..., 0] - s[:, None] * d[..., 2]).T, d[..., 1].T,
                      (s[:, None] * d[..., 0] + c[:, None] * d[..., 2]).T], axis=-1)
    block.setflags(write=False)
    return motion.cache.put("posedist.window", (lo, block))


def features(motion: Motion, joints, frames=None) -> np.ndarray:
    """Joint positions with the root's horizontal position and heading removed, ``(F, K, 3)`` metres,
    laid out joint-major in memory (a ``(K, F, 3)`` block, as :func:`distance_matrix` reads it).

    ``frames``: integer frame indices ``(F,)`` (clamped to the motion), or ``None`` for all.
    """
    idx = np.arange(motion.n_frames) if frames is None else \
        np.minimum(np.maximum(np.asarray(frames, dtype=int), 0), motion.n_frames - 1)
    if len(idx) == 0 or motion.n_frames == 0:
        return np.zeros((len(idx), len(joints), 3))
    lo, hi = int(idx.min()), int(idx.max()) + 1
    a, block = _window(motion, lo, hi)
    rows = np.take(block, np.asarray(joints, dtype=int), axis=0)
    return np.take(rows, idx - a, axis=1).transpose(1, 0, 2)


def distance_matrix(fa: np.ndarray, fb: np.ndarray) -> np.ndarray:
    """eq. (13) for every pair: ``D[i, j]`` = mean over joints of ``|fb[j] - fa[i]|`` (metres), ``(Na, Nb)``.

    ``fa`` ``(Na, K, 3)`` and ``fb`` ``(Nb, K, 3)`` are :func:`features`. Computed joint-major, one
    ``(K, Na, Nb)`` block per coordinate: squares summed x, z, y, the joints' distances summed in joint order
    (the order ``einsum`` and ``mean`` took over the ``(Na, Nb, K, 3)`` difference array, which is no longer
    made: the same bits at a third of the time).
    """
    a, b = fa.transpose(2, 1, 0), fb.transpose(2, 1, 0)  # (3, K, N)
    d = np.subtract(a[0][:, :, None], b[0][:, None, :])  # (K, Na, Nb)
    sq = np.multiply(d, d)
    for c in (2, 1):
        np.subtract(a[c][:, :, None], b[c][:, None, :], out=d)
        sq += np.multiply(d, d, out=d)
    np.sqrt(sq, out=sq)
    return np.add.reduce(sq, axis=0) / len(sq)


def distance(fa: np.ndarray, fb: np.ndarray) -> float:
    """eq. (13) for one pair of poses ``(K, 3)``."""
    return float(np.linalg.norm(fa - fb, axis=-1).mean())

"""Excursions: a joint's rotations scaled about a reference rotation, frame by frame.

The reference of a looping clip is its mean pose (so the loop still closes); of any other clip, the pose
sliding from its first frame's to its last (so the clip still starts and ends where it did and joins its
neighbours as before). A factor above 1 makes every excursion larger (a bigger wave, a longer swing), below 1
smaller; 1 changes nothing.
"""
from __future__ import annotations

import numpy as np

from text2anim.core import quat


def reference(q: np.ndarray, cyclic: bool) -> np.ndarray:
    """The reference of one joint's rotations ``q`` ``(T, 4)``: ``(T, 4)``."""
    if cyclic:
        signed = q * np.where(q @ q[0] < 0, -1.0, 1.0)[:, None]
        mean = signed.mean(axis=0)
        return np.tile(mean / np.linalg.norm(mean), (len(q), 1))
    return quat.slerp(np.broadcast_to(q[0], q.shape), np.broadcast_to(q[-1], q.shape), np.linspace(0.0, 1.0, len(q)))


def scaled(q: np.ndarray, factor: float, cyclic: bool) -> np.ndarray:
    """Rotations ``q`` ``(T, 4)`` with their excursions from :func:`reference` scaled by ``factor``."""
    if factor == 1.0 or len(q) < 2:
        return q
    ref = reference(q, cyclic)
    d = quat.multiply(quat.conjugate(ref), q)
    d = d * np.where(d[:, 3:] < 0, -1.0, 1.0)
    angle = 2.0 * np.arccos(np.clip(d[:, 3], -1.0, 1.0))
    norm = np.linalg.norm(d[:, :3], axis=1)
    axis = d[:, :3] / np.maximum(norm, 1e-12)[:, None]
    half = angle * factor / 2.0
    powered = np.concatenate([axis * np.sin(half)[:, None], np.cos(half)[:, None]], axis=1)
    powered[norm < 1e-12] = (0.0, 0.0, 0.0, 1.0)
    return quat.multiply(ref, powered)

"""scipy's rotation arithmetic without :class:`~scipy.spatial.transform.Rotation` objects: the same bits.

``Rotation`` methods on NumPy stacks of shape ``(N, 4)`` call scipy's compiled backend
(``scipy.spatial.transform._rotation_cy``) after checking and promoting their input and
wrapping the result in a new object; on small stacks (a join's few frames, one frame's 31
joints) that wrapping costs more than the arithmetic. These functions call the backend as the
methods named in their docstrings do, so the results are bit for bit the methods' (tested in
``tests/test_quat.py``); where the backend is not there (another scipy), they are those methods.

Quaternions are ``(N, 4)`` float64 arrays ``(x, y, z, w)``; matrices ``(N, 3, 3)``; rotation
vectors ``(N, 3)`` in radians.
"""
from __future__ import annotations

import numpy as np

try:  # the compiled backend Rotation uses for NumPy input (scipy >= 1.16)
    from scipy.spatial.transform import _rotation_cy as _cy
except ImportError:  # pragma: no cover - older scipy: the public methods
    _cy = None


def _rotation():
    from scipy.spatial.transform import Rotation

    return Rotation


def _stack(a, width: int) -> np.ndarray:
    return np.ascontiguousarray(np.asarray(a, dtype=np.float64).reshape(-1, width))


def normalized(q) -> np.ndarray:
    """``Rotation.from_quat(q).as_quat()``: unit quaternions ``(N, 4)``."""
    if _cy is None:
        return _rotation().from_quat(q).as_quat()
    return np.asarray(_cy.from_quat(_stack(q, 4), normalize=True, copy=True, scalar_first=False))


def compose(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """``(Rotation.from_quat(p) * Rotation.from_quat(q)).as_quat()`` for unit ``p``, ``q`` from :func:`normalized`."""
    if _cy is None:
        return (_rotation().from_quat(p) * _rotation().from_quat(q)).as_quat()
    return np.asarray(_cy.from_quat(_cy.compose_quat(p, q), normalize=True, copy=False, scalar_first=False))


def inverse(q: np.ndarray) -> np.ndarray:
    """``Rotation.from_quat(q).inv().as_quat()`` for unit ``q`` from :func:`normalized`."""
    if _cy is None:
        return _rotation().from_quat(q).inv().as_quat()
    return np.asarray(_cy.inv(q))


def as_rotvec(q: np.ndarray) -> np.ndarray:
    """``Rotation.from_quat(q).as_rotvec()`` for unit ``q`` from :func:`normalized`, ``(N, 3)``."""
    if _cy is None:
        return _rotation().from_quat(q).as_rotvec()
    return np.asarray(_cy.as_rotvec(q, degrees=False))


def from_rotvec(v) -> np.ndarray:
    """``Rotation.from_rotvec(v).as_quat()``, ``(N, 4)``."""
    if _cy is None:
        return _rotation().from_rotvec(v).as_quat()
    return np.asarray(_cy.as_quat(_cy.from_rotvec(_stack(v, 3), degrees=False), canonical=False, scalar_first=False))


def as_matrix(q) -> np.ndarray:
    """``Rotation.from_quat(q).as_matrix()``, ``(N, 3, 3)`` (``q`` is normalised first, as there)."""
    if _cy is None:
        return _rotation().from_quat(q).as_matrix()
    return np.asarray(_cy.as_matrix(_cy.from_quat(_stack(q, 4), normalize=True, copy=True, scalar_first=False)))


def from_matrix(m) -> np.ndarray:
    """``Rotation.from_matrix(m).as_quat()``, ``(N, 4)``."""
    if _cy is None:
        return _rotation().from_matrix(m).as_quat()
    stack = np.ascontiguousarray(np.asarray(m, dtype=np.float64).reshape(-1, 3, 3))
    return np.asarray(_cy.as_quat(_cy.from_matrix(stack, assume_valid=False), canonical=False, scalar_first=False))

"""scipy's rotation arithmetic without :class:`~scipy.spatial.transform.Rotation` objects: the same bits.

``Rotation`` methods on NumPy stacks call scipy's compiled backend
(``scipy.spatial.transform._rotation_cy``) after checking and promoting their input and
wrapping the result in a new object; on small stacks (a join's few frames, one frame's 31
joints) that wrapping costs more than the arithmetic. Here a rotation stack is the array a
``Rotation`` keeps inside (its ``(N, 4)`` quaternions ``(x, y, z, w)``), and each function calls
the backend as the method named in its docstring does, so the results are bit for bit the
methods' (``tests/test_quat.py``). Where the backend is not there (another scipy), the
functions are those methods.

Shapes: quaternions ``(N, 4)``, matrices ``(N, 3, 3)``, rotation vectors and vectors ``(N, 3)``
(radians, metres); all float64.
"""
from __future__ import annotations

import numpy as np

try:  # the compiled backend Rotation uses for NumPy input
    from scipy.spatial.transform import _rotation_cy as _cy
except ImportError:  # pragma: no cover - another scipy: the public methods
    _cy = None


def _backend_answers(cy) -> bool:
    """Whether ``cy`` (a private module) takes the calls below as scipy 1.17's does: one call each on a
    quarter turn, compared with the public methods; another scipy's private signatures fall back, never fail."""
    from scipy.spatial.transform import Rotation

    q = np.array([[0.0, 0.0, np.sqrt(0.5), np.sqrt(0.5)]])
    v = np.array([[1.0, 0.0, 0.0]])
    r = Rotation.from_quat(q)
    try:
        got = [cy.from_quat(q, normalize=True, copy=True, scalar_first=False),
               cy.from_rotvec(r.as_rotvec().reshape(1, 3), degrees=False),
               cy.from_matrix(r.as_matrix().reshape(1, 3, 3), assume_valid=False),
               cy.compose_quat(q, q), cy.inv(q), cy.as_quat(q, canonical=False, scalar_first=False),
               cy.as_rotvec(q, degrees=False), cy.as_matrix(q), cy.apply(q, v, inverse=False)]
        want = [q, q, q, (r * r).as_quat().reshape(1, 4), r.inv().as_quat().reshape(1, 4), q,
                r.as_rotvec().reshape(1, 3), r.as_matrix().reshape(1, 3, 3), r.apply(v).reshape(1, 3)]
        return all(np.allclose(np.asarray(g).reshape(np.shape(w)), w) for g, w in zip(got, want))
    except Exception:  # noqa: BLE001 - any disagreement means: use the public methods
        return False


if _cy is not None and not _backend_answers(_cy):  # pragma: no cover - depends on the installed scipy
    _cy = None


def _R():
    from scipy.spatial.transform import Rotation

    return Rotation


def _stack(a, *shape: int) -> np.ndarray:
    return np.ascontiguousarray(np.asarray(a, dtype=np.float64).reshape((-1,) + shape))


def from_quat(q) -> np.ndarray:
    """``Rotation.from_quat(q)``: quaternions ``(..., 4)`` normalised, as a stack ``(N, 4)``."""
    if _cy is None:
        return _R().from_quat(_stack(q, 4)).as_quat()
    return np.asarray(_cy.from_quat(_stack(q, 4), normalize=True, copy=True, scalar_first=False))


def from_rotvec(v) -> np.ndarray:
    """``Rotation.from_rotvec(v)`` for rotation vectors ``(..., 3)``."""
    if _cy is None:
        return _R().from_rotvec(_stack(v, 3)).as_quat()
    return np.asarray(_cy.from_rotvec(_stack(v, 3), degrees=False))


def from_matrix(m) -> np.ndarray:
    """``Rotation.from_matrix(m)`` for matrices ``(..., 3, 3)``."""
    if _cy is None:
        return _R().from_matrix(_stack(m, 3, 3)).as_quat()
    return np.asarray(_cy.from_matrix(_stack(m, 3, 3), assume_valid=False))


def compose(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """``p * q`` (apply ``q`` first) for stacks of equal length or of one."""
    if _cy is None:
        return (_R().from_quat(p) * _R().from_quat(q)).as_quat()
    return np.asarray(_cy.from_quat(_cy.compose_quat(p, q), normalize=True, copy=False, scalar_first=False))


def inverse(q: np.ndarray) -> np.ndarray:
    """``r.inv()``."""
    if _cy is None:
        return _R().from_quat(q).inv().as_quat()
    return np.asarray(_cy.inv(q))


def as_quat(q: np.ndarray) -> np.ndarray:
    """``r.as_quat()``: the quaternions ``(N, 4)`` as an array of their own."""
    if _cy is None:
        return np.array(q, dtype=np.float64)
    return np.asarray(_cy.as_quat(q, canonical=False, scalar_first=False))


def as_rotvec(q: np.ndarray) -> np.ndarray:
    """``r.as_rotvec()``, ``(N, 3)`` radians."""
    if _cy is None:
        return _R().from_quat(q).as_rotvec()
    return np.asarray(_cy.as_rotvec(q, degrees=False))


def as_matrix(q: np.ndarray) -> np.ndarray:
    """``r.as_matrix()``, ``(N, 3, 3)``."""
    if _cy is None:
        return _R().from_quat(q).as_matrix()
    return np.asarray(_cy.as_matrix(q))


def apply(q: np.ndarray, v) -> np.ndarray:
    """``r.apply(v)`` for vectors ``(N, 3)`` (or one ``(3,)``), ``(N, 3)``."""
    if _cy is None:
        return _R().from_quat(q).apply(v)
    return np.asarray(_cy.apply(q, _stack(v, 3), inverse=False))

"""scipy's rotation arithmetic without :class:`~scipy.spatial.transform.Rotation` objects: the same bits.

``Rotation`` methods on NumPy stacks call scipy's compiled backend
(``scipy.spatial.transform._rotation_cy``) after checking and promoting their input and
wrapping the result in a new object; on small stacks (a join's few frames, one frame's 31
joints) that wrapping costs more than the arithmetic. Here a rotation stack is the array a
``Rotation`` keeps inside (its ``(N, 4)`` quaternions ``(x, y, z, w)``), and each function calls
the backend as the method named in its docstring does, so the results are bit for bit the
methods' (``tests/core/test_quat.py``). Where the backend is not there (another scipy), the
functions are those methods.

Three of the backend's loops cost 2-3 µs a rotation (a memoryview per element):
:func:`compose`, :func:`as_rotvec` and :func:`from_matrix` are its arithmetic written as NumPy
over the stack instead — the same operations in the same order (IEEE ``+ - * / sqrt`` round
alike everywhere; ``atan2`` and ``sin`` are the C library's, through :mod:`math`, as the
backend's), so the same bits, 10-40x faster on a join's stacks.

Shapes: quaternions ``(N, 4)``, matrices ``(N, 3, 3)``, rotation vectors and vectors ``(N, 3)``
(radians, metres); all float64.
"""
from __future__ import annotations

import math

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


def _w(a: np.ndarray) -> np.ndarray:
    """``a`` as scipy's kernels take it: their typed memoryviews refuse read-only buffers (a motion's
    frames), which are copied."""
    return a if a.flags.writeable else a.copy()


def from_quat(q) -> np.ndarray:
    """``Rotation.from_quat(q)``: quaternions ``(..., 4)`` normalised, as a stack ``(N, 4)``."""
    if _cy is None:
        return _R().from_quat(_stack(q, 4)).as_quat()
    return np.asarray(_cy.from_quat(_w(_stack(q, 4)), normalize=True, copy=True, scalar_first=False))


def from_rotvec(v) -> np.ndarray:
    """``Rotation.from_rotvec(v)`` for rotation vectors ``(..., 3)``."""
    if _cy is None:
        return _R().from_rotvec(_stack(v, 3)).as_quat()
    return np.asarray(_cy.from_rotvec(_w(_stack(v, 3)), degrees=False))


def _normalized(q: np.ndarray) -> np.ndarray:
    """Quaternions ``(N, 4)`` divided by their norms, summed x, y, z, w in that order (the backend's)."""
    x, y, z, w = q.T
    return q / np.sqrt(x * x + y * y + z * z + w * w)[:, None]


def _c_map(fn, *args: np.ndarray) -> np.ndarray:
    """``fn`` (a :mod:`math` function: the C library's, as the backend calls it) over flat arrays."""
    return np.fromiter(map(fn, *(a.tolist() for a in args)), np.float64, len(args[0]))


_ORTHOGONAL = 1e-12 + 1e-5 * np.eye(3)


def from_matrix(m) -> np.ndarray:
    """``Rotation.from_matrix(m)`` for matrices ``(..., 3, 3)``: a non-positive determinant is an error,
    matrices not orthogonal to 1e-12 are orthogonalised by SVD (``U Vt``), then the quaternion is
    taken from the largest of the diagonal and the trace (Markley), as the backend does."""
    if _cy is None:
        return _R().from_matrix(_stack(m, 3, 3)).as_quat()
    m = _stack(m, 3, 3)
    if len(m) == 0:
        return np.zeros((0, 4))
    c = m.reshape(-1, 9)  # the nine elements, row by row
    e = c.T  # each (N,)
    det = e[0] * (e[4] * e[8] - e[5] * e[7]) - e[1] * (e[3] * e[8] - e[5] * e[6]) + e[2] * (e[3] * e[7] - e[4] * e[6])
    if (det <= 0).any():  # only its sign is asked: the cofactor expansion, not LAPACK's
        raise ValueError(f"Non-positive determinant (left-handed or null coordinate frame) in rotation matrix "
                         f"{int(np.flatnonzero(det <= 0)[0])}")
    # isclose(M Mt, I, atol=1e-12) (rtol 1e-5 on the diagonal): the backend's test, by the same product
    orthogonal = (np.abs(np.matmul(m, m.transpose(0, 2, 1)) - np.eye(3)) <= _ORTHOGONAL).all(axis=(1, 2))
    if not orthogonal.all():
        u, _, vt = np.linalg.svd(m[~orthogonal], full_matrices=False)
        m = m.copy()
        m[~orthogonal] = u @ vt
        c = m.reshape(-1, 9)
    diag = c[:, 0::4]  # m00, m11, m22
    trace = diag[:, 0] + diag[:, 1] + diag[:, 2]
    choice = np.argmax(np.concatenate([diag, trace[:, None]], axis=1), axis=1)
    # Markley's four quaternions share their terms (addition commutes exactly): the largest diagonal
    # element i's is 1 - trace + 2 m_ii at i, m_ji + m_ij at j, m_ki + m_ik at k, m_kj - m_jk at w
    # (j, k = i + 1, i + 2 mod 3); the trace's is the three differences and 1 + trace
    terms = np.empty((len(m), 10))
    terms[:, 0:3] = (1 - trace)[:, None] + 2 * diag
    terms[:, 3:6] = c.take(_SUM_A, axis=1) + c.take(_SUM_B, axis=1)  # m01 + m10, m12 + m21, m02 + m20
    terms[:, 6:9] = c.take(_DIFF_A, axis=1) - c.take(_DIFF_B, axis=1)  # m21 - m12, m02 - m20, m10 - m01
    terms[:, 9] = 1 + trace
    return _normalized(terms[np.arange(len(m))[:, None], _MARKLEY[choice]])


_SUM_A, _SUM_B = np.array([1, 5, 2]), np.array([3, 7, 6])
_DIFF_A, _DIFF_B = np.array([7, 2, 3]), np.array([5, 6, 1])
#: per case (largest m00, m11, m22, trace), the ``terms`` of :func:`from_matrix` giving x, y, z, w
_MARKLEY = np.array([[0, 3, 5, 6], [3, 1, 4, 7], [5, 4, 2, 8], [6, 7, 8, 9]])


def compose(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """``p * q`` (apply ``q`` first) for stacks of equal length or of one: the Hamilton product
    ``(pw qv + qw pv + pv x qv, pw qw - pv . qv)``, normalised."""
    if _cy is None:
        return (_R().from_quat(p) * _R().from_quat(q)).as_quat()
    p, q = _stack(p, 4), _stack(q, 4)
    if len(p) != len(q) and 1 not in (len(p), len(q)):
        raise ValueError(f"cannot compose {len(p)} rotations with {len(q)}")
    px, py, pz, pw = p.T
    qx, qy, qz, qw = q.T
    out = np.empty((len(p) if len(q) == 1 else len(q), 4))
    out[:, 0] = pw * qx + qw * px + (py * qz - pz * qy)
    out[:, 1] = pw * qy + qw * py + (pz * qx - px * qz)
    out[:, 2] = pw * qz + qw * pz + (px * qy - py * qx)
    out[:, 3] = pw * qw - px * qx - py * qy - pz * qz
    return _normalized(out)


def inverse(q: np.ndarray) -> np.ndarray:
    """``r.inv()``."""
    if _cy is None:
        return _R().from_quat(q).inv().as_quat()
    return np.asarray(_cy.inv(_w(q)))


def as_quat(q: np.ndarray) -> np.ndarray:
    """``r.as_quat()``: the quaternions ``(N, 4)`` as an array of their own."""
    if _cy is None:
        return np.array(q, dtype=np.float64)
    return np.asarray(_cy.as_quat(_w(q), canonical=False, scalar_first=False))


def as_rotvec(q: np.ndarray) -> np.ndarray:
    """``r.as_rotvec()``, ``(N, 3)`` radians: the angle ``2 atan2(|v|, w)`` of the quaternion with
    ``w >= 0`` times the axis, by the backend's series below 1e-3 rad."""
    if _cy is None:
        return _R().from_quat(q).as_rotvec()
    q = _stack(q, 4)
    q = np.where(q[:, 3:] < 0, -q, q)
    x, y, z, w = q.T
    angle = 2 * _c_map(math.atan2, np.sqrt(x * x + y * y + z * z), w)
    small = angle <= 1e-3
    a2 = angle * angle
    scale = 2 + a2 / 12 + 7 * a2 * a2 / 2880  # the series where the angle is small
    big = ~small
    scale[big] = angle[big] / _c_map(math.sin, angle[big] / 2)
    return scale[:, None] * q[:, :3]


def as_matrix(q: np.ndarray) -> np.ndarray:
    """``r.as_matrix()``, ``(N, 3, 3)``."""
    if _cy is None:
        return _R().from_quat(q).as_matrix()
    return np.asarray(_cy.as_matrix(_w(q)))


def apply(q: np.ndarray, v) -> np.ndarray:
    """``r.apply(v)`` for vectors ``(N, 3)`` (or one ``(3,)``), ``(N, 3)``."""
    if _cy is None:
        return _R().from_quat(q).apply(v)
    return np.asarray(_cy.apply(_w(q), _w(_stack(v, 3)), inverse=False))

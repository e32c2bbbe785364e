"""core.quat: numpy quaternion arithmetic gives the rotations scipy gives (the BVH reader relies on it)."""
import numpy as np
import pytest
from scipy.spatial.transform import Rotation, Slerp

from text2anim.core import quat


@pytest.mark.parametrize("order", ["ZYX", "ZXY", "XYZ", "YXZ", "X", "ZY", "YX"])
def test_from_euler_is_scipy_bit_for_bit(order):
    rng = np.random.default_rng(len(order))
    angles = rng.uniform(-400, 400, (500, 4, len(order)))
    angles[::7] = 0.0
    angles[::5, 0] = 180.0
    expect = Rotation.from_euler(order, angles.reshape(-1, len(order)), degrees=True).as_quat()
    got = quat.from_euler(order, angles).reshape(-1, 4)
    assert np.array_equal(got, expect)



def test_from_euler_is_scipy_bit_for_bit_across_blocks():
    """A long clip is converted in blocks (``quat._BLOCK`` rotations each): the blocks join without a seam."""
    rng = np.random.default_rng(3)
    angles = rng.uniform(-400, 400, (2 * quat._BLOCK // 5 + 7, 5, 3))  # 2.4 blocks, the last one partial
    angles[::11] = 0.0
    expect = Rotation.from_euler("ZXY", angles.reshape(-1, 3), degrees=True).as_quat()
    assert np.array_equal(quat.from_euler("ZXY", angles).reshape(-1, 4), expect)

def test_from_euler_empty_order_is_identity():
    assert np.array_equal(quat.from_euler("", np.zeros((3, 0))), np.tile([0.0, 0.0, 0.0, 1.0], (3, 1)))


def test_products_matrices_rotations_and_slerp_match_scipy():
    a = Rotation.random(300, random_state=1)
    b = Rotation.random(300, random_state=2)
    qa, qb = a.as_quat(), b.as_quat()
    v = np.random.default_rng(3).normal(size=(300, 3))
    assert np.allclose(quat.multiply(qa, qb), (a * b).as_quat(), atol=1e-15)
    assert np.allclose(quat.to_matrix(qa), a.as_matrix(), atol=1e-15)
    assert np.allclose(quat.rotate(qa, v), a.apply(v), atol=1e-14)
    assert np.allclose(quat.multiply(qa, quat.conjugate(qa)), [0, 0, 0, 1], atol=1e-15)
    t = np.linspace(0, 1, 300)
    ref = np.array([Slerp([0, 1], Rotation.from_quat([qa[i], qb[i]]))(t[i]).as_quat() for i in range(300)])
    got = quat.slerp(qa, qb, t)
    assert np.allclose(np.abs(np.sum(got * ref, axis=-1)), 1.0, atol=1e-12)


@pytest.mark.parametrize("fps", [24.0, 60.0, 120.0])
def test_resample_slerps_like_scipy(fps):
    from conftest import make_motion

    m = make_motion(45, 30.0, 7)
    t_new = np.minimum(np.arange(len(m.resample(fps).rotations)) / fps, m.times[-1])
    expect = np.stack([Slerp(m.times, Rotation.from_quat(m.rotations[:, j]))(t_new).as_quat()
                       for j in range(m.skeleton.n_joints)], axis=1)
    assert np.allclose(m.resample(fps).rotations, expect, atol=1e-12)


@pytest.mark.parametrize("backend", ["compiled", "public"])
def test_rotation_kernels_are_scipy_rotation_bit_for_bit(backend, monkeypatch):
    """core.rotkernels calls scipy's compiled backend as Rotation does: the same bits, no objects; with
    another scipy (no backend, or one that answers differently) the public methods give the same rotations."""
    from text2anim.core import rotkernels as rk

    same = np.array_equal
    if backend == "public":  # a round trip through quaternions between calls: equal to rounding
        monkeypatch.setattr(rk, "_cy", None)
        same = lambda x, y: np.allclose(x, y, rtol=0, atol=1e-12)  # noqa: E731
    else:
        assert rk._cy is not None and rk._backend_answers(rk._cy)  # scipy as pinned in CI: the fast path runs

    rng = np.random.default_rng(11)
    for n in (1, 5, 31, 400):
        q = Rotation.random(n, random_state=n).as_quat() * rng.uniform(0.5, 2.0, (n, 1))  # not unit
        p = Rotation.random(n, random_state=n + 1).as_quat()
        p[::3] = -q[::3]
        v = rng.normal(size=(n, 3)) * rng.choice([1e-9, 1e-3, 1.0, 3.0], (n, 1))
        a, b, c = Rotation.from_quat(q), Rotation.from_quat(p), Rotation.from_rotvec(v)
        qa, qb, qc = rk.from_quat(q), rk.from_quat(p), rk.from_rotvec(v)
        assert same(rk.as_quat(qa), a.as_quat()) and same(rk.as_quat(qc), c.as_quat())
        assert same(rk.as_quat(rk.compose(rk.inverse(qa), qb)), (a.inv() * b).as_quat())
        assert same(rk.as_rotvec(rk.compose(qa, qc)), (a * c).as_rotvec())
        assert same(rk.as_matrix(qc), c.as_matrix())
        assert same(rk.apply(qc, v), c.apply(v))
        assert same(rk.apply(qa, v[0]), a.apply(v[0]))
        m = a.as_matrix() + 1e-4 * rng.normal(size=(n, 3, 3))  # not quite orthogonal
        assert same(rk.as_quat(rk.from_matrix(m)), Rotation.from_matrix(m).as_quat())

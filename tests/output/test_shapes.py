"""The props' shapes: every shape fills its bounding box, its triangles face out, and a chair is a chair."""
from __future__ import annotations

import numpy as np
import pytest

from text2anim.output.shapes import PART_KINDS, mesh, parts
from text2anim.output.viewer.types import PROP_SHAPES, Prop

SIZES = {"sphere": (0.22, 0.22, 0.22), "box": (0.4, 0.3, 0.5), "cylinder": (0.3, 0.8, 0.3), "chair": (0.45, 0.9, 0.45),
         "bench": (1.4, 0.45, 0.4), "door": (0.9, 2.0, 0.06), "book": (0.15, 0.03, 0.22), "cup": (0.11, 0.1, 0.08),
         "stick": (0.03, 0.03, 1.2)}


def test_every_shape_has_a_size():
    assert sorted(SIZES) == sorted(PROP_SHAPES)


@pytest.mark.parametrize("shape", PROP_SHAPES)
def test_the_mesh_fills_the_box_and_faces_out(shape):
    size = SIZES[shape]
    pos, nrm, idx = mesh(shape, size)
    np.testing.assert_allclose(pos.max(axis=0), np.array(size) / 2, atol=1e-9)
    np.testing.assert_allclose(pos.min(axis=0), -np.array(size) / 2, atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(nrm, axis=1), 1, atol=1e-9)
    tri = idx.reshape(-1, 3)
    a, b, c = pos[tri[:, 0]], pos[tri[:, 1]], pos[tri[:, 2]]
    face = np.cross(b - a, c - a)
    big = np.linalg.norm(face, axis=1) > 1e-12
    # counter-clockwise seen from outside: each triangle's normal agrees with its vertices' normals
    agree = np.einsum("ij,ij->i", face[big], nrm[tri[big]].sum(axis=1))
    assert (agree > 0).all(), f"{(agree <= 0).sum()} triangles face in"
    for p in parts(shape, size):
        assert p.kind in PART_KINDS
        assert np.all(np.abs(p.centre) + np.array(p.size) / 2 <= np.array(size) / 2 + 1e-9)


def test_a_chair_is_a_seat_on_four_legs_with_a_back_at_minus_z():
    w, h, d = SIZES["chair"]
    ps = parts("chair", (w, h, d))
    seat = max(ps, key=lambda p: p.size[0] * p.size[2])
    legs = [p for p in ps if p.centre[1] + p.size[1] / 2 < seat.centre[1]]
    above = [p for p in ps if p.centre[1] > seat.centre[1]]
    assert seat.size[0] == pytest.approx(w) and seat.size[2] == pytest.approx(d)
    assert 0.4 * h < seat.centre[1] + h / 2 < 0.55 * h  # a seat at about knee height
    assert len(legs) == 4 and {(np.sign(p.centre[0]), np.sign(p.centre[2])) for p in legs} == \
        {(-1, -1), (-1, 1), (1, -1), (1, 1)}
    assert above and all(p.centre[2] < -0.4 * d for p in above)  # the back, behind the sitter


def test_a_stick_lies_along_its_longest_side():
    (p,) = parts("stick", SIZES["stick"])
    assert p.kind == "cylinder" and p.axis == 2


@pytest.mark.parametrize("bad, match", [({"shape": "table"}, "unknown shape"), ({"size": (0.2, 0, 0.2)}, "positive"),
                                        ({"color": "red"}, "#rrggbb"), ({"fps": 0}, "fps"),
                                        ({"rotations": np.zeros((3, 4))}, "quaternion")])
def test_a_bad_prop_is_refused(bad, match):
    args = dict(name="x", shape="box", size=(0.2, 0.2, 0.2), positions=np.zeros((3, 3)),
                rotations=np.tile([0, 0, 0, 1.0], (3, 1)), fps=30.0, color="#123456")
    with pytest.raises(ValueError, match=match):
        Prop(**{**args, **bad})

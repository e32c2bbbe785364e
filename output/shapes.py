"""What each prop shape (:data:`~output.viewer.types.PROP_SHAPES`) is made of: :func:`parts`, and its triangles.

Every shape is a few solid **parts**, each a box, a cylinder or an ellipsoid given by its centre and
extent in the prop's own frame (metres; the frame's origin is the centre of the prop's bounding box
``size = (w, h, d)``, x right, y up, z the front). The GLB (:mod:`output.gltf`) meshes the parts
(:func:`mesh`), the viewer page draws the same parts on its canvas, the top view outlines their
footprint. One table, so the three agree.

- ``sphere`` one ellipsoid filling the box; ``box``, ``book`` one box; ``cylinder`` one cylinder along y;
  ``stick`` one cylinder along the box's longest side;
- ``chair`` (faces +z) a seat at 47 % of the height, four legs, two back posts and a back panel at -z;
- ``bench`` a seat board on top of two end slabs;
- ``door`` a panel in the x-y plane, a knob on its +z face near +x;
- ``cup`` a cylinder (80 % of the width) and a handle at +x.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["PART_KINDS", "Part", "mesh", "parts"]

#: The kinds of part, in the order the viewer page numbers them (0, 1, 2).
PART_KINDS = ("box", "cylinder", "sphere")
#: Segments around a cylinder, and rings x segments of an ellipsoid, in a GLB mesh.
CYLINDER_SEGMENTS = 20
SPHERE_RINGS, SPHERE_SEGMENTS = 12, 20


@dataclass(frozen=True)
class Part:
    """One solid of a shape: ``kind`` (:data:`PART_KINDS`), its ``centre`` and ``size`` (extent along x, y, z),
    metres in the prop's frame; a cylinder's ``axis`` (0 x, 1 y, 2 z)."""

    kind: str
    centre: tuple[float, float, float]
    size: tuple[float, float, float]
    axis: int = 1


def _xyz(v: np.ndarray) -> tuple[float, float, float]:
    return float(v[0]), float(v[1]), float(v[2])


def _part(kind: str, size, centre_frac, size_frac, axis: int = 1) -> Part:
    """A part placed in fractions of the bounding box (centre -0.5 .. 0.5, size 0 .. 1 of each side)."""
    s = np.asarray(size, dtype=float)
    return Part(kind, _xyz(np.asarray(centre_frac) * s), _xyz(np.asarray(size_frac) * s), axis)


def parts(shape: str, size: tuple[float, float, float]) -> list[Part]:
    """The parts of ``shape`` for a bounding box of ``size`` ``(w, h, d)`` metres (see the module docstring)."""
    box = (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)
    if shape == "sphere":
        return [_part("sphere", size, *box)]
    if shape in ("box", "book"):
        return [_part("box", size, *box)]
    if shape == "cylinder":
        return [_part("cylinder", size, *box)]
    if shape == "stick":
        return [_part("cylinder", size, *box, axis=int(np.argmax(size)))]
    if shape == "chair":
        legs = [_part("box", size, (sx * 0.45, -0.28, sz * 0.45), (0.1, 0.44, 0.1)) for sx in (-1, 1) for sz in (-1, 1)]
        posts = [_part("box", size, (sx * 0.45, 0.25, -0.45), (0.1, 0.5, 0.1)) for sx in (-1, 1)]
        return [_part("box", size, (0, -0.03, 0), (1, 0.06, 1)), *legs, *posts,
                _part("box", size, (0, 0.29, -0.45), (0.8, 0.34, 0.06))]
    if shape == "bench":
        ends = [_part("box", size, (sx * 0.4, -0.075, 0), (0.07, 0.85, 0.8)) for sx in (-1, 1)]
        return [_part("box", size, (0, 0.425, 0), (1, 0.15, 1)), *ends]
    if shape == "door":
        return [_part("box", size, (0, 0, -0.2), (1, 1, 0.6)), _part("sphere", size, (0.38, -0.02, 0.3), (0.06, 0.03, 0.4))]
    if shape == "cup":
        return [_part("cylinder", size, (-0.1, 0, 0), (0.8, 1, 1)), _part("box", size, (0.4, 0, 0), (0.2, 0.5, 0.2))]
    raise ValueError(f"unknown prop shape {shape!r}")


# --------------------------------------------------------------------------- triangles
#: A part's triangles as the meshers build them: positions, normals (lists of 3-vectors), indices.
Triangles = tuple[list[np.ndarray], list[np.ndarray], list[int]]


def _box(p: Part) -> Triangles:
    c, half = np.asarray(p.centre), np.asarray(p.size) / 2
    pos: list[np.ndarray] = []
    nrm: list[np.ndarray] = []
    idx: list[int] = []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            u, v = [(1, 2), (2, 0), (0, 1)][axis]  # (u, v, axis) right-handed: u x v = axis
            n = np.zeros(3)
            n[axis] = sign
            base = len(pos)
            for cu, cv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                corner = np.zeros(3)
                corner[axis], corner[u], corner[v] = sign, cu, cv
                pos.append(c + corner * half)
                nrm.append(n)
            tri = [0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2]
            idx.extend(base + t for t in tri)
    return pos, nrm, idx


def _frame(axis: int) -> tuple[int, int, int]:
    """The part's (a, b, axis) coordinates: a x b = axis, so a ring (cos, sin) in (a, b) turns about +axis."""
    return [(1, 2, 0), (2, 0, 1), (0, 1, 2)][axis]


def _cylinder(p: Part, n: int = CYLINDER_SEGMENTS) -> Triangles:
    a, b, ax = _frame(p.axis)
    c, half = np.asarray(p.centre), np.asarray(p.size) / 2
    ang = np.arange(n) * 2 * np.pi / n
    ring = np.zeros((n, 3))
    ring[:, a], ring[:, b] = np.cos(ang) * half[a], np.sin(ang) * half[b]
    side_n = np.zeros((n, 3))
    side_n[:, a], side_n[:, b] = np.cos(ang) / half[a], np.sin(ang) / half[b]  # the ellipse's normal
    side_n /= np.linalg.norm(side_n, axis=1, keepdims=True)
    top = np.zeros(3)
    top[ax] = half[ax]
    pos: list[np.ndarray] = []
    nrm: list[np.ndarray] = []
    idx: list[int] = []
    for i in range(n):  # side: bottom i, bottom i+1, top i+1, top i (counter-clockwise from outside)
        j = (i + 1) % n
        base = len(pos)
        pos += [c + ring[i] - top, c + ring[j] - top, c + ring[j] + top, c + ring[i] + top]
        nrm += [side_n[i], side_n[j], side_n[j], side_n[i]]
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    for sign in (1.0, -1.0):  # caps: a fan about the centre
        n_cap = np.zeros(3)
        n_cap[ax] = sign
        centre = len(pos)
        pos.append(c + sign * top)
        nrm.append(n_cap)
        for i in range(n):
            pos.append(c + ring[i] + sign * top)
            nrm.append(n_cap)
        for i in range(n):
            j = (i + 1) % n
            idx += [centre, centre + 1 + i, centre + 1 + j] if sign > 0 else [centre, centre + 1 + j, centre + 1 + i]
    return pos, nrm, idx


def _sphere(p: Part, rings: int = SPHERE_RINGS, segs: int = SPHERE_SEGMENTS) -> Triangles:
    c, r = np.asarray(p.centre), np.asarray(p.size) / 2
    pos: list[np.ndarray] = []
    nrm: list[np.ndarray] = []
    idx: list[int] = []
    for i in range(rings + 1):
        th = np.pi * i / rings  # from the top (+y) down
        for k in range(segs + 1):
            ph = 2 * np.pi * k / segs
            unit = np.array([np.sin(th) * np.sin(ph), np.cos(th), np.sin(th) * np.cos(ph)])
            pos.append(c + unit * r)
            n = unit / r
            nrm.append(n / np.linalg.norm(n))
    for i in range(rings):
        for k in range(segs):
            a, b = i * (segs + 1) + k, (i + 1) * (segs + 1) + k
            if i > 0:
                idx += [a, b, a + 1]
            if i < rings - 1:
                idx += [a + 1, b, b + 1]
    return pos, nrm, idx


_MESHERS = {"box": _box, "cylinder": _cylinder, "sphere": _sphere}


def mesh(shape: str, size: tuple[float, float, float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Triangles of ``shape``'s parts: positions ``(V, 3)`` and unit normals ``(V, 3)`` metres in the prop's frame,
    indices ``(3 F,)`` counter-clockwise seen from outside."""
    pos: list = []
    nrm: list = []
    idx: list = []
    for p in parts(shape, size):
        pp, nn, ii = _MESHERS[p.kind](p)
        base = len(pos)
        pos += pp
        nrm += nn
        idx += [base + i for i in ii]
    return np.array(pos, dtype=float), np.array(nrm, dtype=float), np.array(idx, dtype=np.int64)

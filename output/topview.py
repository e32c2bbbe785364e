"""The scene seen from above: :func:`top_view` (what is drawn, as numbers) and :func:`plot_top_view` (a picture).

Looking down on the floor (Y up) with +Z up the page, +X points to the page's **left**: that is
what a person standing above sees of a right-handed Y-up world, and it keeps a character's left
on the page's left when it walks up the page (a picture with +X to the right would be seen from
below, every turn mirrored). The axes say so.

Drawn for each actor, in its colour (the viewer's :data:`~output.viewer.PALETTE`): the path of
its hips, its name and a dot where it starts, an arrow at the start and at the end pointing where
the body faces (the mean of the hips' and the shoulders' left-to-right line turned a quarter
about +Y), and a small dot labelled by each time-table element (``"2 蹴る"``) where the hips are
when the element starts. For each prop (:class:`~output.viewer.types.Prop`), in its colour: its
footprint (a circle for round shapes, else the outline of its turned bounding box) where it starts
and, when it moved, where it ends, the path of its centre, and its name. A metre grid, equal
aspect. Japanese labels are drawn with a CJK font when one is installed (:mod:`.fonts`), else
their romanised alternative or ``actor N`` / the shape's name: never boxes.

The same numbers feed the studio's live top view (:meth:`TopView.to_dict`). matplotlib is the
``plot`` extra, imported only when a picture is drawn.
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from text2anim.core.motion import Motion
from . import fonts
from .shapes import parts
from .viewer.types import Prop, Span, as_props, as_spans, as_tracks

__all__ = ["Footprint", "TopActor", "TopProp", "TopView", "footprint", "plot_top_view", "top_view"]

#: Shapes whose footprint is a circle.
ROUND = frozenset({"sphere", "cylinder", "cup"})
#: Seconds at the start and end over which the facing arrows are averaged.
FACING_WINDOW = 0.2


@dataclass(frozen=True)
class Footprint:
    """What a prop covers of the floor, seen from above: a ``circle`` (``centre`` (x, z), ``radius``) or a
    ``polygon`` (``points`` (N, 2) x, z, counter-clockwise), metres."""

    kind: str
    centre: tuple[float, float]
    radius: float = 0.0
    points: tuple[tuple[float, float], ...] = ()


@dataclass(frozen=True, eq=False)
class TopActor:
    """An actor from above: ``path`` (T, 2) its hips' x, z at ``fps``; ``start_facing`` / ``end_facing`` unit (x, z)
    or ``None`` (a skeleton without known hips and shoulders); ``marks`` (label, alt, x, z) per element started."""

    name: str
    color: str
    fps: float
    path: np.ndarray
    start_facing: tuple[float, float] | None
    end_facing: tuple[float, float] | None
    marks: tuple[tuple[str, str | None, float, float], ...]


@dataclass(frozen=True, eq=False)
class TopProp:
    """A prop from above: its footprint at the start and the end, ``path`` (T, 2) of its centre's x, z at ``fps``
    (``None`` when it does not travel)."""

    name: str
    shape: str
    color: str
    fps: float
    start: Footprint
    end: Footprint
    path: np.ndarray | None


@dataclass(frozen=True, eq=False)
class TopView:
    """The scene from above: :class:`TopActor` and :class:`TopProp` items, metres."""

    actors: tuple[TopActor, ...]
    props: tuple[TopProp, ...]

    def bounds(self) -> tuple[float, float, float, float]:
        """``(x0, x1, z0, z1)`` covering every path and footprint."""
        pts = [a.path for a in self.actors]
        for p in self.props:
            for f in (p.start, p.end):
                pts.append(np.array(f.points) if f.kind == "polygon" else
                           np.array(f.centre) + np.array([[-1, -1], [1, 1]]) * f.radius)
            if p.path is not None:
                pts.append(p.path)
        xz = np.vstack(pts)
        return float(xz[:, 0].min()), float(xz[:, 0].max()), float(xz[:, 1].min()), float(xz[:, 1].max())

    def to_dict(self, fps: float = 10.0) -> dict:
        """JSON for a live drawing (the studio): paths at about ``fps`` (and their last point), centimetres."""
        def path(xz: np.ndarray, src_fps: float) -> list[list[float]]:
            step = max(1, int(round(src_fps / fps)))
            keep = np.r_[np.arange(0, len(xz), step), len(xz) - 1] if len(xz) > 1 else np.arange(len(xz))
            return np.round(xz[np.unique(keep)], 2).tolist()

        def path_step(src_fps: float) -> float:  # seconds between two points of a path
            return max(1, int(round(src_fps / fps))) / src_fps

        def foot(f: Footprint) -> dict:
            return ({"circle": [round(f.centre[0], 2), round(f.centre[1], 2), round(f.radius, 3)]}
                    if f.kind == "circle" else {"polygon": np.round(np.array(f.points), 3).tolist()})

        return {
            "actors": [{"name": a.name, "color": a.color, "path": path(a.path, a.fps), "step": path_step(a.fps),
                        "facing": [a.start_facing and [round(v, 3) for v in a.start_facing],
                                   a.end_facing and [round(v, 3) for v in a.end_facing]],
                        "marks": [[m[0], round(m[2], 2), round(m[3], 2)] for m in a.marks]} for a in self.actors],
            "props": [{"name": p.name, "color": p.color, "start": foot(p.start), "end": foot(p.end),
                       "path": None if p.path is None else path(p.path, p.fps), "step": path_step(p.fps)}
                      for p in self.props],
        }


# --------------------------------------------------------------------------- numbers
def _facing(motion: Motion, frames: np.ndarray) -> tuple[float, float] | None:
    """Unit (x, z) the body faces over ``frames``: hips and shoulders, left minus right, turned a quarter."""
    from text2anim.core.rigs import RigError, rig_roles

    try:
        roles = rig_roles(motion.skeleton)[1]
    except RigError:
        return None
    P = motion.positions[frames]
    left = np.zeros(3)
    for a, b in (("leftUpperLeg", "rightUpperLeg"), ("leftUpperArm", "rightUpperArm")):
        if a in roles and b in roles:
            d = P[:, roles[a]] - P[:, roles[b]]
            left += (d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-9)).mean(axis=0)
    fwd = np.array([-left[2], left[0]])  # left x up = (-l_z, 0, l_x)
    n = float(np.linalg.norm(fwd))
    return None if n < 1e-6 else (float(fwd[0] / n), float(fwd[1] / n))


def _hips(motion: Motion) -> int:
    from text2anim.core.rigs import RigError, rig_roles

    try:
        return rig_roles(motion.skeleton)[1]["hips"]
    except (RigError, KeyError):
        return 0


def _short(label: str) -> str:
    """``"2 蹴る (transition) [right_leg]"`` -> ``"2 蹴る"``."""
    return label.split(" (", 1)[0].split(" [", 1)[0]


def _actor(name: str, color: str, motion: Motion, spans: list[Span]) -> TopActor:
    path = motion.positions[:, _hips(motion)][:, [0, 2]]
    n = max(1, int(round(FACING_WINDOW * motion.fps)))
    T = motion.n_frames
    marks = []
    for s in spans:
        if s.actor == name and s.kind == "element":
            f = int(np.clip(round(s.start * motion.fps), 0, T - 1))
            marks.append((_short(s.label), _short(s.alt) if s.alt else None, float(path[f, 0]), float(path[f, 1])))
    return TopActor(name, color, float(motion.fps), path, _facing(motion, np.arange(min(n, T))),
                    _facing(motion, np.arange(max(0, T - n), T)), tuple(marks))


def _hull(pts: np.ndarray) -> np.ndarray:
    """The convex hull of 2-D points, counter-clockwise (Andrew's monotone chain)."""
    unique = sorted(set(map(tuple, np.round(pts, 6))))
    if len(unique) < 3:
        return np.array(unique)

    def half(seq):
        out: list = []
        for p in seq:
            while len(out) >= 2 and ((out[-1][0] - out[-2][0]) * (p[1] - out[-2][1])
                                     - (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0])) <= 0:
                out.pop()
            out.append(p)
        return out

    lower, upper = half(unique), half(reversed(unique))
    return np.array(lower[:-1] + upper[:-1])


def footprint(prop: Prop, frame: int) -> Footprint:
    """What ``prop`` covers of the floor at ``frame``: a circle for round shapes, else the outline of its
    parts' corners, turned as the prop is, seen from above."""
    c = prop.positions[frame]
    if prop.shape in ROUND:
        return Footprint("circle", (float(c[0]), float(c[2])), max(prop.size[0], prop.size[2]) / 2)
    rot = Rotation.from_quat(prop.unit_rotations[frame])
    corners = []
    for p in parts(prop.shape, prop.size):
        half = np.asarray(p.size) / 2
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
        corners.append(np.asarray(p.centre) + signs * half)
    world = rot.apply(np.vstack(corners)) + c
    hull = _hull(world[:, [0, 2]])
    return Footprint("polygon", (float(c[0]), float(c[2])), points=tuple(map(tuple, hull.tolist())))


def _prop(prop: Prop) -> TopProp:
    xz = prop.positions[:, [0, 2]]
    moved = float(np.linalg.norm(xz - xz[0], axis=1).max()) > 0.01 or not prop.is_static
    return TopProp(prop.name, prop.shape, prop.color, float(prop.fps), footprint(prop, 0), footprint(prop, prop.n_frames - 1),
                   xz if moved else None)


def top_view(tracks, spans=(), props=()) -> TopView:
    """The scene of ``tracks`` (:class:`~output.viewer.types.Track` list, ``{name: Motion}`` or one Motion),
    the time-table ``spans`` and the ``props``, from above (see the module docstring)."""
    from .viewer import PALETTE

    spans = as_spans(spans)
    actors = tuple(_actor(t.name, PALETTE[i % len(PALETTE)], t.motion, spans) for i, t in enumerate(as_tracks(tracks)))
    return TopView(actors, tuple(_prop(p) for p in as_props(props)))


# --------------------------------------------------------------------------- picture
def _darker(color: str, k: float = 0.75) -> tuple[float, float, float]:
    """``color`` times ``k``, and dark enough to read on white (luma at most 0.5: a white ball's outline is grey)."""
    rgb = np.array([int(color[i:i + 2], 16) for i in (1, 3, 5)]) / 255 * k
    luma = float(rgb @ [0.299, 0.587, 0.114])
    if luma > 0.5:
        rgb *= 0.5 / luma
    return float(rgb[0]), float(rgb[1]), float(rgb[2])


def _patch(f: Footprint, color: str, final: bool):
    from matplotlib.patches import Circle, Polygon

    style = dict(facecolor=color, alpha=0.35 if not final else 0.18, edgecolor=_darker(color, 0.6), lw=1.4,
                 ls="--" if final else "-", zorder=2)
    return Circle(f.centre, f.radius, **style) if f.kind == "circle" else Polygon(np.array(f.points), closed=True, **style)


def _arrow(ax, x: float, z: float, d: tuple[float, float] | None, color, length: float) -> None:
    if d is not None:
        ax.annotate("", xy=(x + d[0] * length, z + d[1] * length), xytext=(x, z), zorder=5,
                    arrowprops=dict(arrowstyle="-|>,head_length=0.6,head_width=0.35", color=color, lw=2.2,
                                    shrinkA=0, shrinkB=0))


def _draw(Figure, view: TopView, title: str, size: tuple[int, int], dpi: float):
    from matplotlib.ticker import MultipleLocator

    fig = Figure(figsize=(size[0] / dpi, size[1] / dpi), dpi=dpi, layout="constrained")
    ax = fig.subplots()
    x0, x1, z0, z1 = view.bounds()
    pad = 0.08 * max(x1 - x0, z1 - z0) + 0.6
    w, h = max(x1 - x0, 1.0) + 2 * pad, max(z1 - z0, 1.0) + 2 * pad
    aspect = size[0] / size[1]  # the wider side of the data grows so the metre squares fill the picture
    w, h = max(w, h * aspect), max(h, w / aspect)
    cx, cz = (x0 + x1) / 2, (z0 + z1) / 2
    ax.set_xlim(cx + w / 2, cx - w / 2)  # +x to the left: seen from above with +z up the page
    ax.set_ylim(cz - h / 2, cz + h / 2)
    ax.set_aspect("equal", adjustable="box")
    label_step = next((m for m in (1, 2, 5, 10, 20, 50) if max(w, h) / m <= 16), 100)  # labelled ticks
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_locator(MultipleLocator(label_step))
        axis.set_minor_locator(MultipleLocator(1.0))  # the metre grid
    ax.grid(True, which="both", color="#dddddd", lw=0.8, zorder=0)
    ax.tick_params(which="minor", length=0)
    ax.set_axisbelow(True)
    ax.set_xlabel("x (m): +x to the left")
    ax.set_ylabel("z (m): +z up the page")
    arrow = 0.04 * max(w, h) + 0.2
    for p in view.props:
        ax.add_patch(_patch(p.start, p.color, False))
        if p.path is not None:
            ax.add_patch(_patch(p.end, p.color, True))
            ax.plot(p.path[:, 0], p.path[:, 1], color=_darker(p.color), lw=1.2, ls=(0, (2, 2)), zorder=3)
        below = p.start.centre[1] - p.start.radius if p.start.kind == "circle" else min(z for _, z in p.start.points)
        ax.annotate(fonts.label(p.name, fallback=p.shape), (p.start.centre[0], below), xytext=(0, -3),
                    textcoords="offset points", ha="center", va="top", fontsize=9, color=_darker(p.color, 0.55),
                    zorder=6)
    for i, a in enumerate(view.actors):
        name = fonts.label(a.name, fallback=f"actor {i + 1}") if a.name else f"actor {i + 1}"
        ax.plot(a.path[:, 0], a.path[:, 1], color=a.color, lw=2.4, zorder=4, solid_capstyle="round")
        (sx, sz), (ex, ez) = a.path[0], a.path[-1]
        ax.plot([sx], [sz], "o", ms=9, color=a.color, mec="white", mew=1.5, zorder=6)
        _arrow(ax, sx, sz, a.start_facing, a.color, arrow)
        _arrow(ax, ex, ez, a.end_facing, _darker(a.color), arrow)
        fx, fz = a.start_facing or (0.0, 1.0)  # the name behind the start (the page's x runs the other way)
        ax.annotate(name, (sx, sz), xytext=(18 * fx, -18 * fz), textcoords="offset points", ha="center",
                    va="center", fontsize=11, fontweight="bold", color=_darker(a.color, 0.8), zorder=7)
        for label, alt, x, z in a.marks:
            ax.plot([x], [z], "o", ms=4.5, color=_darker(a.color, 0.7), zorder=6)
            ax.annotate(fonts.label(label, alt), (x, z), xytext=(6, 0), textcoords="offset points", va="center",
                        ha="left", fontsize=8, color="#333333", zorder=7)
    shown = title if title and fonts.drawable(title) else ""  # a title without its Japanese would say nothing
    fig.suptitle(f"{shown} (seen from above)" if shown else "The scene seen from above", x=0.01, ha="left",
                 fontsize=12, fontweight="bold")
    return fig


def plot_top_view(tracks, path: str | os.PathLike, spans=(), props=(), *, title: str = "",
                  size: tuple[int, int] = (900, 900), dpi: float = 100) -> None:
    """Draw :func:`top_view` of ``tracks``, ``spans`` and ``props`` to ``path`` (``.png``, ``.svg``, ``.pdf``),
    ``size`` pixels at ``dpi``, atomically."""
    from .plots import check_figure_path, figure_style, figure_tools, save_figure

    _, Figure, Canvas = figure_tools("a top view (--top-view)")
    out, fmt = check_figure_path(Path(path))
    view = top_view(tracks, spans, props)
    with figure_style():
        save_figure(_draw(Figure, view, title, size, dpi), Canvas, out, fmt, dpi)

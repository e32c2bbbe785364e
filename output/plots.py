"""Figures for a person to look at: :func:`plot_speeds` (Fig. 5 of the optimal-blending
paper: upper- and lower-body speed over time, blend intervals shaded) and
:func:`plot_gantt` (the time table as a Gantt chart per actor).

matplotlib is an optional extra (``pip install 'text2anim[plot]'``), imported
only when a plot is drawn; without it :class:`PlotDependencyError` says so.
Figures are drawn on matplotlib's Agg canvas directly (no pyplot, no global
backend switch) and written atomically; the format follows the file's suffix
(``.png``, ``.svg``, ``.pdf``).

Japanese text: matplotlib's default font (DejaVu Sans) has no CJK glyphs. A
CJK font that matplotlib knows (Noto Sans CJK JP from Debian's
``fonts-noto-cjk``, IPAexGothic, Hiragino, Yu Gothic, ...) is used as a
fallback after DejaVu Sans when there is one; none is ever installed at run
time. Without one, every label is checked glyph by glyph and a label that
cannot be drawn is replaced by its :attr:`~output.viewer.types.Span.alt`
(e.g. the clip name), or else loses the characters that cannot be drawn
(``"2 蹴る (transition)"`` → ``"2 (transition)"``); an actor's name becomes
``actor N``. No "missing glyph" warnings are emitted.
"""
from __future__ import annotations

import io
import os
import warnings
from collections.abc import Iterable, Mapping
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from ..core import extras

from . import fonts
from text2anim.core.atomic import OutputError, atomic_write_bytes
from text2anim.core.motion import Motion
from .viewer.types import Span, as_spans

__all__ = ["PlotDependencyError", "PlotError", "check_figure_path", "figure_style", "figure_tools", "plot_gantt",
           "plot_speeds", "save_figure"]

CJK_FAMILIES, BASE_FAMILY = fonts.CJK_FAMILIES, fonts.BASE_FAMILY
UPPER_COLOR = "#d9a400"
LOWER_COLOR = "#2e9e6a"
FORMATS = ("png", "svg", "pdf")
#: line colours of the compared motions (the viewer's palette, darkened for a white page)
LINE_COLORS = ("#1f6fd1", "#e0662a", "#2a9d63", "#9a48d0", "#c79a12", "#d43b5e", "#1e9aa6", "#6b6b6b")


#: matplotlib is not installed (:class:`.extras.MissingExtraError`).
PlotDependencyError = extras.MissingExtraError


class PlotError(ValueError):
    """A plot that cannot be drawn from what it was given."""

    user_facing = True


def figure_tools(what: str = "a plot"):
    """``(matplotlib, Figure, FigureCanvasAgg)``; :class:`PlotDependencyError` without matplotlib, naming ``what``
    needs it."""
    matplotlib = extras.require("matplotlib", what)
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    return matplotlib, Figure, FigureCanvasAgg


def _fonts() -> tuple[str | None, frozenset]:
    """The CJK fallback family (or ``None``) and the code points the chosen fonts can draw (:mod:`.fonts`)."""
    return fonts.available()


def _drawable(text: str) -> bool:
    return fonts.drawable(text, _fonts()[1])


def _label(text: str, alt: str | None = None, fallback: str = "?") -> str:
    """``text`` if the fonts can draw it, else ``alt``, else ``text`` without what cannot be drawn."""
    return fonts.label(text, alt, fallback, _fonts()[1])


@contextmanager
def figure_style():
    """The house style for a figure, with a font that draws Japanese when one is installed, and no glyph warnings."""
    matplotlib, _, _ = figure_tools()
    cjk, _chars = _fonts()
    families = [BASE_FAMILY] + ([cjk] if cjk else [])
    rc = {"font.family": families, "font.size": 10, "axes.spines.top": False, "axes.spines.right": False,
          "axes.titleweight": "bold", "axes.edgecolor": "#555555", "axes.labelcolor": "#222222",
          "xtick.color": "#444444", "ytick.color": "#444444", "svg.fonttype": "none", "pdf.fonttype": 42}
    with matplotlib.rc_context(rc), warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=r"Glyph .* missing from")
        yield


def _format_of(path: Path) -> str:
    fmt = path.suffix.lower().lstrip(".")
    if fmt not in FORMATS:
        raise PlotError(f"{path}: cannot tell the image format from the suffix; use one of "
                        + ", ".join("." + f for f in FORMATS))
    return fmt


def check_figure_path(path) -> tuple[Path, str]:
    """``(path, format)`` of a figure to write, its format from the suffix; :class:`PlotError` or
    :class:`~core.atomic.OutputError` before anything is drawn."""
    path = Path(path)
    fmt = _format_of(path)
    directory = path.parent if str(path.parent) else Path(".")
    if not directory.is_dir():  # fail before drawing
        raise OutputError(f"{path}: the folder {directory} does not exist")
    return path, fmt


def save_figure(fig, canvas_cls, path: Path, fmt: str, dpi: float) -> None:
    """Draw ``fig`` on ``canvas_cls`` and write it to ``path`` in ``fmt``, atomically, on white."""
    canvas_cls(fig)
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=dpi, facecolor="white")
    atomic_write_bytes(path, buf.getvalue())


def _as_labelled(motions) -> list[tuple[str, Motion]]:
    if isinstance(motions, Motion):
        return [("", motions)]
    if isinstance(motions, Mapping):
        items = list(motions.items())
    else:
        items = [tuple(x) for x in motions]
    out = []
    for label, m in items:
        if not isinstance(m, Motion):
            raise TypeError(f"{label!r}: expected a Motion, got {type(m).__name__}")
        out.append((str(label), m))
    if not out:
        raise PlotError("no motions to plot")
    return out


def _pack(spans: list[Span]) -> tuple[list[int], int]:
    """Lane of each span so that overlapping ones do not share one; and the lane count."""
    order = sorted(range(len(spans)), key=lambda i: (spans[i].start, -spans[i].end))
    ends: list[float] = []
    lanes = [0] * len(spans)
    for i in order:
        k = 0
        while k < len(ends) and ends[k] > spans[i].start + 1e-9:
            k += 1
        if k == len(ends):
            ends.append(spans[i].end)
        else:
            ends[k] = spans[i].end
        lanes[i] = k
    return lanes, max(1, len(ends))


def plot_speeds(motions_by_label, path: str | os.PathLike, spans: Iterable[Span] = (), *,
                title: str = "", size: tuple[int, int] = (1200, 720), dpi: float = 100) -> None:
    """Upper- and lower-body speed over time (Fig. 5 of the optimal-blending paper).

    ``motions_by_label``: one Motion, a ``{label: Motion}`` mapping or ``(label, Motion)``
    pairs, overlaid (e.g. the same time table synthesized by several methods).
    Speeds are :func:`core.metrics.speed_curves`: lower = mean world speed of
    both feet and the hips, upper = of both hands, the chest and the head.
    Blend intervals of ``spans`` are shaded in the panel of the body part they
    blend (both panels for whole-body blends); element starts are marked.
    ``size`` is in pixels at ``dpi``.
    """
    from text2anim.core.metrics import speed_curves

    path, fmt = check_figure_path(path)
    labelled = _as_labelled(motions_by_label)
    spans = as_spans(spans)
    _, Figure, Canvas = figure_tools()
    curves = [(label, speed_curves(m)) for label, m in labelled]
    t_end = max([c.times[-1] if len(c.times) else 0.0 for _, c in curves] + [s.end for s in spans])
    with figure_style():
        fig = Figure(figsize=(size[0] / dpi, size[1] / dpi), dpi=dpi, layout="constrained")
        ax_u, ax_l = fig.subplots(2, 1, sharex=True)
        for ax, part, name in ((ax_u, "upper", "upper body"), (ax_l, "lower", "lower body")):
            for s in spans:
                if s.kind == "blend" and s.lane in (part, "both"):
                    ax.axvspan(s.start, s.end, color=UPPER_COLOR if part == "upper" else LOWER_COLOR,
                               alpha=0.18, lw=0, zorder=0)
            for s in spans:
                if s.kind == "element":
                    ax.axvline(s.start, color="#888888", lw=0.8, ls=(0, (4, 3)), zorder=1)
            for i, (label, c) in enumerate(curves):
                ys = c.upper if part == "upper" else c.lower
                ax.plot(c.times, ys, color=LINE_COLORS[i % len(LINE_COLORS)], lw=1.6, zorder=3,
                        label=_label(label, fallback=f"actor {i + 1}") if label else None)
            ax.set_ylabel(f"{name} speed (m/s)")
            ax.set_ylim(bottom=0)
            ax.grid(True, color="#e6e6e6", lw=0.8, zorder=0)
            ax.set_xlim(0, max(t_end, 1e-3))
        ax_l.set_xlabel("time (s)")
        # element labels along the top of the upper panel, overlapping ones on separate lines
        elements = [s for s in spans if s.kind == "element"]
        lanes, n_lanes = _pack(elements)
        several = len({s.actor for s in elements}) > 1
        actor_no = {a: i + 1 for i, a in enumerate(dict.fromkeys(s.actor for s in elements))}
        for s, lane in zip(elements, lanes):
            text = _label(s.label, s.alt)
            if several:
                text = f"{_label(s.actor, fallback=f'actor {actor_no[s.actor]}')}: {text}"
            ax_u.annotate(text, (s.start, 1), xycoords=("data", "axes fraction"),
                          xytext=(3, -3 - 11 * lane), textcoords="offset points", va="top", ha="left", fontsize=8,
                          color="#555555", annotation_clip=True)
        if elements:  # head room for the labels
            top = max(float(np.max(c.upper)) if len(c.upper) else 0.0 for _, c in curves)
            ax_u.set_ylim(0, max(top, 0.1) * (1.12 + 0.08 * n_lanes))
        from matplotlib.patches import Patch

        handles, names = ax_u.get_legend_handles_labels()
        if any(s.kind == "blend" and s.lane in ("upper", "both") for s in spans):
            handles.append(Patch(color=UPPER_COLOR, alpha=0.3, lw=0))
            names.append("blend (upper body)")
        if any(s.kind == "blend" and s.lane in ("lower", "both") for s in spans):
            handles.append(Patch(color=LOWER_COLOR, alpha=0.3, lw=0))
            names.append("blend (lower body)")
        if handles:
            fig.legend(handles, names, loc="outside upper right", ncols=min(len(handles), 6), frameon=False)
        default = "Upper / lower body speed"
        fig.suptitle(_label(title, fallback=default) if title else default, x=0.01, ha="left",
                     fontsize=12, fontweight="bold")
        save_figure(fig, Canvas, path, fmt, dpi)


def plot_gantt(spans: Iterable[Span], path: str | os.PathLike, *, title: str = "",
               width: int = 1200, dpi: float = 100) -> None:
    """The time table as a Gantt chart: per actor, the elements as labelled bars (overlapping
    ones, transitions and compositions, on separate lanes) and a blend lane under them
    (upper-body blends in its top half, lower-body in its bottom half). Height follows the rows."""
    from matplotlib.patches import Patch, Rectangle

    path, fmt = check_figure_path(path)
    spans = as_spans(spans)
    if not spans:
        raise PlotError("no time-table elements to plot")
    _, Figure, Canvas = figure_tools()
    actors = list(dict.fromkeys(s.actor for s in spans))
    lane_h, blend_h, gap = 1.0, 0.7, 0.5
    rows = []
    y = 0.0
    for a in actors:
        els = [s for s in spans if s.actor == a and s.kind == "element"]
        bls = [s for s in spans if s.actor == a and s.kind == "blend"]
        lanes, n = _pack(els)
        h = n * lane_h + (blend_h if bls else 0)
        rows.append((a, els, lanes, n, bls, y, h))
        y += h + gap
    total = y - gap
    t_end = max(s.end for s in spans)
    height_px = 110 + 34 * total
    with figure_style():
        fig = Figure(figsize=(width / dpi, height_px / dpi), dpi=dpi, layout="constrained")
        ax = fig.subplots()
        ax.set_ylim(total + 0.15, -0.15)
        ax.set_xlim(0, max(t_end, 1e-3) * 1.01)
        yt, yl = [], []
        for k, (a, els, lanes, n, bls, y0, h) in enumerate(rows):
            color = LINE_COLORS[k % len(LINE_COLORS)]
            if k % 2:
                ax.axhspan(y0 - gap / 2, y0 + h + gap / 2, color="#f4f5f7", lw=0, zorder=0)
            for i, (s, lane) in enumerate(zip(els, lanes)):
                top = y0 + lane * lane_h + 0.1
                rect = Rectangle((s.start, top), max(s.end - s.start, 1e-6), lane_h - 0.2, facecolor=color,
                                 alpha=0.85 if i % 2 == 0 else 0.65, edgecolor="white", lw=1, zorder=2)
                ax.add_patch(rect)
                txt = ax.text(s.start, top + (lane_h - 0.2) / 2, " " + _label(s.label, s.alt), va="center",
                              ha="left", fontsize=9, color="white", zorder=3, fontweight="bold")
                txt.set_clip_path(rect)
            if bls:
                by = y0 + n * lane_h + 0.05
                ax.add_patch(Rectangle((0, by), t_end, blend_h - 0.1, facecolor="#eef0f3", lw=0, zorder=1))
                half = (blend_h - 0.1) / 2
                for s in bls:
                    for part, yy, col in (("upper", by, UPPER_COLOR), ("lower", by + half, LOWER_COLOR)):
                        if s.lane in (part, "both"):
                            ax.add_patch(Rectangle((s.start, yy), max(s.end - s.start, 1e-6), half,
                                                   facecolor=col, alpha=0.8, lw=0, zorder=2))
                ax.text(-0.004, by + half, "blend", transform=ax.get_yaxis_transform(), ha="right", va="center",
                        fontsize=8, color="#777777")
            yt.append(y0 + n * lane_h / 2)
            yl.append(_label(a, fallback=f"actor {k + 1}") if a else f"actor {k + 1}")
        ax.set_yticks(yt, yl)
        ax.tick_params(axis="y", length=0)
        ax.set_xlabel("time (s)")
        ax.grid(True, axis="x", color="#e3e3e3", lw=0.8, zorder=0)
        ax.set_axisbelow(True)
        if any(s.kind == "blend" for s in spans):
            fig.legend([Patch(color=UPPER_COLOR, alpha=0.8), Patch(color=LOWER_COLOR, alpha=0.8)],
                       ["blend (upper body)", "blend (lower body)"], loc="outside upper right", ncols=2,
                       frameon=False, fontsize=9)
        fig.suptitle(_label(title, fallback="Time table") if title else "Time table", x=0.01, ha="left", fontsize=12,
                     fontweight="bold")
        save_figure(fig, Canvas, path, fmt, dpi)

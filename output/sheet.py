"""Contact sheets: a PNG of stick-figure frames so a person can look at a clip.

Two rows of ``n`` frames spread evenly over the clip (first and last
included): a front view (the viewer stands in front of the character, so
the character's left, +X, is on the image's right) and a side view from
the character's right (it faces right, +Z). Left limbs are blue, right limbs
red, the spine and head black, with a tick on the head where the face
points (so nods and head turns show). Each panel is centred on that frame's root;
the ground is the grey line, with ticks every 50 cm fixed to the world (a
foot that slides moves against them). A foot in contact (as
:func:`core.contacts.detect_contacts` labels it) is marked with a green
dot. Frames inside the ``core`` interval have a bold title. A strip under the
frames plots root and foot heights over the whole clip with the contact
intervals shaded, and the core interval if given. A character far from a
person's size (a 0.2 m rig, a 20 m giant) is drawn at a person's size
(:func:`core.size.at_human_size`), the factor in the strip's label: drawn as it
is it filled a corner of each panel, and its contacts were read by a person's
thresholds. A Japanese title needs a CJK font; without one a romanised
alternative is drawn (:mod:`.fonts`).

matplotlib is an optional extra (``pip install text2anim[plot]``); it is
imported only when a sheet is drawn.
"""
from __future__ import annotations

import io
import os
import warnings

import numpy as np

from ..core import extras

from . import fonts
from text2anim.core.atomic import atomic_write_bytes
from text2anim.core.bodyparts import body_map, side_of
from text2anim.core.contacts import detect_contacts, foot_tracks
from text2anim.core.motion import Motion
from text2anim.core.size import at_human_size


#: matplotlib is not installed (:class:`.extras.MissingExtraError`).
PlotUnavailableError = extras.MissingExtraError


def _matplotlib():
    matplotlib = extras.require("matplotlib", "a contact sheet")
    matplotlib.use("Agg", force=False)
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    return Figure, FigureCanvasAgg


_COLOURS = {"left": "#1f5fbf", "right": "#c62828", None: "#222222"}


def _segments(motion: Motion):
    skel = motion.skeleton
    segs = []
    for j in range(1, skel.n_joints):
        p = int(skel.parents[j])
        side = side_of(skel.names[j])
        segs.append((p, j, _COLOURS[side]))
    return segs


def contact_sheet(motion: Motion, path: str | os.PathLike, title: str = "", n: int = 8,
                  *, core: tuple[float, float] | None = None, dpi: int = 80, alt_title: str | None = None) -> None:
    """Draw ``n`` frames of ``motion`` (front and side views) and a height strip to a PNG at ``path``.

    ``title`` is drawn as given when the installed fonts have all its glyphs (Japanese needs a CJK
    font, :mod:`.fonts`); otherwise ``alt_title`` (a romanised title), else the title without what
    cannot be drawn: never boxes.
    """
    Figure, FigureCanvasAgg = _matplotlib()
    import matplotlib

    with matplotlib.rc_context({"font.family": fonts.families()}), warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Glyph .* missing from")
        shown = fonts.label(title, alt_title, fallback="") if title else ""
        fig = _figure(Figure, FigureCanvasAgg, motion, shown, n, core, dpi)
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight")
    atomic_write_bytes(path, buf.getvalue())


def _strip_label(motion: Motion) -> str:
    """The label under the height strip of ``motion``'s sheet: what the bars are, and the factor the
    character is drawn at when it is far from a person's size (:func:`core.size.at_human_size`)."""
    k = at_human_size(motion)[1]
    return ("seconds (bars: contacts, left above right)"
            + (f"; drawn at a person's size, {k:.3g} times the character's" if k != 1.0 else ""))


#: frames: a longer motion is drawn from its frames at :data:`LONG_FPS` (the sheet shows a dozen poses and a
#: strip a few hundred pixels wide; the kinematics of 80,000 frames at 120 fps took most of 10 s)
LONG_FRAMES = 10_000
LONG_FPS = 30.0


def _figure(Figure, FigureCanvasAgg, motion: Motion, title: str, n: int, core, dpi: int):
    if motion.n_frames > LONG_FRAMES and motion.fps > LONG_FPS:
        motion = motion.resample(LONG_FPS)
    label = _strip_label(motion)
    motion = at_human_size(motion)[0]
    T = motion.n_frames
    if T == 0:
        raise ValueError("cannot draw a contact sheet of an empty motion")
    n = max(1, min(int(n), T))
    frames = np.unique(np.round(np.linspace(0, T - 1, n)).astype(int))
    n = len(frames)
    pos = motion.positions
    ends = motion.end_site_positions()
    contacts = detect_contacts(motion)
    bm = body_map(motion.skeleton)
    segs = _segments(motion)
    end_parents = [j for j, _ in motion.skeleton.end_sites]
    root = motion.root_positions
    head_rot = motion.pose.rotations[:, bm.head]
    head_up = head_rot[:, :, 1]  # the head's local +Y and +Z (face) in world
    head_fwd = head_rot[:, :, 2]

    rel = pos - root[:, None, :]
    ext_x = max(0.6, float(np.abs(rel[frames][..., 0]).max()) + 0.15)
    ext_z = max(0.6, float(np.abs(rel[frames][..., 2]).max()) + 0.15)
    top = max(1.9, float(pos[frames][..., 1].max()) + 0.15)
    bottom = min(-0.1, float(pos[frames][..., 1].min()) - 0.05)

    fig = Figure(figsize=(1.9 * n, 8.2), dpi=dpi)
    FigureCanvasAgg(fig)
    gs = fig.add_gridspec(3, n, height_ratios=[3.2, 3.2, 1.6], hspace=0.25, wspace=0.05)
    fps = motion.fps
    for col, f in enumerate(frames):
        t = f / fps
        in_core = core is not None and core[0] - 1e-9 <= t <= core[1] + 1e-9
        for row, (h, ext) in enumerate(((0, ext_x), (2, ext_z))):
            ax = fig.add_subplot(gs[row, col])
            c0 = root[f, h]
            ax.axhline(0.0, color="#999999", lw=1.0, zorder=0)
            ticks = np.arange(np.floor((c0 - ext) / 0.5) * 0.5, c0 + ext + 0.5, 0.5)
            for tk in ticks:
                ax.plot([tk - c0, tk - c0], [0.0, -0.04], color="#999999", lw=1.0)
            for p, j, colour in segs:
                ax.plot([pos[f, p, h] - c0, pos[f, j, h] - c0], [pos[f, p, 1], pos[f, j, 1]],
                        color=colour, lw=2.0, solid_capstyle="round")
            for k, j in enumerate(end_parents):
                colour = _COLOURS[side_of(motion.skeleton.names[j])]
                ax.plot([pos[f, j, h] - c0, ends[f, k, h] - c0], [pos[f, j, 1], ends[f, k, 1]],
                        color=colour, lw=2.0, solid_capstyle="round")
            centre = pos[f, bm.head] + head_up[f] * 0.08
            ax.plot([centre[h] - c0], [centre[1]], "o", ms=9, mfc="none", mec="#222222")
            nose = centre + head_fwd[f] * 0.11
            ax.plot([centre[h] - c0, nose[h] - c0], [centre[1], nose[1]], color="#222222", lw=1.5)
            for side in ("left", "right"):
                if contacts.of(side)[f]:
                    ankle, toe = bm.feet[side]
                    low = toe if pos[f, toe, 1] <= pos[f, ankle, 1] else ankle
                    ax.plot([pos[f, low, h] - c0], [pos[f, low, 1]], "o", ms=7, color="#2e9d3a", zorder=5)
            ax.set_xlim(-ext, ext)
            ax.set_ylim(bottom, top)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            if row == 0:
                ax.set_title(f"{t:.2f} s" + (" ●" if in_core else ""), fontsize=9,
                             fontweight="bold" if in_core else "normal")
            if col == 0:
                ax.set_ylabel("front" if row == 0 else "side (faces right)", fontsize=9)

    ax = fig.add_subplot(gs[2, :])
    times = motion.times
    tracks = foot_tracks(motion)
    ax.plot(times, root[:, 1], color="#222222", lw=1.2, label="root height")
    for side in ("left", "right"):
        ax.plot(times, tracks[side].height, color=_COLOURS[side], lw=1.2, label=f"{side} foot height")
        for a, b in contacts.intervals(side):
            y0 = -0.06 if side == "left" else -0.12
            ax.plot([times[a], times[b - 1]], [y0, y0], color=_COLOURS[side], lw=4, solid_capstyle="butt")
    if core is not None:
        ax.axvspan(core[0], core[1], color="#f2c94c", alpha=0.25, lw=0, label="core")
    for f in frames:
        ax.axvline(f / fps, color="#cccccc", lw=0.6, zorder=0)
    ax.set_xlim(0, max(times[-1], 1e-3))
    ax.set_ylim(-0.16, max(1.2, float(root[:, 1].max()) + 0.1))
    ax.set_xlabel(label, fontsize=8)
    ax.tick_params(labelsize=7)
    ax.legend(fontsize=7, loc="upper right", ncol=4)
    if title:
        fig.suptitle(title, fontsize=12)
    return fig

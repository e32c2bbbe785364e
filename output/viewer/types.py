"""What the outputs a person looks at (viewer page, GLB, plots) are given.

- :class:`Track`: one actor's animation, a named :class:`~core.motion.Motion`;
- :class:`Span`: an interval on an actor's timeline, either a time-table
  element (``kind="element"``, label like ``"2 蹴る (transition)"``) or a blend
  interval (``kind="blend"``, ``part`` ``"upper"``, ``"lower"`` or ``None`` for
  the whole body);
- :class:`Prop`: a thing of the scene (a ball, a chair, a cup) as a simple shape moving
  over the same frames.

Times are seconds from the start of the animation, the same clock for every actor.
"""
from __future__ import annotations

import math
import re
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from text2anim.core.motion import Motion, unroll_quaternions

SPAN_KINDS = ("element", "blend")

#: The shapes a :class:`Prop` is drawn as. Each is centred on its bounding box, ``size`` (w, h, d) metres
#: along its own x, y, z; a ``chair`` (seat, four legs, a back) faces +z (its back at -z), as does a
#: ``bench`` (seat and legs, no back); a ``door`` is a thin panel in its x-y plane.
PROP_SHAPES = ("sphere", "box", "cylinder", "chair", "bench", "door", "book", "cup", "stick")

#: Body-part names (``core.bodyparts.GROUPS``) drawn in the lower-body lane of a blend;
#: every other named part (arms, head, torso, "upper") in the upper lane; ``None``: both.
LOWER_PARTS = frozenset({"lower", "right_leg", "left_leg", "legs", "hips"})


@dataclass(frozen=True)
class Track:
    """One actor: its name (shown in the viewer, the GLB's node names) and its motion."""

    name: str
    motion: Motion

    def __post_init__(self):
        if not isinstance(self.name, str):
            raise TypeError(f"track name must be a string, got {type(self.name).__name__}")
        if not isinstance(self.motion, Motion):
            raise TypeError(f"track {self.name!r}: expected a Motion, got {type(self.motion).__name__}")
        if self.motion.n_frames == 0:
            raise ValueError(f"track {self.name!r}: the motion has no frames")


@dataclass(frozen=True)
class Span:
    """An interval of an actor's timeline.

    Attributes:
        actor: the :attr:`Track.name` it belongs to.
        label: text shown on the bar (Japanese is fine in the viewer).
        start, end: seconds, ``start <= end``.
        kind: ``"element"`` (a time-table element) or ``"blend"`` (a blend interval).
        part: for blends, the body part blended: ``"upper"``, ``"lower"`` (or a
            body-part group name) or ``None`` for the whole body.
        alt: optional ASCII label (e.g. the clip name ``"kick_ball"``) used where
            Japanese cannot be drawn (plots on a machine without a CJK font).
    """

    actor: str
    label: str
    start: float
    end: float
    kind: str = "element"
    part: str | None = None
    alt: str | None = None

    def __post_init__(self):
        if self.kind not in SPAN_KINDS:
            raise ValueError(f"span kind must be one of {SPAN_KINDS}, got {self.kind!r}")
        start, end = float(self.start), float(self.end)
        if not (math.isfinite(start) and math.isfinite(end)):
            raise ValueError(f"span {self.label!r}: times must be finite, got {start}..{end}")
        if end < start:
            raise ValueError(f"span {self.label!r}: end {end} is before start {start}")
        object.__setattr__(self, "start", start)
        object.__setattr__(self, "end", end)

    @property
    def lane(self) -> str:
        """``"upper"``, ``"lower"`` or ``"both"``: where a blend is drawn."""
        if self.part is None or self.part in ("whole", "full", "all"):
            return "both"
        return "lower" if self.part in LOWER_PARTS else "upper"


def as_tracks(tracks) -> list[Track]:
    """Accept a list of :class:`Track`, one :class:`Motion`, or a ``{name: Motion}`` mapping."""
    if isinstance(tracks, Motion):
        tracks = [Track("", tracks)]
    elif isinstance(tracks, Track):
        tracks = [tracks]
    elif isinstance(tracks, dict):
        tracks = [Track(str(k), v) for k, v in tracks.items()]
    out = list(tracks)
    if not out:
        raise ValueError("no tracks to show")
    for t in out:
        if not isinstance(t, Track):
            raise TypeError(f"expected Track objects, got {type(t).__name__}")
    names = [t.name for t in out]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ValueError(f"two tracks share the name {dup[0]!r}")
    return out


def as_spans(spans: Iterable[Span]) -> list[Span]:
    out = list(spans or ())
    for s in out:
        if not isinstance(s, Span):
            raise TypeError(f"expected Span objects, got {type(s).__name__}")
    return out


@dataclass(frozen=True, eq=False)
class Prop:
    """A thing of the scene: its name as the text writes it (ボール), a simple shape, and where it is.

    Attributes:
        name: the noun as written; the GLB node's name and the viewer's label.
        shape: one of :data:`PROP_SHAPES`.
        size: ``(w, h, d)`` metres, the shape's bounding box (a sphere of diameter 0.22: ``(0.22,) * 3``).
        positions: ``(T, 3)`` metres, Y up: the bounding box's centre at each frame.
        rotations: ``(T, 4)`` quaternions ``(x, y, z, w)`` as scipy writes them: the shape's turn at each frame.
        fps: frames per second, the actors' own (frame ``i`` is at ``i / fps`` s).
        color: ``#rrggbb``.
    """

    name: str
    shape: str
    size: tuple[float, float, float]
    positions: np.ndarray
    rotations: np.ndarray
    fps: float
    color: str = "#c8b27a"

    def __post_init__(self):
        if self.shape not in PROP_SHAPES:
            raise ValueError(f"prop {self.name!r}: unknown shape {self.shape!r}; one of {', '.join(PROP_SHAPES)}")
        pos = np.asarray(self.positions, dtype=float)
        rot = np.asarray(self.rotations, dtype=float)
        if pos.ndim != 2 or pos.shape[1] != 3 or len(pos) == 0:
            raise ValueError(f"prop {self.name!r}: positions must be (T, 3), got {pos.shape}")
        if rot.shape != (len(pos), 4):
            raise ValueError(f"prop {self.name!r}: rotations must be ({len(pos)}, 4), got {rot.shape}")
        if not (np.all(np.isfinite(pos)) and np.all(np.isfinite(rot))):
            raise ValueError(f"prop {self.name!r}: non-finite positions or rotations")
        if np.any(np.linalg.norm(rot, axis=1) < 1e-6):
            raise ValueError(f"prop {self.name!r}: a rotation is not a quaternion (length 0)")
        size = tuple(float(v) for v in self.size)
        if len(size) != 3 or not all(math.isfinite(v) and v > 0 for v in size):
            raise ValueError(f"prop {self.name!r}: size must be three positive lengths (w, h, d), got {self.size}")
        if not (math.isfinite(float(self.fps)) and self.fps > 0):
            raise ValueError(f"prop {self.name!r}: fps must be positive, got {self.fps}")
        if not re.fullmatch(r"#[0-9a-fA-F]{6}", str(self.color)):
            raise ValueError(f"prop {self.name!r}: colour must be #rrggbb, got {self.color!r}")
        object.__setattr__(self, "positions", pos)
        object.__setattr__(self, "rotations", rot)
        object.__setattr__(self, "size", size)

    @property
    def n_frames(self) -> int:
        return len(self.positions)

    @property
    def unit_rotations(self) -> np.ndarray:
        """``(T, 4)`` the rotations as unit quaternions, signs made continuous (interpolation takes the short way)."""
        return unroll_quaternions(self.rotations / np.linalg.norm(self.rotations, axis=1, keepdims=True))

    def scaled(self, k: float) -> "Prop":
        """The prop in a world scaled by ``k`` about the origin (the scene of a character of another size)."""
        w, h, d = self.size
        return Prop(self.name, self.shape, (w * k, h * k, d * k), self.positions * k, self.rotations, self.fps,
                    self.color)

    @property
    def is_static(self) -> bool:
        """True when the prop stays where it is, turned as it is, on every frame."""
        pos, rot = self.positions, self.unit_rotations
        return bool(np.all(np.abs(pos - pos[0]) < 1e-9) and np.all(np.abs(rot - rot[0]) < 1e-9))


def as_props(props: Iterable[Prop] | None) -> list[Prop]:
    """A list of :class:`Prop` (``None`` or empty: none)."""
    out = list(props or ())
    for p in out:
        if not isinstance(p, Prop):
            raise TypeError(f"expected Prop objects, got {type(p).__name__}")
    return out

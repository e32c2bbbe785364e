"""The built-in library's motion-capture clips: the cut list and the shipped arrays.

``capture.toml`` (next to this file) is the cut list: for every clip the CMU
file, the seconds cut from it, the core interval, the verbs and postures (its
format is described at its top). ``capture.npz`` holds what
``tools/library/build_capture.py`` made of it: per clip the root positions ``<name>.root``
``(T, 3)`` float32 metres and the local joint rotations ``<name>.rot``
``(T, J, 4)`` float32 quaternions ``(x, y, z, w)`` on
:func:`.skeleton.canonical_skeleton`, at :data:`FPS`, feet on ``y = 0``,
facing +Z at the first frame (or travelling along +Z), and ``<name>.source_gmd`` ``(1,)``
GMD's skating ratio of the cut as captured (:func:`source_skating`).

Loading is a ``numpy.load`` and a renormalisation: no generation at first use.
The data is CMU's (http://mocap.cs.cmu.edu); see the package README.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from text2anim.core.bodyparts import GROUPS, BodyPart
from text2anim.core.motion import Motion
from text2anim.motiondb.types import ClipRecord

from .keyframes import POSTURE_OF, ClipDataError
from .skeleton import canonical_skeleton

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib  # type: ignore[import-not-found]

CUT_LIST = Path(__file__).with_name("capture.toml")
ARRAYS = Path(__file__).with_name("capture.npz")
#: Frame rate of the shipped arrays.
FPS = 30.0


@dataclass(frozen=True)
class Cut:
    """One clip of the cut list (seconds are on the take's clock, 0 = first captured frame)."""

    name: str
    file: str
    cut: tuple[float, float]
    core: tuple[float, float] | None  # None: the whole clip
    verbs: tuple[str, ...]
    objects: tuple[str, ...] = ()
    body_part: BodyPart | None = None
    cyclic: bool = False
    starts: str = "stand"
    ends: str = "stand"
    replaces: str | None = None
    loop: str | None = None
    blend: float = 0.0
    face: str = "start"
    starts_from: str | None = None
    ease: float = 0.0
    lowpass: float = 0.0  # Hz; 0: none (see tools/library/smooth.py)
    about: str = ""
    cycle: tuple[float, float] | None = None  # a stretch of the cut played ``cycles`` more times
    cycles: int = 0
    folder: str = "cmu"  # the shared capture folder the file is in (../shared/mocap/FOLDER): cmu, cmu_everyday
    mime: bool = False  # a climb played on the flat: the height the feet climb taken out of the hips (README)

    @property
    def extra(self) -> float:
        """Seconds the repeated ``cycle`` adds to the cut."""
        return self.cycles * (self.cycle[1] - self.cycle[0]) if self.cycle else 0.0

    @property
    def trial(self) -> str:
        """The CMU subject and trial, ``16_15``."""
        return "_".join(self.file.split("_")[:2]).removesuffix(".bvh")

    @property
    def source(self) -> str:
        """The database's ``source`` of the clip: built-in, captured, and where from."""
        return f"builtin:capture:CMU {self.trial} {self.cut[0]:.2f}-{self.cut[1]:.2f}s"


def _cut(raw: dict) -> Cut:
    name = raw.get("name", "?")
    try:
        t0, t1 = (float(x) for x in raw["cut"])
        core = raw.get("core", "all")
        core = None if core == "all" else (float(core[0]), float(core[1]))
        cut = Cut(name=name, file=str(raw["file"]), cut=(t0, t1), core=core, verbs=tuple(raw["verbs"]),
                  objects=tuple(raw.get("objects", ())), body_part=raw.get("body_part"),
                  cyclic=bool(raw.get("cyclic", False)), starts=raw.get("starts", "stand"),
                  ends=raw.get("ends", "stand"), replaces=raw.get("replaces"), loop=raw.get("loop"),
                  blend=float(raw.get("blend", 0.0)), face=raw.get("face", "start"),
                  starts_from=raw.get("starts_from"), ease=float(raw.get("ease", 0.0)),
                  lowpass=float(raw.get("lowpass", 0.0)), about=raw.get("about", ""),
                  cycle=tuple(float(x) for x in raw["cycle"]) if "cycle" in raw else None,  # type: ignore[arg-type]
                  cycles=int(raw.get("cycles", 0)), folder=str(raw.get("folder", "cmu")),
                  mime=bool(raw.get("mime", False)))
    except (KeyError, TypeError, ValueError) as exc:
        raise ClipDataError(f"capture.toml: clip {name}: {exc}") from None
    if not 0 <= t0 < t1:
        raise ClipDataError(f"capture.toml: clip {name}: cut {t0}-{t1} is empty")
    if core is not None and not t0 <= core[0] < core[1] <= t1 + 1e-9:
        raise ClipDataError(f"capture.toml: clip {name}: core {core} is not inside the cut {t0}-{t1}")
    if cut.body_part is not None and cut.body_part not in GROUPS:
        raise ClipDataError(f"capture.toml: clip {name}: unknown body part {cut.body_part!r}")
    for word in (cut.starts, cut.ends):
        if word not in POSTURE_OF:
            raise ClipDataError(f"capture.toml: clip {name}: unknown posture {word!r}")
    if cut.face not in ("start", "travel") or cut.loop not in (None, "blend", "stride", "spot"):
        raise ClipDataError(f"capture.toml: clip {name}: face must be start|travel, loop blend|stride|spot or absent")
    if cut.cycle is not None and not (len(cut.cycle) == 2 and t0 < cut.cycle[0] < cut.cycle[1] < t1
                                      and cut.cycles > 0 and cut.blend > 0 and not cut.loop):
        raise ClipDataError(f"capture.toml: clip {name}: a cycle must lie inside the cut, with cycles > 0, "
                            "blend > 0 seconds and no loop")
    if not 0 <= cut.lowpass < 60:
        raise ClipDataError(f"capture.toml: clip {name}: lowpass must be 0 (none) or a cut-off below 60 Hz")
    if cut.loop and not (cut.cyclic and cut.blend > 0):
        raise ClipDataError(f"capture.toml: clip {name}: a loop needs cyclic = true and blend > 0 seconds")
    return cut


@lru_cache(maxsize=1)
def cut_list(path: Path = CUT_LIST) -> tuple[Cut, ...]:
    """The clips of ``capture.toml``, in file order (names unique)."""
    with open(path, "rb") as f:
        cuts = tuple(_cut(raw) for raw in tomllib.load(f).get("clip", []))
    names = [c.name for c in cuts]
    if len(set(names)) != len(names):
        raise ClipDataError("capture.toml: two clips share a name")
    for i, c in enumerate(cuts):
        if c.starts_from is not None and (c.starts_from not in names[:i] or not c.ease > 0):
            raise ClipDataError(f"capture.toml: clip {c.name}: starts_from must name an earlier clip, "
                                "with ease > 0 seconds")
    return cuts


def _motion(root: np.ndarray, rot: np.ndarray, fps: float) -> Motion:
    q = rot.astype(np.float64)
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    return Motion(canonical_skeleton(), FPS, root.astype(np.float64), q).resample(fps)


@lru_cache(maxsize=4)
def captured_clip(name: str, fps: float = FPS) -> Motion:
    """One captured clip's motion at ``fps`` (read-only, cached), read alone from the arrays: what a stage
    needs when it wants a clip of the built-in character without the whole library (the idle, for one)."""
    with np.load(ARRAYS) as data:
        if f"{name}.rot" not in data.files:
            raise ClipDataError(f"capture.npz has no clip {name!r}: rebuild it "
                                "(python tools/library/build_capture.py)")
        return _motion(data[f"{name}.root"], data[f"{name}.rot"], float(fps))


@lru_cache(maxsize=1)
def source_skating() -> dict[str, float]:
    """``{clip: GMD's skating ratio of its cut as captured}`` (30 fps, above the cut's own lowest foot
    point), as the build measured it: what a captured clip is held to when the capture itself is over
    :data:`core.metrics.CAPTURE_GMD_LIMIT` (a walking turn of subject 16 on feet that barely lift)."""
    with np.load(ARRAYS) as data:
        return {k.removesuffix(".source_gmd"): float(data[k][0]) for k in data.files if k.endswith(".source_gmd")}


@lru_cache(maxsize=8)
def capture_records(fps: float = FPS) -> tuple[ClipRecord, ...]:
    """The captured clips as :class:`ClipRecord` s at ``fps`` (read-only motions, cached)."""
    cuts = cut_list()
    with np.load(ARRAYS) as data:
        arrays = {k: data[k] for k in data.files}
    out = []
    for c in cuts:
        if f"{c.name}.rot" not in arrays:
            raise ClipDataError(f"capture.npz has no clip {c.name!r}: rebuild it "
                                "(python tools/library/build_capture.py)")
        motion = _motion(arrays[f"{c.name}.root"], arrays[f"{c.name}.rot"], float(fps))
        if c.core is None:
            core = (0.0, motion.duration)
        else:
            extra = c.extra if c.cycle and c.core[1] > c.cycle[0] else 0.0  # the repeated cycle lengthens the core
            core = (round(c.core[0] - c.cut[0], 6), min(round(c.core[1] - c.cut[0] + extra, 6), motion.duration))
        out.append(ClipRecord(name=c.name, motion=motion, verbs=c.verbs, objects=c.objects, character="default",
                              core=core, body_part=c.body_part, cyclic=c.cyclic, source=c.source,
                              start_posture=POSTURE_OF[c.starts], end_posture=POSTURE_OF[c.ends]))
    return tuple(out)


def replaced() -> frozenset[str]:
    """Names of the keyframed clips that a captured clip stands in for."""
    return frozenset(c.replaces for c in cut_list() if c.replaces)

"""Validating a clip record and computing what storing it needs (blob, fingerprint, contacts, postures)."""
from __future__ import annotations

import hashlib
import math
import re
from dataclasses import dataclass, field, replace

import numpy as np

from text2anim.core.bodyparts import GROUPS, BodyMapError, BodyPart
from text2anim.core.contacts import detect_contacts
from text2anim.core.inputs import control_in, printable
from text2anim.core.motion import Motion
from text2anim.core.skeleton import Skeleton
from text2anim.core.styles import STYLES

from .blobs import encode_frames, skeleton_json
from .description import describe
from .errors import ClipValidationError
from .postures import classify_posture
from .readings import normalize
from .types import DEFAULT_POSTURE, POSTURES, ClipDescription, ClipRecord, Posture

#: Longest clip or character name, characters.
MAX_NAME = 200
#: Longest verb or object, characters.
MAX_WORD = 100


@dataclass
class PreparedClip:
    """A validated record with everything computed that the insert needs."""

    name: str
    verbs: tuple[str, ...]
    objects: tuple[str, ...]
    character: str
    skeleton: Skeleton
    skeleton_def: str
    fingerprint: str
    fps: float
    frames: int
    duration: float
    core: tuple[float, float]
    body_part: BodyPart | None
    cyclic: bool
    source: str
    blob: bytes
    start_posture: Posture = DEFAULT_POSTURE
    end_posture: Posture = DEFAULT_POSTURE
    contacts: list[tuple[str, int, int]] = field(default_factory=list)
    description: ClipDescription = ClipDescription()
    style: str | None = None


def _words(values, what: str, where: str, *, required: bool) -> tuple[str, ...]:
    if isinstance(values, str):
        values = (values,)
    out: list[str] = []
    for v in values or ():
        if not isinstance(v, str):
            raise ClipValidationError(f"{where}: {what} must be text, got {v!r}")
        w = normalize(v)
        if not w:
            raise ClipValidationError(f"{where}: empty {what}")
        if len(w) > MAX_WORD:
            raise ClipValidationError(f"{where}: {what} {w[:20]!r}… is longer than {MAX_WORD} characters")
        _refuse_controls(w, what, where)
        if w not in out:
            out.append(w)
    if required and not out:
        raise ClipValidationError(f"{where}: a clip needs at least one verb")
    return tuple(out)


def _actions(values, where: str) -> tuple[str, ...]:
    """A record's actions: WordNet verb synset offsets, 8 digits each (``"01908923"``)."""
    out = tuple(str(v) for v in values or ())
    bad = [v for v in out if not re.fullmatch(r"[0-9]{8}", v)]
    if bad:
        raise ClipValidationError(f"{where}: an action must be a WordNet verb synset offset of 8 digits, "
                                  f"not {printable(bad[0][:20])!r}")
    return tuple(dict.fromkeys(out))


def _check_name(name, what: str, where: str) -> str:
    if not isinstance(name, str) or not normalize(name):
        raise ClipValidationError(f"{where}: the {what} name is empty")
    n = normalize(name)
    if len(n) > MAX_NAME:
        raise ClipValidationError(f"{where}: bad {what} name {n[:40]!r} (at most {MAX_NAME} printable characters)")
    _refuse_controls(n, f"{what} name", where)
    return n


def _refuse_controls(word: str, what: str, where: str) -> None:
    """A control or text-direction character would reach every terminal that lists the database."""
    ch = control_in(word)
    if ch is not None:
        raise ClipValidationError(f"{where}: the {what} '{printable(word[:40])}' holds the control character "
                                  f"U+{ord(ch):04X}; remove it")


def prepare_record(rec: ClipRecord, where: str | None = None, *,
                   contacts: list[tuple[str, int, int]] | None = None,
                   measured: ClipDescription | None = None) -> PreparedClip:
    """Validate a record and compute its blob, skeleton fingerprint, foot contacts and description.

    ``contacts`` (``(side, start, stop)`` frames) are the record's foot contacts, and ``measured``
    its description without actions, when already known (the built-in library ships them):
    they are not computed again.
    Raises :class:`ClipValidationError` naming ``where`` (a file) or the clip.
    """
    where = where or f"clip {getattr(rec, 'name', '?')!r}"
    name = _check_name(rec.name, "clip", where)
    character = _check_name(rec.character, "character", where)
    verbs = _words(rec.verbs, "verb", where, required=True)
    objects = _words(rec.objects, "object", where, required=False)
    m = rec.motion
    if not isinstance(m, Motion):
        raise ClipValidationError(f"{where}: motion must be a synthesis.Motion, got {type(m).__name__}")
    if m.n_frames < 1:
        raise ClipValidationError(f"{where}: the motion has no frames")
    if not math.isfinite(m.fps):
        raise ClipValidationError(f"{where}: fps must be finite, got {m.fps}")
    arrays = [m.root_positions, m.rotations] + ([] if m.translations is None else [m.translations])
    if not all(np.all(np.isfinite(a)) for a in arrays):
        raise ClipValidationError(f"{where}: the motion has non-finite values")
    norms = np.linalg.norm(m.rotations, axis=-1)
    if np.any(np.abs(norms - 1.0) > 1e-3):
        raise ClipValidationError(
            f"{where}: rotations are not unit quaternions (norm {norms.min():.3g}..{norms.max():.3g})")
    duration = m.n_frames / m.fps
    if rec.core is None:
        core = (0.0, duration)
    else:
        try:
            b, e = (float(x) for x in rec.core)
        except (TypeError, ValueError):
            raise ClipValidationError(f"{where}: core must be (begin, end) seconds, got {rec.core!r}") from None
        # up to one frame past the end is rounding (a core given in seconds on a frame grid): clamped
        slack = 1.0 / m.fps + 1e-9
        if not (math.isfinite(b) and math.isfinite(e) and 0 <= b < e <= duration + slack and b < duration):
            raise ClipValidationError(
                f"{where}: core {b:g}..{e:g} s must satisfy 0 <= begin < end <= duration ({duration:.3f} s)")
        core = (b, min(e, duration))
    if rec.body_part is not None and rec.body_part not in GROUPS:
        raise ClipValidationError(f"{where}: unknown body part {rec.body_part!r}; known: {', '.join(GROUPS)}")
    if contacts is None:
        try:
            fc = detect_contacts(m)
        except BodyMapError as exc:
            raise ClipValidationError(f"{where}: cannot compute foot contacts: {exc}") from None
        contacts = [(side, a, b) for side in ("left", "right") for a, b in fc.intervals(side)]
    elif not all(side in ("left", "right") and 0 <= a < b <= m.n_frames for side, a, b in contacts):
        raise ClipValidationError(f"{where}: foot contacts outside the clip's {m.n_frames} frames")
    postures = []
    for what, declared, frame in (("start", rec.start_posture, 0), ("end", rec.end_posture, -1)):
        if declared is None:
            postures.append(classify_posture(m, frame))
        elif declared not in POSTURES:
            raise ClipValidationError(f"{where}: unknown {what} posture {declared!r}; known: {', '.join(POSTURES)}")
        else:
            postures.append(declared)
    actions = _actions(rec.actions, where)
    if rec.style is not None and rec.style not in STYLES:
        raise ClipValidationError(f"{where}: unknown style {printable(str(rec.style)[:20])!r}; known: {', '.join(STYLES)}")
    definition = skeleton_json(m.skeleton)
    return PreparedClip(
        name=name, verbs=verbs, objects=objects, character=character, skeleton=m.skeleton,
        skeleton_def=definition, fingerprint=hashlib.sha256(definition.encode("utf-8")).hexdigest(),
        fps=float(m.fps), frames=int(m.n_frames), duration=float(duration), core=core,
        body_part=rec.body_part, cyclic=bool(rec.cyclic), source=str(rec.source or ""),
        blob=encode_frames(m), start_posture=postures[0], end_posture=postures[1], contacts=contacts,
        description=(describe(m, core, actions) if measured is None else replace(measured, actions=actions)),
        style=rec.style,
    )

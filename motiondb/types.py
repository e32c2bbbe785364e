"""What goes into and comes out of the motion database (frozen records), and the posture vocabulary."""
from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime
from typing import TYPE_CHECKING, Any, Literal, get_args

from text2anim.core.bodyparts import BodyPart

if TYPE_CHECKING:  # only named: reading clip metadata (`text2anim plan`) loads no numpy
    from text2anim.core.motion import Motion

#: The postures a clip starts and ends in (``ClipRecord.start_posture``/``end_posture``):
#:
#: - ``standing``: on the feet (whatever the arms and trunk do: bending to pick something up,
#:   holding a box, a punch are all standing);
#: - ``seated``: the hips resting on something: a chair-height seat (the built-in ``sit_down``
#:   ends on a 0.45 m seat) or the floor; the weight is not over the feet;
#: - ``crouched``: squatting on the feet, hips low and over the feet, no seat;
#: - ``kneeling``: on one or both knees (also on hands and knees), hips above the knees;
#: - ``lying``: the trunk on the floor, face down or up (``fall`` ends lying face down).
#:
#: The built-in library declares them per clip; imported clips are classified from their
#: first and last frames (:func:`motiondb.postures.classify_posture`) unless the importer says.
Posture = Literal["standing", "seated", "crouched", "kneeling", "lying"]
POSTURES: tuple[Posture, ...] = get_args(Posture)

#: The posture of a clip that declares none and cannot be classified (and of clips stored
#: before postures existed, until they are classified).
DEFAULT_POSTURE: Posture = "standing"


@dataclass(frozen=True)
class ClipDescription:
    """What the body does in a clip (stored with it; :mod:`motiondb.description` measures it).

    Attributes:
        actions: WordNet 3.1 verb synsets (8-digit offsets, ``"01908923"`` is walk) naming what
            the body does; what makes the clip a stand-in for a verb it does not list
            (``api/fallback.py``). Empty: the clip stands in for nothing.
        locomotion: the hips travel (more than ``description.LOCOMOTION`` leg lengths per second).
        moving: the parts that move relative to the hips, among ``head``, ``arms``, ``legs``, ``trunk``.
        energy: mean speed of hands, feet and head relative to the hips, leg lengths per second.
    """

    actions: tuple[str, ...] = ()
    locomotion: bool = False
    moving: tuple[str, ...] = ()
    energy: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        return {"actions": list(self.actions), "locomotion": self.locomotion, "moving": list(self.moving),
                "energy": self.energy}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> "ClipDescription":
        return cls(actions=tuple(d.get("actions", ())), locomotion=bool(d.get("locomotion", False)),
                   moving=tuple(d.get("moving", ())), energy=float(d.get("energy", 0.0)))


@dataclass(frozen=True, eq=False)
class ClipRecord:
    """A clip to store: the motion and its metadata.

    Attributes:
        name: unique clip name (``walk``, ``kick_ball``).
        motion: the frames (metres, Y up, the character's skeleton).
        verbs: verb lemmas that retrieve this clip; the first is the primary
            one, the others synonyms (``("蹴る", "キックする", "シュートする")``).
        objects: object nouns the action is about (``("ボール",)``).
        character: name of the character (and so the skeleton) it belongs to.
        core: ``(begin, end)`` seconds: the part that must be kept (コア区間).
        body_part: the group a partial action is declared for (``right_arm``), ``None`` for whole-body.
        cyclic: the clip loops (locomotion); its last frame flows into its first.
        source: where it came from (``builtin``, a file path).
        start_posture, end_posture: the posture (one of :data:`POSTURES`) of the
            first and of the last frame; ``None``: classified from those frames
            when the clip is stored (:func:`motiondb.postures.classify_posture`).
        actions: what the body does, as WordNet verb synsets (:class:`ClipDescription`); the
            rest of the clip's description is measured from its frames when it is stored.
        style: the style it was performed in (:data:`core.styles.STYLES`: ``sad``), ``None`` for neutral.
    """

    name: str
    motion: Motion
    verbs: tuple[str, ...]
    objects: tuple[str, ...] = ()
    character: str = "default"
    core: tuple[float, float] | None = None
    body_part: BodyPart | None = None
    cyclic: bool = False
    source: str = ""
    start_posture: Posture | None = None
    end_posture: Posture | None = None
    actions: tuple[str, ...] = ()
    style: str | None = None


@dataclass(frozen=True)
class ClipInfo:
    """A stored clip's metadata, without its frames (``MotionDB.load`` reads those).

    Attributes:
        name: unique clip name.
        character: the character it belongs to.
        verbs: its verbs, primary first, then synonyms.
        objects: object nouns it declares (may be empty).
        fps: frames per second.
        frames: frame count.
        duration: seconds (``frames / fps``).
        core: ``(begin, end)`` seconds, the interval that must be kept.
        body_part: group a partial action is declared for, ``None`` for whole body.
        cyclic: the clip loops.
        source: ``builtin`` or the imported file's path.
        created: when it was stored (UTC).
        joints: joint count of its skeleton.
        left_contacts, right_contacts: foot-contact intervals ``[start, stop)`` in frames.
        start_posture, end_posture: the posture of its first and of its last frame
            (:data:`motiondb.types.POSTURES`: ``standing``, ``seated``, ``crouched``,
            ``kneeling``, ``lying``).
        description: what the body does (:class:`ClipDescription`).
        style: the style it was performed in (:data:`core.styles.STYLES`), ``None`` for a neutral clip.
    """

    name: str
    character: str
    verbs: tuple[str, ...]
    objects: tuple[str, ...]
    fps: float
    frames: int
    duration: float
    core: tuple[float, float]
    body_part: BodyPart | None
    cyclic: bool
    source: str
    created: datetime
    joints: int
    left_contacts: tuple[tuple[int, int], ...] = ()
    right_contacts: tuple[tuple[int, int], ...] = ()
    start_posture: Posture = DEFAULT_POSTURE
    end_posture: Posture = DEFAULT_POSTURE
    description: ClipDescription = ClipDescription()
    style: str | None = None

    @property
    def verb(self) -> str:
        """The primary verb."""
        return self.verbs[0]

    def contacts(self, side: str) -> tuple[tuple[int, int], ...]:
        """Contact intervals of the ``left`` or ``right`` foot, ``[start, stop)`` frames."""
        if side not in ("left", "right"):
            raise ValueError(f"side must be 'left' or 'right', not {side!r}")
        return self.left_contacts if side == "left" else self.right_contacts

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (lists for tuples, ISO 8601 time)."""
        return {
            "name": self.name, "character": self.character, "verbs": list(self.verbs),
            "objects": list(self.objects), "fps": self.fps, "frames": self.frames,
            "duration": self.duration, "core": list(self.core), "body_part": self.body_part,
            "cyclic": self.cyclic, "source": self.source, "created": self.created.isoformat(),
            "joints": self.joints, "start_posture": self.start_posture, "end_posture": self.end_posture,
            "description": self.description.to_dict(), "style": self.style,
            "contacts": {"left": [list(c) for c in self.left_contacts],
                         "right": [list(c) for c in self.right_contacts]},
        }


@dataclass(frozen=True)
class VerbInfo:
    """A verb the database knows: ``clips`` clips use it, ``primary`` of them as their primary verb."""

    lemma: str
    reading: str
    clips: int
    primary: int

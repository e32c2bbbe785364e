"""What goes into and comes out of the motion database (frozen records), and the posture vocabulary."""
from __future__ import annotations

from dataclasses import dataclass

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
#: first and last frames (:func:`motiondb.store.classify_posture`) unless the importer says.
POSTURES = ("standing", "seated", "crouched", "kneeling", "lying")

#: The posture of a clip that declares none and cannot be classified (and of clips stored
#: before postures existed, until they are classified).
DEFAULT_POSTURE = "standing"


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
            when the clip is stored (:func:`motiondb.store.classify_posture`).
    """

    name: str
    motion: Motion
    verbs: tuple[str, ...]
    objects: tuple[str, ...] = ()
    character: str = "default"
    core: tuple[float, float] | None = None
    body_part: str | None = None
    cyclic: bool = False
    source: str = ""
    start_posture: str | None = None
    end_posture: str | None = None

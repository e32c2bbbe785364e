"""What goes into and comes out of the motion database (frozen records)."""
from __future__ import annotations

from dataclasses import dataclass

from synthesis.motion import Motion


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

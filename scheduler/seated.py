"""A posture carries on until the text changes it: which motions of a sequence play seated or kneeling.

Most clips are captured or keyframed standing (``read``, ``drink``, ``pray``). After 座る, a
following action that does not need the legs is still done on the chair: 椅子に座って本を
読む reads seated. And a later 立ち上がる says the actions before it were done seated:
コーヒーを飲んで立ち上がる drinks seated, then stands up (no sitting down first). Kneeling
carries on alike: 膝をついて、祈る。そして立ち上がる prays on one knee and rises from it; so does a
crouch: しゃがんで、花を見た。それから立ち上がった looks at the flower crouched (``wait_crouched``).

- :func:`plays_in` tells an action that can be played seated or kneeling from its clip's
  metadata: a clip of the action that starts and ends in that posture, or a standing clip
  whose feet stay on the ground from first frame to last (no foot-moving interval:
  reading, drinking, waving, clapping, praying; not walking, jumping, crouching) and that
  keeps its posture.
- :func:`seated_motions` reads one actor's sequence (the clips :func:`postures.choose`
  picked) and says which motions play seated or kneeling, and whether the actor starts seated.

:func:`arrangement.arrange` plays each of them as its upper body composed onto the idle of
that posture (the clip of :data:`fillers.IDLE_VERB` that keeps it, :func:`postures.matching`:
``wait_seated``, ``wait_kneeling``, ``wait_crouched``), as ながら composes, instead of a bridge that stands up.
Only clip metadata is read.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from .clips import ClipMeta, foot_moving

SEATED = "seated"
KNEELING = "kneeling"
CROUCHED = "crouched"
#: The postures an action that does not need the legs is played in when the actor is already there.
KEPT = (SEATED, KNEELING, CROUCHED)


def plays_in(clip: ClipMeta, posture: str) -> bool:
    """Whether the action of ``clip`` can be played by someone in ``posture`` (one of :data:`KEPT`).

    True for a clip that starts and ends in ``posture``, and for a standing clip that keeps
    its posture with both feet on the ground throughout (its upper body is composed
    onto a seated or kneeling body); False for everything that moves the feet or changes posture.
    """
    if clip.start_posture == clip.end_posture == posture:
        return True
    return clip.start_posture == clip.end_posture == "standing" and not clip.cyclic and not foot_moving(clip)


@dataclass(frozen=True)
class SeatedPlan:
    """What :func:`seated_motions` decided for one sequence.

    Attributes:
        starts_seated: the actor is seated before its first motion (a later
            motion starts seated and nothing before it needs the legs).
        composed: the standing clips played seated or kneeling (their upper body on
            that posture's idle), as ``(motion id, posture)``, in playing order.
    """

    starts_seated: bool
    composed: tuple[tuple[int, str], ...]


def seated_motions(ids: Sequence[int], clips: Mapping[int, ClipMeta],
                   composing: frozenset[int] = frozenset()) -> SeatedPlan:
    """Which motions of one actor's sequence play seated or kneeling.

    Args:
        ids: the sequence's motion ids in playing order.
        clips: id -> its chosen clip.
        composing: ids that take part in a composition of the text (ながら, たまま):
            they are left as they are.

    Rules, along the sequence with the posture the actor is in:

    1. the actor starts seated when the first clip that changes posture starts
       seated (立ち上がる), it is not the first motion, and every motion before it
       :func:`plays_in` seated (none is in ``composing``);
    2. while the actor is seated or kneeling (:data:`KEPT`), a standing clip that
       :func:`plays_in` that posture (and is not in ``composing``) is played in it
       and the actor stays there; any other clip sets the posture to the one it ends in.
    """
    first_change = next((k for k, i in enumerate(ids) if clips[i].start_posture != clips[i].end_posture), None)
    starts = (first_change is not None and first_change > 0 and clips[ids[first_change]].start_posture == SEATED
              and all(plays_in(clips[i], SEATED) and i not in composing for i in ids[:first_change]))
    posture = SEATED if starts else None
    out: list[tuple[int, str]] = []
    for i in ids:
        c = clips[i]
        if posture in KEPT and c.start_posture != posture and i not in composing and plays_in(c, posture):
            out.append((i, posture))
            continue
        posture = c.end_posture
    return SeatedPlan(starts, tuple(out))


__all__ = ["KEPT", "KNEELING", "SEATED", "SeatedPlan", "plays_in", "seated_motions"]

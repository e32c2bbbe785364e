"""Props for the output tests, made from real animations: a ball in an actor's right hand and a chair beside it.

The scene stage that places things from the text is not what these tests check; they check that what
the outputs draw is where the props are, so the props follow a real motion's joints (the hand's world
position at every frame) or stand where a real actor starts.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.spatial.transform import Rotation

from text2anim.core.bodyparts import body_map
from text2anim.core.motion import Motion
from text2anim.output.viewer.types import Prop

#: Colours apart from the first actors' (blue, orange) and the floor's red x axis, so a test can find each thing's pixels.
BALL = "#d63384"
CHAIR = "#6aa84f"


def in_hand(motion: Motion, name: str = "ボール", side: str = "right", diameter: float = 0.22,
            color: str = BALL) -> Prop:
    """A ball whose centre is the ``side`` hand joint of ``motion`` at every frame, turning with the hand."""
    hand = body_map(motion.skeleton).hands[side]
    rot = Rotation.from_matrix(motion.pose.rotations[:, hand]).as_quat()
    return Prop(name, "sphere", (diameter,) * 3, motion.positions[:, hand], rot, motion.fps, color)


def chair_beside(motion: Motion, name: str = "椅子", across: float = 1.0, ahead: float = 0.4,
                 color: str = CHAIR) -> Prop:
    """A still chair ``across`` metres to the +x side of where ``motion``'s root starts and ``ahead`` metres
    along +z, its seat facing +z (the shape's front), 0.45 x 0.9 x 0.45 m, on the floor."""
    root = motion.root_positions[0]
    centre = np.array([root[0] + across, 0.45, root[2] + ahead])
    T = motion.n_frames
    return Prop(name, "chair", (0.45, 0.9, 0.45), np.tile(centre, (T, 1)), np.tile([0.0, 0.0, 0.0, 1.0], (T, 1)),
                motion.fps, color)


#: Two actors, one of whom waves: the ball in 花子's right hand goes up and down and across.
TEXT = "太郎は走って、ボールを蹴る。花子は手を振る。"


@lru_cache(maxsize=None)
def scene(db: str, text: str = TEXT):
    """``(animation, [ball in the last actor's right hand, chair beside the first actor])`` of ``text``, animated
    once per test session and database."""
    import text2anim

    anim = text2anim.animate(text, db=db)
    motions = list(anim.motions.values())
    return anim, [in_hand(motions[-1]), chair_beside(motions[0], across=-1.0)]  # on the side away from the other

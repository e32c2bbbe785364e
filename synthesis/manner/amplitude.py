"""Amplitude: the arms' excursions, and the legs' outside a gait, larger or smaller (:mod:`.excursion`).

The upper arms take the style's ``amplitude`` factor, the forearms its square root when it enlarges (an
elbow pushed past its captured range would bend backwards), the whole factor when it shrinks. The thighs of
a clip that is not a gait take it too (its square root when it enlarges: a kick's swing is the fastest
motion of the body, and jerk grows with it) while their foot is off the floor (a bigger kick on a leg that stands
still: :func:`.plant.held_weight`); a gait's legs are :mod:`.stride`'s. Factors at
intensity 1, raised to the intensity.
"""
from __future__ import annotations

import numpy as np

from text2anim.core import quat
from text2anim.core.contacts import detect_contacts
from text2anim.core.motion import Motion

from .body import Body
from .excursion import scaled
from .plant import held_weight


def amplify(motion: Motion, body: Body, factor: float, cyclic: bool, gait: bool) -> Motion:
    """``motion`` with its limbs' excursions scaled by ``factor``."""
    if factor == 1.0:
        return motion
    rot = np.array(motion.rotations)
    elbow = factor if factor < 1.0 else float(np.sqrt(factor))  # the forearms' and the thighs' factor
    for side in ("left", "right"):
        arm = body.map.joints(f"{side}_arm")
        for j, f in ((arm[1], factor), (arm[2], elbow)):
            rot[:, j] = scaled(rot[:, j], f, cyclic)
        if not gait:
            thigh = body.map.joints(f"{side}_leg")[1]
            free = 1.0 - held_weight(detect_contacts(motion).intervals(side), motion.n_frames)
            rot[:, thigh] = quat.slerp(rot[:, thigh], scaled(rot[:, thigh], elbow, cyclic), free)
    return motion.replace(rotations=rot)

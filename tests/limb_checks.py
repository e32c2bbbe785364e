"""The check every retargeting test makes: hands and feet of the output where the source's are."""
from __future__ import annotations

import numpy as np

from text2anim.core.contacts import detect_contacts
from text2anim.core.motion import Motion
from text2anim.core.retarget import Mapping

#: The end effectors compared: what a viewer sees slide or float when retargeting goes wrong.
LIMBS = ("leftHand", "rightHand", "leftFoot", "rightFoot", "leftToes", "rightToes")


def limb_errors(source: Motion, positions: np.ndarray, mapping: Mapping,
                columns: dict[int, int] | None = None) -> dict[str, float]:
    """Per limb role, the largest distance (m) over the source's planted frames between the output's joint
    (``positions`` ``(T, J, 3)``; ``columns[j]`` is the column of the mapping's target joint ``j``,
    default ``j``) and the source's, scaled by ``mapping.scale`` (the leg-length ratio). The source must plant its
    feet on more than 10 frames."""
    fc = detect_contacts(source)
    planted = fc.left | fc.right
    assert planted.sum() > 10
    out = {}
    for role in LIMBS:
        j = mapping.target[role] if columns is None else columns[mapping.target[role]]
        err = np.linalg.norm(positions[planted, j] - mapping.scale * source.positions[planted, mapping.source[role]],
                             axis=-1)
        out[role] = float(err.max())
    return out

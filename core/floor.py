"""A clip's floor, found from its foot contacts, and moving the clip onto y = 0.

The floor is the level of the soles. Joint centres sit above it: the
convention of the whole project (import, the built-in library) is that a
planted foot's lowest joint (the ball of the foot, CMU's ``ToeBase``) is
:data:`FOOT_CLEARANCE` (3.8 cm) above the floor. That figure is measured, not
chosen: over the 35 shared CMU takes (``../shared/mocap/cmu``, 10 subjects,
calibrated capture floors at the files' ``y = 0``, at 30 fps) the median
height of the planted toe joint (the median over each take's contact frames)
is 3.76 cm, interquartile range 3.3-4.3 cm, 1.5-5.6 cm in all; the toe joint
is the planted foot's lowest joint in every take (the ankle is higher), so
this is also the sole's thickness under the lowest joint centre (a shod
foot: ~2 cm of foot under the ball plus the shoe). GMD's skating ratio
counts a toe below 5 cm, so this matters to it: a captured walk measures
0.012-0.017 (02_01, 16_15) on its own floor; with the toe joint put 2 cm
up, 0.14. So

    floor = median height of the lowest foot joint on contact frames - FOOT_CLEARANCE

(for a foot that ends at the ankle, its toes an end site, the lowest of the ankle and the tip:
:func:`sole_heights`)

and :func:`place_on_floor` moves the whole clip down by ``floor`` (the root's
``y`` only; nothing else changes).

Steps (:func:`find_floor`):

1. **Coarse level.** The 5th percentile of the lowest foot joint's height over
   the clip, minus the clearance. The clip is shifted by it first, so the
   contact detector's height threshold (5 cm, see :mod:`core.contacts`) is
   applied near the real floor even when the capture's floor was far off
   (a clip 30 cm too high would otherwise have no contacts at all).
2. **Contacts.** :func:`core.contacts.detect_contacts` on the shifted clip.
   With at least :data:`MIN_CONTACT_FRAMES` contact frames (both feet
   together), the floor is the median planted height of step 0's formula:
   the median ignores the few frames of a heel strike or a toe-off.
3. **Few contacts** (a jump filmed mostly in the air, a clip of under 0.2 s):
   the coarse level of step 1 is kept, i.e. the floor is where the feet
   reach lowest (5th percentile) during the clip. ``method`` says which
   rule was used. A clip whose feet never touch the ground (a seated clip
   with the feet dangling, a hanging one) is therefore put with its lowest
   foot reach at the clearance: the best guess without a floor in the data.

Shapes: positions ``(T, J, 3)`` metres, Y up.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .bodyparts import body_map
from .contacts import HEIGHT_THRESHOLD, detect_contacts
from .motion import Motion

#: Height of a planted foot's lowest joint centre above the floor (m): median of the CMU takes (docstring).
FOOT_CLEARANCE = 0.038
#: m at a person's size: a lowest joint higher than this above the floor touches nothing (a planted foot's
#: height and the contact rule's margin over it): the balance figure's feet on the floor, the hang's air
ON_FLOOR = FOOT_CLEARANCE + HEIGHT_THRESHOLD
#: Contact frames (both feet together) needed to trust the contact-based floor; fewer: the coarse level.
MIN_CONTACT_FRAMES = 6
#: Percentile of the lowest foot joint's height used for the coarse level.
COARSE_PERCENTILE = 5.0


@dataclass(frozen=True)
class Floor:
    """Where a clip's floor was found.

    Attributes:
        height: the floor's ``y`` in the clip as given, metres (the clip is moved by ``-height``).
        method: ``"contacts"`` (median planted height) or ``"lowest"`` (too few contacts:
            5th percentile of the feet's lowest joint).
        contact_frames: contact frames of both feet together that the estimate used.
    """

    height: float
    method: str
    contact_frames: int


def lowest_foot_heights(motion: Motion) -> np.ndarray:
    """Height of each foot's lowest joint (ankle or toe) per frame, ``(T, 2)`` metres: left, right."""
    bm = body_map(motion.skeleton)
    y = motion.positions[..., 1]
    return np.stack([y[:, list(bm.feet[side])].min(axis=1) for side in ("left", "right")], axis=1)


def sole_heights(motion: Motion) -> np.ndarray:
    """Height of each foot's ball per frame, ``(T, 2)`` metres (left, right): its lowest joint, or for a
    foot that ends at the ankle (no toe joint, the toes an end site: the cmu_everyday takes) the lowest of
    the ankle and its end sites. The ankle of such a foot stands 7.7 cm up where a ball stands 3.8
    (``benchmarks/bench_floor.py``): taken for a ball, it put those takes 3.9 cm under their floor."""
    low = lowest_foot_heights(motion)
    bm = body_map(motion.skeleton)
    for k, side in enumerate(("left", "right")):
        ankle, toe = bm.feet[side]
        if ankle == toe:
            low[:, k] = chain_lowest(motion, ankle)
    return low


def chain_lowest(motion: Motion, joint: int) -> np.ndarray:
    """Height (m) of the lowest point of ``joint``'s subtree per frame, ``(T,)``: its joints and the end
    sites hanging from them (a foot: ankle, ball, toe tip; a hand: wrist, fingers, fingertips)."""
    below = [int(j) for j in motion.skeleton.subtree(joint)]
    y = motion.positions[:, below, 1].min(axis=1)
    sites = [k for k, (j, _) in enumerate(motion.skeleton.end_sites) if j in below]
    if sites:
        y = np.minimum(y, motion.end_site_positions()[:, sites, 1].min(axis=1))
    return y


def lowest_points(motion: Motion) -> np.ndarray:
    """Height (m) of the lowest joint or end site (a toe tip, a fingertip) on each frame, ``(T,)``."""
    return chain_lowest(motion, 0)


def shifted(motion: Motion, dy: float) -> Motion:
    """The clip moved up by ``dy`` metres (root ``y`` only)."""
    if dy == 0.0:
        return motion
    root = motion.root_positions.copy()
    root[:, 1] += dy
    return motion.replace(root_positions=root)


def find_floor(motion: Motion) -> Floor:
    """The floor of ``motion`` (see the module docstring for the rule).

    Raises :class:`core.bodyparts.BodyMapError` when the skeleton has no feet.
    """
    if motion.n_frames == 0:
        return Floor(0.0, "lowest", 0)
    low = sole_heights(motion)
    coarse = float(np.percentile(low, COARSE_PERCENTILE)) - FOOT_CLEARANCE
    moved = shifted(motion, -coarse)
    fc = detect_contacts(moved)
    planted = np.stack([fc.left, fc.right], axis=1)
    n = int(planted.sum())
    if n < MIN_CONTACT_FRAMES:
        return Floor(coarse, "lowest", n)
    return Floor(float(np.median(low[planted])) - FOOT_CLEARANCE, "contacts", n)


def place_on_floor(motion: Motion) -> tuple[Motion, Floor]:
    """``motion`` moved vertically so its floor is at ``y = 0``, and the floor that was found."""
    floor = find_floor(motion)
    return shifted(motion, -floor.height), floor

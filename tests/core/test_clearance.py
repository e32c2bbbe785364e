"""Toe tips out of the floor: a foot on the ground bends its toes at the ball; a swinging one is lifted."""
from __future__ import annotations

import numpy as np

from shared_data import cmu, requires_cmu
from text2anim.core import read_bvh
from text2anim.core.bodyparts import body_map
from text2anim.core.clearance import FLOOR_RAMP_SECONDS, clear_floor, envelope
from text2anim.core.contacts import horizontal_speed
from text2anim.core.floor import chain_lowest, place_on_floor
from text2anim.core.metrics import SKATE_SPEED
from text2anim.core.retarget import retarget
from text2anim.motiondb.library.skeleton import canonical_skeleton

pytestmark = requires_cmu


def test_a_toe_tip_in_the_floor_under_a_still_ball_is_bent_up_and_the_foot_stays_where_it_stands():
    """Issue 46: subject 05's dance on the built-in body (a longer foot) puts its toe tips 2.5 cm under the
    floor as a heel rises over a still ball. Lifting the whole foot out of the floor there raised the planted
    foot (and, on a dancer, added jerk); the toes bend at the ball instead, as a shoe's do."""
    dance, _ = place_on_floor(read_bvh(cmu("05_03_dance"), drop_first=True))
    body = retarget(dance, canonical_skeleton())
    cleared = clear_floor(body)
    skel = body.skeleton
    seen = 0
    for ankle, toe in body_map(skel).feet.values():
        tip = [k for k, (j, _) in enumerate(skel.end_sites) if j == toe]
        before, after = body.end_site_positions()[:, tip, 1].min(axis=1), cleared.end_site_positions()[:, tip, 1].min(axis=1)
        still = horizontal_speed(body.positions[:, toe], body.fps) < SKATE_SPEED
        bent = still & (before < -0.01) & (chain_lowest(body, ankle) >= before)  # only the tip is in the floor
        joints = body.positions[:, [ankle, toe], 1].min(axis=1)  # a joint in the floor lifts the foot, eased
        bent &= envelope(np.maximum(0.0, -joints), int(round(FLOOR_RAMP_SECONDS * body.fps))) == 0.0
        seen += int(bent.sum())
        if not bent.any():
            continue
        assert after[bent].min() > -1e-6  # on the floor, not in it
        moved = np.linalg.norm(cleared.positions[bent, toe] - body.positions[bent, toe], axis=-1)
        assert moved.max() < 2e-3  # the ball where it stood: bent, not lifted
        assert np.abs(cleared.positions[bent, ankle] - body.positions[bent, ankle]).max() < 2e-3
    assert seen >= 5  # the dancer's heel raises
    assert chain_lowest(cleared, 0).min() > -1e-6

"""Retargeting keeps the knees as smooth as the capture (core.retarget.soft_reach).

Real CMU capture played on the test rigs (Mixamo, SMPL, VRM proportions): where a leg's goal reached the
rig's full leg length for a frame, the two-bone IK snapped the knee straight for that frame and bent it
again on the next — knee jerk up to 1.7x the capture's own (3,417 m/s³ on a run), a Mixamo character's
whole animation over the jerk limit. The reach is soft now: no knee snaps, and the knees jerk about as the
capture's do.
"""
from __future__ import annotations

import numpy as np
import pytest

from rig_builders import mixamo_rig, smpl_rig, vrm_rig
from shared_data import cmu, requires_cmu
from text2anim.core import read_bvh
from text2anim.core.metrics import at_rate, joint_jerk
from text2anim.core.retarget import retarget
from text2anim.core.rigs import rig_roles

RIGS = {"mixamo": mixamo_rig, "smpl": smpl_rig, "vrm": vrm_rig}


def _knees(m):
    """Per side: the knee's bend (degrees, ``(T,)``) and its jerk p99 (m/s³, at 30 fps)."""
    _, roles = rig_roles(m.skeleton)
    p = m.positions
    jerk = joint_jerk(at_rate(m, 30.0).positions, 30.0)
    out = {}
    for side in ("left", "right"):
        hip, knee, ankle = (roles[side + r] for r in ("UpperLeg", "LowerLeg", "Foot"))
        u, v = p[:, knee] - p[:, hip], p[:, ankle] - p[:, knee]
        cos = np.einsum("ti,ti->t", u, v) / (np.linalg.norm(u, axis=-1) * np.linalg.norm(v, axis=-1))
        out[side] = (np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))), float(np.percentile(jerk[:, knee], 99)))
    return out


@requires_cmu
@pytest.mark.parametrize("take", ["02_01_walk", "09_02_run", "05_02_dance"])
@pytest.mark.parametrize("rig", sorted(RIGS))
def test_the_knees_on_a_rig_are_as_smooth_as_the_capture(tmp_path, take, rig):
    source = at_rate(read_bvh(cmu(take), drop_first=True), 30.0)
    out = retarget(source, read_bvh(RIGS[rig](tmp_path / f"{rig}.bvh")).skeleton)
    own = max(j for _, j in _knees(source).values())
    for side, (bend, jerk) in _knees(out).items():
        snaps = (bend[1:-1] < 2.0) & ((bend[:-2] > 8.0) | (bend[2:] > 8.0))  # straight for one frame
        assert not snaps.any(), (side, np.flatnonzero(snaps))
        assert jerk <= 1.3 * own, (side, jerk, own)

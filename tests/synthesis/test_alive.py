"""Held poses settle into the captured idle (issue 12), through the engines' last step (synthesis.finish)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from text2anim.core.bvh import read_bvh
from text2anim.core.metrics import frozen_pairs
from text2anim.core.motion import Motion
from text2anim.motiondb.library import capture
from text2anim.synthesis.finish import finish

WALK = Path(__file__).resolve().parents[1] / "data" / "walk_tiny.bvh"


def held(m: Motion, seconds: float = 4.0) -> Motion:
    """``m``'s last frame held still for ``seconds``: what a track holds after an action ends."""
    n = int(seconds * m.fps)
    return m.replace(rotations=np.repeat(m.rotations[-1:], n, 0), root_positions=np.repeat(m.root_positions[-1:], n, 0))


def joint_range_cm(m: Motion, name: str) -> float:
    p = m.positions[:, m.skeleton.names.index(name)]
    return float(np.linalg.norm(np.ptp(p, axis=0)) * 100)


def test_a_held_pose_of_the_built_in_character_plays_the_captured_idle():
    idle = capture.captured_clip("wait")  # the built-in character's captured idle (what the API hands a track)
    out = finish(held(capture.captured_clip("kick_front")), idle=lambda: idle)
    assert not frozen_pairs(out).any()
    # the idle sways the trunk and turns the head by centimetres; breathing alone moves the head by millimetres
    assert joint_range_cm(out, "Head") > 5.0
    for toe in ("LeftToeBase", "RightToeBase", "Hips"):
        assert joint_range_cm(out, toe) < 1e-6  # the legs and the hips keep the held pose: feet stay planted


def test_another_character_breathes_without_the_built_in_idle():
    walk = read_bvh(WALK)  # the built-in's joint names, a CMU subject's bone lengths: not the built-in character
    out = finish(held(walk), feet=False, idle=lambda: capture.captured_clip("wait"))
    assert not frozen_pairs(out).any()
    assert joint_range_cm(out, "Head") < 2.5  # the breathing layer alone (the idle moves it 12 cm)
    assert joint_range_cm(out, "LeftToeBase") < 1e-6


def test_a_body_lying_still_stays_alive_on_another_rig(library_db, tmp_path):
    """After 転ぶ the body lies moving its legs at about 0.6 cm/s, just above the frozen speed, so it got no
    breathing layer; retargeted onto a Mixamo-named A-pose character (the legs solved again on its own
    proportions) it moved at 0.3 cm/s and 6 % of its frames read frozen."""
    import text2anim
    from rig_builders import mixamo_glb
    from text2anim.core.metrics import at_rate
    from text2anim.export import ExportOptions

    anim = text2anim.animate("太郎は転んでしまう。", db=library_db)
    rig = ExportOptions(rig=mixamo_glb(tmp_path / "rig.glb", scale=1.0))
    for motion in (*anim.motions.values(), *anim.exported_motions(rig, units=False).values()):
        assert not frozen_pairs(at_rate(motion, 30.0)).any(), motion.skeleton.names[0]

"""A motion adapted to a wider stance than its own stands in it lower, both feet on the floor.

構えて、殴る: the punch (CMU 02_05) is adapted to the ready stance's feet, the back foot 53 cm from where
the punch has it. The legs could not reach that far from the punch's own hip height: the back foot hung
up to 8.5 cm above the floor on a straight leg through the punch (the body standing on one foot, its centre
of mass 24 cm outside it). Now the hips sink until both legs reach (synthesis.optimal.adaptation._sink).
"""
from __future__ import annotations

import numpy as np

import text2anim
from text2anim.core.floor import lowest_foot_heights


def test_the_punch_from_a_wide_stance_keeps_both_feet_down(library_db):
    anim = text2anim.animate("太郎は構えて、殴る。", db=library_db)
    (join,) = anim.result.joins
    assert join.blend == "motion_adaptation" and max(join.metrics["adapt_offset_cm"].values()) > 40
    motion = anim.motions["太郎"]
    low = lowest_foot_heights(motion)  # (T, 2) m
    punch = np.arange(motion.n_frames) / motion.fps >= join.intervals[0].begin
    rise = low[punch] - low[punch][0]  # each foot's height over where it stood when the punch began
    assert rise.max() < 0.02  # both feet stay planted (the back foot rose 7.6 cm before)

"""The seed-003 engine on the built-in library's keyframed clips (no shared data needed).

These clips plant their feet exactly, so any skating or jerk the checks find is the engine's own;
the library's captured clips are checked end to end in ``test_capture_library.py``.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

from text2anim.core.bodyparts import body_map
from text2anim.synthesis.constraint.engine import synthesize
from text2anim.core.metrics import SKATING_MARGIN, skating_ratio
from text2anim.scene import default_spots
from text2anim.synthesis.tracks import Clip, Element, Track

from text2anim.motiondb import library
FPS = 30


@lru_cache(maxsize=None)
def clips() -> dict[str, Clip]:
    out = {}
    for c in (b.record for b in library.build_all(FPS)):
        core = c.core if c.core is not None else (0.0, c.motion.duration)
        out[c.name] = Clip(c.name, c.motion, core, c.cyclic, c.body_part)
    return out


def need(*names):
    C = clips()
    missing = [n for n in names if n not in C]
    if missing:
        pytest.skip(f"built-in library has no {', '.join(missing)} yet")
    return C


def run(*elements, **kw):
    res = synthesize([Track(None, tuple(elements))], FPS, **kw)
    return res, res.motions[None]


def test_walk_run_walk_transitions_are_clean():
    C = need("walk", "run")
    res, m = run(Element(1, C["walk"], 0.0, 3.0, "initial"), Element(2, C["run"], 2.5, 5.0, "transition", prev=1),
                 Element(3, C["walk"], 4.6, 7.0, "transition", prev=2))
    assert [j.blend for j in res.joins] == ["transition", "transition"]
    for j in res.joins:
        bound = j.metrics["source_skating_ratio"] + SKATING_MARGIN
        assert j.metrics["skating_ratio"] <= bound and j.metrics["region"]["skating_ratio"] <= bound
        assert j.metrics["jerk_max"] <= 1.5 * j.metrics["source_jerk_max"]
    assert skating_ratio(m) == 0.0
    assert all(e.core_fidelity_cm < 0.5 for e in res.elements.values())
    # the time table's 7 s and the time the joins took to change speed within the clips' own accelerations
    assert m.n_frames == 7 * FPS + round(sum(j.metrics["post"]["added_s"] for j in res.joins) * FPS)


@pytest.mark.parametrize("part", ["right_arm", "left_arm"])
def test_wave_while_walking_uses_the_asked_hand(part):
    C = need("walk", "wave_hand")
    res, m = run(Element(1, C["walk"], 0.0, 4.0, "initial"),
                 Element(2, C["wave_hand"], 0.5, 3.5, "composition", prev=1, body_part=part))
    (j,) = res.joins
    assert j.metrics["skating_ratio"] <= j.metrics["source_skating_ratio"] + SKATING_MARGIN
    bm = body_map(m.skeleton)
    side = part.split("_")[0]
    other = "left" if side == "right" else "right"
    t0, t1 = (round(x * FPS) for x in j.metrics["switch_s"])
    mid = slice((2 * t0 + t1) // 3, (t0 + 2 * t1) // 3)
    head = m.positions[mid, bm.head, 1]
    assert (m.positions[mid, bm.hands[side], 1] > head - 0.25).mean() > 0.5  # raised to the head
    assert (m.positions[mid, bm.hands[other], 1] < head - 0.4).all()  # the other hand stays down
    assert res.elements[2].part_fidelity_cm < 3.0


def test_connection_with_delay_and_gap_free_connection():
    C = need("run", "walk_back", "walk")
    res, m = run(Element(1, C["run"], 0.0, 2.0, "initial"), Element(2, C["walk_back"], 2.5, 5.0, "connection", prev=1))
    (j,) = res.joins
    assert j.metrics["skating_ratio"] <= j.metrics["source_skating_ratio"] + SKATING_MARGIN
    assert j.metrics["jerk_max"] <= 1.5 * j.metrics["source_jerk_max"]  # the run eases to a stop, never freezes
    res, m = run(Element(1, C["walk"], 0.0, 2.0, "initial"), Element(2, C["walk_back"], 2.0, 5.0, "connection", prev=1))
    (j,) = res.joins
    assert j.metrics["skating_ratio"] <= j.metrics["source_skating_ratio"] + SKATING_MARGIN
    assert skating_ratio(m) == 0.0
    assert all(e.core_fidelity_cm < 0.5 for e in res.elements.values())


def test_three_actors_side_by_side():
    C = need("walk")
    spots = default_spots(list("ABC"))  # the staging's default: side by side
    tracks = [Track(n, (Element(i, C["walk"], 0.0, 2.0, "initial"),), s.origin, s.heading)
              for (i, n), s in zip(enumerate("ABC"), spots)]
    res = synthesize(tracks, FPS)
    starts = np.array([res.motions[n].root_positions[0, [0, 2]] for n in "ABC"])
    d = np.linalg.norm(starts[:, None] - starts[None], axis=-1)
    assert d[np.triu_indices(3, 1)].min() >= 1.0
    ends = np.array([res.motions[n].root_positions[-1, [0, 2]] for n in "ABC"])
    d_end = np.linalg.norm(ends[:, None] - ends[None], axis=-1)
    assert d_end[np.triu_indices(3, 1)].min() >= 1.0  # walking the same way, they stay apart

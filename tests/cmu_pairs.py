"""CMU clip pairs for the join tests and benchmarks: clips cut from real takes, stored in a motion
database and read back, two of them laid on one track as the scheduler would lay them.

Used by ``tests/synthesis/test_joins_cmu.py``, ``benchmarks/bench_quality.py`` and
``benchmarks/bench_blend.py`` (the benchmarks put ``tests/`` on ``sys.path``). It needs no pytest:
the callers say where the takes are.
"""
from __future__ import annotations

from pathlib import Path

from text2anim.core import read_bvh
from text2anim.core.motion import Motion
from text2anim.motiondb import ClipInfo, ImportOptions, MotionDB
from text2anim.scheduler.clips import timing
from text2anim.scheduler.lengths import transition_window
from text2anim.synthesis.join.cycles import gait_cycle
from text2anim.synthesis.tracks import Clip, Element, Track
from text2anim.output.bvh_write import write_bvh

#: A cut: ``"cycle"`` (one gait cycle, found by :func:`gait_cycle`, to be looped) or ``(from, to)`` seconds.
Cut = str | tuple[float, float]


def cut_take(path: Path, cut: Cut, core: tuple[float, float] | None) -> tuple[Motion, tuple[float, float] | None]:
    """A clip cut from the take at ``path`` (its T-pose frame 0 dropped) and its core (s, in the cut):
    a gait cycle's core is the whole cycle."""
    m = read_bvh(path, drop_first=True)
    if cut == "cycle":
        a, b = gait_cycle(m)
        return m[a:b], (0.0, (b - a) / m.fps)
    assert not isinstance(cut, str), f"unknown cut {cut!r}"
    return m.between(*cut), core


def import_cut(db: MotionDB, workdir: Path, name: str, motion: Motion, core: tuple[float, float] | None,
               cyclic: bool, verb: str) -> None:
    """Store a cut as ``text2anim db import`` does (:meth:`MotionDB.import_bvh` of a BVH file written in
    ``workdir``), under the character ``cmu``: its floor found from the foot contacts and moved to y = 0,
    a clip of another capture subject retargeted onto the first clip's skeleton."""
    path = workdir / f"{name}.bvh"
    write_bvh(motion, path)
    db.import_bvh([path], ImportOptions(verbs=(verb,), character="cmu", core=core, cyclic=cyclic, scale=1.0))


def read_back(db: MotionDB, fps: float) -> dict[str, tuple[ClipInfo, Clip]]:
    """Every clip of ``db`` as the pipeline reads it: ``{name: (info, Clip)}``, resampled to ``fps``."""
    out = {}
    for info in db.clips():
        m = db.load(info)
        out[info.name] = (info, Clip(info.name, m.resample(fps) if m.fps != fps else m, tuple(info.core),
                                     info.cyclic, info.body_part))
    return out


def pair_track(first: tuple[ClipInfo, Clip], second: tuple[ClipInfo, Clip], played: tuple[float, float],
               transition: bool) -> Track:
    """Two clips on one track, playing ``played`` seconds each: with ``transition`` the second starts at
    the first's last foot-moving interval (:func:`transition_window`, where the first then ends), else,
    or when the first has no such interval, a connection (the second starts when the first ends)."""
    (ia, ca), (_, cb) = first, second
    la, lb = played
    how, start, end_a = "connection", la, la
    if transition:
        win = transition_window(timing(ia), 1.0, 1, la)
        if win is not None:
            how, (start, end_a) = "transition", win
    return Track(None, (Element(1, ca, 0.0, end_a, "initial"), Element(2, cb, start, start + lb, how, prev=1)))

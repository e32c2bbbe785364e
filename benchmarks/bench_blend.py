"""Optimal blending (paper 000) against the constraint engine and the two baselines, on real captures.

Clips cut from ``../shared/mocap/cmu/`` (walk and run cycles, kicks, jumps,
punches, throws, turns, a pick-up, a dance, a laugh, a wave) are imported into
a temporary SQLite motion database (:class:`motiondb.MotionDB`, as a user's
``text2anim db import`` would), read back and resampled to 30 fps (as the
pipeline does), and :data:`PAIRS` (25 joins + a composition) are each
synthesised with every method of :mod:`synthesis.registry`. The time table of a
pair follows the scheduler's rules (``scheduler.lengths``): a *transition*
starts the second clip at the first clip's last step after its core and ends
the first when that step ends; a *connection* starts it when the first ends.

Figures per join (``docs/timetable.md`` §3, from the engines' own reports and
:mod:`core.metrics`):

- ``slide``: distance the feet slide while in contact over the whole motion
  (cm; the clips' own marker noise is in every method's figure alike);
- ``skate``: mean horizontal speed of feet in contact over the whole motion (cm/s);
- ``ratio``: the foot-skating ratio (GMD) of the join's blend window;
- ``jerk max`` / ``jerk rms``: in the blend intervals (m/s³), as reported;
- ``core``: the largest core fidelity error of the two elements (cm);
- ``dur``: the animation's length (s).

Also: planning time per join of the optimal search (method, ranges, all
candidate pairs, weights; p50/p95 ms) and the synthesis real-time factor per
method (seconds of animation per second of compute).

Run: ``python benchmarks/bench_blend.py [--json out.json] [--pairs N]``.
"""
from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "tests"))  # cmu_pairs: the CMU pairs the join tests use too

from text2anim.motiondb import ClipRecord, MotionDB  # noqa: E402
from text2anim.synthesis.optimal import join as optimal  # noqa: E402  (join_next looks plan_join up there)
from text2anim.synthesis.registry import METHODS, synthesize_with  # noqa: E402
from text2anim.core.metrics import foot_skate  # noqa: E402
from text2anim.synthesis.tracks import Clip, Element, Track  # noqa: E402

from cmu_pairs import cut_take, pair_track, read_back  # noqa: E402

CMU = REPO.parent / "shared" / "mocap" / "cmu"
FPS = 30.0

#: name: (file stem, (from, to) s or "cycle", core (s, relative to the cut), cyclic, body part)
CLIPS = {
    "walk16": ("16_15_walk", "cycle", None, True, None),
    "walk02": ("02_01_walk", "cycle", None, True, None),
    "run16": ("16_35_run", "cycle", None, True, None),
    "run02": ("02_03_run", "cycle", None, True, None),
    "run127": ("127_07_run", "cycle", None, True, None),
    "kick10_03": ("10_03_kick", (0.0, 2.8), (0.7, 1.5), False, None),
    "kick10_01": ("10_01_kick", (3.6, 6.6), (0.6, 1.8), False, None),
    "frontkick": ("135_04_kick", (1.7, 4.0), (0.8, 1.9), False, None),
    "jump_inplace": ("16_01_jump", (0.0, 2.6), (0.8, 1.8), False, None),
    "jump_forward": ("16_05_jump", (0.0, 2.4), (0.8, 1.8), False, None),
    "jump118": ("118_10_jump", (0.4, 3.0), (0.6, 1.8), False, None),
    "punch": ("02_05_punch", (0.6, 2.4), (0.3, 1.2), False, None),
    "lunge": ("135_09_punch", (1.4, 3.6), (0.5, 1.2), False, None),
    "pitch": ("124_01_throw", (1.8, 5.3), (0.6, 2.2), False, None),
    "shot": ("06_14_throw", (1.8, 4.0), (0.4, 1.5), False, None),
    "pickup": ("02_06_pickup", (0.2, 2.6), (0.5, 1.8), False, None),
    "walkturn": ("16_17_turn", (0.0, 4.3), (1.0, 3.3), False, None),
    "runturn": ("127_15_turn", (0.0, 1.35), (0.3, 1.0), False, None),
    "dance": ("05_03_dance", (0.0, 3.6), (0.5, 3.0), False, None),
    "laugh": ("14_17_laugh", (0.0, 3.0), (0.5, 2.5), False, None),
    "wave": ("14_24_wave", (11.55, 12.95), (0.3, 1.1), False, "right_arm"),
}

#: (first, second, how): transition / connection / composition
PAIRS = [
    ("walk16", "run16", "transition"), ("walk02", "run02", "transition"), ("run16", "walk16", "transition"),
    ("run02", "walk02", "transition"), ("walk16", "run127", "transition"), ("walk16", "kick10_03", "transition"),
    ("run16", "kick10_03", "transition"), ("run127", "kick10_01", "transition"),
    ("walk02", "jump_forward", "connection"), ("walk16", "jump_inplace", "connection"),
    ("jump_inplace", "walk16", "connection"), ("jump_forward", "run16", "connection"),
    ("kick10_03", "walk16", "connection"), ("punch", "frontkick", "connection"), ("punch", "walk02", "connection"),
    ("walk16", "punch", "connection"), ("walk02", "pitch", "connection"), ("shot", "run16", "connection"),
    ("walk16", "walkturn", "transition"), ("run16", "runturn", "transition"), ("walk16", "pickup", "connection"),
    ("kick10_03", "jump118", "connection"), ("lunge", "kick10_03", "connection"), ("dance", "walk02", "connection"),
    ("laugh", "punch", "connection"), ("walk16", "wave", "composition"),
]

CYCLIC_LENGTH = {"walk": 3.0, "run": 2.4}


def build_database(url: str) -> dict:
    """Cut the clips, store them in the database at ``url``, read them back at :data:`FPS`."""
    records = []
    for name, (stem, cut, core, cyclic, part) in CLIPS.items():
        m, core = cut_take(CMU / f"{stem}.bvh", cut, core)
        records.append(ClipRecord(name=name, motion=m, verbs=("動く",), core=core, cyclic=cyclic, body_part=part,
                                  source=str(CMU / f"{stem}.bvh")))
    with MotionDB.open(url, seed=False) as db:
        db.add(records)
        return read_back(db, FPS)


def played(info, clip: Clip) -> float:
    if clip.cyclic:
        return CYCLIC_LENGTH["run" if "run" in clip.name else "walk"]
    return clip.motion.duration


def track_of(clips: dict, first: str, second: str, how: str) -> Track:
    (ia, ca), (ib, cb) = clips[first], clips[second]
    la, lb = played(ia, ca), played(ib, cb)
    if how == "composition":
        return Track(None, (Element(1, ca, 0.0, la, "initial"),
                            Element(2, cb, 0.6, 0.6 + lb, "composition", prev=1, body_part=cb.body_part)))
    return pair_track((ia, ca), (ib, cb), (la, lb), how == "transition")


def figures(res, motion) -> dict:
    fs = foot_skate(motion)
    n = sum(f.contact_frames for f in fs.values())
    js = [j for j in res.joins if j.metrics and j.method != "not_executed"]
    fid = [v.fidelity_cm or 0.0 for v in res.elements.values()]
    return {"slide": sum(f.slide_cm for f in fs.values()),
            "skate": sum(f.mean_speed_cm_s * f.contact_frames for f in fs.values()) / max(n, 1),
            "ratio": max([j.metrics["skating_ratio"] for j in js] or [0.0]),
            "jerk_max": max([j.metrics["jerk_max"] for j in js] or [0.0]),
            "jerk_rms": max([j.metrics["jerk_rms"] for j in js] or [0.0]),
            "core": max(fid or [0.0]), "dur": motion.duration,
            "blend": ",".join(j.blend for j in res.joins)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", help="write every figure here")
    ap.add_argument("--pairs", type=int, default=len(PAIRS), help="only the first N pairs")
    ap.add_argument("--smoothness", type=float, default=0.5)
    ap.add_argument("--repeat", type=int, default=3, help="timed repetitions per synthesis (the best is kept)")
    args = ap.parse_args(argv)
    if not CMU.is_dir():
        print(f"no CMU clips at {CMU}", file=sys.stderr)
        return 1
    with tempfile.TemporaryDirectory() as tmp:
        clips = build_database(f"sqlite:///{tmp}/bench.sqlite")
    plan_ms: list[float] = []
    real_plan = optimal.plan_join

    def timed(*a, **k):
        t = time.perf_counter()
        out = real_plan(*a, **k)
        plan_ms.append(1000 * (time.perf_counter() - t))
        return out

    rows, rtf = [], {m: [0.0, 0.0] for m in METHODS}
    for first, second, how in PAIRS[:args.pairs]:
        track = track_of(clips, first, second, how)
        for method in METHODS:
            best = None
            for k in range(args.repeat):
                optimal.plan_join = timed if (method == "optimal" and k == 0) else real_plan
                t = time.perf_counter()
                res = synthesize_with(method, [track], FPS, smoothness=args.smoothness)
                dt = time.perf_counter() - t
                best = dt if best is None else min(best, dt)
            optimal.plan_join = real_plan
            motion = res.motions[None]
            rtf[method][0] += motion.duration
            rtf[method][1] += best
            rows.append({"pair": f"{first}→{second}", "how": how, "method": method, **figures(res, motion),
                         "warnings": list(res.warnings)})
    keys = ("slide", "skate", "ratio", "jerk_max", "jerk_rms", "core", "dur")
    print(f"{'pair':28} {'method':10} {'slide cm':>8} {'skate':>6} {'ratio':>6} {'jerk max':>9} {'jerk rms':>8} "
          f"{'core cm':>7} {'dur s':>6}  blend")
    for r in rows:
        print(f"{r['pair']:28} {r['method']:10} {r['slide']:8.1f} {r['skate']:6.2f} {r['ratio']:6.3f} "
              f"{r['jerk_max']:9.0f} {r['jerk_rms']:8.0f} {r['core']:7.1f} {r['dur']:6.2f}  {r['blend']}")
    print("\nmeans over the joins (composition included; it is the same code for all methods)")
    means = {}
    for method in METHODS:
        sel = [r for r in rows if r["method"] == method]
        means[method] = {k: float(np.mean([r[k] for r in sel])) for k in keys}
        m = means[method]
        print(f"  {method:10} slide {m['slide']:6.1f} cm  skate {m['skate']:5.2f} cm/s  ratio {m['ratio']:.4f}  "
              f"jerk max {m['jerk_max']:7.0f}  rms {m['jerk_rms']:6.0f}  core {m['core']:5.1f} cm  dur {m['dur']:.2f} s")
    wins = {}
    by_pair = {}
    for r in rows:
        by_pair.setdefault(r["pair"], {})[r["method"]] = r
    for other in ("pose", "crossfade", "constraint"):
        wins[other] = {k: sum(1 for p in by_pair.values() if p["optimal"][k] <= p[other][k] + 1e-9) for k in
                       ("slide", "ratio", "jerk_max", "jerk_rms")}
        print(f"  optimal <= {other:10} in {wins[other]} of {len(by_pair)} pairs")
    p50, p95 = (float(np.percentile(plan_ms, q)) for q in (50, 95))
    print(f"\nplanning per join (optimal: method, ranges, search of all pairs, weights): p50 {p50:.1f} ms, "
          f"p95 {p95:.1f} ms over {len(plan_ms)} joins")
    print("synthesis real-time factor (s of animation per s of compute, best of "
          f"{args.repeat}): " + ", ".join(f"{m} {a / b:.0f}x" for m, (a, b) in rtf.items()))
    if args.json:
        Path(args.json).write_text(json.dumps({"rows": rows, "means": means, "wins": wins,
                                               "planning_ms": {"p50": p50, "p95": p95, "n": len(plan_ms)},
                                               "realtime_factor": {m: a / b for m, (a, b) in rtf.items()}},
                                              ensure_ascii=False, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())

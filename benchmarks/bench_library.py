"""The built-in library: what it is made of, and how alive the sentences it animates are.

    python benchmarks/bench_library.py [--engine optimal|constraint] [--db URL]

Prints these tables:

1. the library: clips and verbs by source (CMU capture or keyframed), the size of the
   shipped arrays, the time to seed a fresh SQLite database (CPU beside wall);
2. per clip at 30 fps, the worst first: skating on the floor y = 0 and as GMD measures it (above the
   clip's lowest foot point), floor penetration (joints, toe and finger tips), floating foot, and how
   many clips are over what issues 24 and 46 hold them to;
3. per sentence (the golden set and the issue's cases): length, the share of frozen frames
   (``docs/timetable.md`` §3: every joint slower than 0.5 cm/s), the longest frozen run, the
   foot-skating ratio, and for repeats the seconds per repetition;
4. co-actors: whether two actors doing the same verb play identical joint angles;
5. loops and repeats: each looping captured clip's cycle and the hips' net travel over it (a
   dance loops on the spot, a gait cycle moves on by a stride), and for repeated and long
   sentences the seconds per repetition and how far the hips get from where they started.

Frozen frames are measured on the output at 30 fps: a frame pair (t, t+1) is frozen when no
joint moves 0.5 cm/s or more.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from text2anim.core.contacts import runs  # noqa: E402
from text2anim.core.metrics import FROZEN_SPEED, frozen_pairs  # noqa: E402  (m/s, docs/timetable.md §3)

#: The golden sentences (tests/golden/sentences.txt, one a line), then a few more.
SENTENCES = (REPO / "tests" / "golden" / "sentences.txt").read_text(encoding="utf-8").splitlines() + [
    "太郎は待つ。そして歩く。",
    "太郎はしゃがむ。そして跳ぶ。",
    "太郎と花子が跳ぶ。",
    "太郎は2回蹴る。",
]


def frozen(motion) -> tuple[float, float]:
    """``(share of frozen frame pairs, longest frozen run in seconds)`` of ``motion`` (:func:`frozen_pairs`)."""
    still = frozen_pairs(motion)
    if not len(still):
        return 0.0, 0.0
    spans = runs(still)
    longest = int((spans[:, 1] - spans[:, 0]).max()) if len(spans) else 0
    return float(still.mean()), longest / motion.fps


def library_table(db_url: str) -> None:
    from text2anim.motiondb import MotionDB
    from text2anim.motiondb.library import capture

    t0, c0 = time.perf_counter(), time.process_time()
    db = MotionDB.open(db_url)
    clips = db.clips()
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    cap = [c for c in clips if c.source.startswith("builtin:capture")]
    key = [c for c in clips if c.source.startswith("builtin:keyframed")]
    cap_verbs = {v for c in cap for v in c.verbs}
    key_verbs = {v for c in key for v in c.verbs} - cap_verbs
    print("| library | clips | verbs (lemmas) | seconds of motion |")
    print("| --- | ---: | ---: | ---: |")
    print(f"| CMU capture | {len(cap)} | {len(cap_verbs)} | {sum(c.duration for c in cap):.1f} |")
    print(f"| keyframed | {len(key)} | {len(key_verbs)} | {sum(c.duration for c in key):.1f} |")
    print()
    print(f"capture.npz: {capture.ARRAYS.stat().st_size / 1e6:.2f} MB; seeding a fresh database: "
          f"{wall:.2f} s wall, {cpu:.2f} s CPU")
    print(f"capture verbs (primary): {', '.join(sorted({c.verbs[0] for c in cap}))}")
    print()
    db.close()


def sentence_table(db_url: str, engine: str) -> None:
    import text2anim
    from text2anim.motiondb import MotionDB

    db = MotionDB.open(db_url)
    print(f"engine: {engine}; frozen = every joint slower than {FROZEN_SPEED * 100:g} cm/s (30 fps)")
    print()
    print("| sentence | actor | seconds | frozen share | longest frozen (s) | skating ratio | clips |")
    print("| --- | --- | ---: | ---: | ---: | ---: | --- |")
    worst = 0.0
    coactors = []
    for text in SENTENCES:
        anim = text2anim.animate(text, db=db, blend=engine)
        report = anim.report
        names = {e["id"]: e["clip"] for e in report["time_table"]}
        for actor, m in anim.motions.items():
            share, longest = frozen(m)
            worst = max(worst, share)
            clips = ", ".join(f"{names[e.id]}" + ("~m" if e.id in anim.planned.mirrored else "")
                              for e in anim.table.elements if (e.actor or "default") == actor)
            reps = anim.planned.repeats
            if reps:
                clips += " | repeats: " + " ".join(p.clip.name + ("~m" if p.mirrored else "")
                                                   for ps in reps.values() for p in ps)
            print(f"| {text} | {actor} | {m.duration:.2f} | {share:.3f} | {longest:.2f} | "
                  f"{report['actors'][actor]['skating_ratio']:.3f} | {clips} |")
        if len(anim.motions) > 1:
            ms = list(anim.motions.values())
            n = min(len(m) for m in ms)
            same = np.allclose(ms[0].rotations[:n], ms[1].rotations[:n], atol=1e-6)
            coactors.append((text, same))
    print()
    print(f"largest frozen share over all outputs: {worst:.3f}")
    print()
    print("| co-actors | identical joint angles |")
    print("| --- | --- |")
    for text, same in coactors:
        print(f"| {text} | {'yes' if same else 'no'} |")
    db.close()


LOOP_SENTENCES = ["太郎は3回跳ぶ。", "花子は20秒踊る。", "太郎と花子は20秒踊る。", "太郎は手を振る。"]


def loop_table(db_url: str, engine: str) -> None:
    import text2anim
    from text2anim.motiondb import MotionDB
    from text2anim.motiondb.library import capture

    print()
    print("| looping clip | cycle (s) | hips' net travel a cycle (m) |")
    print("| --- | ---: | ---: |")
    for r in capture.capture_records():
        if r.cyclic:
            root = r.motion.root_positions
            print(f"| {r.name} | {r.motion.duration:.2f} | {np.linalg.norm(root[-1, [0, 2]] - root[0, [0, 2]]):.2f} |")
    db = MotionDB.open(db_url)
    print()
    print("| sentence | actor | seconds | per repetition (s) | hips furthest from start (m) |")
    print("| --- | --- | ---: | ---: | ---: |")
    for text in LOOP_SENTENCES:
        anim = text2anim.animate(text, db=db, blend=engine)
        for e in anim.table.elements:
            m = anim.motions[e.actor or "default"]
            n = len(anim.planned.repeats.get(e.id, ())) or 1
            hips = m.root_positions[:, [0, 2]]
            far = float(np.linalg.norm(hips - hips[0], axis=1).max())
            print(f"| {text} | {e.actor or 'default'} | {m.duration:.2f} | {(e.end - e.start) / n:.2f} | {far:.2f} |")
    db.close()


def clip_table(db_url: str, worst: int = 12) -> None:
    """Per built-in clip at 30 fps: skating, floor penetration and floating foot; the worst rows and the
    clips over :data:`core.metrics.CLIP_LIMITS`."""
    from text2anim.core.metrics import CLIP_LIMITS, quality
    from text2anim.motiondb import MotionDB

    with MotionDB.open(db_url) as db:
        rows = [(c.name, c.source.split(":")[1] if c.source.startswith("builtin:") else c.source,
                 quality(db.load(c.name))) for c in db.clips()]
    over = [r for r in rows if any(getattr(r[2], k) > v for k, v in CLIP_LIMITS.items())]
    print(f"per clip at 30 fps: {len(rows)} clips, {len(over)} over a limit "
          f"(skating <= {CLIP_LIMITS['skating_ratio']}, GMD's <= {CLIP_LIMITS['skating_gmd']} (capture), "
          f"floor <= {CLIP_LIMITS['floor_penetration_cm']:g} cm, floating <= {CLIP_LIMITS['floating_cm']:g} cm)")
    print("| clip | source | skating | GMD's | floor cm | floating cm |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    key = lambda r: max(getattr(r[2], k) / v for k, v in CLIP_LIMITS.items())  # noqa: E731 - the worst first
    for name, source, q in sorted(rows, key=key, reverse=True)[:worst]:
        print(f"| {name} | {source} | {q.skating_ratio:.3f} | {q.skating_gmd:.3f} | {q.floor_penetration_cm:.2f} "
              f"| {q.floating_cm:.1f} |")
    print()


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--engine", default="optimal")
    p.add_argument("--db", default=None, help="database URL (default: a fresh temporary SQLite file)")
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        url = args.db or str(Path(tmp) / "bench.sqlite")
        library_table(url)
        clip_table(url)
        sentence_table(url, args.engine)
        loop_table(url, args.engine)


if __name__ == "__main__":
    main()

"""Text to animation: time per sentence, synthesis real-time factor, CLI cold start.

    python benchmarks/bench_e2e.py [--repeat N]

Runs the built-in library in a temporary SQLite database. "Warm" means the
database is open and the analyser loaded; every figure is the median of
``--repeat`` runs on this machine: compare rows of one run as ratios.
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

SENTENCES = {
    1: "太郎は歩く。",
    2: "太郎は走って、ボールを蹴る。",
    3: "太郎は走って、ボールを蹴る。そして喜ぶ。",
    4: "花子は歩いて、止まる。そして振り向いて、手を振る。",
    5: "太郎は走って、ボールを蹴る。そして喜ぶ。それから歩いて、座る。",
}


def median_time(fn, repeat: int) -> tuple[float, object]:
    times, out = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="t2a-bench-")
    url = f"sqlite:///{tmp}/motions.sqlite"
    os.environ["TEXT2ANIM_DB"] = url

    from text2anim.motiondb import MotionDB
    from text2anim.synthesis.registry import DEFAULT, synthesize_with
    from text2anim import animate
    from text2anim.pipeline import plan_text
    from text2anim.tracks import build_tracks

    t = time.perf_counter()
    db = MotionDB.open(url)
    print(f"first open + seeding the built-in library: {time.perf_counter() - t:.2f} s")
    animate(SENTENCES[1], db=db)  # warm up the analyser and caches

    print(f"\nsynthesis: {DEFAULT} blending (the default)")
    print(f"{'motions':>7} {'animation s':>11} {'end-to-end ms':>13} {'plan ms':>8} {'synth ms':>9} {'RT factor':>10}")
    for n, text in SENTENCES.items():
        total, anim = median_time(lambda: animate(text, db=db), args.repeat)
        plan_s, planned = median_time(lambda: plan_text(text, db), args.repeat)
        tracks = build_tracks(planned, db, 30.0)
        synth_s, result = median_time(lambda: synthesize_with(DEFAULT, tracks, 30.0), args.repeat)
        seconds = max(m.duration for m in result.motions.values())
        print(f"{len(planned.table.elements):7d} {seconds:11.2f} {total * 1000:13.1f} {plan_s * 1000:8.1f} "
              f"{synth_s * 1000:9.1f} {seconds / synth_s:9.0f}x")
    db.close()

    env = {**os.environ, "PYTHONPATH": str(REPO)}
    def cli(*argv):
        return subprocess.run([sys.executable, "-m", "text2anim.cli.main", *argv], cwd=tmp, env=env,
                              capture_output=True, check=True)
    cold, _ = median_time(lambda: cli(SENTENCES[3], "-o", "x.bvh"), max(3, args.repeat // 2))
    parse, _ = median_time(lambda: cli("parse", SENTENCES[3]), max(3, args.repeat // 2))
    print(f"\ncold start, whole process: text2anim TEXT -o x.bvh {cold * 1000:.0f} ms; "
          f"text2anim parse {parse * 1000:.0f} ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())

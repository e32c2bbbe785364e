"""BVH parse and forward-kinematics throughput.

    python benchmarks/bench_bvh.py [--repeat N]

Parses CMU files from ``../shared/mocap/cmu`` with our reader and, when they
are installed (``pip install bvhio bvh``; benchmark only, not dependencies),
with bvhio and the ``bvh`` package, and prints frames per second. Figures are
best-of-N wall times on this machine: compare them as ratios between rows of
one run, not across machines.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from text2anim.core import read_bvh  # noqa: E402

CMU = REPO.parent / "shared" / "mocap" / "cmu"
FILES = ["02_01_walk", "16_35_run", "10_01_kick", "02_05_punch", "14_06_squat"]


def best_of(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def readers():
    yield "text2anim.read_bvh", lambda p: read_bvh(p)
    try:
        import bvhio

        yield "bvhio.readAsBvh", lambda p: bvhio.readAsBvh(str(p))
    except ImportError:
        print("bvhio: not installed (pip install bvhio)")
    try:
        from bvh import Bvh

        def parse_bvh_pkg(p):
            mocap = Bvh(Path(p).read_text())
            return np.array(mocap.frames, dtype=float)

        yield "bvh.Bvh (+ float array)", parse_bvh_pkg
    except ImportError:
        print("bvh: not installed (pip install bvh)")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    paths = [CMU / f"{f}.bvh" for f in FILES if (CMU / f"{f}.bvh").exists()]
    if not paths:
        print(f"no CMU files under {CMU}")
        return 1
    frames = sum(read_bvh(p).n_frames for p in paths)
    print(f"BVH parse: {len(paths)} CMU files, {frames} frames, 31 joints, best of {args.repeat}")
    print(f"{'reader':28} {'seconds':>9} {'frames/s':>11} {'vs ours':>8}")
    ours = None
    for name, fn in readers():
        sec = best_of(lambda: [fn(p) for p in paths], args.repeat)
        ours = ours or sec
        print(f"{name:28} {sec:9.3f} {frames / sec:11.0f} {ours / sec:8.2f}x")

    motion = read_bvh(paths[-1])
    def fk():
        object.__delattr__(motion, "pose") if "pose" in motion.__dict__ else None
        return motion.positions
    sec = best_of(fk, args.repeat)
    print(f"\nFK: {motion.n_frames} frames x {motion.skeleton.n_joints} joints: {sec:.4f} s, "
          f"{motion.n_frames / sec:,.0f} frames/s")
    return 0


if __name__ == "__main__":
    sys.exit(main())

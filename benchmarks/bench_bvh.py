"""BVH parse throughput against the peers, the floors that bound ours, and forward kinematics.

    python benchmarks/bench_bvh.py [--repeat N] [--profile]

Parses CMU files from ``../shared/mocap/cmu`` with our reader and with ``bvhio`` and the ``bvh``
package (``pip install -e '.[bench]'``), each doing the same work (``bvh_peers.py`` says what each
contender produces), the contenders taking turns within each round. Medians of process CPU time,
wall time beside it; compare ratios within one run.

The floors are the two steps whose cost the reader cannot cut without changing its output:
turning the MOTION text into float64 (numpy's C reader ``np.loadtxt``, beside the other ways
numpy and Python offer) and the sines and cosines of the half angles (the Euler-to-quaternion
conversion must evaluate them bit for bit as before). ``--profile`` prints where ``read_bvh``'s
time goes (cProfile, own time).
"""
from __future__ import annotations

import argparse
import cProfile
import io
import pstats
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bvh_peers import cmu_paths, contenders, same_output  # noqa: E402

from text2anim.core import Motion, read_bvh  # noqa: E402


def timed(fn) -> tuple[float, float]:
    c, w = time.process_time(), time.perf_counter()
    fn()
    return time.process_time() - c, time.perf_counter() - w


def interleaved(fns: dict, repeat: int) -> dict[str, tuple[float, float]]:
    """Median (CPU, wall) per contender; each round runs every contender once, the order rotating."""
    names = list(fns)
    times: dict[str, list[tuple[float, float]]] = {n: [] for n in names}
    for fn in fns.values():
        fn()
    for k in range(repeat):
        for n in names[k % len(names):] + names[:k % len(names)]:
            times[n].append(timed(fns[n]))
    return {n: (statistics.median(t[0] for t in v), statistics.median(t[1] for t in v)) for n, v in times.items()}


def table(title: str, res: dict[str, tuple[float, float]], frames: int, ref: str | None = "text2anim") -> None:
    print(f"\n{title}")
    print(f"  {'':36} {'CPU ms':>8} {'wall ms':>8} {'frames/s':>10} {'ours faster':>11}")
    for n, (c, w) in res.items():
        ratio = f"{c / res[ref][0]:10.1f}x" if ref and n != ref else ""
        print(f"  {n:36} {c * 1e3:8.1f} {w * 1e3:8.1f} {frames / c:10,.0f} {ratio:>11}")


def floors(paths: list[Path], repeat: int, frames: int) -> None:
    """The float parsing and the trigonometry alone, on the same files."""
    texts = [p.read_text() for p in paths]
    blocks = [t.split("Frame Time:", 1)[1].split("\n", 1)[1] for t in texts]
    lines = [[ln for ln in b.split("\n") if ln.strip()] for b in blocks]
    mb = sum(len(b) for b in blocks) / 1e6
    fns = {
        "np.loadtxt(lines) (ours)": lambda: [np.loadtxt(x, comments=None, ndmin=2) for x in lines],
        "np.fromstring(text, sep=' ')": lambda: [np.fromstring(b, sep=" ") for b in blocks],
        "np.array(text.split(), float)": lambda: [np.array(b.split(), dtype=float) for b in blocks],
        "list(map(float, text.split()))": lambda: [list(map(float, b.split())) for b in blocks],
        "text.split() alone": lambda: [b.split() for b in blocks],
    }
    res = interleaved(fns, repeat)
    table(f"Floor 1: MOTION text ({mb:.1f} MB, {sum(len(b.split()) for b in blocks):,} values) to float64",
          res, frames, ref=None)
    best = res["np.loadtxt(lines) (ours)"][0]
    print(f"  np.loadtxt reads {mb / best:.0f} MB/s; the others are slower, so it is the reader's floor")
    angles = [np.loadtxt(x, comments=None, ndmin=2)[:, 3:] for x in lines]  # CMU: root position, then rotations
    halves = [np.deg2rad(a) * 0.5 for a in angles]
    res = interleaved({"sin + cos of the half angles": lambda: [(np.sin(h), np.cos(h)) for h in halves]}, repeat)
    table(f"Floor 2: {sum(a.size for a in angles):,} Euler angles", res, frames, ref=None)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--profile", action="store_true", help="print cProfile's top functions of read_bvh")
    args = ap.parse_args()
    paths = cmu_paths()
    if not paths:
        print("no CMU files under ../shared/mocap/cmu")
        return 1
    frames = sum(read_bvh(p).n_frames for p in paths)
    print(f"BVH parse: {len(paths)} CMU files, {frames} frames, 31 joints; medians of {args.repeat} interleaved rounds")
    for output, title in (("rotations", "To joint quaternions (T, J, 4) + root positions"),
                          ("raw", "To the raw channel values (T, C), float64")):
        fns, notes = contenders(paths, output)
        for note in notes:
            print(f"  ({note})")
        table(title, interleaved(fns, args.repeat), frames)
    check = same_output(paths)
    if check:
        print(f"  same output: {check}")
    floors(paths, args.repeat, frames)

    if args.profile:
        prof = cProfile.Profile()
        prof.enable()
        for _ in range(args.repeat):
            for p in paths:
                read_bvh(p)
        prof.disable()
        out = io.StringIO()
        pstats.Stats(prof, stream=out).sort_stats("tottime").print_stats(12)
        print("\nread_bvh, cProfile by own time:\n" + "\n".join(out.getvalue().splitlines()[4:]))

    motion = read_bvh(paths[-1])

    def fk():  # on a new motion of the same arrays: its pose is not known yet
        return Motion(motion.skeleton, motion.fps, motion.root_positions, motion.rotations, motion.translations).positions
    cpu = statistics.median(timed(fk)[0] for _ in range(args.repeat))
    print(f"\nFK: {motion.n_frames} frames x {motion.skeleton.n_joints} joints: {cpu * 1e3:.1f} ms CPU, "
          f"{motion.n_frames / cpu:,.0f} frames/s")
    return 0


if __name__ == "__main__":
    sys.exit(main())

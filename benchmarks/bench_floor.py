"""Where the calibrated capture floor puts a planted foot: the measurement behind ``core.floor.FOOT_CLEARANCE``.

    python benchmarks/bench_floor.py [--cmu DIR]

For every take of ``../shared/mocap/cmu`` (``index.tsv``; T-pose frame dropped,
resampled to 30 fps, the file's own ``y = 0``, which is the capture session's
calibrated floor), on the frames ``core.contacts.detect_contacts`` calls planted:

- toe: median height (cm) of the planted foot's toe joint (the ball of the foot);
- lowest: median height of the planted foot's lowest joint (ankle or toe): the
  sole's thickness under the lowest joint centre;
- skating (GMD ratio, docs/timetable.md §3) with the floor at the file's ``y = 0``, with the
  floor put 2 cm under the planted toe joint (the old convention) and with the
  floor put ``FOOT_CLEARANCE`` under it (``core.floor.place_on_floor``);
- GMD: the skating ratio as GMD measures it, above the take's lowest foot point
  (``core.metrics.skating_ratio_gmd``).

The last rows give the median and interquartile range over the takes: the
convention adopted is their median, rounded to the millimetre. Then GMD's figure over
every take of the shared capture (``cmu``, ``cmu_everyday``, ``cmu_repro``): its spread,
against which ``core.metrics.CAPTURE_GMD_LIMIT`` is set (the largest, rounded up).
"""
from __future__ import annotations

import argparse
import csv
import time
from pathlib import Path

import numpy as np

from text2anim.core.bodyparts import body_map
from text2anim.core.bvh import read_bvh
from text2anim.core.contacts import detect_contacts
from text2anim.core.floor import FOOT_CLEARANCE
from text2anim.core.metrics import CAPTURE_GMD_LIMIT, at_rate, skating_ratio, skating_ratio_gmd

CMU = Path(__file__).resolve().parents[1] / ".." / "shared" / "mocap" / "cmu"


def planted_heights(path: Path) -> tuple[object, np.ndarray, np.ndarray]:
    """The take at 30 fps and the heights (m) of its toe and lowest foot joint on planted frames."""
    m = at_rate(read_bvh(path, scale="auto", drop_first=True))
    fc = detect_contacts(m)
    y = m.positions[..., 1]
    bm = body_map(m.skeleton)
    toe, low = [], []
    for side in ("left", "right"):
        ankle, t = bm.feet[side]
        planted = fc.of(side)
        toe.append(y[planted, t])
        low.append(np.minimum(y[planted, ankle], y[planted, t]))
    return m, np.concatenate(toe), np.concatenate(low)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--cmu", type=Path, default=CMU)
    args = p.parse_args()
    c0, w0 = time.process_time(), time.perf_counter()
    rows = list(csv.DictReader(open(args.cmu / "index.tsv", encoding="utf-8"), delimiter="\t"))
    print(f"{'take':22s} {'frames':>6s} {'toe cm':>7s} {'lowest cm':>9s} {'skate@file':>10s} "
          f"{'@toe-2cm':>8s} {'@toe-' + format(FOOT_CLEARANCE * 100, '.1f') + 'cm':>10s} {'GMD':>6s}")
    toes, lows = [], []
    for r in rows:
        m, toe, low = planted_heights(args.cmu / r["file"])
        t, lo = float(np.median(toe)), float(np.median(low))
        toes.append(t)
        lows.append(lo)
        print(f"{r['file']:22s} {len(toe):6d} {100 * t:7.2f} {100 * lo:9.2f} {skating_ratio(m):10.3f} "
              f"{skating_ratio(m, floor=t - 0.02):8.3f} {skating_ratio(m, floor=t - FOOT_CLEARANCE):10.3f} "
              f"{skating_ratio_gmd(m):6.3f}")
    for name, v in (("toe", toes), ("lowest", lows)):
        q1, med, q3 = np.percentile(v, [25, 50, 75])
        print(f"{name:7s} over {len(v)} takes: median {100 * med:.2f} cm, IQR {100 * q1:.2f}-{100 * q3:.2f} cm, "
              f"range {100 * min(v):.2f}-{100 * max(v):.2f} cm")
    print(f"convention: core.floor.FOOT_CLEARANCE = {100 * FOOT_CLEARANCE:.1f} cm")
    capture_spread(args.cmu.parent)
    print(f"total: {time.process_time() - c0:.1f} s CPU, {time.perf_counter() - w0:.1f} s wall")


def capture_spread(mocap: Path) -> None:
    """GMD's skating ratio (30 fps, whole takes, T-pose frame dropped) over every take of the shared capture."""
    takes = sorted(p for d in ("cmu", "cmu_everyday", "cmu_repro") for p in (mocap / d).glob("*.bvh"))
    gmd = {p.name: skating_ratio_gmd(at_rate(read_bvh(p, scale="auto", drop_first=True))) for p in takes}
    v = np.array(list(gmd.values()))
    print(f"GMD's skating ratio over {len(v)} capture takes: median {np.median(v):.3f}, 90th percentile "
          f"{np.percentile(v, 90):.3f}, range {v.min():.3f}-{v.max():.3f} "
          f"(the largest: {max(gmd, key=gmd.__getitem__)}); core.metrics.CAPTURE_GMD_LIMIT = {CAPTURE_GMD_LIMIT}")


if __name__ == "__main__":
    main()

"""Transitions a body could do (docs/timetable.md §3): balance (core.balance), glides (core.glide) and hanging
in the air (core.hang), calibrated on capture, then measured on what we generate.

    python benchmarks/bench_transitions.py [--scenes N]

Prints three tables, each with CPU beside wall time:

1. **Capture** (``../shared/mocap/cmu`` and ``cmu_everyday``, at 30 fps, each take's T-pose first frame
   dropped): per take the frames the balance figure judges (a foot down, the centre of mass slower than
   0.3 m/s, the hips above 0.75 leg lengths), the figure (cm the centre of mass stays outside its support
   area for 0.2 s or more, at a person's size), the share of judged frames outside at all, and the longest
   glide (s: the hips travelling at a steady speed). The limits ``core.balance.LIMIT_CM`` and
   ``core.glide.LIMIT_S`` are the largest of these (the sit-down 14_27 left out of balance).
2. **The built-in library**, per clip, the worst first.
3. **Generated transitions**: the scene set (tests/corpus/scenes.txt) and the golden sentences, both
   figures over the frames no source clip plays as recorded (``text2anim.quality.played_frames``) beside
   the whole motion's.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
SHARED = REPO.parent / "shared" / "mocap"

from bench_quality import Clock  # noqa: E402  (CPU and wall seconds of a part)


#: words of a take's CMU description that say a prop holds the body up (a ladder, steps, a stool, a bar to
#: hang from): the hang in the air is not read on those takes
PROPS = ("climb", "stool", "jump up to grab")
#: takes whose floor is not level (08_04: the lowest foot joint rises 9 cm over the walk), left out of the hang
SLOPED = ("cmu/08_04_slowwalk",)


def _descriptions() -> dict[str, str]:
    """``"folder/stem" → CMU description`` of the shared takes."""
    import csv

    out = {}
    for folder in ("cmu", "cmu_everyday"):
        index = SHARED / folder / "index.tsv"
        if index.is_file():
            with open(index, encoding="utf-8") as fh:
                out.update({f"{folder}/{r['file'][:-4]}": r["cmu_description"] for r in csv.DictReader(fh, delimiter="\t")})
    return out


def capture() -> list[tuple[str, int, float, float, float, float | None]]:
    """Per take: judged frames, balance (cm), share outside, longest glide (s), and the longest hang in the air
    (s, placed on its floor as an import places it; None where a prop holds the body or the floor slopes)."""
    from text2anim.core import read_bvh
    from text2anim.core.balance import balance_heights, balance_runs
    from text2anim.core.floor import place_on_floor
    from text2anim.core.glide import glide_s
    from text2anim.core.hang import hang_s
    from text2anim.core.metrics import at_rate
    from text2anim.core.size import HUMAN_LEG, leg_length

    said = _descriptions()
    rows = []
    for path in sorted(SHARED.glob("cmu/*.bvh")) + sorted(SHARED.glob("cmu_everyday/*.bvh")):
        m = at_rate(read_bvh(path, drop_first=True), 30.0)
        k = 100.0 * HUMAN_LEG / leg_length(m.skeleton)
        h = balance_heights(m)
        judged = np.isfinite(h)
        outside = float((h[judged] > 0).mean()) if judged.any() else 0.0
        name = f"{path.parent.name}/{path.stem}"
        propped = any(w in said.get(name, "") for w in PROPS) or name in SLOPED
        rows.append((name, int(judged.sum()), float(balance_runs(m).max()) * k, outside, glide_s(m),
                     None if propped else hang_s(place_on_floor(m)[0])))
    return rows


def library(db) -> list[tuple[str, float, float]]:
    """Per built-in clip of the database ``db``: its balance (cm) and longest glide (s) at 30 fps."""
    from text2anim.core.balance import balance_cm
    from text2anim.core.glide import glide_s
    from text2anim.core.metrics import at_rate

    return [(c.name, balance_cm(m), glide_s(m)) for c in db.clips() for m in [at_rate(db.load(c.name), 30.0)]]


def generated(db, texts: list[str]) -> list[tuple[str, str, float, float, float, float, float]]:
    import text2anim
    from text2anim.core.balance import balance_cm
    from text2anim.core.glide import glide_s
    from text2anim.core.hang import hang_s
    from text2anim.core.metrics import at_rate
    from text2anim.quality import played_frames

    rows = []
    for text in texts:
        anim = text2anim.animate(text, db=db)
        for actor, motion in anim.motions.items():
            m30 = at_rate(motion, 30.0)
            paths = anim.result.placed_paths.get(actor)
            changed = None if paths is None else ~played_frames(motion, paths, 30.0)  # None: one clip, as placed
            rows.append((text, str(actor), 0.0 if changed is None else balance_cm(m30, changed), balance_cm(m30),
                         0.0 if changed is None else glide_s(m30, changed), glide_s(m30),
                         0.0 if changed is None else hang_s(m30, changed)))
    return rows


def main(argv=None) -> int:
    from text2anim.core import hang
    from text2anim.core.balance import LIMIT_CM
    from text2anim.core.glide import LIMIT_S
    from text2anim.motiondb import MotionDB

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", type=int, default=None, help="only the first N scenes (default all)")
    args = ap.parse_args(argv)
    if SHARED.is_dir():
        with Clock() as c:
            rows = capture()
        print(f"capture: {len(rows)} takes ({c.cpu:.1f} s CPU, {c.wall:.1f} s wall)")
        print(f"{'take':28} {'judged':>7} {'outside cm':>11} {'share outside':>14} {'glide s':>8} {'hang s':>7}")
        for name, n, cm, share, gl, hg in sorted(rows, key=lambda r: (-r[2], -r[4]))[:10]:
            print(f"{name:28} {n:7d} {cm:11.1f} {share:14.2f} {gl:8.2f} {'-' if hg is None else f'{hg:.2f}':>7}")
        standing = [r for r in rows if not r[0].endswith("14_27_sit")]
        print(f"balance, largest: {max(r[2] for r in rows):.1f} cm; without the sit-down 14_27: "
              f"{max(r[2] for r in standing):.1f} cm (the limit: {LIMIT_CM} cm)")
        worst = max(rows, key=lambda r: r[4])
        print(f"glide, longest: {worst[4]:.2f} s ({worst[0]}; the limit: {LIMIT_S} s)")
        free = [r for r in rows if r[5] is not None]
        hung = max(free, key=lambda r: r[5])
        print(f"hang in the air, longest: {hung[5]:.2f} s ({hung[0]}; {len(rows) - len(free)} takes held by a prop "
              f"or on a sloping floor left out; the limit: {hang.LIMIT_S} s)\n")
    else:
        print(f"no capture at {SHARED}: the calibration table is skipped\n")
    with tempfile.TemporaryDirectory(prefix="bench-transitions-") as tmp, \
            MotionDB.open(f"sqlite:///{tmp}/library.sqlite") as db:
        return _library_and_generated(db, args)


def _library_and_generated(db, args) -> int:
    """Tables 2 and 3 of the module docstring, on the built-in library's database ``db``."""
    from text2anim.core.hang import LIMIT_S as HANG_S
    from text2anim.core.balance import LIMIT_CM
    from text2anim.core.glide import LIMIT_S

    with Clock() as c:
        lib = library(db)
    print(f"built-in library: {len(lib)} clips, {sum(r[1] > LIMIT_CM for r in lib)} over {LIMIT_CM} cm of balance, "
          f"{sum(r[2] > LIMIT_S for r in lib)} gliding over {LIMIT_S} s ({c.cpu:.1f} s CPU, {c.wall:.1f} s wall)")
    for name, cm, gl in sorted(lib, key=lambda r: (-r[1], -r[2]))[:6]:
        print(f"  {name:28} {cm:6.1f} cm {gl:5.2f} s")
    for name, cm, gl in sorted(lib, key=lambda r: -r[2])[:4]:
        print(f"  {name:28} {cm:6.1f} cm {gl:5.2f} s")
    scenes = [t for t in (line.strip() for line in (REPO / "tests" / "corpus" / "scenes.txt")
                          .read_text(encoding="utf-8").splitlines()) if t and not t.startswith("#")]
    golden = [t for t in (REPO / "tests" / "golden" / "sentences.txt").read_text(encoding="utf-8").splitlines() if t]
    texts = scenes[:args.scenes] + golden
    with Clock() as c:
        gen = generated(db, texts)
    print(f"\ngenerated transitions: {len(gen)} animations of {len(texts)} sentences; "
          f"{sum(r[2] > LIMIT_CM for r in gen)} over {LIMIT_CM} cm of balance, "
          f"{sum(r[4] > LIMIT_S for r in gen)} gliding over {LIMIT_S} s, {sum(r[6] > HANG_S for r in gen)} hanging in "
          f"the air over {HANG_S} s ({c.cpu:.1f} s CPU, {c.wall:.1f} s wall)")
    print(f"  {'balance cm':>10} {'(whole)':>8} {'glide s':>8} {'(whole)':>8} {'hang s':>7}  sentence")
    for text, actor, g, w, gl, glw, hg in sorted(gen, key=lambda r: (-max(r[2] / LIMIT_CM, r[4] / LIMIT_S,
                                                                          r[6] / HANG_S)))[:10]:
        print(f"  {g:10.1f} {w:8.1f} {gl:8.2f} {glw:8.2f} {hg:7.2f}  {text} ({actor})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

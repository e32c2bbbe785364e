"""Motion-database benchmarks: search latency, seeding time, size.

    python benchmarks/bench_db.py [--sizes 1000 100000] [--queries 300]

1. Search latency (p50/p95, milliseconds) in SQLite databases of N clips of
   synthetic metadata (tiny frame blobs): a vocabulary of 1000 verbs, each
   clip with a primary verb and two synonyms, a third of the clips with one of
   50 objects, 10 characters, 4 foot contacts per clip. Queries are random
   known verbs (seeded RNG), half of them with an object and a third with a
   preferred character; timed through ``MotionDB.search`` both with
   ``limit=10`` (what a scheduler needs) and without a limit (every match,
   which grows with N: a verb has ~3N/1000 clips). The growth ratio is
   p50(largest N) / p50(smallest N).
2. Storing clips through the API (``MotionDB.add``, validation and contact
   detection included), clips per second.
3. First-run seeding: a fresh process opening a new database file, which
   reads the built-in library (``motiondb.library.builtin_clips``: the shipped
   ``capture.npz`` and ``keyframed.npz``) and stores it in one transaction.
4. Database file sizes.

The synthetic databases are written with bulk inserts (not the API) so that
100k clips take seconds; the schema is the real one, the ranking table filled
as storing through the API fills it.
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

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from sqlalchemy import insert  # noqa: E402

from text2anim.motiondb import ClipRecord, MotionDB  # noqa: E402
from text2anim.motiondb.blobs import ENCODING, encode_frames  # noqa: E402
from text2anim.motiondb.readings import to_katakana  # noqa: E402
from text2anim.motiondb.schema import (  # noqa: E402
    characters as Character,
    clip_frames as ClipFrames,
    clip_objects as ClipObject,
    clip_verbs as ClipVerb,
    clips as Clip,
    contacts as Contact,
    objects as ObjectRow,
    skeletons as SkeletonRow,
    verbs as Verb,
)
from text2anim.motiondb.blobs import skeleton_json  # noqa: E402
from text2anim.motiondb.ranks import fill as fill_ranks  # noqa: E402

sys.path.insert(0, str(REPO / "tests"))
from conftest import make_motion  # noqa: E402

N_VERBS = 1000
N_OBJECTS = 50
N_CHARACTERS = 10
HIRAGANA = [chr(c) for c in range(0x3042, 0x3093) if chr(c) not in "ぁぃぅぇぉっゃゅょゎ"]


def vocabulary(rng: np.random.Generator, n: int, suffix: str) -> list[str]:
    words: set[str] = set()
    out = []
    while len(out) < n:
        w = "".join(rng.choice(HIRAGANA, size=int(rng.integers(2, 5)))) + suffix
        if w not in words:
            words.add(w)
            out.append(w)
    return out


def build(path: Path, n_clips: int, seed: int = 0) -> tuple[list[str], list[str], list[str]]:
    """A database of ``n_clips`` synthetic clips at ``path``; returns (verbs, objects, characters)."""
    rng = np.random.default_rng(seed)
    verbs = vocabulary(rng, N_VERBS, "する")
    objects = vocabulary(rng, N_OBJECTS, "")
    characters = [f"actor{k}" for k in range(N_CHARACTERS)]
    tiny = make_motion(frames=2)
    blob = encode_frames(tiny)
    db = MotionDB.open(path, seed=False)
    with db.engine.begin() as conn:
        conn.execute(insert(SkeletonRow), [{"id": 1, "fingerprint": "bench", "n_joints": tiny.skeleton.n_joints,
                                            "definition": skeleton_json(tiny.skeleton)}])
        conn.execute(insert(Character), [{"id": k + 1, "name": c, "skeleton_id": 1} for k, c in enumerate(characters)])
        conn.execute(insert(Verb), [{"id": k + 1, "lemma": v, "reading": to_katakana(v[:-2]) + "スル"}
                                    for k, v in enumerate(verbs)])
        conn.execute(insert(ObjectRow), [{"id": k + 1, "name": o, "reading": to_katakana(o)}
                                         for k, o in enumerate(objects)])
        step = 20000
        for a in range(0, n_clips, step):
            ids = range(a + 1, min(n_clips, a + step) + 1)
            clips, frames, links, objs, contacts = [], [], [], [], []
            for i in ids:
                frames_n = int(rng.integers(30, 300))
                clips.append({"id": i, "name": f"clip{i:06d}", "character_id": int(rng.integers(N_CHARACTERS)) + 1,
                              "skeleton_id": 1, "fps": 30.0, "frames": frames_n, "duration": frames_n / 30.0,
                              "core_begin": 0.0, "core_end": frames_n / 30.0, "body_part": None,
                              "cyclic": bool(rng.random() < 0.2), "source": "bench"})
                frames.append({"clip_id": i, "encoding": ENCODING, "data": blob})
                for pos, v in enumerate(rng.choice(N_VERBS, size=3, replace=False)):
                    links.append({"clip_id": i, "verb_id": int(v) + 1, "position": pos, "is_primary": pos == 0})
                if rng.random() < 1 / 3:
                    objs.append({"clip_id": i, "object_id": int(rng.integers(N_OBJECTS)) + 1, "position": 0})
                for side in ("left", "right"):
                    contacts += [{"clip_id": i, "side": side, "start_frame": 0, "stop_frame": 10},
                                 {"clip_id": i, "side": side, "start_frame": 20, "stop_frame": 29}]
            conn.execute(insert(Clip), clips)
            conn.execute(insert(ClipFrames), frames)
            conn.execute(insert(ClipVerb), links)
            if objs:
                conn.execute(insert(ClipObject), objs)
            conn.execute(insert(Contact), contacts)
        fill_ranks(conn)  # the search's ranking table, as storing clips through the API writes it
    db.close()
    return verbs, objects, characters, len(blob) * n_clips


def percentile(values: list[float], q: float) -> float:
    return float(np.percentile(np.asarray(values), q))


def time_searches(path: Path, verbs, objects, characters, n_queries: int, limit: int | None, seed: int = 1):
    rng = np.random.default_rng(seed)
    times, hits = [], []
    with MotionDB.open(path, seed=False) as db:
        db.search(verbs[0], limit=limit)  # warm: connection, analyser, caches
        for _ in range(n_queries):
            verb = verbs[int(rng.integers(len(verbs)))]
            obj = objects[int(rng.integers(len(objects)))] if rng.random() < 0.5 else None
            pref = characters[int(rng.integers(len(characters)))] if rng.random() < 1 / 3 else None
            t = time.perf_counter()
            found = db.search(verb, object=obj, prefer_character=pref, limit=limit)
            times.append((time.perf_counter() - t) * 1000)
            hits.append(len(found))
    return percentile(times, 50), percentile(times, 95), statistics.mean(hits)


def time_add(path: Path, n: int = 200) -> float:
    records = [ClipRecord(f"added{k}", make_motion(frames=60, seed=k), ("歩く", "進む"), objects=("ボール",))
               for k in range(n)]
    with MotionDB.open(path, seed=False) as db:
        t = time.perf_counter()
        db.add(records)
        return n / (time.perf_counter() - t)


def time_first_run(folder: Path) -> tuple[float, int, int] | None:
    """Seconds for a fresh process to open (create + seed) a new database; clip count; file size."""
    path = folder / "seeded.sqlite"
    code = ("import sys, time; sys.path.insert(0, sys.argv[2]); t = time.perf_counter();"
            "from text2anim.motiondb import MotionDB; db = MotionDB.open(sys.argv[1]); n = len(db.clips());"
            "print(time.perf_counter() - t, n)")
    proc = subprocess.run([sys.executable, "-c", code, str(path), str(REPO)], capture_output=True, text=True,
                          cwd=REPO)
    if proc.returncode != 0:
        print(proc.stderr, file=sys.stderr)
        return None
    seconds, n = proc.stdout.split()
    return float(seconds), int(n), path.stat().st_size


def human(n_bytes: int) -> str:
    for unit in ("B", "KB", "MB", "GB"):
        if n_bytes < 1024 or unit == "GB":
            return f"{n_bytes:.0f} {unit}" if unit == "B" else f"{n_bytes:.1f} {unit}"
        n_bytes /= 1024
    return ""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[1000, 100000])
    ap.add_argument("--queries", type=int, default=300)
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="t2a-bench-") as tmp:
        tmp = Path(tmp)
        rows = []
        for n in args.sizes:
            path = tmp / f"bench_{n}.sqlite"
            t = time.perf_counter()
            *vocab, blob_bytes = build(path, n)
            built = time.perf_counter() - t
            p50, p95, hits = time_searches(path, *vocab, args.queries, limit=10)
            f50, f95, fhits = time_searches(path, *vocab, args.queries, limit=None)
            rows.append((n, p50, p95, hits, f50, f95, fhits, os.path.getsize(path), blob_bytes, built))
        print(f"\nSearch latency, SQLite, {args.queries} random queries (ms)")
        print(f"{'clips':>8} | {'p50 @10':>8} {'p95 @10':>8} | {'p50 all':>8} {'p95 all':>8} {'hits':>6} |"
              f" {'DB size':>9} {'blobs':>9} {'build s':>8}")
        for n, p50, p95, hits, f50, f95, fhits, size, blobs, built in rows:
            print(f"{n:>8} | {p50:8.2f} {p95:8.2f} | {f50:8.2f} {f95:8.2f} {fhits:6.1f} | {human(size):>9}"
                  f" {human(blobs):>9} {built:8.1f}")
        if len(rows) > 1:
            a, b = rows[0], rows[-1]
            print(f"growth ratio p50 {b[0]}/{a[0]} clips: limit 10: {b[1] / a[1]:.2f}x, every match: "
                  f"{b[4] / a[4]:.2f}x (matches per query grow {b[6] / max(a[6], 1e-9):.0f}x)")
        rate = time_add(tmp / "add.sqlite")
        print(f"\nMotionDB.add: {rate:.0f} clips/s (60-frame clips, 23 joints, contacts + validation, one transaction)")
        first = time_first_run(tmp)
        if first is None:
            print("first-run seeding: failed (see stderr)")
        else:
            seconds, n, size = first
            print(f"first run (new process: import, create, generate + store the built-in library): "
                  f"{seconds:.2f} s for {n} clips; DB size {human(size)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

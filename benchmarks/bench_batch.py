"""Batch throughput: the single-process path against Dask with 1, 2 and 4 local workers.

    python benchmarks/bench_batch.py [--lines 2000] [--workers 1,2,4] [--chunk 16]

The project corpus (tests/corpus/nlp_corpus.jsonl, refusals included) is
repeated to ``--lines`` lines and animated with the built-in library from a
temporary SQLite database (shipped to each worker). Each row: wall time,
lines/s, CPU seconds of every process involved (this one, which also hosts the
scheduler, and the workers), lines per CPU second, the scaling efficiency
(lines/s over n × the 1-worker row's) and the overhead against the
single-process path. Cluster start-up and a warm-up of every worker (analyser
and database loaded) are timed apart. The load average is printed before and
after each row: on a shared machine compare the CPU columns, not the wall ones.
"""
from __future__ import annotations

import argparse
import hashlib
import json
import logging
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
CORPUS = REPO / "tests" / "corpus" / "nlp_corpus.jsonl"


def build_corpus(folder: Path, lines: int) -> Path:
    from text2anim.cli.batch import load_corpus

    texts = [it.text for it in load_corpus(str(CORPUS))]
    path = folder / f"corpus_{lines}.jsonl"  # JSON lines: one corpus text has a line break in it
    path.write_text("".join(json.dumps({"text": texts[i % len(texts)]}, ensure_ascii=False) + "\n"
                            for i in range(lines)), encoding="utf-8")
    return path


def digest(folder: Path) -> str:
    h = hashlib.sha256()
    for p in sorted(folder.rglob("*.bvh")):
        h.update(str(p.relative_to(folder)).encode() + p.read_bytes())
    return h.hexdigest()


def _cpu() -> float:
    return time.process_time()


def load() -> str:
    return "{:.1f}".format(os.getloadavg()[0])


def run_row(corpus: Path, out: Path, opts_db: str, scheduler: str | None, client=None, chunk: int = 16):
    from text2anim.cli.batch import Options, run_corpus

    workers0 = client.run(_cpu) if client else {}
    cpu0, t0, load0 = time.process_time(), time.perf_counter(), load()
    outcome = run_corpus(str(corpus), Options(out=str(out), db=opts_db), scheduler=scheduler, chunk=chunk)
    wall = time.perf_counter() - t0
    cpu = time.process_time() - cpu0
    if client:
        workers1 = client.run(_cpu)
        cpu += sum(workers1[w] - workers0.get(w, 0.0) for w in workers1)
    return outcome, wall, cpu, f"{load0}→{load()}"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lines", type=int, default=2000, help="corpus lines (the corpus repeated; default 2000)")
    ap.add_argument("--workers", default="1,2,4", help="local Dask worker counts (default 1,2,4)")
    ap.add_argument("--chunk", type=int, default=16, help="lines per task (default 16)")
    args = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="t2a-bench-batch-"))
    try:
        return measure(args, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def measure(args, tmp: Path) -> int:
    from distributed import Client, LocalCluster

    from text2anim.motiondb import MotionDB

    db = f"sqlite:///{tmp}/motions.sqlite"
    MotionDB.open(db).close()
    corpus = build_corpus(tmp, args.lines)
    warm = build_corpus(tmp, 8)
    print(f"{args.lines} lines ({CORPUS.name} repeated), chunk {args.chunk}, {os.cpu_count()} CPUs, "
          f"load average {load()}")

    # single-process path, warmed up first (analyser and database loaded)
    run_row(warm, tmp / "warm-1", db, None)
    outcome, wall, cpu, ld = run_row(corpus, tmp / "single", db, None, chunk=args.chunk)
    ref = digest(tmp / "single")
    rows = [("single process", None, wall, cpu, ld, True, 0.0)]
    for n in [int(x) for x in args.workers.split(",")]:
        t = time.perf_counter()
        with LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0",
                          silence_logs=logging.ERROR) as lc, Client(lc) as client:
            run_row(build_corpus(tmp, 2 * n), tmp / f"warm-{n}-dask", db, lc.scheduler_address, client)
            startup = time.perf_counter() - t
            outcome, wall, cpu, ld = run_row(corpus, tmp / f"dask-{n}", db, lc.scheduler_address, client,
                                             args.chunk)
        rows.append((f"dask, {n} worker{'s' if n > 1 else ''}", n, wall, cpu, ld,
                     digest(tmp / f"dask-{n}") == ref, startup))

    single_wall, single_cpu = rows[0][2], rows[0][3]
    one = next((r for r in rows if r[1] == 1), None)
    print(f"\n{'run':<18}{'wall s':>8}{'lines/s':>9}{'CPU s':>8}{'lines/CPU s':>12}{'efficiency':>11}"
          f"{'wall vs 1 proc':>15}{'CPU vs 1 proc':>14}{'start-up s':>11}{'load':>12}  same bytes")
    for name, n, wall, cpu, ld, same, startup in rows:
        rate = args.lines / wall
        eff = f"{rate / (n * args.lines / one[2]):.2f}" if n and one else "-"
        print(f"{name:<18}{wall:8.1f}{rate:9.2f}{cpu:8.1f}{args.lines / cpu:12.2f}{eff:>11}"
              f"{wall / single_wall - 1:+15.0%}{cpu / single_cpu - 1:+14.0%}{startup:11.1f}{ld:>12}  "
              f"{'yes' if same else 'NO'}")
    if one:
        two = next((r for r in rows if r[1] == 2), None)
        if two:
            print(f"\nthroughput 1 → 2 workers: {one[2] / two[2]:.2f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""``text2anim batch``: run a corpus through the pipeline, on this machine or a Dask cluster.

A corpus line is plain text or a JSON object ``{"text": …, "category": …,
"expect": {…}}`` (see :mod:`.batch.corpus`). Every line is parsed; with
``--out DIR`` it is also planned and animated: ``DIR/0000/line_0000012.bvh``
(1000 lines per folder), one record per line in ``DIR/manifest.jsonl`` written
as results arrive, ``DIR/summary.json`` at the end. A rerun skips the lines
already done with the same text and options. ``--jobs N`` runs on a local
Dask cluster of N worker processes, ``--scheduler tcp://HOST:8786`` on a
running one (``pip install 'text2anim[cluster]'``); the outputs are the same
bytes either way.
"""
from __future__ import annotations

import argparse
import sys
import time
from typing import Any

from text2anim.core.inputs import printable

from .arg_types import fps_type
from .batch import DEFAULT_CHUNK, Options, run_corpus
from .bvh_options import add_budget_option

NAME = "batch"
HELP = ("run every line of a corpus through parse (and plan + animation with --out), locally or on a "
        "Dask cluster; print a summary and, with --check, fail when an expectation is not met")

EXIT_FAILED = 1


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("corpus", metavar="CORPUS",
                        help="file of text lines or JSON lines with expected parses")
    parser.add_argument("--check", action="store_true",
                        help="exit 1 when any line fails its expectation or errors")
    parser.add_argument("--out", metavar="DIR",
                        help="also plan and animate every line: sharded BVH files, DIR/manifest.jsonl "
                             "(one record per line, resumable) and DIR/summary.json")
    parser.add_argument("--wait", action="store_true",
                        help="with --out: if another batch run owns DIR, wait for it to finish instead of "
                             "refusing (a resumed run then does only what it left)")
    parser.add_argument("--jobs", type=int, default=1, metavar="N",
                        help="worker processes of a local Dask cluster (default 1: run in this process)")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="run on the Dask cluster of this scheduler (tcp://HOST:8786); --out must "
                             "be a folder every worker shares")
    parser.add_argument("--chunk", type=int, default=DEFAULT_CHUNK, metavar="N",
                        help=f"lines sent to a worker at a time (default {DEFAULT_CHUNK})")
    parser.add_argument("--parse-only", action="store_true",
                        help="with --out: write the parse results only, do not plan or animate")
    parser.add_argument("--db", metavar="URL", help="motion database for --out (default: $TEXT2ANIM_DB "
                        "or the user's data directory); SQLite is copied to each worker, PostgreSQL shared")
    parser.add_argument("--fps", type=fps_type, default=30.0, help="frame rate of the animations, 1 to 240 (default 30)")
    add_budget_option(parser)


class Progress:
    """A tqdm bar with rate and ETA on a terminal; about ten lines of the same figures off one."""

    def __init__(self, stream=None):
        self.stream = stream or sys.stderr
        self.bar: Any = None  # a tqdm bar once started

    def start(self, total: int, skipped: int) -> None:
        from tqdm import tqdm

        if skipped:
            self.stream.write(f"batch: {skipped} lines already done, {total} to run\n")
        self.total = total
        self.tty = self.stream.isatty()
        self.bar = tqdm(total=total, file=self.stream, unit="line", dynamic_ncols=True,
                        disable=not self.tty or not total)
        self._t0 = time.monotonic()

    def update(self, _record: dict, done: int, total: int) -> None:
        self.bar.update(1)
        if not self.tty and (done == total or done % max(1, total // 10) == 0):
            from tqdm import tqdm

            meter = tqdm.format_meter(done, total, time.monotonic() - self._t0, unit="line")
            self.stream.write(f"batch: {meter}\n")

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def run(args: argparse.Namespace) -> int:
    opts = Options(out=args.out, db=args.db, fps=args.fps, max_seconds=args.max_seconds, parse_only=args.parse_only)
    progress = Progress()
    try:
        outcome = run_corpus(args.corpus, opts, jobs=args.jobs, scheduler=args.scheduler, chunk=args.chunk,
                             on_start=progress.start, on_record=progress.update, wait=args.wait)
    finally:
        progress.close()
    sys.stdout.write(printable(outcome.summary.format(), keep="\n"))  # corpus lines: ESC shown as \x1b
    if args.check and not outcome.summary.ok:
        return EXIT_FAILED
    return 0
